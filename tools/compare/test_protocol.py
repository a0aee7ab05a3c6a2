"""Checks of the protocol's pure parts (no renderer runs): the stripped [integrator], --set edits,
what is refused, and the reference-noise subtraction of the scores.

Run: /work/wt/cond-venv/bin/python tools/compare/test_protocol.py  (or pytest, if installed)
"""

from __future__ import annotations

import sys
import tomllib
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import protocol  # noqa: E402
import protocol_scene  # noqa: E402

REPO = HERE.parents[1]


def test_strip_keeps_max_depth_and_the_rest():
    text = "[film]\nbins = 8\n\n[integrator] # c\nq = 0.5\n# why\nmax_depth = 8\nradius = \"auto\"\n\n[[lights]]\ntype = \"x\"\n"
    new, kept, removed = protocol_scene.strip_integrator(text)
    d = tomllib.loads(new)
    assert d["integrator"] == {"max_depth": 8}
    assert kept == ["max_depth"] and removed == ["q", "radius"]
    assert d["film"] == {"bins": 8} and d["lights"] == [{"type": "x"}]


def test_strip_fog_cube_removes_every_tuning_key():
    new, kept, removed = protocol_scene.strip_integrator((REPO / "scenes/fog-cube.toml").read_text())
    assert "integrator" not in tomllib.loads(new) or tomllib.loads(new)["integrator"] == {}
    assert kept == [] and "radius" in removed and "expected_transmission" in removed


def test_set_edits_nested_keys_and_list_items():
    d = protocol_scene.edited_desc(REPO / "scenes/fog-cube.toml", ["media.fog.sigma_s=0.9", "lights.0.irradiance=5"])
    assert d["media"]["fog"]["sigma_s"] == 0.9 and d["lights"][0]["irradiance"] == 5


def test_refusals_and_integrator_choice():
    room = protocol_scene.edited_desc(REPO / "scenes/fog-room-laser.toml", [])
    try:
        protocol_scene.check_mappable(room, REPO / "scenes")
        raise AssertionError("a spectral line must be refused")
    except NotImplementedError as e:
        assert "lights.3" in str(e)
    cube = REPO / "tools/compare/scenes/chromatic-cube.toml"
    assert protocol_scene.spectral_media(tomllib.loads(cube.read_text()), cube.parent)
    fog = REPO / "scenes/fog-cube.toml"
    assert not protocol_scene.spectral_media(tomllib.loads(fog.read_text()), fog.parent)


def test_reference_noise_is_removed():
    """Image = truth + noise of sd s; reference halves = truth + noise of sd r each. The score must
    be s / mean(truth), not sqrt(s^2 + r^2 / 2): within 4 standard errors of the MSE estimate
    (relative sd of a mean of n squared normals: sqrt(2 / n), and of the subtracted term alike)."""
    rng = np.random.default_rng(7)
    truth = 1.0 + rng.random((128, 128, 3))
    s, r = 0.3, 0.5
    img = truth + rng.normal(0, s, truth.shape)
    a, b = (truth + rng.normal(0, r, truth.shape) for _ in range(2))
    ref = {"mean": 0.5 * (a + b), "var": float(np.mean((a - b) ** 2) / 4),
           "var_bin4": float(np.mean((protocol.bin4(a) - protocol.bin4(b)) ** 2) / 4)}
    sc = protocol.scores(img, ref, wall=4.0, budget=1.0)
    m = truth.mean()
    n = truth.size
    se = (s * s + r * r / 2) * np.sqrt(2 / n) * 2  # both estimated terms, each sqrt(2 / n) relative
    mse = (sc["rel_rmse"] * ref["mean"].mean()) ** 2
    assert abs(mse - s * s) < 4 * se, (mse, s * s, se)
    # 4x4 bins average 16 independent pixels: variance / 16, over n / 16 values.
    mse4 = (sc["rel_rmse_bin4"] * ref["mean"].mean()) ** 2
    se4 = (s * s + r * r / 2) / 16 * np.sqrt(2 * 16 / n) * 2
    assert abs(mse4 - s * s / 16) < 4 * se4, (mse4, s * s / 16, se4)
    assert abs(sc["rel_rmse_nominal"] - 2.0 * sc["rel_rmse"]) < 1e-12  # sqrt(4 s / 1 s)
    assert abs(sc["k"] - 1.0) < 0.01 and abs(m - ref["mean"].mean()) < 0.01


if __name__ == "__main__":
    for name, fn in list(globals().items()):
        if name.startswith("test_"):
            fn()
            print(f"ok {name}")
