#!/usr/bin/env bash
# Final equal-time comparisons with Mitsuba 3 (issue 9), both scenes, then the 60 s RMSE ratios.
# Run from the repository root on an otherwise idle machine: about 40 minutes in all
# (fog-cube ~9 min, fog-room-laser ~30 min: its Mitsuba renders use brume's floor BSDF as a
# Python plugin, 5 to 14x slower than the native-speed time Mitsuba is charged). The room's
# brume settings are the scene's (20 000 forward rays per pass since the pilots found it best).
# Environment: PYTHON (default .venv/bin/python, with tools/compare/requirements.txt),
# BRUME (default target/release/brume), OUT (default docs/images).
set -euo pipefail
PYTHON=${PYTHON:-.venv/bin/python}
BRUME=${BRUME:-target/release/brume}
OUT=${OUT:-docs/images}
HERE=$(dirname "$0")

"$PYTHON" "$HERE/compare.py" scenes/fog-cube.toml --brume "$BRUME" \
    --ref-seconds 120 --times 5 15 60 --out "$OUT/perf-fog-cube"

# The room: brume's reference is the one both renderers are measured against (Mitsuba's does not
# converge on the laser), so it gets 10x the longest ladder time. Mitsuba's own reference only
# serves the agreement check away from the beam.
"$PYTHON" "$HERE/compare.py" scenes/fog-room-laser.toml --brume "$BRUME" \
    --ref-seconds 600 --mitsuba-ref-seconds 300 --times 5 15 60 --out "$OUT/perf-room"

# Optional (LAMPS_CHECK=1, ~15 min more): the room without its laser, where Mitsuba's reference
# converges too, to check the translation and brume's lamps, floor and fog (k should be 1).
if [[ "${LAMPS_CHECK:-0}" == 1 ]]; then
    "$PYTHON" "$HERE/compare.py" scenes/fog-room-laser.toml --brume "$BRUME" --drop-light 3 \
        --ref-seconds 300 --mitsuba-ref-seconds 400 --times 15 --out "$OUT/perf-room-lamps"
fi

"$PYTHON" - "$OUT" <<'EOF'
import csv, math, sys
def rows_of(name):
    return list(csv.DictReader(open(f"{sys.argv[1]}/{name}.csv")))
for name, brume_from in (("perf-fog-cube", None), ("perf-room", None)):
    rows = rows_of(name)
    if brume_from:
        rows = [r for r in rows if r["renderer"] == "mitsuba"] + rows_of(brume_from)
        name = f"{name} (brume from {brume_from})"
    at = {r["renderer"]: r for r in rows if float(r["budget_s"]) == 60}
    # Each error rescaled to exactly 60 s with error ~ t^-1/2 (brume's --time runs whole passes).
    e = {k: float(r["rel_rmse"]) * math.sqrt(float(r["measured_s"]) / 60) for k, r in at.items()}
    e4 = {k: float(r["rel_rmse_bin4"]) * math.sqrt(float(r["measured_s"]) / 60) for k, r in at.items()}
    print(f"{name}: 60 s relative RMSE brume {e['brume']:.4g}, mitsuba {e['mitsuba']:.4g}, "
          f"ratio brume/mitsuba {e['brume'] / e['mitsuba']:.3f} "
          f"(4x4-binned: {e4['brume'] / e4['mitsuba']:.3f})")
EOF
