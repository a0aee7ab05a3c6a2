"""Writes tests/data/mie-reference.csv: droplet-ensemble cross sections from miepython.

The Rust suite (tests/medium_droplets.rs, `ensemble_matches_miepython`) compares brume's
size-averaged Lorenz-Mie extinction, scattering and asymmetry with these values, so a wrong
sum in src/medium/droplets/mie.rs fails `cargo test` and not only the Python checks.

Independent of brume: miepython solves each sphere, the size distributions are written out
here from their definitions (lognormal in r with geometric standard deviation sigma_g;
Deirmendjian's modified gamma r^alpha exp(-b r^gamma)), and the size integral is a trapezoid
rule on radii 0.005 / k apart (4x finer than brume's default step, which averages the
resonance ripple; 4000 radii at least) over the range holding all but ~1e-9 of the
cross-section weight. The
refractive index of each row is written to the file (n, k with k >= 0 absorbing), so the test
uses exactly the index solved here.

Run once (a virtualenv with miepython):
    python3 -m venv /tmp/mvenv && /tmp/mvenv/bin/pip install miepython
    /tmp/mvenv/bin/python tools/mie_reference.py > tests/data/mie-reference.csv
"""

import math
import sys
from pathlib import Path

import miepython
import numpy as np

ROOT = Path(__file__).resolve().parent.parent
DX = 0.005

# (distribution, r_eff µm, width or (alpha, gamma), wavelength nm)
CASES = [
    ("lognormal", 2.0, 1.5, 450.0),
    ("lognormal", 2.0, 1.5, 550.0),
    ("lognormal", 2.0, 1.5, 650.0),
    ("lognormal", 0.5, 2.0, 550.0),
    ("modified-gamma", 1.5, (6.0, 1.0), 550.0),
    ("modified-gamma", 1.0, (3.0, 0.5), 700.0),
    ("lognormal", 0.01, 1.01, 550.0),
    ("lognormal", 0.05, 1.05, 400.0),
]


def water_index(lam_nm):
    """n, k of liquid water (Hale & Querry 1973), linear in wavelength between table rows."""
    path = ROOT / "spectra" / "water_hale_querry_1973.csv"
    rows = [l for l in path.read_text().splitlines() if l.strip() and not l.startswith("#")][1:]
    t = np.array([[float(v) for v in r.split(",")] for r in rows])
    return float(np.interp(lam_nm, t[:, 0], t[:, 1])), float(np.interp(lam_nm, t[:, 0], t[:, 2]))


def ln_density(kind, r_eff, shape):
    """ln n(r) up to a constant, for the distribution of effective radius <r^3>/<r^2> = r_eff."""
    if kind == "lognormal":
        s = math.log(shape)
        r_g = r_eff * math.exp(-2.5 * s * s)
        return lambda r: -0.5 * (np.log(r / r_g) / s) ** 2 - np.log(r)
    alpha, gamma = shape
    # r_eff = b^(-1/gamma) Gamma((alpha + 4)/gamma) / Gamma((alpha + 3)/gamma)
    ratio = math.exp(math.lgamma((alpha + 4) / gamma) - math.lgamma((alpha + 3) / gamma))
    b = (ratio / r_eff) ** gamma
    return lambda r: alpha * np.log(r) - b * r**gamma


def radii(ln_n, k):
    """Evenly spaced radii where n(r) r^2 is above 1e-12 of its peak: DX / k apart, or 4000
    across the range when that is closer (narrow distributions of small droplets)."""
    grid = np.exp(np.linspace(math.log(1e-4), math.log(1e3), 2_000_001))
    f = ln_n(grid) + 2 * np.log(grid)
    keep = grid[f > f.max() - math.log(1e12)]
    step = min(DX / k, (keep[-1] - keep[0]) / 4000)
    return np.arange(keep[0], keep[-1], step)


def ensemble(kind, r_eff, shape, lam_nm):
    n, kk = water_index(lam_nm)
    k = 2 * math.pi / (lam_nm / 1000)
    ln_n = ln_density(kind, r_eff, shape)
    r = radii(ln_n, k)
    lw = ln_n(r)
    w = np.exp(lw - lw.max())
    w[0] *= 0.5
    w[-1] *= 0.5
    # miepython: an absorbing index has a negative imaginary part.
    qext, qsca, _, g = miepython.efficiencies_mx(complex(n, -kk), k * r)
    area = np.pi * r * r
    c_ext = np.sum(w * area * qext) / np.sum(w)
    c_sca = np.sum(w * area * qsca) / np.sum(w)
    g_mean = np.sum(w * area * qsca * g) / np.sum(w * area * qsca)
    return n, kk, float(c_ext), float(c_sca), float(g_mean), len(r)


def main():
    out = sys.stdout
    out.write(
        f"# Droplet-ensemble Lorenz-Mie cross sections (µm² per droplet) from miepython "
        f"{miepython.__version__} (numpy {np.__version__}),\n"
        f"# made by tools/mie_reference.py: trapezoid over radii {DX}/k apart, water index of "
        f"spectra/water_hale_querry_1973.csv.\n"
        "# width: lognormal sigma_g; alpha, gamma: modified gamma; k >= 0 absorbs.\n"
        "distribution,r_eff_um,width,alpha,gamma,lambda_nm,n,k,c_ext_um2,c_sca_um2,g,radii\n"
    )
    for kind, r_eff, shape, lam in CASES:
        n, kk, c_ext, c_sca, g, count = ensemble(kind, r_eff, shape, lam)
        width, (alpha, gamma) = (shape, ("", "")) if kind == "lognormal" else ("", shape)
        out.write(
            f"{kind},{r_eff},{width},{alpha},{gamma},{lam},{n!r},{kk!r},"
            f"{c_ext!r},{c_sca!r},{g!r},{count}\n"
        )


if __name__ == "__main__":
    main()
