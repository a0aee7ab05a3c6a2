"""examples/python run as written, at a small size, and say what they should."""

import json
import os
import subprocess
import sys

from conftest import ROOT

EXAMPLES = ROOT / "examples" / "python"


def run(script, out):
    env = {**os.environ, "MPLBACKEND": "Agg"}
    r = subprocess.run([sys.executable, str(EXAMPLES / script), "--small", "-o", str(out)],
                       capture_output=True, text=True, timeout=600, env=env)
    assert r.returncode == 0, r.stdout + r.stderr
    return r


def test_chromatic_fog_study(tmp_path):
    run("chromatic_fog_study.py", tmp_path)
    rows = json.loads((tmp_path / "study.json").read_text())
    assert [r["angstrom_exponent"] for r in rows] == [0.0, 2.0, 4.0]
    assert (tmp_path / "study.png").stat().st_size > 0
    # A steeper power law scatters more blue: the veil's x falls as p grows.
    assert rows[0]["x"] > rows[1]["x"] > rows[2]["x"]
    # colour-science's conversion of the same spectrum agrees with brume's.
    for r in rows:
        assert abs(r["x"] - r["x_colour_science"]) < 2e-3
        assert abs(r["y"] - r["y_colour_science"]) < 2e-3


def test_lamp_fog_sensor_sweep(tmp_path):
    run("lamp_fog_sensors.py", tmp_path)
    rows = json.loads((tmp_path / "sweep.json").read_text())
    assert [r["visibility_m"] for r in rows] == [10.0, 50.0, 400.0]
    assert (tmp_path / "sweep.png").stat().st_size > 0
    for r in rows:
        # Scattered light only adds to the direct light (within 4 standard errors).
        assert r["illuminance_lx"] > r["direct_lx"] - 4 * r["std_error_lx"]
    # Clearer air, more light on the road.
    assert rows[0]["illuminance_lx"] < rows[1]["illuminance_lx"] < rows[2]["illuminance_lx"]
