#!/usr/bin/env bash
# Same bytes after a change to the search (evo/search/)? Runs every shipped experiment
# (experiments/*.toml, experiments/ablations/*.toml, experiments/bench/*.toml) for a few
# generations with two binaries, and compares fitness.csv, best.json, champions.jsonl and every
# checkpoint byte for byte (both binaries must carry the same version, which checkpoints
# record). Also: --jobs 1 against --jobs 2 for a few experiments, and PGPE runs stopped after 2
# generations and resumed to 4 against uninterrupted runs of 4 (tests/fixtures/tiny-pgpe.toml
# with validation and behaviour measures added, so that the centre's candidacy is exercised).
#
#   cargo build --release && cp target/release/berry-evolve /tmp/before   (before the change)
#   bash scripts/bytecmp-search.sh BEFORE_BINARY [AFTER_BINARY] [GENERATIONS]
#
# AFTER_BINARY defaults to target/release/berry-evolve, GENERATIONS to 3 (2 for the large
# bench experiments population-10000 and waterworld). Prints one line per difference and
# "all identical" at the end when there is none; exits 1 on a difference.
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -ge 1 ] || { sed -n 2,15p "$0"; exit 2; }
before=$(realpath "$1"); after=$(realpath "${2:-target/release/berry-evolve}"); gens=${3:-3}
work=$(mktemp -d /tmp/bytecmp-search.XXXXXX)
# Copies, so that a rebuild during the comparison cannot change what is compared.
cp "$before" "$work/before-bin"; cp "$after" "$work/after-bin"
before=$work/before-bin; after=$work/after-bin
status=0
differs() { echo "DIFFERS: $*"; status=1; }

# Compares two run folders file by file.
compare() {
  local a=$1 b=$2 label=$3 f rel
  for f in fitness.csv best.json champions.jsonl; do
    if [ -e "$a/$f" ] || [ -e "$b/$f" ]; then
      cmp -s "$a/$f" "$b/$f" || differs "$label: $f"
    fi
  done
  for f in "$a"/checkpoints/*.json "$b"/checkpoints/*.json; do
    [ -e "$f" ] || continue
    rel=checkpoints/$(basename "$f")
    cmp -s "$a/$rel" "$b/$rel" || differs "$label: $rel"
  done
  ls "$a/checkpoints" >/dev/null 2>&1 || differs "$label: no checkpoints in $a"
}

run() { # binary out file generations jobs
  mkdir -p "$(dirname "$2")"
  "$1" run "$3" --generations "$4" --out "$2" --quiet --no-estimate --force --jobs "$5" \
    >"$2.stdout" 2>"$2.stderr" || differs "$(basename "$2"): run failed (see $2.stderr)"
}

# experiments/ablations/x.toml -> ablations-x
label() { case "$1" in "$work"/*) echo "extra-$(basename "$1" .toml)" ;; *) echo "$(basename "$(dirname "$1")")-$(basename "$1" .toml)" ;; esac; }

# A PGPE experiment with validation and behaviour measures.
pgpe="$work/tiny-pgpe-validated.toml"
cat tests/fixtures/tiny-pgpe.toml >"$pgpe"
printf '\n[behaviour]\nmeasures = ["distinct_food"]\n\n[validation]\nevery = 2\ntop = 2\ntrials = 2\n' >>"$pgpe"

files=(experiments/*.toml experiments/ablations/*.toml experiments/bench/*.toml tests/fixtures/tiny-pgpe.toml "$pgpe")
for file in "${files[@]}"; do
  name=$(label "$file")
  g=$gens
  case "$name" in bench-population-10000|bench-waterworld) g=2 ;; esac
  run "$before" "$work/before/$name" "$file" "$g" 2
  run "$after" "$work/after/$name" "$file" "$g" 2
  compare "$work/before/$name" "$work/after/$name" "$name (before vs after)"
  echo "compared $name ($g generations)"
done

# Thread counts: --jobs 1 against the --jobs 2 runs above.
for file in experiments/foraging.toml experiments/bench/vehicle-space-pgpe.toml "$pgpe"; do
  name=$(label "$file")
  run "$after" "$work/jobs1/$name" "$file" "$gens" 1
  compare "$work/jobs1/$name" "$work/after/$name" "$name (--jobs 1 vs --jobs 2)"
  echo "compared $name --jobs 1 vs 2"
done

# Resume: 2 generations, then resume to 4, against an uninterrupted 4 (both binaries).
for file in "$pgpe" experiments/bench/vehicle-space-pgpe.toml experiments/foraging.toml; do
  name=$(label "$file")
  for bin in "$before" "$after"; do
    tag=$([ "$bin" = "$before" ] && echo before || echo after)
    run "$bin" "$work/resume-$tag/$name" "$file" 2 2
    mkdir -p "$work/resume-$tag"
    "$bin" resume "$work/resume-$tag/$name" --generations 4 --quiet --jobs 2 \
      >/dev/null 2>"$work/resume-$tag/$name.resume.stderr" || differs "$name: resume failed"
    run "$bin" "$work/whole-$tag/$name" "$file" 4 2
    compare "$work/resume-$tag/$name" "$work/whole-$tag/$name" "$name ($tag: resumed 2 -> 4 vs 4)"
  done
  compare "$work/whole-before/$name" "$work/whole-after/$name" "$name (4 generations, before vs after)"
  echo "compared $name resumed 2 -> 4 vs uninterrupted 4"
done

if [ $status = 0 ]; then echo "all identical"; rm -rf "$work"; else echo "outputs kept in $work"; fi
exit $status
