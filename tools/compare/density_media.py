"""brume's density fields (`[media.NAME] density = { type = ... }`) for the Mitsuba 3 comparison:
the translation into Mitsuba's `heterogeneous` medium (used by mitsuba_scene.load), and the same
fields evaluated in numpy (used by density_check.py for its region masks).

Translation. brume: sigma_t(x, l) = rho(x) sigma_t(l), albedo and phase independent of x. Mitsuba
3's `heterogeneous` medium: sigma_t(x) = scale * volume(x), with `scale` a float and a 1-channel
`gridvolume` a wavelength-independent value, so Mitsuba gets `scale` = one sigma_t and a grid of
rho. That is exact for a grey medium (the same coefficients in every film bin). A chromatic one
is rendered once per group of film bins whose coefficients are equal (`bin_groups`), each time
with that group's coefficients and with every light's spectrum zeroed outside the group
(`only_bins`); the images add up to the spectral image, because brume's lights and media are
constant within each bin and the groups partition the film's range (density_check.py does the
sum).
- type "grid": `gridvolume` of the same `.vol` file. With `transform`, its `to_world` is brume's
  transform (scale, rotate X, Y, Z, translate) of the unit cube, exactly as brume places it
  (`use_grid_bbox = false`); without it, `use_grid_bbox = true` (the file's own box). Both
  renderers put sample (i, j, k) at the centre of cell (i, j, k), trilinear between centres and
  clamped in the outer half cells (checked against Mitsuba's eval in density_check.py
  --self-test). `multiplier` multiplies `scale`. An OpenVDB file is not translated (Mitsuba 3
  reads only .vol).
- types "height" and "layer": a 1 x N x 1 `.vol` (N = 1024 by default) sampling rho along `up`,
  in a frame whose local y is `up` and whose box encloses the medium's box shape. The grid is
  placed so that its first and last sample centres lie exactly on the lowest and highest point
  of the shape along `up`: inside the shape the field is pure linear interpolation between
  samples a step D = (h_max - h_min) / (N - 1) apart (the clamped half cells lie outside it).
  Linear interpolation of a function with |rho''| <= M errs by at most D^2 M / 8:
  height fog (rho'' = rho / H^2): relative error <= D^2 / (8 H^2) e^{D / H};
  fog bank (the smooth step, |rho''| <= 6 / w^2 inside the transition): absolute error
  <= 3 D^2 / (4 w^2), zero outside the transition (rho is constant there and the knots at its
  ends are exact). `interpolation_bound` returns the figure; density_check.py prints it.
  The medium must be the interior of a `box` shape (the top-level `medium` filling all space is
  not translated: Mitsuba's grid needs a box).
"""

from __future__ import annotations

import hashlib
import math
import os
import struct
import tempfile
from pathlib import Path

import numpy as np

GRID_SAMPLES = 1024
VOL_DIR = Path(os.environ.get("BRUME_DENSITY_VOL_DIR", Path(tempfile.gettempdir()) / "brume-density-vol"))


# ----------------------------------------------------------------------------- transforms

def _rot(axis: int, deg: float) -> np.ndarray:
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    r = np.eye(3)
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    r[i, i], r[i, j], r[j, i], r[j, j] = c, -s, s, c
    return r


def brume_matrix(t: dict | None, base_scale=(1.0, 1.0, 1.0)) -> np.ndarray:
    """4 x 4 matrix of a brume transform (scale, rotate about X, then Y, then Z, translate),
    after `base_scale`."""
    t = t or {}
    rx, ry, rz = (float(a) for a in t.get("rotate", [0, 0, 0]))
    s = np.array(t.get("scale", [1, 1, 1]), dtype=float) * np.array(base_scale, dtype=float)
    m = np.eye(4)
    m[:3, :3] = _rot(2, rz) @ _rot(1, ry) @ _rot(0, rx) @ np.diag(s)
    m[:3, 3] = np.array(t.get("translate", [0, 0, 0]), dtype=float)
    return m


def _mi_transform(mi, m: np.ndarray):
    return mi.ScalarTransform4f(m.tolist())


# ----------------------------------------------------------------------------- .vol files

def read_vol(path: Path) -> tuple[np.ndarray, np.ndarray]:
    """(values (nz, ny, nx) float64, bbox (6,)) of a 1-channel float32 Mitsuba .vol file."""
    b = Path(path).read_bytes()
    if b[:3] != b"VOL" or b[3] != 3:
        raise ValueError(f"{path}: not a version 3 .vol file")
    enc, nx, ny, nz, ch = struct.unpack("<5i", b[4:24])
    if enc != 1 or ch != 1:
        raise ValueError(f"{path}: encoding {enc}, {ch} channels: only float32, 1 channel")
    bbox = np.array(struct.unpack("<6f", b[24:48]), dtype=float)
    vals = np.frombuffer(b[48:48 + 4 * nx * ny * nz], dtype="<f4").reshape(nz, ny, nx)
    return vals.astype(np.float64), bbox


def write_vol(path: Path, vals: np.ndarray, bbox) -> None:
    nz, ny, nx = vals.shape
    head = b"VOL" + bytes([3]) + struct.pack("<5i", 1, nx, ny, nz, 1) + struct.pack("<6f", *bbox)
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_bytes(head + np.ascontiguousarray(vals, dtype="<f4").tobytes())
    tmp.replace(path)


def trilinear_centres(vals: np.ndarray, u: np.ndarray) -> np.ndarray:
    """The grid's value at unit-cube points u (n, 3): samples at cell centres, trilinear between
    them, clamped in the outer half cells, 0 outside [0, 1]^3."""
    nz, ny, nx = vals.shape
    out = np.zeros(len(u))
    inside = np.all((u >= 0.0) & (u <= 1.0), axis=1)
    p = u[inside]
    idx, frac = [], []
    for a, n in enumerate((nx, ny, nz)):
        x = np.clip(p[:, a] * n - 0.5, 0.0, n - 1)
        i0 = np.minimum(np.floor(x).astype(int), max(n - 2, 0))
        idx.append(i0)
        frac.append(x - i0 if n > 1 else np.zeros_like(x))
    acc = 0.0
    for corner in range(8):
        w, ijk = 1.0, []
        for a, n in enumerate((nx, ny, nz)):
            bit = (corner >> a) & 1
            w = w * (frac[a] if bit else 1.0 - frac[a])
            ijk.append(np.minimum(idx[a] + bit, n - 1))
        acc = acc + w * vals[ijk[2], ijk[1], ijk[0]]
    out[inside] = acc
    return out


# ----------------------------------------------------------------------------- the fields

def box_of(desc: dict, name: str) -> dict:
    """The `box` shape whose interior is medium `name`."""
    boxes = [s for s in desc.get("shapes", []) if s.get("interior") == name]
    if len(boxes) != 1 or boxes[0]["type"] != "box":
        raise NotImplementedError(f"medium {name}: a density is translated only as the interior of one box shape")
    return boxes[0]


def box_matrix(box: dict) -> np.ndarray:
    """Maps [-1, 1]^3 onto the box shape in the world (brume's box of `size`, then its transform)."""
    return brume_matrix(box.get("transform"), [x / 2 for x in box.get("size", [1, 1, 1])])


def _unit(v) -> np.ndarray:
    v = np.array(v if v is not None else [0, 1, 0], dtype=float)
    return v / np.linalg.norm(v)


def profile(dens: dict, h: np.ndarray) -> np.ndarray:
    """rho of a height or layer field at heights h = up . x."""
    if dens["type"] == "height":
        return np.exp(-(h - float(dens.get("base", 0.0))) / float(dens["scale_height"]))
    if dens["type"] == "layer":
        top, w = float(dens["top"]), float(dens["transition"])
        x = np.clip((h - top + w / 2) / w, 0.0, 1.0)
        return 1.0 - (3 * x * x - 2 * x**3)
    raise NotImplementedError(f"density type {dens['type']!r}")


class Field:
    """A brume density field evaluated in numpy: rho at world points (zero outside the medium's
    box shape), and for height and layer fields the height h = up . x."""

    def __init__(self, desc: dict, base: Path, name: str):
        m = desc["media"][name]
        self.dens = dict(m["density"])
        self.kind = self.dens["type"]
        self.box = box_of(desc, name)
        self.box_to_world = box_matrix(self.box)
        self.world_to_box = np.linalg.inv(self.box_to_world)
        if self.kind == "grid":
            path = base / self.dens["file"]
            if path.suffix.lower() != ".vol":
                raise NotImplementedError(f"{path}: only .vol grids are evaluated and translated")
            self.vals, bbox = read_vol(path)
            self.vals = self.vals * float(self.dens.get("multiplier", 1.0))
            if "transform" in self.dens:
                self.grid_to_world = brume_matrix(self.dens["transform"])
            else:
                self.grid_to_world = np.eye(4)
                self.grid_to_world[:3, :3] = np.diag(bbox[3:] - bbox[:3])
                self.grid_to_world[:3, 3] = bbox[:3]
            self.world_to_grid = np.linalg.inv(self.grid_to_world)
        else:
            self.up = _unit(self.dens.get("up"))

    def corners(self) -> np.ndarray:
        c = np.array([[x, y, z, 1.0] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)])
        return (c @ self.box_to_world.T)[:, :3]

    def inside_box(self, p: np.ndarray) -> np.ndarray:
        q = p @ self.world_to_box[:3, :3].T + self.world_to_box[:3, 3]
        return np.all(np.abs(q) <= 1.0, axis=1)

    def rho(self, p: np.ndarray) -> np.ndarray:
        """rho at world points p (n, 3)."""
        if self.kind == "grid":
            u = p @ self.world_to_grid[:3, :3].T + self.world_to_grid[:3, 3]
            r = trilinear_centres(self.vals, u)
        else:
            r = profile(self.dens, p @ self.up)
        return np.where(self.inside_box(p), r, 0.0)

    def rho_range(self) -> tuple[float, float]:
        if self.kind == "grid":
            return float(self.vals.min()), float(self.vals.max())
        h = self.corners() @ self.up
        hs = np.linspace(h.min(), h.max(), 4097)
        r = profile(self.dens, hs)
        return float(r.min()), float(r.max())


# ----------------------------------------------------------------------------- Mitsuba

def interpolation_bound(desc: dict, name: str, n: int = GRID_SAMPLES) -> str:
    """The sampled profile's interpolation error inside the shape (see the module's text)."""
    m = desc["media"][name]
    dens = m["density"]
    if dens["type"] == "grid":
        return "exact (the same grid file)"
    f = Field(desc, Path("."), name)
    h = f.corners() @ f.up
    step = (h.max() - h.min()) / (n - 1)
    if dens["type"] == "height":
        H = float(dens["scale_height"])
        return f"relative error <= {step**2 / (8 * H * H) * math.exp(step / H):.2e} (step {step:.3g} m, H {H:g} m)"
    w = float(dens["transition"])
    return f"absolute error <= {0.75 * step**2 / (w * w):.2e} of rho = 1 (step {step:.3g} m, transition {w:g} m)"


def _profile_grid(mi, desc: dict, name: str, n: int) -> dict:
    """gridvolume sampling a height or layer profile along up (see the module's text)."""
    f = Field(desc, Path("."), name)
    up = f.up
    helper = np.array([1.0, 0.0, 0.0]) if abs(up[0]) < 0.9 else np.array([0.0, 0.0, 1.0])
    ex = np.cross(up, helper)
    ex /= np.linalg.norm(ex)
    ez = np.cross(ex, up)
    frame = np.stack([ex, up, ez], axis=1)  # columns: local x, y, z in world
    loc = f.corners() @ frame  # corners in the frame
    lo, hi = loc.min(0), loc.max(0)
    step = (hi[1] - lo[1]) / (n - 1)
    pad = 1e-3 * max(hi - lo)
    lo_g = np.array([lo[0] - pad, lo[1] - step / 2, lo[2] - pad])
    hi_g = np.array([hi[0] + pad, hi[1] + step / 2, hi[2] + pad])
    hs = lo[1] + step * np.arange(n)
    dens = desc["media"][name]["density"]
    vals = profile(dens, hs).reshape(1, n, 1)
    VOL_DIR.mkdir(parents=True, exist_ok=True)
    key = hashlib.sha1(repr((sorted((k, str(v)) for k, v in dens.items()), lo_g.tolist(), hi_g.tolist(), n)).encode()).hexdigest()[:16]
    path = VOL_DIR / f"{dens['type']}-{key}.vol"
    write_vol(path, vals, [0, 0, 0, 1, 1, 1])
    to_world = np.eye(4)
    to_world[:3, :3] = frame @ np.diag(hi_g - lo_g)
    to_world[:3, 3] = frame @ lo_g
    return {"type": "gridvolume", "filename": str(path), "to_world": _mi_transform(mi, to_world),
            "filter_type": "trilinear", "use_grid_bbox": False}


def coefficients(desc: dict, base: Path, m: dict, grid) -> tuple[np.ndarray, np.ndarray]:
    """(sigma_t, albedo) per film bin at rho = 1, as mitsuba_scene reads brume's coefficients."""
    import mitsuba_scene

    unsupported = [k for k in ("phase", "droplets", "visibility", "albedo") if k in m]
    if unsupported:
        raise NotImplementedError(f"medium keys {unsupported} are not translated")
    ss = np.broadcast_to(np.asarray(mitsuba_scene.coefficient(desc, base, m.get("sigma_s", 0.0), grid), dtype=float), (grid.n,))
    sa = np.broadcast_to(np.asarray(mitsuba_scene.coefficient(desc, base, m.get("sigma_a", 0.0), grid), dtype=float), (grid.n,))
    st = ss + sa
    return st, np.divide(ss, st, out=np.zeros(grid.n), where=st > 0)


def bin_groups(desc: dict, base: Path, grid) -> list[list[int]] | None:
    """None when every medium with a density is grey (one render of the whole spectrum), else
    runs of consecutive film bins whose coefficients are equal in every such medium."""
    keys = []
    for m in desc.get("media", {}).values():
        if "density" in m:
            st, al = coefficients(desc, base, m, grid)
            keys.append(np.stack([st, al], 1))
    if not keys or all(np.all(k == k[0]) for k in keys):
        return None
    k = np.concatenate(keys, 1)
    groups = [[0]]
    for i in range(1, grid.n):
        (groups[-1].append(i) if np.array_equal(k[i], k[i - 1]) else groups.append([i]))
    return groups


def only_bins(shape: np.ndarray, bins: list[int] | None) -> np.ndarray:
    """A light's per-bin spectrum with every bin outside `bins` zeroed."""
    if bins is None:
        return shape
    mask = np.zeros(len(shape))
    mask[bins] = 1.0
    return shape * mask


def heterogeneous(mi, desc: dict, base: Path, name: str, grid, bins: list[int] | None, n: int = GRID_SAMPLES) -> dict:
    """Mitsuba's `heterogeneous` medium for brume medium `name` with a density, its coefficients
    those of film bins `bins` (which must be equal; None: the medium must be grey)."""
    m = desc["media"][name]
    dens = m["density"]
    st, al = coefficients(desc, base, m, grid)
    sel = list(range(grid.n)) if bins is None else list(bins)
    if not (np.all(st[sel] == st[sel[0]]) and np.all(al[sel] == al[sel[0]])):
        raise ValueError(f"medium {name}: coefficients differ across bins {sel}: render per bin group (bin_groups)")
    scale = float(st[sel[0]])
    if dens["type"] == "grid":
        path = (base / dens["file"]).resolve()
        if path.suffix.lower() != ".vol":
            raise NotImplementedError(f"{path}: Mitsuba 3 reads only .vol grids")
        vol = {"type": "gridvolume", "filename": str(path), "filter_type": "trilinear"}
        if "transform" in dens:
            vol["to_world"] = _mi_transform(mi, brume_matrix(dens["transform"]))
            vol["use_grid_bbox"] = False
        else:
            vol["use_grid_bbox"] = True
        scale *= float(dens.get("multiplier", 1.0))
    else:
        vol = _profile_grid(mi, desc, name, n)
    return {
        "type": "heterogeneous",
        "sigma_t": vol,
        "scale": scale,
        "albedo": float(al[sel[0]]),
        "phase": {"type": "hg", "g": float(m.get("g", 0.0))},
    }
