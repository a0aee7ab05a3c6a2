"""The package against the CLI: same seed, same bytes; spectral sums to XYZ; sensors; info."""

import csv
import json
import math

import numpy as np
import pytest

import brume
from conftest import LAMP, SCENE, SMALL, cli_sets


@pytest.fixture(scope="module")
def small():
    return brume.load(SCENE, set=SMALL)


def test_exr_png_and_film_are_byte_identical_to_the_cli(small, cli, tmp_path):
    result = small.render(passes=3, seed=5, progress=False)
    for ext in ("exr", "png", "brume"):
        result.save(tmp_path / f"py.{ext}")
    cli("render", SCENE, *cli_sets(SMALL), "--passes", 3, "--seed", 5, "-q",
        "-o", tmp_path / "cli.exr", "-o", tmp_path / "cli.png", "-o", tmp_path / "cli.brume")
    for ext in ("exr", "png", "brume"):
        py, c = (tmp_path / f"py.{ext}").read_bytes(), (tmp_path / f"cli.{ext}").read_bytes()
        assert py == c, f".{ext} differs between Python and the CLI"


def test_the_image_is_the_same_bits_whatever_the_thread_count(small):
    a = small.render(passes=2, seed=2, threads=1, progress=False)
    b = small.render(passes=2, seed=2, threads=2, progress=False)
    assert a.spectral.tobytes() == b.spectral.tobytes()


def cie_weights(result):
    """The CIE 1931 bin integrals of colour-science's 1 nm table over brume's bins, divided by
    the integral of y-bar: the piecewise-linear table integrated exactly with numpy."""
    import colour

    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
    lam, tab = cmfs.wavelengths, cmfs.values
    y_integral = np.trapezoid(tab[:, 1], lam) if hasattr(np, "trapezoid") else np.trapz(tab[:, 1], lam)
    edges = result.bin_edges
    w = np.zeros((len(edges) - 1, 3))
    for i, (a, b) in enumerate(zip(edges[:-1], edges[1:])):
        x = np.concatenate(([a], lam[(lam > a) & (lam < b)], [b]))
        for c in range(3):
            y = np.interp(x, lam, tab[:, c])
            w[i, c] = np.sum((y[1:] + y[:-1]) * np.diff(x)) / 2
    return w / y_integral


def test_spectral_summed_with_the_cie_tables_is_xyz(small):
    result = small.render(passes=2, seed=1, progress=False)
    assert result.spectral.shape == (12, 24, 32) and result.xyz.shape == (12, 24, 3)
    xyz = result.spectral.astype(np.float64) @ cie_weights(result)
    scale = np.abs(result.xyz).max()
    # float32 sums of 32 terms: a few units in the last place of the largest value.
    np.testing.assert_allclose(result.xyz, xyz, rtol=0, atol=1e-5 * scale)
    assert scale > 0


def rust_e(v):
    """`v` as Rust's `format!("{v:.6e}")` writes it: `2.461506e0`, `1.5e-3` as `1.500000e-3`."""
    mantissa, exponent = f"{v:.6e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def test_sensors_equal_the_cli_csv(cli, tmp_path):
    result = brume.load(LAMP).render(passes=3, seed=4, progress=False)
    cli("render", LAMP, "--passes", 3, "--seed", 4, "-q", "-o", tmp_path / "lamp.exr")
    rows = list(csv.DictReader(open(tmp_path / "lamp.sensors.csv")))
    assert [r["name"] for r in rows] == [s["name"] for s in result.sensors] == ["road", "veil"]
    for r, s in zip(rows, result.sensors):
        # The CSV prints 7 significant digits (Rust's `{:.6e}`); every digit agrees.
        assert r["value"] == rust_e(s["value"]) and r["std_error"] == rust_e(s["std_error"])
        assert [r["ci95_low"], r["ci95_high"]] == [rust_e(v) for v in s["ci95"]]
        assert r["unit"] == s["unit"] and int(r["passes"]) == s["passes"] == 3
    # The JSON beside it holds the same readings in full.
    assert json.loads((tmp_path / "lamp.sensors.json").read_text())["sensors"] == result.sensors


def test_info_is_what_brume_info_json_prints(small, cli):
    ours = small.info()
    theirs = json.loads(cli("info", SCENE, *cli_sets(SMALL), "--json").stdout)
    assert ours == theirs
    assert ours["bins"] == 32 and len(ours["bin_edges"]) == 33
    fog = ours["media"]["fog"]
    # sigma_s = 0.5 (lambda / 550)^-4 /m, no absorption: visibility ln(20) / sigma_t per bin.
    assert all(math.isclose(v, math.log(20) / s, rel_tol=1e-5)
               for v, s in zip(fog["visibility"], fog["sigma_t"]))


def test_with_set_sweeps_and_the_result_holds_its_arrays(small):
    grey = small.with_set({"spectra.rayleigh.power_law.p": 0.0})
    assert grey.sets[-1] == "spectra.rayleigh.power_law.p=0.0"
    r = grey.render(passes=2, seed=1, progress=False)
    assert set(r.layers) == {"medium", "surface"}
    assert r.stderr.shape == r.spectral.shape and r.rgb.shape == (12, 24, 3)
    assert r.wavelengths.shape == (32,) and r.passes == 2 and r.settings["seed"] == 1
    assert r.settings["forward_rays"] == 2000
    # No radius for scattered light set or chosen: the radius.
    assert r.settings["radius_indirect"] == r.settings["radius"]
    twice = grey.with_set({"integrator.radius_indirect": 2 * r.settings["radius"]})
    assert twice.render(passes=1, seed=1, progress=False).settings["radius_indirect"] == pytest.approx(
        2 * r.settings["radius"], rel=1e-6)
    assert np.isfinite(r.luminance).all() and r.luminance.mean() > 0
    # The layers add up to the image.
    total = r.layers["medium"] + r.layers["surface"]
    np.testing.assert_allclose(total, r.spectral, rtol=1e-5, atol=1e-7)


def test_toml_text_loads_like_a_file(cli):
    text = SCENE.read_text()
    a = brume.load(text, set=SMALL).render(passes=1, seed=3, progress=False)
    b = brume.load(SCENE, set=SMALL).render(passes=1, seed=3, progress=False)
    assert a.spectral.tobytes() == b.spectral.tobytes()


def test_merge_of_pass_ranges_is_the_single_render(small, tmp_path):
    whole = small.render(passes=4, seed=9, progress=False)
    parts = [small.render(pass_range=r, seed=9, progress=False) for r in [(2, 4), (0, 1), (1, 2)]]
    parts[0].save(tmp_path / "p.brume")
    merged = brume.merge([tmp_path / "p.brume", parts[1], parts[2]])
    assert merged.passes == 4 and merged.first_pass == 0
    whole.save(tmp_path / "whole.brume")
    merged.save(tmp_path / "merged.brume")
    assert (tmp_path / "whole.brume").read_bytes() == (tmp_path / "merged.brume").read_bytes()
    again = brume.read_film(tmp_path / "merged.brume")
    assert again.spectral.tobytes() == whole.spectral.tobytes()


def test_spectrum_is_what_brume_spectrum_json_prints(cli):
    d65 = brume.spectrum("D65")
    assert d65 == json.loads(cli("spectrum", "D65", "--json").stdout)
    assert d65["bins"] == 32 and d65["luminous_efficacy_lm_per_w"] > 0
    line = brume.spectrum(532.0)
    assert line == json.loads(cli("spectrum", "--line", "532", "--json").stdout)
    assert line["bins"] == 34  # the band holding the line is split around a bin of its own
    assert brume.spectrum([(532.0, 1.0)]) == line


def test_help_is_useful():
    doc = brume.Scene.render.__doc__
    assert "pass_range" in doc and "KeyboardInterrupt" in doc
    assert "progress=True" in (brume.Scene.render.__text_signature__ or "")
