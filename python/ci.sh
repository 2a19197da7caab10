#!/usr/bin/env bash
# The Python package's CI steps (run by .ci/run, or alone from the repository's root):
# a fresh virtual environment, the pinned test requirements (maturin included), the wheel built
# with maturin and installed, then pytest on python/tests. Needs python3 with venv (apt's
# python3-venv on Debian) and Rust; everything else comes from the package index.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! python3 -m venv --help >/dev/null 2>&1 || ! python3 -c "import ensurepip" 2>/dev/null; then
    apt-get install -y -qq python3-venv >/dev/null ||
        { apt-get update -qq && apt-get install -y -qq python3-venv >/dev/null; }
fi
venv=$(mktemp -d)/venv
python3 -m venv "$venv"
"$venv/bin/pip" install -q --upgrade pip
"$venv/bin/pip" install -q -r python/requirements-test.txt
rm -rf target/wheels
"$venv/bin/maturin" build --release -q -i "$venv/bin/python" -m python/Cargo.toml
"$venv/bin/pip" install -q --no-deps target/wheels/berry_evolve-*.whl
cargo build --release --bin berry-evolve
BERRY_EVOLVE_BIN="$PWD/target/release/berry-evolve" "$venv/bin/pytest" -q python/tests
