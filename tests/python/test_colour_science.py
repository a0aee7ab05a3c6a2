"""brume's colorimetry against colour-science."""

import numpy as np
import pytest

import colour
from conftest import brume_json, run_brume
from reference import checker_errors, reference_xyz, patches

# brume's default bin count (SpectralGrid::default, `brume spectrum --bins`): chosen as the
# smallest of 8/16/32/64 that meets the acceptance bounds (docs/colour.md has the table).
DEFAULT_BINS = 32


@pytest.mark.parametrize("illuminant", ["D65", "A"])
def test_colorchecker_xyz_matches_colour_science(brume, illuminant):
    # Acceptance: mean CIEDE2000 <= 0.3 and max <= 1.0 at the default bin count.
    e = checker_errors(brume_json, DEFAULT_BINS, illuminant)
    assert e.mean() <= 0.3, f"mean dE00 {e.mean():.3f}, per patch {np.round(e, 3)}"
    assert e.max() <= 1.0, f"max dE00 {e.max():.3f}, per patch {np.round(e, 3)}"


def test_error_shrinks_with_bin_count(brume):
    # Exact bin integration converges: each doubling of the bins must cut the mean error. At
    # 64 bins what is left is interpolation (linear vs colour-science's Sprague) and range
    # (380-780 vs 360-830 nm), far below visibility.
    means = [checker_errors(brume_json, n, "D65").mean() for n in (8, 16, 32, 64)]
    assert all(a > 1.5 * b for a, b in zip(means, means[1:])), means
    assert means[-1] < 0.1, means


def test_emission_luminance_convention(brume):
    # A constant radiance of 1 has Y = 1 when the bins span the CMF table.
    d = brume_json("spectrum", "D65", "--bins", 47,
                   "--lambda-min", 360, "--lambda-max", 830)
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
    ill = colour.SDS_ILLUMINANTS["D65"].copy().align(cmfs.shape)
    ybar = cmfs.values[:, 1]
    y_ref = np.trapezoid(ill.values * ybar, dx=1.0) / np.trapezoid(ybar, dx=1.0)
    assert abs(d["XYZ"][1] - y_ref) / y_ref < 2e-3, (d["XYZ"][1], y_ref)


def test_observer_1964_matches(brume):
    for k in [1, 13, 19]:
        sd = patches()[k - 1]
        ref, white = reference_xyz(sd, "D65", "1964")
        got = brume_json("spectrum", f"colorchecker:{k}", "--illuminant", "D65",
                         "--observer", "1964", "--bins", 32)["XYZ"]
        from reference import delta_e
        assert delta_e(got, ref, white) < 0.3


def _xyz_white(xy):
    return colour.xy_to_XYZ(np.asarray(xy))


def test_matrices_match_colour_science(brume):
    m = brume_json("spectrum", "--matrices")
    # brume derives its matrices from primaries and white (as OCIO does); colour-science's sRGB
    # otherwise uses the 4-decimal matrix printed in IEC 61966-2-1, which is off by 4e-4.
    srgb = colour.RGB_COLOURSPACES["sRGB"].copy()
    srgb.use_derived_transformation_matrices(True)
    aces = colour.RGB_COLOURSPACES["ACEScg"].copy()
    aces.use_derived_transformation_matrices(True)
    np.testing.assert_allclose(m["xyz_to_srgb"], srgb.matrix_XYZ_to_RGB, atol=1e-5, rtol=0)
    np.testing.assert_allclose(m["xyz_to_acescg"], aces.matrix_XYZ_to_RGB, atol=1e-5, rtol=0)
    d65, acesw = _xyz_white(srgb.whitepoint), _xyz_white(aces.whitepoint)
    for name, cat in [("bradford", "Bradford"), ("cat02", "CAT02")]:
        ref = colour.adaptation.matrix_chromatic_adaptation_VonKries(d65, acesw, transform=cat)
        np.testing.assert_allclose(m[f"cat_{name}_d65_to_aces"], ref, atol=1e-4, rtol=0)
        # The full D65-scene XYZ -> ACEScg path equals colour-science's XYZ_to_RGB with the
        # same adaptation.
        full = aces.matrix_XYZ_to_RGB @ ref
        np.testing.assert_allclose(m[f"xyz_d65_to_acescg_{name}"], full, atol=1e-5, rtol=0)


def test_rec709_to_acescg_matches_ocio(brume):
    # brume's default adaptation (Bradford) is the one OCIO's CG config uses.
    import PyOpenColorIO as ocio

    cfg = ocio.Config.CreateFromFile("ocio://cg-config-latest")
    p = cfg.getProcessor("Linear Rec.709 (sRGB)", "ACEScg").getDefaultCPUProcessor()
    ocio_m = np.array([p.applyRGB([1.0, 0, 0]), p.applyRGB([0, 1.0, 0]),
                       p.applyRGB([0, 0, 1.0])]).T
    m = brume_json("spectrum", "--matrices")
    brume_m = np.asarray(m["xyz_d65_to_acescg_bradford"]) @ np.linalg.inv(m["xyz_to_srgb"])
    np.testing.assert_allclose(brume_m, ocio_m, atol=2e-4, rtol=0)


def test_default_bin_count_is_the_chosen_one(brume):
    d = brume_json("spectrum", "colorchecker:1", "--illuminant", "D65")
    assert d["bins"] == DEFAULT_BINS and (d["lambda_min"], d["lambda_max"]) == (380, 780)


# Spectral lines (issue 17): a line gets a narrow bin of its own, so its colour is the colour of
# its wavelength. Acceptance: within 0.002 in xy of colour-science.
LINE_SCENE = """
[film]
colour_space = "xyz"
spectral_layers = true
[camera]
type = "orthographic"
width = 8
height = 8
position = [0, 0, 2]
look_at = [0, 0, 0]
view_width = 0.5
view_height = 0.5
[integrator]
passes = 1
[[shapes]]
type = "quad"
size = [1, 1]
emit = { line = LAMBDA }
"""


def _line_xy(wavelength):
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
    return colour.XYZ_to_xy(colour.wavelength_to_XYZ(wavelength, cmfs))


@pytest.mark.parametrize("wavelength", [450.0, 532.0, 589.3, 632.8])
def test_line_spectrum_chromaticity_matches_colour_science(brume, wavelength):
    d = brume_json("spectrum", "--line", wavelength)
    want = _line_xy(wavelength)
    assert np.hypot(*(np.asarray(d["xy"]) - want)) < 0.002, (d["xy"], want)
    assert d["lines"] == [wavelength] and d["bins"] > DEFAULT_BINS


def test_rendered_532_nm_line_has_its_chromaticity(brume, tmp_path):
    # An emitting quad seen directly, rendered to a CIE XYZ EXR through the whole pipeline.
    import OpenEXR

    scene = tmp_path / "line.toml"
    scene.write_text(LINE_SCENE.replace("LAMBDA", "532.0"))
    out = tmp_path / "line.exr"
    run_brume("render", scene, "-o", out, "--quiet")
    f = OpenEXR.File(str(out))
    header, ch = f.header(), {k: v.pixels for k, v in f.channels().items()}
    xyz = np.asarray(ch["RGB"], dtype=np.float64).reshape(-1, 3).mean(axis=0)
    got = colour.XYZ_to_xy(xyz)
    want = _line_xy(532.0)
    assert np.hypot(*(got - want)) < 0.002, (got, want)
    # The line's channel is named at the line; the bin edges let a reader integrate it.
    assert "S0.532,000000nm" in ch
    edges = [float(e) for e in str(header["brumeBinEdges"]).split()]
    lo, hi = max(e for e in edges if e < 532.0), min(e for e in edges if e > 532.0)
    assert len(edges) == DEFAULT_BINS + 3 and abs(hi - lo - 0.1) < 1e-9, edges
