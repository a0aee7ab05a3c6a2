"""Spectra for light_trace.py, from brume's documented definitions and the CIE tables in
spectra/: bin averages of a scene's spectra, the film's XYZ weights per bin, linear Rec.709, and
the upsampling of a texture's colours to reflectance spectra (Jakob & Hanika 2019's sigmoid
family, fitted here). Shares no code with brume or Mitsuba."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
SPECTRA = ROOT / "spectra"


class Refused(ValueError):
    """A scene this tracer cannot reproduce exactly."""


# ------------------------------------------------------------------------------ spectra

def read_table(path: Path) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    lines = [ln for ln in path.read_text().splitlines() if ln.strip() and not ln.startswith("#")]
    head = [h.strip() for h in lines[0].split(",")]
    rows = np.array([[float(v) for v in ln.split(",")] for ln in lines[1:]])
    return rows[:, 0], {h: rows[:, i] for i, h in enumerate(head) if i > 0}


def bin_average(x: np.ndarray, y: np.ndarray, a: float, b: float) -> float:
    """Exact average over [a, b] of the piecewise-linear table (constant beyond its ends)."""
    pts = np.unique(np.concatenate([[a, b], x[(x > a) & (x < b)]]))
    return float(np.trapezoid(np.interp(pts, x, y), pts) / (b - a))


def bin_edges(film: dict) -> np.ndarray:
    if "lines" in film:
        raise Refused("film.lines: line bins are not supported")
    return np.linspace(film.get("lambda_min", 380.0), film.get("lambda_max", 780.0), film.get("bins", 32) + 1)


def spectrum(value, desc: dict, scene_dir: Path, edges: np.ndarray, key: str) -> np.ndarray:
    """Bin averages of a spectrum given as a number, a [spectra] name or a built-in illuminant."""
    n = len(edges) - 1
    if isinstance(value, (int, float)):
        return np.full(n, float(value))
    if not isinstance(value, str):
        raise Refused(f"{key}: a number or a spectrum name")
    entry = desc.get("spectra", {}).get(value)
    if entry is None:
        path = SPECTRA / f"illuminant_{value}.csv"
        if not path.exists():
            raise Refused(f"{key}: no spectrum {value!r}")
        x, cols = read_table(path)
        y = next(iter(cols.values()))
        return np.array([bin_average(x, y, a, b) for a, b in zip(edges[:-1], edges[1:])])
    if "constant" in entry:
        return np.full(n, float(entry["constant"]))
    if "power_law" in entry:
        pl = entry["power_law"]
        k, p, lr = pl["k"], pl["p"], pl["lambda_ref"]
        out = []
        for a, b in zip(edges[:-1], edges[1:]):
            integral = lr * math.log(b / a) if abs(p - 1) < 1e-12 else lr**p * (b ** (1 - p) - a ** (1 - p)) / (1 - p)
            out.append(k * integral / (b - a))
        return np.array(out)
    if "file" in entry:
        x, cols = read_table(scene_dir / entry["file"])
        y = cols[entry["column"]] if "column" in entry else next(iter(cols.values()))
        return np.array([bin_average(x, y, a, b) for a, b in zip(edges[:-1], edges[1:])])
    raise Refused(f"spectra.{value}: only constant, power_law and file spectra")


def xyz_weights(edges: np.ndarray) -> np.ndarray:
    """(3, bins): the integral of each CIE 1931 colour-matching function over each bin, over the
    integral of y-bar over its whole table (brume's normalisation: a constant spectral radiance
    of 1 has Y = 1)."""
    x, cols = read_table(SPECTRA / "cie1931_2deg.csv")
    total = float(np.trapezoid(cols["y_bar"], x))
    return np.array([[bin_average(x, cols[c], a, b) * (b - a) for a, b in zip(edges[:-1], edges[1:])]
                     for c in ("x_bar", "y_bar", "z_bar")]) / total


def jakob_hanika(rgb: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A reflectance spectrum whose linear Rec.709 colour under D65 is `rgb` (Jakob & Hanika
    2019: a sigmoid of a quadratic in wavelength, 1/2 + x / (2 sqrt(1 + x^2))), on the CIE table's
    wavelengths (360-830 nm). Solved here by damped Newton steps on the three coefficients,
    walking from grey to the target (the continuation the paper describes); written from the
    paper's definition, sharing nothing with brume's or Mitsuba's fits."""
    lam, cmf = read_table(SPECTRA / "cie1931_2deg.csv")
    dx, dcol = read_table(SPECTRA / "illuminant_D65.csv")
    d65 = np.interp(lam, dx, next(iter(dcol.values())))
    bar = np.stack([cmf["x_bar"], cmf["y_bar"], cmf["z_bar"]])
    to_rgb = xyz_to_rec709() @ (bar * d65) / float(np.sum(bar[1] * d65))
    t = (lam - lam[0]) / (lam[-1] - lam[0])

    def spec(c):
        x = c[0] * t * t + c[1] * t + c[2]
        return 0.5 + x / (2 * np.sqrt(1 + x * x))

    c = np.zeros(3)
    grey = np.full(3, float((to_rgb @ spec(c)).mean()))
    for k in range(1, 41):
        target = grey + (np.asarray(rgb, float) - grey) * k / 40
        for _ in range(50):
            r = to_rgb @ spec(c) - target
            if np.abs(r).max() < 1e-10:
                break
            jac = np.stack([(to_rgb @ spec(c + e) - to_rgb @ spec(c - e)) / 2e-6 for e in np.eye(3) * 1e-6], axis=1)
            c = c - np.linalg.lstsq(jac, r, rcond=None)[0]
    if np.abs(to_rgb @ spec(c) - rgb).max() > 1e-6:
        raise Refused(f"texture colour {rgb}: no reflectance spectrum fits it")
    return lam, spec(c)


def upsampled_texture(path: Path, edges: np.ndarray) -> np.ndarray:
    """(bins, H, W): each texel's sRGB-encoded colour decoded to linear, upsampled
    (`jakob_hanika`) and averaged over each film bin (one fit per distinct colour)."""
    from PIL import Image

    try:
        img = np.asarray(Image.open(path).convert("RGB"))
    except OSError as e:
        raise Refused(f"texture {path}: {e}") from e
    colours, inverse = np.unique(img.reshape(-1, 3), axis=0, return_inverse=True)
    table = []
    for col in colours:
        c = col / 255.0
        lam, refl = jakob_hanika(np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4))
        table.append([bin_average(lam, refl, a, b) for a, b in zip(edges[:-1], edges[1:])])
    return np.asarray(table)[inverse.ravel()].T.reshape(len(edges) - 1, img.shape[0], img.shape[1])


def xyz_to_rec709() -> np.ndarray:
    """XYZ -> linear Rec.709 (D65 white, so no adaptation: brume's default `colour_space`),
    from the primaries' and the white's chromaticities."""
    prim = np.array([[0.64, 0.33], [0.30, 0.60], [0.15, 0.06]])
    white = np.array([0.3127, 0.3290])
    def xyz(c):
        return np.array([c[0] / c[1], 1.0, (1 - c[0] - c[1]) / c[1]])
    m = np.stack([xyz(c) for c in prim], axis=1)
    scale = np.linalg.solve(m, xyz(white))
    return np.linalg.inv(m * scale[None, :])
