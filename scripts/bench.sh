#!/usr/bin/env bash
# Reproduces the README's performance figures (median of 3 runs each): simulator
# creature-ticks per second on both benchmark worlds with 1 and 2 threads, the scaling
# series (the bench world tiled 1, 2, 5 and 10 times in each direction), and whole
# generations of experiments/foraging.toml with the GA's share of the time.
#
#   bash scripts/bench.sh                 # about half a minute on 2 cores
#   bash scripts/bench.sh --ticks 1000    # any other `berry-evolve bench` option
#
# Run it on an otherwise idle machine: the figures are wall-clock rates.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
uname -m; nproc
grep -m1 'model name' /proc/cpuinfo || true
target/release/berry-evolve bench --repeat 3 "$@"
