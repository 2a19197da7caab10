#!/usr/bin/env bash
# Compares the simulator speed of two berry-evolve binaries on this VM, whose speed drifts
# from second to second: runs A and B back to back (alternating which goes first), each on
# 1 thread, 16 worlds x 5,000 ticks of the standard world, and prints each pair's B/A speed
# ratio and their median (> 1: B is faster). The docs' "paired short runs" come from
#
#   bash scripts/paired-bench.sh OLD_BINARY target/release/berry-evolve 10
#
# Usage: scripts/paired-bench.sh BINARY_A BINARY_B [PAIRS (10)] [WORLD]
set -euo pipefail
if [ $# -lt 2 ]; then
    echo "usage: $0 BINARY_A BINARY_B [PAIRS] [WORLD]" >&2
    exit 2
fi
a=$1
b=$2
pairs=${3:-10}
world=${4:-experiments/bench/foraging-world.toml}
cd "$(dirname "$0")/.."
command -v jq >/dev/null || { echo "$0 needs jq (apt-get install jq)" >&2; exit 2; }
# The 1-thread rate from `bench --json`; for an older binary without --json, from its text.
rate() {
    local args=(bench --world "$world" --worlds 16 --ticks 5000 --generations 0 --scaling 0)
    if "$1" bench --help | grep -q -- '--json'; then
        "$1" "${args[@]}" --json 2>/dev/null | jq -r '.simulator[0].one_thread | floor'
    else
        "$1" "${args[@]}" |
            awk '/^simulator/ { for (i = 1; i <= NF; i++) if ($(i + 1) == "creature-ticks/s") print $i }'
    fi
}
ratios=()
for i in $(seq "$pairs"); do
    if ((i % 2)); then
        ra=$(rate "$a")
        rb=$(rate "$b")
    else
        rb=$(rate "$b")
        ra=$(rate "$a")
    fi
    ratio=$(awk -v x="$rb" -v y="$ra" 'BEGIN { printf "%.3f", x / y }')
    ratios+=("$ratio")
    echo "pair $i: A $ra, B $rb creature-ticks/s on 1 thread: B/A $ratio"
done
printf '%s\n' "${ratios[@]}" | sort -g | awk '{ r[NR] = $1 } END {
    m = (NR % 2) ? r[(NR + 1) / 2] : (r[NR / 2] + r[NR / 2 + 1]) / 2
    printf "median B/A over %d pairs: %.3f (%.3f to %.3f)\n", NR, m, r[1], r[NR]
}'
