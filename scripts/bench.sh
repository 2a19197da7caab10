#!/usr/bin/env bash
# Reproduces the README's performance figures: simulator creature-ticks per second on the
# benchmark world with 1 and 2 threads, and whole generations of experiments/foraging.toml.
#
#   bash scripts/bench.sh
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
uname -m; nproc
grep -m1 'model name' /proc/cpuinfo || true
target/release/berry-evolve bench "$@"
