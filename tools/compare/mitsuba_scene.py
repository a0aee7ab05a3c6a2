"""Translate a brume scene TOML (the subset fog-cube uses) into a Mitsuba 3 scene dict.

Mirrored exactly: orthographic camera (position, look_at, up, view size, resolution), a box of
homogeneous fog with index-matched faces (Mitsuba `cube` with a `null` BSDF and an interior
`homogeneous` medium: sigma_t = sigma_s + sigma_a, albedo = sigma_s / sigma_t, `hg` phase with
the same g), Lambert quads (`rectangle` + `diffuse`), a directional light.

Approximations (each also listed in docs/performance.md):
- Texture: the PNG is decoded from sRGB to linear and multiplied by the material's albedo (brume
  folds the albedo into each texel too), then given to Mitsuba as a linear float bitmap. Mitsuba
  upsamples RGB to spectra with Jakob-Hanika 2019, brume with its own method: the wall's spectra
  differ slightly for the same RGB.
- Light: D65 shape in both. brume integrates over its film grid (380-780 nm, 32 bins) and
  normalises the shape to the given irradiance over that range; Mitsuba samples 360-830 nm
  continuously. The absolute scale therefore differs by a constant; compare.py fits one scalar
  from the two long references and reports it.
- Path depth: brume stops at integrator.max_depth (32 by default); Mitsuba gets the same
  max_depth (its count includes the camera vertex, so brume's depth + 1).
- Pixel filter: box in both.
"""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np


def _srgb_to_linear(c: np.ndarray) -> np.ndarray:
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def _texture(mi, path: Path, albedo: float):
    from PIL import Image

    rgb = np.asarray(Image.open(path).convert("RGB"), dtype=np.float32) / 255.0
    # brume's v = 0 is the image's bottom row; Mitsuba's bitmap puts v = 0 at the top row.
    lin = np.ascontiguousarray(np.flipud(_srgb_to_linear(rgb) * albedo), dtype=np.float32)
    return mi.Bitmap(lin, pixel_format=mi.Bitmap.PixelFormat.RGB)


def _transform(mi, t: dict | None, base_scale):
    """brume transform (translate, scale; rotate unsupported here) composed with the scale that
    maps Mitsuba's [-1, 1] primitives onto brume's sizes."""
    T = mi.ScalarTransform4f
    t = t or {}
    if any(abs(a) > 0 for a in t.get("rotate", [0, 0, 0])):
        raise NotImplementedError("rotated shapes are not translated yet")
    s = np.array(t.get("scale", [1, 1, 1]), dtype=float) * np.array(base_scale, dtype=float)
    return T().translate(list(t.get("translate", [0, 0, 0]))) @ T().scale(s.tolist())


def load(scene_path: Path, spp: int, overrides: dict | None = None) -> dict:
    """Returns the Mitsuba scene dict for `scene_path` (the variant must already be set)."""
    import mitsuba as mi

    desc = tomllib.loads(scene_path.read_text())
    base = scene_path.parent
    cam = desc["camera"]
    if cam.get("type") != "orthographic":
        raise NotImplementedError("only orthographic cameras are translated")
    T = mi.ScalarTransform4f
    to_world = T().look_at(
        origin=cam["position"], target=cam["look_at"], up=cam.get("up", [0, 1, 0])
    ) @ T().scale([cam["view_width"] / 2, cam["view_height"] / 2, 1])
    max_depth = desc.get("integrator", {}).get("max_depth", 32)
    d: dict = {
        "type": "scene",
        "integrator": {"type": "volpath", "max_depth": max_depth + 1},
        "sensor": {
            "type": "orthographic",
            "to_world": to_world,
            "film": {
                "type": "hdrfilm",
                "width": cam["width"],
                "height": cam["height"],
                "rfilter": {"type": "box"},
                "pixel_format": "rgb",
            },
            "sampler": {"type": "independent", "sample_count": spp},
        },
    }
    media = {}
    for name, m in desc.get("media", {}).items():
        st = m["sigma_s"] + m["sigma_a"]
        media[name] = {
            "type": "homogeneous",
            "sigma_t": st,
            "albedo": m["sigma_s"] / st,
            "phase": {"type": "hg", "g": m.get("g", 0.0)},
        }
    bsdfs = {}
    for name, m in desc.get("materials", {}).items():
        if m.get("type", "lambert") != "lambert":
            raise NotImplementedError(f"material {name}: only lambert is translated")
        albedo = m.get("albedo", 0.5)
        if "texture" in m:
            refl = {"type": "bitmap", "bitmap": _texture(mi, base / m["texture"], albedo)}
        else:
            refl = {"type": "rgb", "value": [albedo] * 3}
        bsdfs[name] = {"type": "diffuse", "reflectance": refl}
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
            shape["interior"] = media[s["interior"]]
        d[f"shape{i}"] = shape
    for i, l in enumerate(desc.get("lights", [])):
        if l["type"] != "directional":
            raise NotImplementedError(f"light type {l['type']}")
        if l.get("spectrum", "D65") != "D65":
            raise NotImplementedError("only D65 lights are translated")
        d[f"light{i}"] = {
            "type": "directional",
            "direction": l["direction"],
            "irradiance": {"type": "d65", "scale": float(l["irradiance"])},
        }
    for k, v in (overrides or {}).items():
        d[k] = v
    return d
