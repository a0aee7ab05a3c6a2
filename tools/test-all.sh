#!/usr/bin/env bash
# Runs every test brume has, from a fresh clone: formatting, clippy, the Rust test suite, the
# Python reference checks (colour-science, OpenColorIO, OpenEXR) and the Python package
# (python/: built with maturin, its pytest suite and examples) in a virtualenv under .venv that
# this script creates. Needs only Rust (cargo) and Python 3 with venv.
set -euo pipefail
cd "$(dirname "$0")/.."

echo "== python virtualenv (.venv)"
if [ ! -x .venv/bin/python ]; then
  python3 -m venv .venv
fi
.venv/bin/python -m pip install --quiet --upgrade pip
.venv/bin/python -m pip install --quiet -r tests/python/requirements.txt -r python/requirements.txt

echo "== cargo fmt --check"
cargo fmt --all -- --check

echo "== cargo clippy"
cargo clippy --all-targets -- -D warnings
# The Python package's crate is a workspace member outside the default members.
cargo clippy -p brume-python --all-targets -- -D warnings

echo "== cargo test"
cargo test

echo "== python reference checks"
PROFILE=dev bash tools/python-checks.sh

echo "== python package (python/)"
# The extension in the dev profile, installed into .venv as `pip install ./python` would: the
# dev build of the CLI above compiled brume and every dependency it shares, with the same
# features (Cargo.toml's [build-dependencies]), so this adds pyo3, numpy and the bindings only
# (26 s here, against 11.7 min for a cold build in a profile of its own; docs/python.md). Its
# tests compare with that CLI.
VIRTUAL_ENV="$PWD/.venv" .venv/bin/maturin develop --quiet -m python/Cargo.toml --profile dev
BRUME_BIN=${CARGO_TARGET_DIR:-target}/debug/brume .venv/bin/python -m pytest -q python/tests
