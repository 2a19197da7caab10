#!/usr/bin/env bash
# Reproduces the README's memory figure (performance issue, target 5): the peak resident
# memory of a run with a population of 10,000 and the standard brain, two generations, a
# checkpoint after each (experiments/bench/population-10000.toml).
#
#   bash scripts/memory.sh
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
/usr/bin/time -v target/release/berry-evolve run experiments/bench/population-10000.toml \
    --out "$out/run" --quiet 2> "$out/time.txt"
grep -E 'Maximum resident set size|Elapsed' "$out/time.txt"
kb=$(awk -F': ' '/Maximum resident set size/ {print $2}' "$out/time.txt")
echo "peak memory: $((kb / 1024)) MB for a population of 10,000 (target: under 500 MB)"
ls -l "$out/run/checkpoints" | tail -n +2
