#!/usr/bin/env bash
# Does evolution work? Runs experiments/foraging.toml for several seeds, then evaluates each
# run's best genome, the hand-designed Braitenberg forager and 32 random genomes on the same
# 20 held-out trial worlds (worlds no individual was selected on).
#
#   bash scripts/evolution-check.sh [seeds...]      (default seeds: 1 2 3)
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
bin=target/release/berry-evolve
seeds=("$@")
[ ${#seeds[@]} -gt 0 ] || seeds=(1 2 3)
printf '%-6s %-12s %-14s %-14s %-18s\n' seed best_ever evolved_test hand_test random_test_mean
# Both commands print one JSON document with --json (see the README's "Scripting"); python3
# reads the numbers from it.
field() { python3 -c "import json, sys; d = json.load(sys.stdin); print($1)"; }
for seed in "${seeds[@]}"; do
  out=results/evolution-check/seed-$seed
  best_ever=$($bin experiments/foraging.toml --seed "$seed" --out "$out" --force --quiet --json \
    | field 'd["best_ever"]["fitness"] if d["best_ever"] else "nan"')
  read -r evolved hand random < <($bin compare "$out/best.json" genomes/braitenberg-forager.json \
    --experiment experiments/foraging.toml --trials 20 --random 32 --json \
    | field '" ".join(["non-finite" if g["fitness"] is None else "%.4f" % g["fitness"]
                       for g in d["genomes"]] + ["%.4f" % d["random"]["fitness"]["mean"]])')
  printf '%-6s %-12.3f %-14s %-14s %-18s\n' "$seed" "$best_ever" "$evolved" "$hand" "$random"
done
