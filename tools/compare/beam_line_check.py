"""Checks the laser beam's brightness in a brume image of fog-room-laser against single scattering.

Mitsuba cannot check the beam (its volpath reaches the 2 mm beam only from path vertices inside
it, its ptracer ignores media), so this is the independent value. For a thin collimated beam of
power P, the radiance of a camera ray crossing it at distance D, integrated over the angle
perpendicular to the beam's image, is

    int L dtheta = sigma_s p(theta) exp(-sigma_t (s + D)) P / (D sin psi)

(s: distance along the beam from the laser, p: Henyey-Greenstein phase at the scattering angle,
psi: angle between the camera ray and the beam), times the linear-sRGB G of a unit radiance of the
laser's spectrum (brume's bins and CIE 1931 weights, Y of a constant 1 being 1). The image side:
for each column the beam crosses, the sum over rows within 5 px of the beam's image of
(G - the mean G 6-10 px away, which removes the multiply scattered glow) times each pixel's solid
angle, divided by the beam's angular length in that column.

Usage: python tools/compare/beam_line_check.py scenes/fog-room-laser.toml IMAGE.exr
Prints the ratio image / single scattering over all columns (1 expected; brume blurs the beam by
its integration radius, which the 5 px band contains) and its standard error across columns.
"""

from __future__ import annotations

import math
import sys
import tomllib
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))
import beam_mask  # noqa: E402
import mitsuba_scene  # noqa: E402
from compare import read_rgb  # noqa: E402

XYZ_TO_SRGB_G = (-0.969266, 1.8760108, 0.041556)


def g_of_unit_radiance(desc: dict, base: Path, light: dict) -> float:
    grid = mitsuba_scene.Grid(desc.get("film", {}))
    shape = mitsuba_scene.light_spectrum(desc, base, light.get("spectrum"), grid)
    rows = [r for r in (mitsuba_scene.REPO / "spectra/cie1931_2deg.csv").read_text().splitlines() if r[:1].isdigit()]
    t = np.array([[float(v) for v in r.split(",")[:4]] for r in rows])
    lam, cmf = t[:, 0], t[:, 1:]
    norm = np.trapezoid(cmf[:, 1], lam)
    xyz = [float(np.sum(shape * mitsuba_scene.bin_averages(lam, cmf[:, i], grid.edges) * grid.width)) / norm for i in range(3)]
    return sum(c * v for c, v in zip(XYZ_TO_SRGB_G, xyz))


def check(scene: Path, img: np.ndarray) -> tuple[float, float, float, int]:
    """(sum ratio, mean per-column ratio, its standard error, columns) for an RGB image."""
    desc = tomllib.loads(scene.read_text())
    cam = desc["camera"]
    laser = next(l for l in desc["lights"] if l["type"] == "laser")
    medium = next(iter(desc["media"].values()))
    s_s, s_t, g = medium["sigma_s"], medium["sigma_s"] + medium["sigma_a"], medium.get("g", 0.0)
    g_unit = g_of_unit_radiance(desc, scene.parent, laser)
    a = np.array(laser["position"], float)
    u = np.array(laser["direction"], float)
    u /= np.linalg.norm(u)
    length = mitsuba_scene.beam_length(a, u, desc)
    o = np.array(cam["position"], float)
    f, r, up = beam_mask._basis(cam["position"], cam["look_at"], cam.get("up", [0, 1, 0]))
    w, h = int(cam["width"]), int(cam["height"])
    tv = math.tan(math.radians(float(cam["fov"])) / 2)
    pix = 2 * tv / h

    def project(p):
        v = p - o
        z = v @ f
        return ((v @ r) / (z * tv * w / h) + 1) / 2 * w, (1 - (v @ up) / (z * tv)) / 2 * h

    img = img[..., 1]
    cols: dict[int, float] = {}
    for s in np.linspace(0.05 * length, 0.95 * length, 4000):
        c = int(project(a + u * s)[0])
        if 0 <= c < w:
            cols.setdefault(c, s)
    ratios, meas_sum, ana_sum = [], 0.0, 0.0
    rows = np.arange(h) + 0.5
    for c, s in cols.items():
        p = a + u * s
        px, py = project(p)
        px2, py2 = project(p + u * 0.05)
        slope = (py2 - py) / (px2 - px)
        dist = np.abs(rows - (py + slope * (c + 0.5 - px)))
        band, bg = dist < 5, (dist >= 6) & (dist < 10)
        if band.sum() < 8 or bg.sum() < 4:
            continue
        sx, sy = 2 * (c + 0.5) / w - 1, 1 - 2 * rows / h
        d_omega = pix * pix / (1 + (sx * tv * w / h) ** 2 + (sy * tv) ** 2) ** 1.5
        meas = np.sum((img[band, c] - img[bg, c].mean()) * d_omega[band]) / (pix * math.sqrt(1 + slope * slope))
        d = np.linalg.norm(p - o)
        cos_sc = u @ (o - p) / d
        phase = (1 - g * g) / (4 * math.pi * (1 + g * g - 2 * g * cos_sc) ** 1.5)
        sin_psi = math.sqrt(max(1 - (u @ (p - o) / d) ** 2, 0.0))
        ana = s_s * phase * math.exp(-s_t * (s + d)) * laser["power"] / (d * sin_psi) * g_unit
        ratios.append(meas / ana)
        meas_sum += meas
        ana_sum += ana
    rt = np.array(ratios)
    return meas_sum / ana_sum, float(rt.mean()), float(rt.std(ddof=1) / math.sqrt(len(rt))), len(rt)


def main() -> None:
    scene, image = Path(sys.argv[1]), Path(sys.argv[2])
    total, mean, se, n = check(scene, read_rgb(image))
    print(
        f"{image}: {n} columns; image / single scattering: sum ratio {total:.3f}, "
        f"mean per column {mean:.3f} +- {se:.3f} (1 sigma)"
    )


if __name__ == "__main__":
    main()
