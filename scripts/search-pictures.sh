#!/usr/bin/env bash
# The search comparison's pictures (issue 30), from the runs scripts/search-comparison.sh left
# in results/search/: the main job without forward_bonus, the GA's champion and novelty
# search's (each the seed with the median held-out score, drawn on held-out trial 0); the
# MAP-Elites archive of seed 1 as a heat map, with the paths of three of its elites (the
# fittest of the backward, the middle and the forward column of the grid); and, for
# predator-arena without its beacon, the champion of each search on held-out trial 1.
#
#   bash scripts/search-comparison.sh && bash scripts/search-pictures.sh
#   (needs rsvg-convert and ImageMagick: apt-get install -y librsvg2-bin imagemagick)
set -euo pipefail
cd "$(dirname "$0")/.."
for tool in rsvg-convert convert montage; do
  command -v "$tool" >/dev/null || { echo "search-pictures: $tool is missing (apt-get install -y librsvg2-bin imagemagick)" >&2; exit 1; }
done
RUNS=${RUNS:-results/search}
bin=target/release/berry-evolve
[ -x "$bin" ] || cargo build --release
out=docs/pictures
tmp=${KEEP_TMP:-$(mktemp -d)}
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out"

# The seed whose champion has the median score on 20 held-out worlds among the runs of one file.
median_seed() {
  local file=$1 name
  name=$(basename "$file" .toml)
  local genomes=()
  for d in "$RUNS/$name"/seed-*; do [ -f "$d/best.json" ] && genomes+=("$d/best.json"); done
  "$bin" compare "${genomes[@]}" --experiment "$file" --worlds held-out --trials 20 --json |
    python3 -c '
import json, sys
g = sorted(json.load(sys.stdin)["genomes"], key=lambda g: g["fitness"])
print(g[(len(g) - 1) // 2]["path"])'
}

# A genome's path on one held-out trial, as a PNG with a caption.
draw() {
  local genome=$1 experiment=$2 trial=$3 caption=$4 png=$5
  "$bin" render "$genome" --experiment "$experiment" --worlds held-out --trial "$trial" -o "$tmp/r.svg"
  rsvg-convert -w 600 "$tmp/r.svg" -o "$tmp/r.png"
  convert "$tmp/r.png" -background white -flatten -gravity north -splice 0x34 \
    -pointsize 20 -annotate +0+6 "$caption" "$png"
}

plain=experiments/search/foraging-plain.toml
ga=$(median_seed "$plain")
novelty=$(median_seed experiments/search/foraging-plain-novelty.toml)
# A genome's forward share on the 20 held-out worlds.
forward() {
  "$bin" compare "$1" --experiment "$plain" --worlds held-out --trials 20 --json |
    python3 -c 'import json, sys; g = json.load(sys.stdin)["genomes"][0]; print("%.2f" % g["measures"]["forward_share"])'
}
draw "$ga" "$plain" 0 "GA, $(dirname "$ga" | xargs basename): forward share $(forward "$ga")" "$tmp/ga.png"
draw "$novelty" "$plain" 0 "novelty search, $(dirname "$novelty" | xargs basename): forward share $(forward "$novelty")" "$tmp/novelty.png"
montage "$tmp/ga.png" "$tmp/novelty.png" -tile 2x1 -geometry +8+0 "$tmp/champions.png"
convert "$tmp/champions.png" -resize '1100x1100>' -colors 64 "PNG8:$out/search-champions.png"

# The MAP-Elites archive of seed 1 and three elites' paths.
me=$RUNS/foraging-plain-map-elites/seed-1
"$bin" plot "$me" -o "$tmp/me.svg" >/dev/null
rsvg-convert -w 700 "$tmp/me-archive.svg" -o "$tmp/archive.png"
i=0
for column in 0 5 9; do
  cell=$(python3 - "$me/archive.csv" "$column" <<'PY'
import csv, sys
rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["cell_forward_share"] == sys.argv[2]]
best = max(rows, key=lambda r: float(r["fitness"]))
print(f'{best["cell_forward_share"]},{best["cell_path_length"]} {float(best["forward_share"]):.2f} {float(best["path_length"]):.0f} {best["fitness"]}')
PY
)
  read -r at share length fitness <<< "$cell"
  "$bin" extract "$me" --cell "$at" -o "$tmp/elite-$i.json" >/dev/null
  draw "$tmp/elite-$i.json" "$plain" 0 "cell $at: forward share $share, path $length LU, training $fitness" "$tmp/elite-$i.png"
  i=$((i + 1))
done
montage "$tmp/elite-0.png" "$tmp/elite-1.png" "$tmp/elite-2.png" -tile 3x1 -geometry +6+0 "$tmp/elites.png"
convert "$tmp/archive.png" -background white -flatten "$tmp/archive-flat.png"
convert "$tmp/elites.png" -background white -flatten -resize '1200x>' "$tmp/elites-flat.png"
convert "$tmp/archive-flat.png" "$tmp/elites-flat.png" -background white -gravity center -append \
  +repage -colors 64 "PNG8:$out/map-elites-archive.png"

# predator-arena without its beacon: each search's median champion on held-out trial 1.
pa=experiments/search/predator-arena-no-beacon.toml
frames=()
for file in "$pa" experiments/search/predator-arena-no-beacon-novelty.toml experiments/search/predator-arena-no-beacon-map-elites.toml; do
  name=$(basename "$file" .toml)
  ls "$RUNS/$name"/seed-*/best.json >/dev/null 2>&1 || continue
  champion=$(median_seed "$file")
  algorithm=${name#predator-arena-no-beacon}
  algorithm=${algorithm#-}
  draw "$champion" "$pa" 1 "${algorithm:-ga}, $(dirname "$champion" | xargs basename)" "$tmp/pa-$name.png"
  frames+=("$tmp/pa-$name.png")
done
if [ ${#frames[@]} -gt 0 ]; then
  montage "${frames[@]}" -tile "${#frames[@]}x1" -geometry +6+0 "$tmp/pa.png"
  convert "$tmp/pa.png" -resize '1200x1200>' -colors 64 "PNG8:$out/predator-no-beacon-champions.png"
fi
ls -l "$out"/search-champions.png "$out"/map-elites-archive.png "$out"/predator-no-beacon-champions.png 2>/dev/null
