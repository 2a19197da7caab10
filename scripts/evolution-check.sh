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
for seed in "${seeds[@]}"; do
  out=results/evolution-check/seed-$seed
  $bin experiments/foraging.toml --seed "$seed" --out "$out" --force --quiet
  best_ever=$(tail -n 1 "$out/fitness.csv" | cut -d, -f8)
  report=$($bin compare "$out/best.json" genomes/braitenberg-forager.json \
    --experiment experiments/foraging.toml --trials 20 --random 32)
  evolved=$(echo "$report" | grep "^$out/best.json" | awk '{print $3}')
  hand=$(echo "$report" | grep '^genomes/braitenberg-forager.json' | awk '{print $3}')
  random=$(echo "$report" | grep 'random genomes' | sed 's/.*fitness mean \([^,]*\),.*/\1/')
  printf '%-6s %-12.3f %-14s %-14s %-18s\n' "$seed" "$best_ever" "$evolved" "$hand" "$random"
done
