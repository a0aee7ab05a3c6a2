"""brume's EXR and PNG output against OpenEXR, OpenColorIO and colour-science."""

import re
import subprocess
import zlib

import numpy as np
import pytest
import OpenEXR
import PyOpenColorIO as ocio
from PIL import Image

import colour
from conftest import brume_json

BINS = 16
OCIO_CONFIG = "ocio://cg-config-latest"


def chart(chart_bin, tmp_path, name, *args):
    paths = [tmp_path / f"{name}.exr", tmp_path / f"{name}.png"]
    subprocess.run([str(chart_bin), *map(str, paths), "--bins", str(BINS), *args],
                   check=True, capture_output=True, timeout=120)
    return paths


def channel(centre):
    """Fichet et al. 2021 emissive channel name: comma as the decimal separator."""
    return "S0." + f"{centre:.6f}".replace(".", ",") + "nm"


def read_exr(path):
    f = OpenEXR.File(str(path))
    return f.header(), {k: v.pixels for k, v in f.channels().items()}


def ocio_display(rgb):
    cfg = ocio.Config.CreateFromFile(OCIO_CONFIG)
    proc = cfg.getProcessor(
        "Linear Rec.709 (sRGB)", "sRGB - Display", "Un-tone-mapped",
        ocio.TRANSFORM_DIR_FORWARD,
    ).getDefaultCPUProcessor()
    flat = np.ascontiguousarray(rgb.reshape(-1, 3), dtype=np.float32)
    proc.applyRGB(flat)
    return flat.reshape(rgb.shape)


@pytest.mark.parametrize("half", [False, True])
def test_png_equals_ocio_display_of_exr(brume, chart_bin, tmp_path, half):
    exr, png = chart(chart_bin, tmp_path, "chart", *(["--half"] if half else []))
    _, ch = read_exr(exr)
    rgb = ch["RGB"].astype(np.float32)
    assert rgb.min() < -0.01 and rgb.max() > 4.0, "chart must hold out-of-gamut and HDR values"
    want = np.floor(np.clip(ocio_display(rgb), 0.0, 1.0) * 255.0 + 0.5)
    got = np.asarray(Image.open(png).convert("RGB"), dtype=np.float64)
    diff = np.abs(got - want)
    assert diff.max() <= 1.0, f"max {diff.max()} code values at {np.argwhere(diff > 1)[:5]}"


def png_chunks(path):
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    i, names = 8, []
    while i < len(data):
        n = int.from_bytes(data[i:i + 4], "big")
        names.append(data[i + 4:i + 8].decode())
        i += 12 + n
    return names


def test_png_has_srgb_chunk(brume, chart_bin, tmp_path):
    _, png = chart(chart_bin, tmp_path, "c")
    assert "sRGB" in png_chunks(png)


@pytest.mark.parametrize(
    "space,prim",
    [
        ("srgb", [0.64, 0.33, 0.30, 0.60, 0.15, 0.06, 0.3127, 0.3290]),
        ("acescg", [0.713, 0.293, 0.165, 0.830, 0.128, 0.044, 0.32168, 0.33767]),
        ("xyz", [1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1 / 3, 1 / 3]),
    ],
)
def test_exr_chromaticities_and_values(brume, chart_bin, tmp_path, space, prim):
    exr, _ = chart(chart_bin, tmp_path, space, "--space", space, "--spectral")
    header, ch = read_exr(exr)
    np.testing.assert_allclose(header["chromaticities"], prim, atol=1e-6)
    # Independent check of the pixel values: XYZ from the spectral channels with
    # colour-science's 1 nm CMFs (bin edges fall on whole nm, so the trapezoid sums are the
    # exact bin integrals), then colour-science's XYZ -> RGB with a Bradford D65 adaptation.
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
    ybar_total = np.trapezoid(cmfs.values[:, 1], dx=1.0)
    edges = np.linspace(380, 780, BINS + 1)
    centres = 0.5 * (edges[1:] + edges[:-1])
    w = np.zeros((BINS, 3))
    for i in range(BINS):
        lam = np.arange(edges[i], edges[i + 1] + 0.5, 1.0)
        w[i] = np.trapezoid(cmfs[lam], lam, axis=0)
    spec = np.stack([ch[channel(c)]
                     for c in centres], axis=-1)
    xyz = spec @ w / ybar_total
    if space == "xyz":
        want = xyz
    else:
        cs = colour.RGB_COLOURSPACES["sRGB" if space == "srgb" else "ACEScg"].copy()
        cs.use_derived_transformation_matrices(True)
        want = colour.XYZ_to_RGB(xyz, cs, illuminant=np.array([0.3127, 0.3290]),
                                 chromatic_adaptation_transform="Bradford")
    np.testing.assert_allclose(ch["RGB"], want, atol=2e-5 * max(1.0, np.abs(want).max()))


def test_spectral_layers_names_and_values(brume, chart_bin, tmp_path):
    exr, _ = chart(chart_bin, tmp_path, "s", "--spectral", "--noise")
    header, ch = read_exr(exr)
    assert header["spectralLayoutVersion"] == "1.0"
    assert header["emissiveUnits"] == "W.m^-2.sr^-1"
    names = sorted(k for k in ch if re.fullmatch(r"S0\.\d+,\d{6}nm", k))
    assert len(names) == BINS
    centres = sorted(float(n[3:-2].replace(",", ".")) for n in names)
    np.testing.assert_allclose(centres, 380 + 12.5 + 25.0 * np.arange(BINS), atol=1e-9)
    # Patch 1 (dark skin) occupies the top-left 16 x 16 pixels: radiance = reflectance bins
    # times D65 bins, with D65 scaled to Y = 1.
    refl = np.array(brume_json("spectrum", "colorchecker:1", "--illuminant", "D65",
                               "--bins", BINS)["bin_values"])
    d65 = brume_json("spectrum", "D65", "--bins", BINS)
    light = np.array(d65["bin_values"]) / d65["XYZ"][1]
    for i, c in enumerate(380 + 12.5 + 25.0 * np.arange(BINS)):
        name = channel(c)
        assert abs(ch[name][8, 8] - refl[i] * light[i]) < 1e-5 * light[i]
        # The example's noise layer is 5% of the value, bin by bin.
        assert abs(ch["noise." + name][8, 8] - 0.05 * ch[name][8, 8]) < 1e-6
    assert "noise" in ch  # the RGB standard error (OpenEXR groups noise.R/G/B as "noise")


def test_colour_science_reads_the_spectral_layout(brume, chart_bin, tmp_path):
    # colour-science's reader of the Fichet et al. layout (via OpenImageIO) must find exactly
    # the emissive S0 bins (not the noise layer's), at the bin centres, with the same values.
    from colour.io import read_spectral_image_Fichet2021

    exr, _ = chart(chart_bin, tmp_path, "cs", "--spectral", "--noise")
    comps, spec = read_spectral_image_Fichet2021(str(exr), additional_data=True)
    assert spec.is_emissive and not spec.is_polarised and not spec.is_bispectral
    assert list(comps) == ["S0"]
    wl, cube = comps["S0"]
    np.testing.assert_allclose(wl, 380 + 12.5 + 25.0 * np.arange(BINS))
    _, ch = read_exr(exr)
    for i, c in enumerate(wl):
        np.testing.assert_array_equal(cube[..., i], ch[channel(c)])
