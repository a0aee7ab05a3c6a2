"""An independent reference for spot- and point-lit homogeneous fog: a light tracer, sharing no
code with brume or Mitsuba, with a quadrature of single scattering to check it (single_scatter.py).

    python tools/compare/light_trace.py SCENE --photons 3e8 --renders 2 --seed 1 --out DIR [--orders]

Photons leave each light with its profile (brume's: a cone whose intensity falls linearly in
cos(theta) over the soft edge), fly through the fog box (free-flight distances), scatter
(Henyey-Greenstein) and bounce off Lambertian quads; every collision and every surface hit is
connected to the pinhole camera and added to the pixel that sees it (box filter, as brume's
pixels are the mean radiance over their rectangle on the image plane). Each film bin is traced
with its own coefficients (a grey problem), and the bins are summed as brume's film sums them:
X, Y, Z = sum over bins of L_b * (integral of the CIE 1931 function over the bin) / (integral
of y-bar over its table), with each light's power split over the bins by its spectrum's bin
averages. So the images are in brume's radiometric units (scale 1), as linear Rec.709 (brume's
default colour space; other `film.colour_space` values are refused).

Writes reference-K.exr (K independent renders of seeds SEED + K: two of them are a reference's
halves for `protocol.py --reference files`; `column_ratio.py` reads them too),
and with --orders reference-K-orders.npz: the Y image of single scattering (order 1), of double
scattering in the fog (order 2) and of everything else (3: more scatterings, or any surface).

The scene may hold: a perspective camera; one axis-aligned `box` (translate only) whose
`interior` medium is homogeneous (sigma_s, sigma_a as numbers, `power_law` or `constant`
spectra, or CSV `file` spectra; g); `quad`s with `lambert` materials (constant albedo); `spot`
and `point` lights with radiometric `power` and a named spectrum (a [spectra] entry or a
built-in illuminant such as "D65"). Anything else is refused, naming the key.
"""
from __future__ import annotations

import argparse
import math
import sys
import tomllib
from dataclasses import dataclass
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


# ------------------------------------------------------------------------------ the scene

@dataclass
class Camera:
    pos: np.ndarray
    fwd: np.ndarray
    right: np.ndarray
    up: np.ndarray
    tanv: float
    w: int
    h: int

    @property
    def plane_area(self) -> float:
        """Image-plane area of a pixel at distance 1 from the pinhole."""
        return (2 * self.tanv * self.w / self.h / self.w) * (2 * self.tanv / self.h)

    def ray(self, px: np.ndarray, py: np.ndarray) -> np.ndarray:
        sx, sy = 2 * px / self.w - 1, 1 - 2 * py / self.h
        d = self.fwd + np.outer(sx * self.tanv * self.w / self.h, self.right) + np.outer(sy * self.tanv, self.up)
        return d / np.linalg.norm(d, axis=1)[:, None]


@dataclass
class Box:
    lo: np.ndarray
    hi: np.ndarray
    sigma_s: np.ndarray
    sigma_a: np.ndarray
    g: float

    def interval(self, o: np.ndarray, d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Entry and exit distances (entry >= 0; empty where exit <= entry)."""
        with np.errstate(divide="ignore", invalid="ignore"):
            t0, t1 = (self.lo - o) / d, (self.hi - o) / d
        tn = np.nanmax(np.minimum(t0, t1), axis=1)
        tf = np.nanmin(np.maximum(t0, t1), axis=1)
        return np.maximum(tn, 0.0), tf


@dataclass
class Quad:
    centre: np.ndarray
    normal: np.ndarray
    u: np.ndarray
    v: np.ndarray
    half: tuple[float, float]
    albedo: float

    def hit(self, o: np.ndarray, d: np.ndarray) -> np.ndarray:
        """Distance to the quad along each ray (inf where missed)."""
        dn = d @ self.normal
        with np.errstate(divide="ignore", invalid="ignore"):
            t = ((self.centre - o) @ self.normal) / dn
        p = o + t[:, None] * d
        inside = (np.abs((p - self.centre) @ self.u) <= self.half[0]) & (np.abs((p - self.centre) @ self.v) <= self.half[1])
        return np.where((t > 1e-6) & inside & np.isfinite(t), t, np.inf)


@dataclass
class Light:
    pos: np.ndarray
    axis: np.ndarray | None  # None: a point light
    c_full: float
    c_edge: float
    power: np.ndarray  # W per nm in each bin

    @property
    def norm(self) -> float:
        """Solid-angle integral of the profile (sr)."""
        if self.axis is None:
            return 4 * math.pi
        return 2 * math.pi * ((1 - self.c_full) + 0.5 * (self.c_full - self.c_edge))

    def profile(self, c: np.ndarray) -> np.ndarray:
        """Intensity per watt towards directions of axis cosine c (1/sr)."""
        if self.axis is None:
            return np.full(np.shape(c), 1 / (4 * math.pi))
        if self.c_full > self.c_edge:
            ramp = np.clip((c - self.c_edge) / (self.c_full - self.c_edge), 0.0, 1.0)
        else:
            ramp = (c >= self.c_edge).astype(float)
        return ramp / self.norm


def rotation(deg) -> np.ndarray:
    """brume's Euler rotation: about world X, then Y, then Z (degrees)."""
    rx, ry, rz = (math.radians(a) for a in deg)
    X = np.array([[1, 0, 0], [0, math.cos(rx), -math.sin(rx)], [0, math.sin(rx), math.cos(rx)]])
    Y = np.array([[math.cos(ry), 0, math.sin(ry)], [0, 1, 0], [-math.sin(ry), 0, math.cos(ry)]])
    Z = np.array([[math.cos(rz), -math.sin(rz), 0], [math.sin(rz), math.cos(rz), 0], [0, 0, 1]])
    return Z @ Y @ X


def _basis(axis) -> np.ndarray:
    a = np.array(axis, float)
    return a / np.linalg.norm(a)


@dataclass
class Scene:
    camera: Camera
    box: Box
    quads: list[Quad]
    lights: list[Light]
    edges: np.ndarray
    max_depth: int


def _need(table: dict, key: str, where: str):
    """table[key], or a refusal naming where it is missing."""
    if not isinstance(table, dict) or key not in table:
        raise Refused(f"{where}: `{key}` is missing")
    return table[key]


def load(path: Path) -> Scene:
    try:
        desc = tomllib.loads(Path(path).read_text())
    except OSError as e:
        raise Refused(f"cannot read it: {e.strerror}") from e
    except tomllib.TOMLDecodeError as e:
        raise Refused(f"not valid TOML: {e}") from e
    film = desc.get("film", {})
    if (film.get("colour_space", "srgb"), film.get("units", "radiometric"), str(film.get("observer", "1931"))) != (
            "srgb", "radiometric", "1931"):
        raise Refused("film: only the default colour_space (srgb), units (radiometric) and observer (1931)")
    edges = bin_edges(film)
    cam = desc.get("camera", {})
    if cam.get("type", "perspective") != "perspective":
        raise Refused("camera.type: only perspective")
    pos = np.array(cam.get("position", [0.0, 0.0, 5.0]), float)
    fwd = _basis(np.array(cam.get("look_at", [0.0, 0.0, 0.0]), float) - pos)
    right = _basis(np.cross(fwd, cam.get("up", [0.0, 1.0, 0.0])))
    camera = Camera(pos, fwd, right, np.cross(right, fwd), math.tan(math.radians(cam.get("fov", 40.0)) / 2),
                    int(cam.get("width", 256)), int(cam.get("height", 256)))
    boxes, quads = [], []
    for i, s in enumerate(desc.get("shapes", [])):
        t = s.get("transform", {}) or {}
        if any(k not in ("rotate", "translate") for k in t) or "scale" in s:
            raise Refused(f"shapes[{i}].transform: only rotate and translate")
        kind = _need(s, "type", f"shapes[{i}]")
        if kind == "box":
            if any(abs(a) > 0 for a in t.get("rotate", [0, 0, 0])) or "material" in s:
                raise Refused(f"shapes[{i}]: only an axis-aligned, index-matched box")
            c, half = np.array(t.get("translate", [0, 0, 0]), float), np.array(s.get("size", [1, 1, 1]), float) / 2
            m = _need(desc.get("media", {}), _need(s, "interior", f"shapes[{i}]"), "media")
            if "density" in m or "phase" in m:
                raise Refused(f"media.{s['interior']}: only homogeneous Henyey-Greenstein media")
            sig = [spectrum(m.get(k, 0.0), desc, Path(path).parent, edges, f"media.{s['interior']}.{k}")
                   for k in ("sigma_s", "sigma_a")]
            boxes.append(Box(c - half, c + half, sig[0], sig[1], float(m.get("g", 0.0))))
        elif kind == "quad":
            mat = _need(desc.get("materials", {}), _need(s, "material", f"shapes[{i}]"), "materials")
            if mat.get("type") != "lambert" or not isinstance(mat.get("albedo"), (int, float)):
                raise Refused(f"materials.{s['material']}: only lambert with a constant albedo")
            R = rotation(t.get("rotate", [0, 0, 0]))
            sx, sy = s.get("size", [1, 1])
            quads.append(Quad(np.array(t.get("translate", [0, 0, 0]), float), R[:, 2], R[:, 0], R[:, 1],
                              (sx / 2, sy / 2), float(mat["albedo"])))
        else:
            raise Refused(f"shapes[{i}].type: {kind!r} (only box and quad)")
    if len(boxes) != 1:
        raise Refused("shapes: exactly one fog box")
    lights = []
    for i, li in enumerate(desc.get("lights", [])):
        if _need(li, "type", f"lights[{i}]") not in ("spot", "point") or "power" not in li or "profile" in li:
            raise Refused(f"lights[{i}]: only spot and point lights given a `power`, without a profile")
        sp = spectrum(li.get("spectrum", "D65"), desc, Path(path).parent, edges, f"lights[{i}].spectrum")
        per_nm = li["power"] * sp / float(np.sum(sp * np.diff(edges)))
        if li["type"] == "spot":
            edge = min(max(_need(li, "angle", f"lights[{i}]"), 0.01), 180.0)
            full = min(max(edge - max(li.get("soft_edge", 0.0), 0.0), 0.0), edge)
            lights.append(Light(np.array(_need(li, "position", f"lights[{i}]"), float), _basis(_need(li, "direction", f"lights[{i}]")),
                                math.cos(math.radians(full)), math.cos(math.radians(edge)), per_nm))
        else:
            lights.append(Light(np.array(_need(li, "position", f"lights[{i}]"), float), None, 1.0, -1.0, per_nm))
    if not lights:
        raise Refused("lights: none to trace (the image would be black)")
    return Scene(camera, boxes[0], quads, lights, edges, int(desc.get("integrator", {}).get("max_depth", 32)))


# ------------------------------------------------------------------------------ transport

def hg(cos: np.ndarray, g: float) -> np.ndarray:
    """Henyey-Greenstein phase function of the cosine between travel directions (1/sr)."""
    return (1 - g * g) / (4 * math.pi * (1 + g * g - 2 * g * cos) ** 1.5)


def sample_hg(rng, d: np.ndarray, g: float) -> np.ndarray:
    """New directions about the travel directions d, with density hg."""
    n = len(d)
    u = rng.random(n)
    if abs(g) < 1e-4:
        c = 1 - 2 * u
    else:
        c = (1 + g * g - ((1 - g * g) / (1 - g + 2 * g * u)) ** 2) / (2 * g)
    return _around(d, np.clip(c, -1, 1), 2 * math.pi * rng.random(n))


def _around(axis: np.ndarray, c: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """Unit vectors at cosine c from each axis, azimuth phi (any orthonormal frame)."""
    a = np.where(np.abs(axis[:, :1]) < 0.9, np.array([[1.0, 0, 0]]), np.array([[0, 1.0, 0]]))
    t = np.cross(axis, a)
    t /= np.linalg.norm(t, axis=1)[:, None]
    b = np.cross(axis, t)
    s = np.sqrt(np.maximum(0.0, 1 - c * c))
    return c[:, None] * axis + (s * np.cos(phi))[:, None] * t + (s * np.sin(phi))[:, None] * b


def emit(rng, light: Light, n: int) -> np.ndarray:
    """n directions with density light.profile (rejection from the cone's cosine range)."""
    if light.axis is None:
        return _around(np.tile([0.0, 0, 1], (n, 1)), rng.uniform(-1, 1, n), 2 * math.pi * rng.random(n))
    out = []
    while sum(len(o) for o in out) < n:
        c = light.c_edge + (1 - light.c_edge) * rng.random(2 * n)
        c = c[rng.random(2 * n) * light.profile(np.array([1.0]))[0] < light.profile(c)]
        out.append(c)
    c = np.concatenate(out)[:n]
    return _around(np.tile(light.axis, (n, 1)), c, 2 * math.pi * rng.random(n))


class Film:
    """Box-filtered pixels: a point's contribution goes to the pixel whose rectangle sees it."""

    def __init__(self, scene: Scene, sigma_t: float, classes: int):
        self.s, self.sigma_t = scene, sigma_t
        self.img = np.zeros((classes, scene.camera.h * scene.camera.w))

    def visible(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(pixel index, ok, unit direction to the camera, importance x transmittance)."""
        cam, box = self.s.camera, self.s.box
        v = cam.pos - x
        dist = np.linalg.norm(v, axis=1)
        to_cam = v / dist[:, None]
        z = -(v @ cam.fwd)
        with np.errstate(divide="ignore", invalid="ignore"):
            sx = -(v @ cam.right) / (z * cam.tanv * cam.w / cam.h)
            sy = -(v @ cam.up) / (z * cam.tanv)
            px = np.floor((sx + 1) * 0.5 * cam.w)
            py = np.floor((1 - sy) * 0.5 * cam.h)
        ok = (z > 0) & (px >= 0) & (px < cam.w) & (py >= 0) & (py < cam.h)
        for q in self.s.quads:
            ok &= q.hit(x, to_cam) >= dist * (1 - 1e-6)
        tn, tf = box.interval(x, to_cam)
        inside = np.clip(np.minimum(tf, dist) - tn, 0.0, None)
        cos_c = np.where(ok, z / dist, 1.0)
        weight = np.exp(-self.sigma_t * inside) / (cam.plane_area * dist**2 * cos_c**3)
        idx = np.where(ok, py * cam.w + px, 0).astype(np.int64)
        return idx, ok, to_cam, weight

    def add(self, cls: np.ndarray, idx: np.ndarray, ok: np.ndarray, val: np.ndarray) -> None:
        for k in range(len(self.img)):
            m = ok & (cls == k)
            if m.any():
                self.img[k] += np.bincount(idx[m], weights=val[m], minlength=self.img.shape[1])


def trace(scene: Scene, light: Light, b: int, n: int, rng, batch: int = 1_000_000) -> np.ndarray:
    """Images per watt of `light` in bin b (3 classes: order 1, order 2, the rest), n photons."""
    box = scene.box
    ss, st, g = box.sigma_s[b], box.sigma_s[b] + box.sigma_a[b], box.g
    film = Film(scene, st, 3)
    done = 0
    while done < n:
        m = min(batch, n - done)
        done += m
        d = emit(rng, light, m)
        o = np.tile(light.pos, (m, 1))
        w = np.full(m, 1.0 / n)
        cls = np.zeros(m, dtype=np.int64)  # the class of the photon's next volume collision
        for depth in range(scene.max_depth):
            if len(o) == 0:
                break
            tn, tf = box.interval(o, d)
            s = rng.exponential(1.0 / st, len(o)) if st > 0 else np.full(len(o), np.inf)
            t_coll = np.where((tf > tn) & (tn + s < tf), tn + s, np.inf)
            t_quad, which = np.full(len(o), np.inf), np.full(len(o), -1)
            for qi, q in enumerate(scene.quads):
                t = q.hit(o, d)
                nearer = t < t_quad
                t_quad, which = np.where(nearer, t, t_quad), np.where(nearer, qi, which)
            coll = t_coll < t_quad
            surf = ~coll & np.isfinite(t_quad)
            nxt_o, nxt_d, nxt_w, nxt_c = [], [], [], []
            if coll.any():
                x, din, wc, cc = o[coll] + t_coll[coll, None] * d[coll], d[coll], w[coll] * ss / st, cls[coll]
                idx, ok, to_cam, tw = film.visible(x)
                film.add(cc, idx, ok, wc * hg(np.sum(din * to_cam, axis=1), g) * tw)
                nxt_o.append(x), nxt_d.append(sample_hg(rng, din, g)), nxt_w.append(wc), nxt_c.append(np.minimum(cc + 1, 2))
            for qi, q in enumerate(scene.quads):
                h = surf & (which == qi)
                if not h.any():
                    continue
                x, din, wq = o[h] + t_quad[h, None] * d[h], d[h], w[h]
                side = np.where((din @ q.normal)[:, None] < 0, q.normal, -q.normal)  # towards the photon's origin
                idx, ok, to_cam, tw = film.visible(x)
                cos_x = np.sum(side * to_cam, axis=1)
                ok &= cos_x > 0
                film.add(np.full(len(x), 2), idx, ok, wq * q.albedo / math.pi * np.maximum(cos_x, 0) * tw)
                u = rng.random(len(x))
                nd = _around(side, np.sqrt(1 - u), 2 * math.pi * rng.random(len(x)))
                nxt_o.append(x), nxt_d.append(nd), nxt_w.append(wq * q.albedo), nxt_c.append(np.full(len(x), 2))
            if not nxt_o:
                break
            o, d, w, cls = (np.concatenate(a) for a in (nxt_o, nxt_d, nxt_w, nxt_c))
            # Russian roulette on faint photons (unbiased: survivors carry w / p).
            p = np.minimum(1.0, w * n / 0.25)
            keep = rng.random(len(w)) < p
            o, d, w, cls = o[keep], d[keep], w[keep] / p[keep], cls[keep]
    return film.img.reshape(3, scene.camera.h, scene.camera.w)


def render(scene: Scene, photons: float, seed: int) -> np.ndarray:
    """XYZ images of the three classes, (3, 3, H, W), of all lights and bins; photons spread in
    proportion to each (light, bin)'s weight in X + Y + Z, at least 1 % of an equal share each."""
    cw = xyz_weights(scene.edges)
    jobs = [(li, b, light.power[b] * cw[:, b]) for li, light in enumerate(scene.lights) for b in range(cw.shape[1])]
    total = sum(j[2].sum() for j in jobs)
    out = np.zeros((3, 3, scene.camera.h, scene.camera.w))
    rng = np.random.default_rng(seed)
    for li, b, w in jobs:
        if w.sum() <= 0:
            continue
        n = int(max(photons * w.sum() / total, 0.01 * photons / len(jobs), 1000))
        img = trace(scene, scene.lights[li], b, n, rng)
        out += w[None, :, None, None] * img[:, None]
    return out


# ------------------------------------------------------------------------------ main

def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene", type=Path)
    ap.add_argument("--photons", type=float, default=1e8, help="per render, over all lights and bins")
    ap.add_argument("--renders", type=int, default=2)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--out", type=Path, required=True)
    ap.add_argument("--orders", action="store_true", help="also write each render's classes (npz)")
    a = ap.parse_args()
    sys.path.insert(0, str(Path(__file__).parent))
    from compare import write_rgb

    try:
        scene = load(a.scene)
    except Refused as e:
        raise SystemExit(f"{a.scene}: {e}")
    a.out.mkdir(parents=True, exist_ok=True)
    for k in range(a.renders):
        xyz = render(scene, a.photons, a.seed + k)
        rgb = np.einsum("ij,jhw->hwi", xyz_to_rec709(), xyz.sum(0))
        write_rgb(a.out / f"reference-{k}.exr", rgb)
        if a.orders:
            np.savez_compressed(a.out / f"reference-{k}-orders.npz", single=xyz[0, 1], double=xyz[1, 1], rest=xyz[2, 1])
        print(f"{a.out / f'reference-{k}.exr'}: Y summed {xyz[:, 1].sum():.6g}", flush=True)


if __name__ == "__main__":
    main()
