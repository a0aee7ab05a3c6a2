"""Chromatic fog: how the colour of the fog veil follows the Angstrom exponent.

scenes/chromatic-fog.toml crosses a slab of fog with a white (D65) beam; the fog scatters
sigma_s(lambda) = k (lambda / 550 nm)^-p. This sweeps p (the Angstrom exponent: 0 is grey fog
of large droplets, 4 is Rayleigh scattering), renders each with brume, and plots the luminance
and the CIE 1931 xy chromaticity of the veil (the glowing beam near the lamp) against p. The
veil's mean spectrum is also converted to xy by colour-science, as an independent check of
brume's own spectral -> XYZ conversion.

    python examples/python/chromatic_fog_study.py -o study/           # full size
    python examples/python/chromatic_fog_study.py -o study/ --small   # what the tests run
"""

import argparse
import json
from pathlib import Path

import numpy as np

import brume

ROOT = Path(__file__).resolve().parents[2]
SCENE = ROOT / "scenes" / "chromatic-fog.toml"


def veil(result):
    """The veil's window: the beam in the fog near the lamp (rows around the beam's height,
    the first third of the slab as the camera sees it)."""
    h, w = result.luminance.shape
    return (slice(int(0.42 * h), int(0.58 * h)), slice(int(0.22 * w), int(0.40 * w)))


def colour_science_xy(spectrum, result):
    """xy of a bin-averaged spectrum by colour-science (CIE 1931 2 degree observer): the
    spectrum as a step function on a 1 nm grid, integrated against colour-science's CMFs."""
    import colour

    lam = np.arange(380, 781, dtype=float)
    bins = np.clip(np.searchsorted(result.bin_edges, lam, side="right") - 1, 0, len(spectrum) - 1)
    sd = colour.SpectralDistribution(dict(zip(lam, spectrum[bins])))
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
    xyz = colour.sd_to_XYZ(sd, cmfs=cmfs, method="Integration", shape=colour.SpectralShape(380, 780, 1))
    return colour.XYZ_to_xy(xyz)


def study(exponents, size, passes, seed):
    scene = brume.load(SCENE, set={"camera.width": size[0], "camera.height": size[1]})
    rows = []
    for p in exponents:
        result = scene.with_set({"spectra.rayleigh.power_law.p": float(p)}).render(
            passes=passes, seed=seed, progress=False)
        win = veil(result)
        xyz = result.xyz[win].reshape(-1, 3).mean(axis=0)
        x, y = xyz[0] / xyz.sum(), xyz[1] / xyz.sum()
        cs = colour_science_xy(result.spectral[win].reshape(-1, result.spectral.shape[2]).mean(axis=0), result)
        rows.append({
            "angstrom_exponent": float(p),
            "luminance_cd_m2": float(result.luminance[win].mean()),
            "x": float(x), "y": float(y),
            "x_colour_science": float(cs[0]), "y_colour_science": float(cs[1]),
        })
    return rows


def plot(rows, out):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    p = [r["angstrom_exponent"] for r in rows]
    fig, (a, b) = plt.subplots(1, 2, figsize=(9, 3.5))
    a.plot(p, [r["luminance_cd_m2"] for r in rows], "o-")
    a.set_xlabel("Angstrom exponent p")
    a.set_ylabel("veil luminance (cd/m²)")
    b.plot(p, [r["x"] for r in rows], "o-", label="x (brume)")
    b.plot(p, [r["y"] for r in rows], "s-", label="y (brume)")
    b.plot(p, [r["x_colour_science"] for r in rows], "k+", label="colour-science")
    b.plot(p, [r["y_colour_science"] for r in rows], "k+")
    b.set_xlabel("Angstrom exponent p")
    b.set_ylabel("CIE 1931 chromaticity")
    b.legend()
    fig.tight_layout()
    fig.savefig(out, dpi=100)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("-o", "--out", type=Path, default=Path("chromatic-fog-study"))
    ap.add_argument("--small", action="store_true", help="a quick run (the test suite's)")
    args = ap.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    if args.small:
        rows = study([0.0, 2.0, 4.0], (48, 24), passes=2, seed=1)
    else:
        rows = study([0.0, 1.0, 2.0, 3.0, 4.0], (256, 128), passes=8, seed=1)
    (args.out / "study.json").write_text(json.dumps(rows, indent=1))
    plot(rows, args.out / "study.png")
    for r in rows:
        print(f"p = {r['angstrom_exponent']:.1f}: veil {r['luminance_cd_m2']:.4g} cd/m², "
              f"xy ({r['x']:.4f}, {r['y']:.4f}), colour-science ({r['x_colour_science']:.4f}, "
              f"{r['y_colour_science']:.4f})")


if __name__ == "__main__":
    main()
