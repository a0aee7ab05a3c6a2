"""Single scattering of spot and point lights in light_trace.py's scenes, by quadrature: a check
of the light tracer (and of brume) that shares neither's sampling.

Per pixel, nsub x nsub rays (midpoints of the pixel's rectangle on the image plane, brume's box
filter); along each, the box's chord is cut where it crosses the spot's cones (the profile's
kinks), and each piece is integrated by Gauss-Legendre in the equiangular angle about the light
(dt / d^2 = dtheta / h), which turns the 1/d^2 peak near the light flat. The pixel samples
must resolve the beam: 4 mm apart against a beam 2 cm wide changes nothing between nsub 8 and 16
(tests/python/test_light_trace.py's view); the 3.5 mm entry of a spot 5 cm from the fog needs
far finer ones. The quads are ignored (no occlusion, no reflection): open fog only.

    python tools/compare/single_scatter.py SCENE --nsub 32 --out DIR   # DIR/reference-0.exr

(compare it with brume at `integrator.max_depth = 1`: tools/compare/column_ratio.py DIR B).
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from light_trace import Light, Refused, Scene, hg, load, xyz_to_rec709, xyz_weights  # noqa: E402


def _cone_roots(o, d, light: Light, c: float) -> tuple[np.ndarray, np.ndarray]:
    """Distances where each ray crosses the double cone of axis cosine c about the light
    (NaN where it does not): (v.a)^2 = c^2 |v|^2 with v = o + t d - light.pos."""
    oc = o - light.pos
    da, oa = d @ light.axis, oc @ light.axis
    qa = da**2 - c * c
    qb = 2 * (da * oa - c * c * np.sum(d * oc, axis=1))
    qc = oa**2 - c * c * np.sum(oc * oc, axis=1)
    disc = qb * qb - 4 * qa * qc
    with np.errstate(divide="ignore", invalid="ignore"):
        sq = np.sqrt(np.where(disc >= 0, disc, np.nan))
        r1, r2 = (-qb - sq) / (2 * qa), (-qb + sq) / (2 * qa)
    return np.minimum(r1, r2), np.maximum(r1, r2)


def single_scatter(scene: Scene, light: Light, b: int, nsub: int = 16, nodes: int = 48) -> np.ndarray:
    """Single scattering per watt of `light` in bin b, per pixel (the module's docstring)."""
    cam, box = scene.camera, scene.box
    ss, st, g = box.sigma_s[b], box.sigma_s[b] + box.sigma_a[b], box.g
    gx, gw = np.polynomial.legendre.leggauss(nodes)
    s = (np.arange(nsub) + 0.5) / nsub
    out = np.zeros((cam.h, cam.w))
    for j in range(cam.h):
        px = np.repeat(np.arange(cam.w), nsub * nsub) + np.tile(np.repeat(s, nsub), cam.w)
        py = j + np.tile(np.tile(s, nsub), cam.w)
        d_all = cam.ray(px, py)
        o = np.tile(cam.pos, (len(d_all), 1))
        tn, tf = box.interval(o, d_all)
        live = tf > tn
        cuts = [tn[:, None], tf[:, None]]
        if light.axis is not None:
            for c in (light.c_edge, light.c_full):
                cuts += [r[:, None] for r in _cone_roots(o, d_all, light, c)]
            live &= np.isfinite(cuts[2][:, 0])  # rays that miss the cone see nothing
        total_all = np.zeros(len(d_all))
        if not live.any():
            continue
        d, tn, tf = d_all[live], tn[live], tf[live]
        t = np.concatenate(cuts, axis=1)[live]
        t = np.where(np.isnan(t), tn[:, None], np.clip(t, tn[:, None], np.maximum(tf, tn)[:, None]))
        t.sort(axis=1)
        delta = (light.pos - cam.pos) @ d.T
        h = np.maximum(np.linalg.norm(light.pos - cam.pos - delta[:, None] * d, axis=1), 1e-9)
        th = np.arctan2(t - delta[:, None], h[:, None])
        total = np.zeros(len(d))
        for k in range(t.shape[1] - 1):
            a, bb = th[:, k], th[:, k + 1]
            theta = 0.5 * (a + bb)[:, None] + 0.5 * (bb - a)[:, None] * gx[None]
            tt = delta[:, None] + h[:, None] * np.tan(theta)
            x = cam.pos + tt[..., None] * d[:, None]
            v = x - light.pos
            dist = np.linalg.norm(v, axis=-1)
            u = v / dist[..., None]
            prof = light.profile(u @ light.axis if light.axis is not None else np.ones(dist.shape))
            ltn, ltf = box.interval(np.repeat(light.pos[None], u[..., 0].size, 0), u.reshape(-1, 3))
            t_light = np.clip(np.minimum(ltf, dist.ravel()) - ltn, 0, None).reshape(dist.shape)
            f = ss * hg(np.sum(u * -d[:, None], axis=-1), g) * prof * np.exp(-st * (tt - tn[:, None]) - st * t_light)
            total += (f * gw[None]).sum(1) * 0.5 * (bb - a) / h
        total_all[live] = total
        out[j] = total_all.reshape(cam.w, nsub * nsub).mean(axis=1)
    return out


def single_scatter_xyz(scene: Scene, nsub: int = 16) -> np.ndarray:
    """XYZ (3, H, W) of single scattering from every light, in brume's units (bins of equal
    coefficients computed once)."""
    cw = xyz_weights(scene.edges)
    box = scene.box
    out = np.zeros((3, scene.camera.h, scene.camera.w))
    for light in scene.lights:
        groups: dict[tuple[float, float], list[int]] = {}
        for b in range(cw.shape[1]):
            groups.setdefault((float(box.sigma_s[b]), float(box.sigma_a[b])), []).append(b)
        for bins in groups.values():
            w = sum(light.power[b] * cw[:, b] for b in bins)
            if w.sum() > 0:
                out += w[:, None, None] * single_scatter(scene, light, bins[0], nsub)[None]
    return out


def single_scatter_y(scene: Scene, nsub: int = 16) -> np.ndarray:
    return single_scatter_xyz(scene, nsub)[1]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene", type=Path)
    ap.add_argument("--nsub", type=int, default=16, help="rays per pixel along each side")
    ap.add_argument("--out", type=Path, required=True)
    a = ap.parse_args()
    from compare import write_rgb

    try:
        scene = load(a.scene)
    except Refused as e:
        raise SystemExit(f"{a.scene}: {e}")
    a.out.mkdir(parents=True, exist_ok=True)
    xyz = single_scatter_xyz(scene, a.nsub)
    write_rgb(a.out / "reference-0.exr", np.einsum("ij,jhw->hwi", xyz_to_rec709(), xyz))
    print(f"{a.out / 'reference-0.exr'}: Y summed {xyz[1].sum():.6g}", flush=True)


if __name__ == "__main__":
    main()
