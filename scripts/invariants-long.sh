#!/usr/bin/env bash
# The long version of the simulator-under-load invariants (tests/sim/invariants_under_load.rs):
# many worlds with every element on, fast motors, a crowded arena.
#
#   bash scripts/invariants-long.sh            (200 worlds x 20,000 ticks)
set -euo pipefail
cd "$(dirname "$0")/.."
BERRY_LOAD_WORLDS=${BERRY_LOAD_WORLDS:-200} BERRY_LOAD_TICKS=${BERRY_LOAD_TICKS:-20000} \
  cargo test --release --test sim invariants_under_load:: -- --nocapture
