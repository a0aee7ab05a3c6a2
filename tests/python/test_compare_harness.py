"""The Mitsuba comparison harness (tools/compare): scene translation and the error metric.
Skipped when mitsuba is not installed (it is listed in tools/compare/requirements.txt only)."""

import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools" / "compare"))


def test_own_share_removes_reference_noise():
    import compare

    rng = np.random.default_rng(3)
    truth = np.full((64, 64, 3), 2.0)
    # Variance proportional to 1 / time: image at t = 1, reference at t_ref = 4.
    img = truth + rng.normal(0.0, 0.2, truth.shape)
    ref = truth + rng.normal(0.0, 0.1, truth.shape)
    got = np.sqrt(compare.mse(img, ref) * compare.own_share(1.0, 4.0)) / truth.mean()
    # True relative RMSE is 0.1; the estimate's relative spread over 12288 samples is ~0.6 %:
    # 5 % is a >4 sigma bound, and without the correction the result would be 0.112.
    assert abs(got - 0.1) < 0.005


def test_fog_cube_translation():
    mi = pytest.importorskip("mitsuba")
    mi.set_variant("scalar_spectral")
    import mitsuba_scene

    d = mitsuba_scene.load(ROOT / "scenes" / "fog-cube.toml", 1)
    box = d["shape0"]
    assert box["type"] == "cube" and box["bsdf"]["type"] == "null"
    med = box["interior"]
    assert med["sigma_t"] == pytest.approx(1.0) and med["albedo"] == pytest.approx(0.8)
    assert med["phase"]["g"] == pytest.approx(0.5)
    assert d["shape1"]["bsdf"]["reflectance"]["type"] == "bitmap"
    d["sensor"]["film"]["width"] = d["sensor"]["film"]["height"] = 16
    img = np.asarray(mi.render(mi.load_dict(d), spp=2))
    assert img.shape == (16, 16, 3) and np.all(np.isfinite(img)) and img.mean() > 0
