#!/usr/bin/env bash
# Reproduces the README's WaterWorld comparison (performance issue, target 2): whole
# generations of experiments/bench/waterworld.toml (population 256, 32 trials x 500 ticks,
# 30-pixel 360° eye, 50 items, MLP 98 -> 100 -> 2) with 1 and 2 threads, median of 3, and
# the ratio to EvoJAX 0.2.17's WaterWorld on the same machine class (44,000 agent-steps/s for
# whole generations, measured with EvoJAX's own code and settings; see the issue).
#
#   bash scripts/bench-waterworld.sh      # about 5 minutes on 2 cores
set -euo pipefail
cd "$(dirname "$0")/.."
command -v jq >/dev/null || { echo "$0 needs jq (apt-get install jq)" >&2; exit 2; }
cargo build --release --quiet
uname -m; nproc
grep -m1 'model name' /proc/cpuinfo || true
# The file computes its brains in f32, as EvoJAX does; a copy with precision = "f64" (the
# default precision) is measured the same way.
f64=$(mktemp --suffix=.toml)
trap 'rm -f "$f64"' EXIT
sed 's/^precision = "f32".*/precision = "f64"/' experiments/bench/waterworld.toml >"$f64"
for experiment in experiments/bench/waterworld.toml "$f64"; do
    precision=$(grep -m1 -o '^precision = "f[0-9]*"' "$experiment")
    echo "== $precision"
    # The text goes to the terminal (stderr), the figures come as JSON (stdout).
    rate=$(target/release/berry-evolve bench --repeat 3 --world "$experiment" \
        --ticks 2000 --scaling 0 --evolution "$experiment" --generations 1 --json "$@" |
        jq -r '.evolution.threads[] | select(.threads == 2) | .creature_ticks_per_second')
    awk -v p="$precision" -v rate="$rate" 'BEGIN {
        printf "whole generations on 2 threads (%s): %d agent-steps/s = %.1fx EvoJAX WaterWorld (44,000)\n", p, rate, rate / 44000
    }'
done
