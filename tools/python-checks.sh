#!/usr/bin/env bash
# Runs the Python reference checks (tests/python) against a fresh build of brume and the
# colour_chart example. PROFILE=dev|release|test (default release); honours CARGO_TARGET_DIR.
set -euo pipefail
cd "$(dirname "$0")/.."
profile=${PROFILE:-release}
cargo build --profile "$profile" --bin brume --example colour_chart --example mie_check
case $profile in dev | test) sub=debug ;; *) sub=$profile ;; esac
dir=${CARGO_TARGET_DIR:-target}/$sub
[ -x .venv/bin/python ] || python3 -m venv .venv
.venv/bin/pip install -q -r tests/python/requirements.txt
BRUME_BIN=$dir/brume BRUME_COLOUR_CHART=$dir/examples/colour_chart \
    BRUME_MIE_CHECK=$dir/examples/mie_check \
    .venv/bin/python -m pytest -q tests/python "$@"
