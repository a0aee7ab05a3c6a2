"""brume's photometry against colour-science: luminous efficacy of spectra and the
meteorological optical range (MOR) of a chromatic medium."""

from pathlib import Path

import numpy as np

import colour
from conftest import ROOT, brume_json, run_brume

CMFS = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]


def _v_and_grid():
    wl = np.arange(380.0, 781.0, 1.0)
    v = colour.SDS_LEFS["CIE 1924 Photopic Standard Observer"].copy()
    return wl, np.interp(wl, v.wavelengths, v.values)


def test_luminous_efficacy_matches_colour_science(brume):
    # brume: lumens per watt of power over 380-780 nm, from 64 bin averages. colour-science:
    # K_m * integral(S V) / integral(S) on 1 nm over the same range.
    wl, v = _v_and_grid()
    for name in ["D65", "A"]:
        got = brume_json("spectrum", name, "--bins", 64)["luminous_efficacy_lm_per_w"]
        sd = colour.SDS_ILLUMINANTS[name].copy().align(colour.SpectralShape(380, 780, 1))
        s = sd.values
        ref = 683.0 * np.trapezoid(s * v, wl) / np.trapezoid(s, wl)
        assert abs(got - ref) / ref < 5e-4, (name, got, ref)
        # colour-science's luminous efficacy of the same spectrum cut to 380-780 nm.
        cut = colour.luminous_efficacy(sd)
        assert abs(got - cut) / cut < 5e-4, (name, got, cut)


def _mor(sigma, wl):
    """Distance where a collimated 2700 K beam keeps 5 % of its luminous flux, by bisection."""
    bb = colour.sd_blackbody(2700, colour.SpectralShape(380, 780, 1)).values
    _, v = _v_and_grid()
    w = bb * v
    total = np.trapezoid(w, wl)

    def t(d):
        return np.trapezoid(w * np.exp(-sigma * d), wl) / total

    lo, hi = 0.0, 1.0
    while t(hi) > 0.05:
        hi *= 2.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if t(mid) > 0.05 else (lo, mid)
    return 0.5 * (lo + hi)


def _info_mor(scene, *sets):
    args = ["info", scene]
    for s in sets:
        args += ["--set", s]
    out = run_brume(*args).stdout
    line = next(l for l in out.splitlines() if "meteorological optical range" in l)
    return float(line.split(":")[1].strip().split()[0])


def test_mor_of_a_chromatic_fog_matches_colour_science(brume):
    # scenes/chromatic-fog.toml: sigma_s = 0.5 (lambda / 550)^-4 /m, no absorption. brume
    # solves the definition on its 64 bins (bin-averaged extinction, V times the blackbody
    # integrated per bin); colour-science's blackbody and V on 1 nm with the continuous law.
    scene = ROOT / "scenes" / "chromatic-fog.toml"
    got = _info_mor(scene, "film.bins=64")
    wl, _ = _v_and_grid()
    ref = _mor(0.5 * (wl / 550.0) ** -4.0, wl)
    assert abs(got - ref) / ref < 5e-4, (got, ref)
    # Not the grey formula at any single wavelength near the peak of V.
    assert abs(got - np.log(20) / 0.5) / got > 0.01


def test_mor_of_a_grey_medium_is_ln20_over_sigma(brume, tmp_path: Path):
    scene = tmp_path / "grey.toml"
    scene.write_text(
        "[camera]\ntype = \"orthographic\"\nwidth = 4\nheight = 4\nposition = [0, 0, 2]\n"
        "view_width = 1.0\nview_height = 1.0\n[media.fog]\nsigma_s = 0.07\nsigma_a = 0.01\n"
        "[[shapes]]\ntype = \"box\"\nsize = [1, 1, 1]\ninterior = \"fog\"\n"
        "[[lights]]\ntype = \"point\"\nposition = [0, 0, 0]\npower = 1.0\n"
    )
    got = _info_mor(scene)
    assert abs(got - np.log(20) / 0.08) / got < 1e-5, got
