"""An independent reference for homogeneous fog lit by spots, points or a parallel light: a light
tracer, sharing no code with brume or Mitsuba, with a quadrature of single scattering to check it
(single_scatter.py for spots; tests/python/test_light_trace.py for the parallel light).

    python tools/compare/light_trace.py SCENE --photons 3e8 --renders 2 --seed 1 --out DIR [--orders] [--set K=V]

Photons leave each light with its profile (brume's: a cone whose intensity falls linearly in
cos(theta) over the soft edge; a directional light's photons leave a square upstream of every
shape, uniformly, carrying the irradiance times its area), fly through the fog box (free-flight
distances), scatter (Henyey-Greenstein) and bounce off Lambertian quads; every collision and
every surface hit is connected to the camera (a pinhole, or an orthographic camera that sees each
point along its axis) and added to the pixel that sees it (box filter, as brume's pixels are the
mean radiance over their rectangle on the image plane). Each film bin is traced with its own
coefficients (a grey problem; bins that share them are traced once unless a quad is textured),
and the bins are summed as brume's film sums them:
X, Y, Z = sum over bins of L_b * (integral of the CIE 1931 function over the bin) / (integral
of y-bar over its table), with each light's power split over the bins by its spectrum's bin
averages. So the images are in brume's radiometric units (scale 1), as linear Rec.709 (brume's
default colour space; other `film.colour_space` values are refused).

A quad's `texture` (a PNG, sRGB-encoded, multiplying `albedo`) is upsampled here from the
definition of Jakob & Hanika 2019 (trace_spectra.py's `jakob_hanika`: a sigmoid of a quadratic,
fitted to each distinct texel colour under D65), averaged over each film bin, and looked up
bilinearly as brume's documentation says; brume and Mitsuba fit the same family with their own
code.

Writes reference-K.exr (K independent renders of seeds SEED + K: two of them are a reference's
halves for `protocol.py --reference files`; `column_ratio.py` reads them too),
and with --orders reference-K-orders.npz: the Y image of single scattering (order 1), of double
scattering in the fog (order 2) and of everything else (3: more scatterings, or any surface).

The scene may hold: a perspective or orthographic camera; one axis-aligned `box` (translate
only) whose `interior` medium is homogeneous (sigma_s, sigma_a as numbers, `power_law` or
`constant` spectra, or CSV `file` spectra; g); `quad`s with `lambert` materials (a constant
albedo, optionally times a PNG texture); `spot` and `point` lights with radiometric `power`,
`directional` lights with radiometric `irradiance`, each with a named spectrum (a [spectra]
entry or a built-in illuminant such as "D65"). Anything else is refused, naming the key.
"""
from __future__ import annotations

import argparse
import math
import sys
import tomllib
from dataclasses import dataclass
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from trace_spectra import (  # noqa: E402  (the tracer's spectra: its own module)
    Refused,
    bin_edges,
    spectrum,
    upsampled_texture,
    xyz_to_rec709,
    xyz_weights,
)


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
    # Orthographic: the viewed rectangle's size (m); None for a pinhole.
    view: tuple[float, float] | None = None

    @property
    def pixel_area(self) -> float:
        """Area of a pixel on an orthographic camera's plane (m^2)."""
        return (self.view[0] / self.w) * (self.view[1] / self.h)

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
    # A texture multiplying `albedo`: per film bin, the reflectance of each texel (bins, H, W),
    # row 0 at the image's top; looked up bilinearly, tiling the plane, v = 0 at the bottom row
    # (brume's documented lookup), at uv = (x / size_x + 1/2, y / size_y + 1/2) in the quad's
    # own axes.
    texture: np.ndarray | None = None

    def reflectance(self, b: int, x: np.ndarray) -> np.ndarray:
        """The albedo in film bin b at the points x on the quad."""
        if self.texture is None:
            return np.full(len(x), self.albedo)
        tex = self.texture[b]
        h, w = tex.shape
        rel = x - self.centre
        fu = ((rel @ self.u) / (2 * self.half[0]) + 0.5) * w - 0.5
        fv = (1 - ((rel @ self.v) / (2 * self.half[1]) + 0.5)) * h - 0.5
        x0, y0 = np.floor(fu), np.floor(fv)
        tx, ty = fu - x0, fv - y0
        xa, xb = x0.astype(np.int64) % w, (x0.astype(np.int64) + 1) % w
        ya, yb = y0.astype(np.int64) % h, (y0.astype(np.int64) + 1) % h
        val = ((1 - tx) * (1 - ty) * tex[ya, xa] + tx * (1 - ty) * tex[ya, xb]
               + (1 - tx) * ty * tex[yb, xa] + tx * ty * tex[yb, xb])
        return self.albedo * val

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
    # A directional light: its travel direction, and the square (centre, two half-edge vectors)
    # upstream of the scene that its photons leave, perpendicular to it; `power` is then the
    # irradiance times that square's area.
    parallel: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray] | None = None

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


def parallel_light(d: np.ndarray, per_nm: np.ndarray, box: Box | None, quads: list[Quad]) -> Light:
    """A directional light whose photons leave a square perpendicular to d, upstream of every
    shape and wide enough that each ray towards a shape starts on it."""
    pts = [] if box is None else [np.array([x, y, z]) for x in (box.lo[0], box.hi[0])
                                   for y in (box.lo[1], box.hi[1]) for z in (box.lo[2], box.hi[2])]
    for q in quads:
        pts += [q.centre + a * q.half[0] * q.u + b * q.half[1] * q.v for a in (-1, 1) for b in (-1, 1)]
    pts = np.array(pts)
    centre = 0.5 * (pts.min(0) + pts.max(0))
    r = float(np.linalg.norm(pts - centre, axis=1).max()) * 1.01
    t = _basis(np.cross(d, [1.0, 0, 0] if abs(d[0]) < 0.9 else [0, 1.0, 0]))
    b = np.cross(d, t)
    return Light(centre - d * (r + 1.0), d, 1.0, 1.0, per_nm * (2 * r) ** 2, (centre - d * (r + 1.0), d, r * t, r * b))


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


def load(path: Path, sets: list[str] = ()) -> Scene:
    """The scene, with `sets` (KEY=VALUE, TOML values) applied as the protocol's --set does."""
    try:
        desc = tomllib.loads(Path(path).read_text())
    except OSError as e:
        raise Refused(f"cannot read it: {e.strerror}") from e
    except tomllib.TOMLDecodeError as e:
        raise Refused(f"not valid TOML: {e}") from e
    if sets:
        from protocol_scene import apply_set, parse_value

        for s in sets:
            key, _, val = s.partition("=")
            apply_set(desc, key, parse_value(val))
    film = desc.get("film", {})
    if (film.get("colour_space", "srgb"), film.get("units", "radiometric"), str(film.get("observer", "1931"))) != (
            "srgb", "radiometric", "1931"):
        raise Refused("film: only the default colour_space (srgb), units (radiometric) and observer (1931)")
    edges = bin_edges(film)
    cam = desc.get("camera", {})
    kind = cam.get("type", "perspective")
    if kind not in ("perspective", "orthographic"):
        raise Refused("camera.type: only perspective and orthographic")
    pos = np.array(cam.get("position", [0.0, 0.0, 5.0]), float)
    fwd = _basis(np.array(cam.get("look_at", [0.0, 0.0, 0.0]), float) - pos)
    right = _basis(np.cross(fwd, cam.get("up", [0.0, 1.0, 0.0])))
    view = (float(cam.get("view_width", 1.0)), float(cam.get("view_height", 1.0))) if kind == "orthographic" else None
    camera = Camera(pos, fwd, right, np.cross(right, fwd), math.tan(math.radians(cam.get("fov", 40.0)) / 2),
                    int(cam.get("width", 256)), int(cam.get("height", 256)), view)
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
            if mat.get("type") != "lambert" or not isinstance(mat.get("albedo", 1.0), (int, float)):
                raise Refused(f"materials.{s['material']}: only lambert with a constant albedo")
            if "albedo" not in mat and "texture" not in mat:
                raise Refused(f"materials.{s['material']}: `albedo` is missing")
            texture = None
            if "texture" in mat:
                if not isinstance(mat["texture"], str) or not mat["texture"].lower().endswith(".png"):
                    raise Refused(f"materials.{s['material']}.texture: only a PNG file name (sRGB, tiled)")
                texture = upsampled_texture(Path(path).parent / mat["texture"], edges)
            R = rotation(t.get("rotate", [0, 0, 0]))
            sx, sy = s.get("size", [1, 1])
            quads.append(Quad(np.array(t.get("translate", [0, 0, 0]), float), R[:, 2], R[:, 0], R[:, 1],
                              (sx / 2, sy / 2), float(mat.get("albedo", 1.0)), texture))
        else:
            raise Refused(f"shapes[{i}].type: {kind!r} (only box and quad)")
    if len(boxes) != 1:
        raise Refused("shapes: exactly one fog box")
    lights = []
    for i, li in enumerate(desc.get("lights", [])):
        kind = _need(li, "type", f"lights[{i}]")
        given = "irradiance" if kind == "directional" else "power"
        if kind not in ("spot", "point", "directional") or given not in li or "profile" in li:
            raise Refused(f"lights[{i}]: only spot and point lights given a `power` and directional lights "
                          "given an `irradiance`, without a profile")
        sp = spectrum(li.get("spectrum", "D65"), desc, Path(path).parent, edges, f"lights[{i}].spectrum")
        per_nm = li[given] * sp / float(np.sum(sp * np.diff(edges)))
        if kind == "directional":
            lights.append(parallel_light(_basis(_need(li, "direction", f"lights[{i}]")), per_nm, boxes[0] if boxes else None, quads))
        elif kind == "spot":
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


def emit(rng, light: Light, n: int) -> tuple[np.ndarray, np.ndarray]:
    """n photons' origins and directions: from a point with density light.profile (rejection
    from the cone's cosine range), or uniformly over a directional light's square."""
    if light.parallel is not None:
        c, d, t, b = light.parallel
        u, v = rng.uniform(-1, 1, n), rng.uniform(-1, 1, n)
        return c + np.outer(u, t) + np.outer(v, b), np.tile(d, (n, 1))
    return np.tile(light.pos, (n, 1)), emit_directions(rng, light, n)


def emit_directions(rng, light: Light, n: int) -> np.ndarray:
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
        if cam.view is not None:
            return self.visible_orthographic(x)
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

    def visible_orthographic(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """As `visible`, for an orthographic camera: a point is seen along -fwd by the pixel its
        projection falls in; a unit of power there (per unit area of the film's plane, times the
        area that the pixel's rays sweep through the point's volume) is 1 / the pixel's area."""
        cam, box = self.s.camera, self.s.box
        rel = x - cam.pos
        z = rel @ cam.fwd
        px = np.floor(((rel @ cam.right) / (0.5 * cam.view[0]) + 1) * 0.5 * cam.w)
        py = np.floor((1 - (rel @ cam.up) / (0.5 * cam.view[1])) * 0.5 * cam.h)
        ok = (z > 0) & (px >= 0) & (px < cam.w) & (py >= 0) & (py < cam.h)
        to_cam = np.tile(-cam.fwd, (len(x), 1))
        for q in self.s.quads:
            ok &= q.hit(x, to_cam) >= z * (1 - 1e-6)
        tn, tf = box.interval(x, to_cam)
        inside = np.clip(np.minimum(tf, z) - tn, 0.0, None)
        weight = np.exp(-self.sigma_t * inside) / cam.pixel_area
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
        o, d = emit(rng, light, m)
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
                alb = q.reflectance(b, x)
                film.add(np.full(len(x), 2), idx, ok, wq * alb / math.pi * np.maximum(cos_x, 0) * tw)
                u = rng.random(len(x))
                nd = _around(side, np.sqrt(1 - u), 2 * math.pi * rng.random(len(x)))
                nxt_o.append(x), nxt_d.append(nd), nxt_w.append(wq * alb), nxt_c.append(np.full(len(x), 2))
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
    # Bins with the same fog coefficients are one grey problem when no quad is textured (the
    # other quads' albedos do not vary over bins): traced once, with their weights summed.
    textured = any(q.texture is not None for q in scene.quads)
    jobs = []
    for li, light in enumerate(scene.lights):
        first: dict[tuple, int] = {}
        for b in range(cw.shape[1]):
            key = (float(scene.box.sigma_s[b]), float(scene.box.sigma_a[b])) + ((b,) if textured else ())
            if key in first:
                j = first[key]
                jobs[j] = (li, jobs[j][1], jobs[j][2] + light.power[b] * cw[:, b])
            else:
                first[key] = len(jobs)
                jobs.append((li, b, light.power[b] * cw[:, b]))
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
    ap.add_argument("--set", action="append", default=[], help="KEY=VALUE edit of the scene, as protocol.py's --set (repeatable)")
    a = ap.parse_args()
    from compare import write_rgb

    try:
        scene = load(a.scene, a.set)
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
