"""Translate a brume scene TOML (the subset fog-cube, fog-room-laser and chromatic-fog use) into a
Mitsuba 3 dict.

Mirrored exactly:
- Cameras: `orthographic` (position, look_at, up, view size) and `perspective` (brume's fov is the
  vertical one: Mitsuba `fov_axis = "y"`); resolution; box pixel filter in both.
- Shapes: a box of fog (`cube` with a `null` BSDF and an interior `homogeneous` medium) and quads
  (`rectangle`, normal local +Z like brume's), with brume's transform order: scale, then rotate
  about world X, then Y, then Z (R = Rz Ry Rx), then translate.
- Media: sigma_t = sigma_s + sigma_a, albedo = sigma_s / sigma_t, `hg` phase with the same g.
  Grey media (both coefficients numbers) give plain floats, the dict fog-cube and fog-room-laser
  have always had. A coefficient given as a spectrum (a `[spectra]` name: `power_law`, `value`,
  `file` or `builtin`, times its `scale`; or a built-in name or CSV file) is what brume makes of
  it: one value per film bin, the exact average over the bin (a power law's closed-form
  integral, a table's piecewise-linear one), used for every wavelength inside the bin. Mitsuba
  gets those same steps as `irregular` spectra for sigma_t and albedo (its `homogeneous` takes a
  spectrum for both; its `scale` is a float only), so both render brume's binned medium, not the
  continuous law (for chromatic-fog's lambda^-4 over 12.5 nm bins the average is at most 0.09 %
  above the law at the bin's centre, so that choice hardly matters there). Outside the film's range the steps keep their end values rather
  than dropping to 0: no light exists there, but `volpath` draws free-flight distances from the
  extinction of the first wavelength of a path alone, and a zero there would stop the path from
  ever scattering for its other wavelengths (a bias, not just noise).
- The camera and the lights get the medium of the box that contains them (Mitsuba needs to be told
  that a sensor starts inside a medium).
- Light spectra and units. brume averages every spectrum over its film bins (32 bins over
  380-780 nm here) and normalises each light's shape so that its integral over that range is 1,
  times `power` (W) or `irradiance` (W/m^2). Mitsuba gets exactly that piecewise-constant
  spectrum (an `irregular` spectrum with steps at the bin edges, zero outside the film's range),
  already scaled to brume's radiometric units. Surfaces are grey and media are constant within
  each bin, so every radiance in the scene is constant within each bin too, and Mitsuba's
  continuous integration of these steps against the CIE 1931 functions equals brume's per-bin
  weights. brume normalises Y so that a constant radiance of 1 has Y = 1 (its CIE 1931 table's
  integral of y-bar, 106.857 nm); Mitsuba 3 divides by 106.7503 nm instead
  (`MI_CIE_Y_NORMALIZATION`), which makes its images 0.100 % brighter than its own table's
  integral says (measured on a Lambert floor under a directional light against the closed form:
  brume within 2e-5 of it, Mitsuba 0.094 % above before this correction). So every light's
  emission is divided by `mitsuba_y_excess` (1.0010, computed from Mitsuba's own tables), and
  the two images should agree with a scale k = 1 (compare.py fits k and reports it as a check).
- Spot lights: brume's `power` is the total flux; Mitsuba's `intensity` is W/sr on the axis, so
  intensity = power / (solid-angle integral of brume's profile), with brume's profile (1 inside
  angle - soft_edge, falling linearly in cos(theta) to 0 at angle). With spot_profile="exact"
  the soft edge is brume's too (a projected texture, `spot_profile_texture`); with the default
  "ramp" it is Mitsuba's own (see below).
- Lambert surfaces: `diffuse` with a constant (spectrally flat) reflectance.
- Conductors: `roughconductor` (GGX) with brume's per-bin eta and k (`conductor` below).
- Path depth: brume's integrator.max_depth (32 by default) + 1 (Mitsuba counts the camera vertex).

Approximations:
- Spot soft edge (spot_profile="ramp", the default): Mitsuba's falloff is linear in the angle
  between beam_width and cutoff_angle, brume's linear in cos(theta); at mid-edge (32.5 deg of
  30-35) brume gives 0.517, Mitsuba 0.5. The intensity on the axis is brume's, so Mitsuba's spot
  emits less in all: 0.34 % for fog-room-laser's 35 deg spots with 5 deg edges (only the rim of
  each pool of light differs, by up to 6 % at its outer edge), but 1.3 % for chromatic-fog's 4 deg
  spot with a 1 deg edge (28 % of its flux is in the edge, up to 11 % less at the rim): brume /
  Mitsuba came out 1.012-1.015 on that scene's wall spot with the ramp, 1.00 with the exact
  profile. spot_profile="exact" removes the difference.
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

import density_media

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


# Mitsuba's spectral variants sample wavelengths over the CIE tables' range, 360-830 nm.
_MITSUBA_LAMBDA = (360.0, 830.0)


def mitsuba_y_excess(mi) -> float:
    """Y of a unit spectrum in Mitsuba 3's spectral variants: its CIE 1931 y-bar integrated over
    its tables' range (360-830 nm) times its `MI_CIE_Y_NORMALIZATION`. Mitsuba's constant is
    1 / 106.7503 while its table integrates to 106.857, so this is 1.0010, not 1: a unit radiance
    renders to Y = 1.0010 in Mitsuba and to 1 in brume. The variant must be set (any: scalar or
    vectorised). Mitsuba's table is piecewise linear between whole nanometres, so the trapezoid
    rule on them is its exact integral."""
    variant = mi.variant()
    if variant not in _Y_EXCESS:
        lam = np.arange(mi.MI_CIE_MIN, mi.MI_CIE_MAX + 0.5, 1.0)
        y = np.array([np.ravel(np.asarray(mi.cie1931_y(float(x)), dtype=np.float64))[0] for x in lam])
        _Y_EXCESS[variant] = float(np.sum(0.5 * (y[1:] + y[:-1]) * np.diff(lam)) * mi.MI_CIE_Y_NORMALIZATION)
    return _Y_EXCESS[variant]


# mitsuba_y_excess per variant: 471 table lookups (0.08 s in the LLVM variant) that every scene
# load would otherwise repeat (density_check.py loads one scene per bin group and render).
_Y_EXCESS: dict[str, float] = {}


def irregular(bins: np.ndarray, grid: Grid, scale: float, outside: str = "zero") -> dict:
    """Piecewise-constant spectrum over the film's bins (Mitsuba interpolates linearly between
    the given points: each edge gets two points 1e-3 nm apart). Outside the film's range it is
    zero (`outside="zero"`, for emission: brume's lights emit nothing there), or holds the end
    bins' values out to Mitsuba's whole range (`outside="clamp"`, for medium coefficients: see
    `_coefficient_spectrum`)."""
    eps = 1e-3
    if outside == "zero":
        lam, val = [grid.lo - 2 * eps], [0.0]
    else:
        lam, val = [min(_MITSUBA_LAMBDA[0], grid.lo) - 1.0], [bins[0] * scale]
    for i, v in enumerate(bins):
        a, b = grid.edges[i], grid.edges[i + 1]
        lam += [a + (eps if i > 0 else 0.0), b - (eps if i < len(bins) - 1 else 0.0)]
        val += [v * scale, v * scale]
    if outside == "zero":
        lam.append(grid.hi + 2 * eps)
        val.append(0.0)
    else:
        lam.append(max(_MITSUBA_LAMBDA[1], grid.hi) + 1.0)
        val.append(bins[-1] * scale)
    return {
        "type": "irregular",
        "wavelengths": ", ".join(f"{x:.6f}" for x in lam),
        "values": ", ".join(f"{x:.9g}" for x in val),
    }


def power_law_bins(k: float, lambda_ref: float, p: float, grid: Grid) -> np.ndarray:
    """brume's `power_law` spectrum, k (lambda / lambda_ref)^-p, as the exact average of the law
    over each film bin (the closed-form integral src/spectrum/analytic.rs uses), not its value
    at the bin's centre (for p = 4 over 12.5 nm bins they differ by at most 0.09 %)."""
    a, b = grid.edges[:-1], grid.edges[1:]
    if abs(p - 1.0) < 1e-12:
        integral = lambda_ref * np.log(b / a)
    else:
        integral = lambda_ref**p * (b ** (1.0 - p) - a ** (1.0 - p)) / (1.0 - p)
    return k * integral / (b - a)


def _table_bins(name: str, base: Path, grid: Grid) -> np.ndarray:
    """Bin averages of a spectrum CSV: one of brume's built-in illuminant names (which brume
    tries first, ignoring case) or a file relative to the scene."""
    if ":" in name:
        raise NotImplementedError(f"spectrum {name!r}: a CSV column other than the first is not translated")
    builtin = {k.lower(): v for k, v in _BUILTIN_SPECTRA.items()}
    path = REPO / "spectra" / builtin[name.lower()] if name.lower() in builtin else base / name
    lam, val = _read_table(path)
    return bin_averages(lam, val, grid.edges)


def coefficient(desc: dict, base: Path, ref, grid: Grid) -> float | np.ndarray:
    """brume's per-bin values of a medium coefficient (1/m) given as `ref`: a number stays a
    plain float (a grey medium), anything spectral becomes an array over the film's bins, as
    src/scene/spectra.rs resolves it (a name from [spectra] first, with its optional `scale`,
    else a built-in name or CSV file)."""
    if isinstance(ref, (int, float)) and not isinstance(ref, bool):
        return float(ref)
    if not isinstance(ref, str):
        # An RGB triple would need brume's own "unbounded" RGB-to-spectrum upsampling.
        raise NotImplementedError(f"medium coefficient {ref!r}: only numbers and named spectra are translated")
    named = desc.get("spectra", {}).get(ref)
    if named is None:
        return _table_bins(ref, base, grid)
    scale = float(named.get("scale", 1.0))
    if "column" in named:
        raise NotImplementedError(f"spectra.{ref}: a CSV column other than the first is not translated")
    if "power_law" in named:
        pl = named["power_law"]
        return power_law_bins(float(pl["k"]), float(pl.get("lambda_ref", 550.0)), float(pl["p"]), grid) * scale
    if "value" in named:
        return float(named["value"]) * scale
    if "file" in named or "builtin" in named:
        return _table_bins(named.get("file", named.get("builtin")), base, grid) * scale
    raise NotImplementedError(f"spectra.{ref}: only power_law, value, file and builtin spectra are translated")


def _coefficient_spectrum(bins: np.ndarray, grid: Grid):
    """A per-bin medium parameter for Mitsuba: a float when it is the same in every bin, else a
    piecewise-constant spectrum. Outside the film's range it keeps its end bins' values instead
    of dropping to zero: no light is emitted there, so those values never reach the image, but
    Mitsuba's `volpath` draws free-flight distances from the extinction of the first of the
    wavelengths a path carries alone; with that extinction 0 the path would never scatter for
    the other wavelengths it carries (which may lie inside the range), a bias."""
    if np.all(bins == bins[0]):
        return float(bins[0])
    return irregular(bins, grid, 1.0, outside="clamp")


def medium(desc: dict, base: Path, m: dict, grid: Grid, bins: list[int] | None = None) -> dict:
    """Mitsuba's `homogeneous` medium for brume medium `m` (sigma_s, sigma_a, g). With `bins`
    (film bins whose coefficients are equal), the grey medium of those bins: a render of only
    their light then carries no spectral weights at all (density_check.py --per-bin)."""
    if bins is not None:
        st, al = density_media.coefficients(desc, base, m, grid)
        if np.all(st[bins] == st[bins[0]]) and np.all(al[bins] == al[bins[0]]):
            return {"type": "homogeneous", "sigma_t": float(st[bins[0]]), "albedo": float(al[bins[0]]),
                    "phase": {"type": "hg", "g": m.get("g", 0.0)}}
        # Coefficients that differ within the group: the spectral medium (the lights carry
        # only the group's light anyway).
    unsupported = [k for k in ("phase", "droplets", "visibility", "albedo") if k in m]
    if unsupported:
        raise NotImplementedError(f"medium keys {unsupported} are not translated")
    phase = {"type": "hg", "g": m.get("g", 0.0)}
    ss = coefficient(desc, base, m.get("sigma_s", 0.0), grid)
    sa = coefficient(desc, base, m.get("sigma_a", 0.0), grid)
    if isinstance(ss, float) and isinstance(sa, float):
        # Grey: exactly the dict the grey scenes (fog-cube, fog-room-laser) have always used,
        # from the TOML's own numbers when both are numbers (a named constant: its value).
        raw = (m.get("sigma_s", 0.0), m.get("sigma_a", 0.0))
        if not all(isinstance(x, (int, float)) for x in raw):
            raw = (ss, sa)
        st = raw[0] + raw[1]
        return {"type": "homogeneous", "sigma_t": st, "albedo": raw[0] / st, "phase": phase}
    # Spectral: brume keeps one sigma_s and one sigma_a per bin and uses them for every
    # wavelength inside the bin, so Mitsuba gets those same steps. Its `homogeneous` medium takes
    # sigma_t (float or spectrum; `scale` is a float only) and albedo (float, spectrum or volume).
    ss = np.broadcast_to(np.asarray(ss, dtype=float), (grid.n,))
    sa = np.broadcast_to(np.asarray(sa, dtype=float), (grid.n,))
    st = ss + sa
    albedo = np.divide(ss, st, out=np.zeros(grid.n), where=st > 0)
    return {
        "type": "homogeneous",
        "sigma_t": _coefficient_spectrum(st, grid),
        "albedo": _coefficient_spectrum(albedo, grid),
        "phase": phase,
    }


def spot_norm(angle_deg: float, soft_deg: float) -> float:
    """Solid-angle integral of brume's spot profile (sr), as src/light/spot.rs defines it."""
    edge, full = _spot_angles(angle_deg, soft_deg)
    ce, cf = math.cos(math.radians(edge)), math.cos(math.radians(full))
    return 2 * math.pi * ((1 - cf) + 0.5 * (cf - ce))


def _spot_angles(angle_deg: float, soft_deg: float) -> tuple[float, float]:
    """brume's (edge, full-intensity) half-angles of a cone, in degrees, clamped as
    src/light/spot.rs clamps them."""
    edge = min(max(angle_deg, 0.01), 180.0)
    return edge, min(max(edge - max(soft_deg, 0.0), 0.0), edge)


def spot_profile_texture(mi, angle_deg: float, soft_deg: float, n: int = 512) -> dict | None:
    """A texture that turns Mitsuba's spot ramp into brume's, or None when they already agree
    (a hard edge).

    Mitsuba's spot falls off linearly in the angle theta between beam_width and cutoff_angle;
    brume's linearly in cos(theta). For a wide cone with a thin edge the difference is small
    (35 deg with a 5 deg edge: Mitsuba emits 0.34 % less than brume), but for a narrow cone
    whose soft edge is a large part of it, it is not: 4 deg with a 1 deg edge puts 28 % of the
    flux in the edge and Mitsuba emits 1.3 % less. Mitsuba's spot multiplies its intensity by an
    optional texture looked up at uv = 0.5 + 0.5 (x, y) / (z tan(cutoff)) of the local direction,
    so a bitmap holding brume's profile over Mitsuba's at each texel's angle makes the two
    equal (to bilinear interpolation between 512^2 texels, far below the noise)."""
    edge, full = _spot_angles(angle_deg, soft_deg)
    if full >= edge:
        return None
    if edge >= 89.0:
        raise NotImplementedError("exact spot profile: the uv projection needs a cone under 89 deg")
    c, b = math.radians(edge), math.radians(full)
    t = (np.arange(n) + 0.5) / n  # texel centres, as Mitsuba's bitmap places them
    u, v = np.meshgrid(t, t)
    theta = np.arctan(2.0 * np.hypot(u - 0.5, v - 0.5) * math.tan(c))
    ramp = (c - theta) / (c - b)
    cosine = (np.cos(theta) - math.cos(c)) / (math.cos(b) - math.cos(c))
    # At the cut-off both reach 0; their ratio tends to sin(c) (c - b) / (cos b - cos c). Texels
    # beyond it hold that limit, so interpolating at the rim does not pull towards 0 (Mitsuba
    # emits nothing outside the cone whatever the texture says).
    rim = math.sin(c) * (c - b) / (math.cos(b) - math.cos(c))
    inside = (theta > b) & (theta < c)
    ratio = np.where(theta <= b, 1.0, rim)
    ratio[inside] = cosine[inside] / ramp[inside]
    bitmap = mi.Bitmap(np.ascontiguousarray(ratio[..., None], dtype=np.float32))
    return {"type": "bitmap", "bitmap": bitmap, "raw": True, "filter_type": "bilinear", "wrap_mode": "clamp"}


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


SAMPLERS = ("independent", "stratified", "multijitter", "ldsampler")


def _camera(mi, cam: dict, spp: int, sampler: str = "independent") -> dict:
    T = mi.ScalarTransform4f
    look = T().look_at(origin=cam["position"], target=cam["look_at"], up=cam.get("up", [0, 1, 0]))
    film = {
        "type": "hdrfilm",
        "width": cam["width"],
        "height": cam["height"],
        "rfilter": {"type": "box"},
        "pixel_format": "rgb",
    }
    sampler = {"type": sampler, "sample_count": spp}
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
    grid = Grid(desc.get("film", {}))
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
        elif kind == "conductor":
            bsdfs[name] = conductor(m, grid)
        else:
            raise NotImplementedError(f"material {name}: type {kind}")
    return bsdfs


def _metal_column(metal: str, column: str, grid: Grid) -> np.ndarray:
    """Bin averages of column `n` or `k` of brume's table spectra/metal_<metal>.csv."""
    lines = [l for l in (REPO / "spectra" / f"metal_{metal.lower()}.csv").read_text().splitlines()
             if l.strip() and not l.startswith("#")]
    head = lines[0].split(",")
    rows = np.array([[float(x) for x in l.split(",")] for l in lines[1:]])
    return bin_averages(rows[:, 0], rows[:, head.index(column)], grid.edges)


def conductor(m: dict, grid: Grid) -> dict:
    """brume's `conductor` as Mitsuba's `roughconductor` (GGX, visible-normal sampling, exact
    conductor Fresnel) with brume's per-bin eta and k as step spectra (held at the end bins'
    values outside the film's range), or the smooth `conductor` below brume's SMOOTH_ALPHA.
    Mitsuba's masking-shadowing is the separable Smith G1(wo) G1(wi), brume's the
    height-correlated one: they differ by under 0.5 % where both directions are within 60 deg of
    the normal at alpha 0.3, by several % near grazing. Isotropic roughness and eta/k only
    (`f0`, Schlick, has no Mitsuba counterpart; anisotropic axes follow each renderer's own
    tangent frame)."""
    if "f0" in m:
        raise NotImplementedError("conductor f0 (Schlick) has no Mitsuba counterpart")
    alpha = m.get("roughness", 0.1)
    if not isinstance(alpha, (int, float)):
        raise NotImplementedError("anisotropic roughness: the tangent frames differ")
    eta = m["eta"]
    parts = {}
    for key, column in (("eta", "n"), ("k", "k")):
        ref = m.get(key, eta if key == "k" else None)
        if isinstance(ref, str):
            bins = _metal_column(ref, column, grid)
        elif isinstance(ref, (int, float)):
            bins = np.full(grid.n, float(ref))
        else:
            raise NotImplementedError(f"conductor {key} = {ref!r}")
        parts[key] = irregular(bins, grid, 1.0, outside="clamp")
    if float(alpha) < 1e-3:
        return {"type": "conductor", **parts}
    return {"type": "roughconductor", "distribution": "ggx", "alpha": float(alpha), **parts}


INTEGRATORS = ("volpath", "volpathmis")
SPOT_PROFILES = ("ramp", "exact")


def load(
    scene_path: Path,
    spp: int,
    overrides: dict | None = None,
    floor: str = "exact",
    laser_radius: float | None = None,
    integrator: str = "volpath",
    spot_profile: str = "ramp",
    bins: list[int] | None = None,
    sampler: str = "independent",
    desc: dict | None = None,
) -> dict:
    """Returns the Mitsuba scene dict for `scene_path` (the variant must already be set).
    `laser_radius` replaces the lasers' radius (a wider cone converges faster in Mitsuba: a
    check of the light the beam scatters into the room, not the scene as specified).
    `integrator`: `volpath`, or `volpathmis` (spectral MIS over the wavelengths a path carries,
    the one meant for media whose extinction varies with wavelength); same max_depth.
    `spot_profile`: "ramp" keeps Mitsuba's own soft edge (linear in the angle; what the grey
    scenes have always been compared with), "exact" gives spots brume's edge (linear in
    cos theta) through a projected texture (`spot_profile_texture`).
    Media with a `density` become `heterogeneous` (density_media.py); `bins` (film bin indices)
    renders only the light of those bins, with their coefficients in such media: the per-group
    images of density_media.bin_groups add up to a chromatic scene's image.
    `sampler`: Mitsuba's sampler (one of SAMPLERS; stratified and multijitter want a square
    spp, ldsampler a power of two). `desc`: the scene already parsed (and edited, as the
    protocol's --set does) instead of reading `scene_path`, which still gives the folder that
    relative paths resolve against."""
    import mitsuba as mi

    if integrator not in INTEGRATORS:
        raise ValueError(f"integrator {integrator!r}: one of {INTEGRATORS}")
    if spot_profile not in SPOT_PROFILES:
        raise ValueError(f"spot_profile {spot_profile!r}: one of {SPOT_PROFILES}")
    if sampler not in SAMPLERS:
        raise ValueError(f"sampler {sampler!r}: one of {SAMPLERS}")
    if desc is None:
        desc = tomllib.loads(scene_path.read_text())
    base = scene_path.parent
    grid = Grid(desc.get("film", {}))
    max_depth = desc.get("integrator", {}).get("max_depth", 32)
    d: dict = {"type": "scene", "integrator": {"type": integrator, "max_depth": max_depth + 1}}
    for name, m in desc.get("media", {}).items():
        if "density" in m:
            d[f"medium_{name}"] = density_media.heterogeneous(mi, desc, base, name, grid, bins)
        else:
            d[f"medium_{name}"] = medium(desc, base, m, grid, bins)

    boxes = [s for s in desc.get("shapes", []) if s["type"] == "box" and "interior" in s]

    def medium_at(p) -> dict | None:
        for b in boxes:
            if _inside_box(p, b):
                return {"type": "ref", "id": f"medium_{b['interior']}"}
        return None

    sensor = _camera(mi, desc["camera"], spp, sampler)
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
    # Mitsuba's images would be 0.1 % brighter than brume's for the same radiance (its Y
    # normalisation, `mitsuba_y_excess`): its lights emit that much less instead.
    y_excess = mitsuba_y_excess(mi)
    for i, l in enumerate(desc.get("lights", [])):
        shape = density_media.only_bins(light_spectrum(desc, base, l.get("spectrum"), grid), bins)
        shape = shape / y_excess
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
            if kind == "spot" and spot_profile == "exact":
                if (tex := spot_profile_texture(mi, angle, soft)) is not None:
                    em["texture"] = tex
            if (m := medium_at(pos)) is not None:
                em["medium"] = m
        else:
            raise NotImplementedError(f"light type {kind}")
        d[f"light{i}"] = em
    for k, v in (overrides or {}).items():
        d[k] = v
    return d
