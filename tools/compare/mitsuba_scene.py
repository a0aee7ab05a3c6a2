"""Translate a brume scene TOML (the subset fog-cube and fog-room-laser use) into a Mitsuba 3 dict.

Mirrored exactly:
- Cameras: `orthographic` (position, look_at, up, view size) and `perspective` (brume's fov is the
  vertical one: Mitsuba `fov_axis = "y"`); resolution; box pixel filter in both.
- Shapes: a box of fog (`cube` with a `null` BSDF and an interior `homogeneous` medium:
  sigma_t = sigma_s + sigma_a, albedo = sigma_s / sigma_t, `hg` phase with the same g) and quads
  (`rectangle`, normal local +Z like brume's), with brume's transform order: scale, then rotate
  about world X, then Y, then Z (R = Rz Ry Rx), then translate.
- The camera and the lights get the medium of the box that contains them (Mitsuba needs to be told
  that a sensor starts inside a medium).
- Light spectra and units. brume averages every spectrum over its film bins (32 bins over
  380-780 nm here) and normalises each light's shape so that its integral over that range is 1,
  times `power` (W) or `irradiance` (W/m^2). Mitsuba gets exactly that piecewise-constant
  spectrum (an `irregular` spectrum with steps at the bin edges, zero outside the film's range),
  already scaled to brume's radiometric units. All surfaces and media here are grey, so
  Mitsuba's continuous integration of these steps against the CIE 1931 functions equals brume's
  per-bin weights, and both normalise Y so that a constant radiance of 1 has Y = 1: the two
  images should agree with a scale k = 1 (compare.py fits k and reports it as a check).
- Spot lights: brume's `power` is the total flux; Mitsuba's `intensity` is W/sr on the axis, so
  intensity = power / (solid-angle integral of brume's profile), with brume's profile (1 inside
  angle - soft_edge, falling linearly in cos(theta) to 0 at angle).
- Lambert surfaces: `diffuse` with a constant (spectrally flat) reflectance.
- Path depth: brume's integrator.max_depth (32 by default) + 1 (Mitsuba counts the camera vertex).

Approximations:
- Spot soft edge: Mitsuba's falloff is linear in the angle between beam_width and cutoff_angle,
  brume's linear in cos(theta); at mid-edge (32.5 deg of 30-35) brume gives 0.517, Mitsuba 0.5.
  Only the rim of each pool of light differs (< 2 % there).
- Laser: Mitsuba has no collimated beam of finite radius; it is a `spot` (a point source) at the
  laser's origin with a uniform cone whose radius reaches `radius` at the far wall (cutoff =
  beam_width = atan(radius / L), L = distance to the first wall along the beam), carrying the
  same power. The beam is sub-pixel in both (2 mm against ~20-30 mm per pixel) and the fog is
  thin, so the pixels see the same line flux; the beam's cross-section grows from 0 instead of
  staying 2 mm.
- Glossy floor (brume: Ashikhmin-Shirley coupled diffuse base + GGX coat with Schlick Fresnel,
  height-correlated Smith G). `floor="exact"` (default) registers a Python BSDF, `brume_glossy`,
  that evaluates brume's formulas (it is slower than a built-in BSDF: Python is called per floor
  interaction). `floor="builtin"` uses the closest built-in one, `roughplastic` (GGX, same alpha
  and IOR, diffuse_reflectance = albedo), whose diffuse term is (1 - F_i)(1 - F_o) / (eta^2
  (1 - F_dr)) instead of brume's 28 / 23 (1 - R0) edge(cos_i) edge(cos_o): about 8 % darker at
  normal incidence and up to ~60 % brighter at the grazing angles the camera sees the floor at.
- Texture (fog-cube): the PNG is decoded from sRGB to linear and multiplied by the material's
  albedo, then given as a linear float bitmap; Mitsuba upsamples RGB to spectra with Jakob-Hanika
  2019, brume with its own method, so the wall's spectra differ slightly for the same RGB.
"""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[2]


def _srgb_to_linear(c: np.ndarray) -> np.ndarray:
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def _texture(mi, path: Path, albedo: float):
    from PIL import Image

    rgb = np.asarray(Image.open(path).convert("RGB"), dtype=np.float32) / 255.0
    # brume's v = 0 is the image's bottom row; Mitsuba's bitmap puts v = 0 at the top row.
    lin = np.ascontiguousarray(np.flipud(_srgb_to_linear(rgb) * albedo), dtype=np.float32)
    return mi.Bitmap(lin, pixel_format=mi.Bitmap.PixelFormat.RGB)


def _transform(mi, t: dict | None, base_scale):
    """brume transform (scale, rotate X then Y then Z, translate) composed with the scale that
    maps Mitsuba's [-1, 1] primitives onto brume's sizes."""
    T = mi.ScalarTransform4f
    t = t or {}
    rx, ry, rz = (float(a) for a in t.get("rotate", [0, 0, 0]))
    s = np.array(t.get("scale", [1, 1, 1]), dtype=float) * np.array(base_scale, dtype=float)
    return (
        T().translate([float(x) for x in t.get("translate", [0, 0, 0])])
        @ T().rotate([0, 0, 1], rz)
        @ T().rotate([0, 1, 0], ry)
        @ T().rotate([1, 0, 0], rx)
        @ T().scale(s.tolist())
    )


def _read_table(path: Path) -> tuple[np.ndarray, np.ndarray]:
    """A brume spectrum CSV: `#` comments, a header, then wavelength and value (first column)."""
    rows = []
    header = False
    for line in path.read_text().splitlines():
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        if not header:
            header = True
            continue
        parts = line.split(",")
        rows.append((float(parts[0]), float(parts[1])))
    a = np.array(rows, dtype=float)
    return a[:, 0], a[:, 1]


_BUILTIN_SPECTRA = {
    "D65": "illuminant_D65.csv",
    "D50": "illuminant_D50.csv",
    "A": "illuminant_A.csv",
    "F2": "illuminant_F2.csv",
    "F11": "illuminant_F11.csv",
    "LED-B1": "illuminant_LED-B1.csv",
}


def bin_averages(lam: np.ndarray, val: np.ndarray, edges: np.ndarray) -> np.ndarray:
    """Exact averages over each bin of the piecewise-linear table (clamped outside it), as brume's
    `bin_averages` computes them."""
    out = np.empty(len(edges) - 1)
    for i in range(len(out)):
        a, b = edges[i], edges[i + 1]
        x = np.concatenate(([a], lam[(lam > a) & (lam < b)], [b]))
        y = np.interp(x, lam, val)
        out[i] = np.sum(0.5 * (y[1:] + y[:-1]) * np.diff(x)) / (b - a)
    return out


class Grid:
    def __init__(self, film: dict):
        self.n = int(film.get("bins", 32))
        self.lo = float(film.get("lambda_min", 380.0))
        self.hi = float(film.get("lambda_max", 780.0))
        self.edges = np.linspace(self.lo, self.hi, self.n + 1)
        self.width = (self.hi - self.lo) / self.n


def light_spectrum(desc: dict, base: Path, ref, grid: Grid) -> np.ndarray:
    """brume's per-bin shape of a light, normalised to a unit integral over the film's range."""
    ref = ref if ref is not None else "D65"
    if isinstance(ref, str) and ref in desc.get("spectra", {}):
        ref = desc["spectra"][ref]
    if isinstance(ref, dict):
        if "file" not in ref:
            raise NotImplementedError("only file spectra are translated")
        path = base / ref["file"]
    elif ref in _BUILTIN_SPECTRA:
        path = REPO / "spectra" / _BUILTIN_SPECTRA[ref]
    else:
        path = base / ref
    lam, val = _read_table(path)
    bins = bin_averages(lam, val, grid.edges)
    return bins / (bins.sum() * grid.width)


def irregular(bins: np.ndarray, grid: Grid, scale: float) -> dict:
    """Piecewise-constant spectrum over the film's bins, zero outside (Mitsuba interpolates
    linearly between the given points: each edge gets two points 1e-3 nm apart)."""
    eps = 1e-3
    lam = [grid.lo - 2 * eps]
    val = [0.0]
    for i, v in enumerate(bins):
        a, b = grid.edges[i], grid.edges[i + 1]
        lam += [a + (eps if i > 0 else 0.0), b - (eps if i < len(bins) - 1 else 0.0)]
        val += [v * scale, v * scale]
    lam.append(grid.hi + 2 * eps)
    val.append(0.0)
    return {
        "type": "irregular",
        "wavelengths": ", ".join(f"{x:.6f}" for x in lam),
        "values": ", ".join(f"{x:.9g}" for x in val),
    }


def spot_norm(angle_deg: float, soft_deg: float) -> float:
    """Solid-angle integral of brume's spot profile (sr), as src/light/spot.rs defines it."""
    edge = min(max(angle_deg, 0.01), 180.0)
    full = min(max(edge - max(soft_deg, 0.0), 0.0), edge)
    ce, cf = math.cos(math.radians(edge)), math.cos(math.radians(full))
    return 2 * math.pi * ((1 - cf) + 0.5 * (cf - ce))


def _inside_box(p, box: dict) -> bool:
    t = box.get("transform", {}) or {}
    if any(abs(a) > 0 for a in t.get("rotate", [0, 0, 0])):
        return False
    c = np.array(t.get("translate", [0, 0, 0]), dtype=float)
    h = np.array(box.get("size", [1, 1, 1]), dtype=float) * np.array(t.get("scale", [1, 1, 1])) / 2
    return bool(np.all(np.abs(np.array(p, dtype=float) - c) < h))


def beam_length(p, d, desc: dict) -> float:
    """Distance along the laser to the room's bounding box of quads (the far wall)."""
    lo = np.full(3, np.inf)
    hi = np.full(3, -np.inf)
    for s in desc.get("shapes", []):
        if s["type"] == "quad":
            c = np.array((s.get("transform") or {}).get("translate", [0, 0, 0]), dtype=float)
            lo, hi = np.minimum(lo, c), np.maximum(hi, c)
    p, d = np.array(p, dtype=float), np.array(d, dtype=float)
    d = d / np.linalg.norm(d)
    ts = [((hi if di > 0 else lo)[i] - p[i]) / di for i, di in enumerate(d) if abs(di) > 1e-9]
    ts = [t for t in ts if np.isfinite(t) and t > 0]
    return min(ts) if ts else 1.0


def _camera(mi, cam: dict, spp: int) -> dict:
    T = mi.ScalarTransform4f
    look = T().look_at(origin=cam["position"], target=cam["look_at"], up=cam.get("up", [0, 1, 0]))
    film = {
        "type": "hdrfilm",
        "width": cam["width"],
        "height": cam["height"],
        "rfilter": {"type": "box"},
        "pixel_format": "rgb",
    }
    sampler = {"type": "independent", "sample_count": spp}
    kind = cam.get("type", "perspective")
    if kind == "orthographic":
        to_world = look @ T().scale([cam["view_width"] / 2, cam["view_height"] / 2, 1])
        return {"type": "orthographic", "to_world": to_world, "film": film, "sampler": sampler}
    if kind == "perspective":
        # brume: tan_half_v = tan(fov / 2), the vertical field of view.
        return {
            "type": "perspective",
            "fov": float(cam.get("fov", 45.0)),
            "fov_axis": "y",
            "to_world": look,
            "film": film,
            "sampler": sampler,
        }
    raise NotImplementedError(f"camera type {kind}")


def _materials(mi, desc: dict, base: Path, floor: str) -> dict:
    bsdfs = {}
    for name, m in desc.get("materials", {}).items():
        kind = m.get("type", "lambert")
        albedo = float(m.get("albedo", 0.5))
        if kind == "lambert":
            if "texture" in m:
                refl = {"type": "bitmap", "bitmap": _texture(mi, base / m["texture"], albedo)}
            else:
                refl = {"type": "spectrum", "value": albedo}
            bsdfs[name] = {"type": "diffuse", "reflectance": refl}
        elif kind == "glossy":
            ior, alpha = float(m.get("ior", 1.5)), float(m.get("roughness", 0.1))
            if floor == "exact":
                import brume_glossy

                brume_glossy.register(mi)
                bsdfs[name] = {"type": "brume_glossy", "albedo": albedo, "ior": ior, "alpha": alpha}
            else:
                bsdfs[name] = {
                    "type": "roughplastic",
                    "distribution": "ggx",
                    "alpha": alpha,
                    "int_ior": ior,
                    "ext_ior": 1.0,
                    "diffuse_reflectance": {"type": "spectrum", "value": albedo},
                }
        else:
            raise NotImplementedError(f"material {name}: type {kind}")
    return bsdfs


def load(
    scene_path: Path, spp: int, overrides: dict | None = None, floor: str = "exact", laser_radius: float | None = None
) -> dict:
    """Returns the Mitsuba scene dict for `scene_path` (the variant must already be set).
    `laser_radius` replaces the lasers' radius (a wider cone converges faster in Mitsuba: a
    check of the light the beam scatters into the room, not the scene as specified)."""
    import mitsuba as mi

    desc = tomllib.loads(scene_path.read_text())
    base = scene_path.parent
    grid = Grid(desc.get("film", {}))
    max_depth = desc.get("integrator", {}).get("max_depth", 32)
    d: dict = {"type": "scene", "integrator": {"type": "volpath", "max_depth": max_depth + 1}}
    for name, m in desc.get("media", {}).items():
        st = m["sigma_s"] + m["sigma_a"]
        d[f"medium_{name}"] = {
            "type": "homogeneous",
            "sigma_t": st,
            "albedo": m["sigma_s"] / st,
            "phase": {"type": "hg", "g": m.get("g", 0.0)},
        }

    boxes = [s for s in desc.get("shapes", []) if s["type"] == "box" and "interior" in s]

    def medium_at(p) -> dict | None:
        for b in boxes:
            if _inside_box(p, b):
                return {"type": "ref", "id": f"medium_{b['interior']}"}
        return None

    sensor = _camera(mi, desc["camera"], spp)
    if (m := medium_at(desc["camera"]["position"])) is not None:
        sensor["medium"] = m
    d["sensor"] = sensor

    bsdfs = _materials(mi, desc, base, floor)
    for i, s in enumerate(desc.get("shapes", [])):
        kind = s["type"]
        if kind == "box":
            size = s.get("size", [1, 1, 1])
            shape = {"type": "cube", "to_world": _transform(mi, s.get("transform"), [x / 2 for x in size])}
        elif kind == "quad":
            size = s.get("size", [1, 1])
            shape = {
                "type": "rectangle",
                "to_world": _transform(mi, s.get("transform"), [size[0] / 2, size[1] / 2, 1]),
            }
        else:
            raise NotImplementedError(f"shape type {kind}")
        shape["bsdf"] = bsdfs[s["material"]] if "material" in s else {"type": "null"}
        if "interior" in s:
            shape["interior"] = {"type": "ref", "id": f"medium_{s['interior']}"}
        d[f"shape{i}"] = shape

    T = mi.ScalarTransform4f
    for i, l in enumerate(desc.get("lights", [])):
        shape = light_spectrum(desc, base, l.get("spectrum"), grid)
        kind = l["type"]
        if kind == "directional":
            em = {
                "type": "directional",
                "direction": l["direction"],
                "irradiance": irregular(shape, grid, float(l["irradiance"])),
            }
        elif kind in ("spot", "laser"):
            pos = [float(x) for x in l.get("position", [0, 0, 0])]
            dirn = np.array(l.get("direction", [0, -1, 0]), dtype=float)
            dirn /= np.linalg.norm(dirn)
            if kind == "spot":
                angle, soft = float(l.get("angle", 30.0)), float(l.get("soft_edge", 0.0))
                cutoff, beam = angle, max(angle - soft, 0.0)
                norm = spot_norm(angle, soft)
            else:
                length = beam_length(pos, dirn, desc)
                radius = laser_radius if laser_radius is not None else float(l.get("radius", 1e-3))
                cutoff = math.degrees(math.atan(radius / length))
                beam = cutoff * (1 - 1e-6)
                norm = 2 * math.pi * (1 - math.cos(math.radians(cutoff)))
            # Mitsuba's spot looks along local +Z; `up` only needs to be non-parallel.
            up = [1, 0, 0] if abs(dirn[1]) > 0.9 else [0, 1, 0]
            em = {
                "type": "spot",
                "to_world": T().look_at(origin=pos, target=(np.array(pos) + dirn).tolist(), up=up),
                "cutoff_angle": cutoff,
                "beam_width": beam,
                "intensity": irregular(shape, grid, float(l["power"]) / norm),
            }
            if (m := medium_at(pos)) is not None:
                em["medium"] = m
        else:
            raise NotImplementedError(f"light type {kind}")
        d[f"light{i}"] = em
    for k, v in (overrides or {}).items():
        d[k] = v
    return d
