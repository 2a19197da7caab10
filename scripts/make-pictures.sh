#!/usr/bin/env bash
# Regenerates the README's pictures under docs/pictures/: for the main job
# (experiments/foraging.toml), a gadget experiment (experiments/t-maze.toml) and a shelter
# experiment (experiments/predator-arena.toml), a full-budget run's fitness plot, a trajectory
# picture of its champion and a still of the replay page at the middle of that trial
# (headless Chromium). The trial is trial 0 of the champion's own generation, except for
# predator-arena: held-out trial 1, whose predator wakes at tick 265, so that the picture shows
# both foraging and going home. PNGs are kept small (resized, 64 colours).
#
#   bash scripts/make-pictures.sh            (needs rsvg-convert, ImageMagick, chromium:
#                                             apt-get install -y librsvg2-bin imagemagick chromium)
#   PICTURES="t-maze locked-room" bash scripts/make-pictures.sh   (only these experiments)
#   GENERATIONS=15 bash scripts/make-pictures.sh                  (quick look, short runs)
set -euo pipefail
cd "$(dirname "$0")/.."
for tool in rsvg-convert convert chromium; do
  command -v "$tool" >/dev/null || { echo "make-pictures: $tool is missing (apt-get install -y librsvg2-bin imagemagick chromium)" >&2; exit 1; }
done
cargo build --release --quiet
bin=target/release/berry-evolve
out=docs/pictures
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out"
# Each at its file's own budget unless GENERATIONS says otherwise.
gens=${GENERATIONS:-}
for name in ${PICTURES:-foraging t-maze predator-arena}; do
  run=$tmp/$name
  case $name in
    predator-arena) trial=(--worlds held-out --trial 1) ;;
    *) trial=(--trial 0) ;;
  esac
  "$bin" run "experiments/$name.toml" ${gens:+--generations "$gens"} --out "$run" --force --quiet
  "$bin" plot "$run" -o "$tmp/$name-fitness.svg"
  "$bin" render "$run/best.json" --experiment "$run/experiment.toml" "${trial[@]}" -o "$tmp/$name-trajectory.svg"
  "$bin" replay "$run/best.json" --experiment "$run/experiment.toml" "${trial[@]}" --html "$tmp/$name.html" >/dev/null
  rsvg-convert -w 800 "$tmp/$name-fitness.svg" -o "$tmp/$name-fitness.png"
  rsvg-convert -w 900 "$tmp/$name-trajectory.svg" -o "$tmp/$name-trajectory.png"
  # The middle of the trial: half the experiment's ticks per trial.
  ticks=$(awk '/^\[evaluation\]/{e=1;next} /^\[/{e=0} e&&/^ticks *=/{print $3}' "$run/experiment.toml")
  profile=$(mktemp -d)
  chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
    --disable-background-networking --disable-component-update --disable-sync \
    --user-data-dir="$profile" --hide-scrollbars --window-size=1100,760 --virtual-time-budget=10000 \
    --screenshot="$tmp/$name-replay.png" "file://$tmp/$name.html#tick=$(( ${ticks:-800} / 2 ))" 2>/dev/null >/dev/null
  rm -rf "$profile"
  for kind in fitness trajectory replay; do
    convert "$tmp/$name-$kind.png" -resize '900x900>' -background white -flatten -colors 64 "PNG8:$out/$name-$kind.png"
  done
done
ls -l "$out"
