#!/usr/bin/env bash
# Runs every test brume has, from a fresh clone: formatting, clippy, the Rust test suite, and
# the Python reference checks (colour-science, OpenColorIO, OpenEXR) in a virtualenv under
# .venv that this script creates. Needs only Rust (cargo) and Python 3 with venv.
set -euo pipefail
cd "$(dirname "$0")/.."

echo "== python virtualenv (.venv)"
if [ ! -x .venv/bin/python ]; then
  python3 -m venv .venv
fi
.venv/bin/python -m pip install --quiet --upgrade pip
.venv/bin/python -m pip install --quiet -r tests/python/requirements.txt

echo "== cargo fmt --check"
cargo fmt --all -- --check

echo "== cargo clippy"
cargo clippy --all-targets -- -D warnings

echo "== cargo test"
cargo test

echo "== python reference checks"
PROFILE=dev bash tools/python-checks.sh
