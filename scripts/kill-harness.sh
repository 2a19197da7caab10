#!/usr/bin/env bash
# The long version of tests/signals/sigkill_resume.rs: SIGKILLs real runs of tests/fixtures/slow.toml at
# seeded random moments, resumes each time, and checks every finished run is byte-identical
# to an uninterrupted one. Prints the number of kills survived.
#
#   bash scripts/kill-harness.sh            # 200 kills
#   BERRY_KILLS=1000 BERRY_KILL_SEED=7 bash scripts/kill-harness.sh
#   BERRY_KILL_MAX_DELAY_MS=80 bash scripts/kill-harness.sh   # kill sooner after each start
set -euo pipefail
cd "$(dirname "$0")/.."
export BERRY_KILLS="${BERRY_KILLS:-200}"
export BERRY_KILL_SEED="${BERRY_KILL_SEED:-2026}"
cargo test --release --quiet --test signals sigkill_resume:: -- --nocapture 2>&1 | grep -E 'survived|panicked|FAILED|failed|test result'
