"""Image-space mask of a laser beam and of its glossy reflection in the floor, from geometry only.

A pixel is in the mask when its camera ray (through the pixel centre, brume's pinhole model)
passes within `band_px` pixel widths (as an angle seen from the camera) of the beam's segment, or
when the ray hits the floor plane (y = 0) and its mirror direction passes within
`reflect_rad` radians of the segment (seen from the floor point). The mirror test stands for the
glossy lobe: GGX with alpha 0.08 sends about half of the reflected energy within ~0.17 rad
(P(tan theta_h > t) = alpha^2 / (alpha^2 + t^2), doubled on reflection), so 0.2 rad catches the
bright part of the reflection; its faint tail stays outside the mask.
"""

from __future__ import annotations

import math

import numpy as np


def _basis(pos, look_at, up):
    f = np.asarray(look_at, float) - np.asarray(pos, float)
    f /= np.linalg.norm(f)
    r = np.cross(f, np.asarray(up, float))
    if np.dot(r, r) < 1e-12:
        r = np.cross(f, [0, 1, 0] if abs(f[1]) < 0.9 else [0, 0, 1])
    r /= np.linalg.norm(r)
    return f, r, np.cross(r, f)


def camera_rays(cam: dict) -> tuple[np.ndarray, np.ndarray, float]:
    """Origin, unit directions (h, w, 3) through pixel centres, and the angle of one pixel."""
    w, h = int(cam["width"]), int(cam["height"])
    f, r, u = _basis(cam["position"], cam["look_at"], cam.get("up", [0, 1, 0]))
    tan_v = math.tan(math.radians(float(cam.get("fov", 45.0))) / 2)
    x = (np.arange(w) + 0.5)[None, :]
    y = (np.arange(h) + 0.5)[:, None]
    sx = 2 * x / w - 1
    sy = 1 - 2 * y / h
    d = f[None, None, :] + r[None, None, :] * (sx * tan_v * w / h)[..., None] + u[None, None, :] * sy[..., None] * tan_v
    d = np.broadcast_to(d, (h, w, 3)).copy()
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    return np.asarray(cam["position"], float), d, 2 * tan_v / h


def _ray_segment_angle(o: np.ndarray, d: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Angle (distance / distance along the ray) from rays o + s d (s > 0) to segment a-b."""
    e = b - a
    samples = np.linspace(0.0, 1.0, 257)
    best = np.full(d.shape[:-1], np.inf)
    for t in samples:
        p = a + t * e
        v = p - o
        s = np.sum(v * d, axis=-1)
        perp = np.linalg.norm(v - s[..., None] * d, axis=-1)
        ang = np.where(s > 1e-6, perp / np.maximum(s, 1e-6), np.inf)
        best = np.minimum(best, ang)
    return best


def beam_mask(cam: dict, start, direction, length: float, band_px: float = 3.0, reflect_rad: float = 0.2) -> np.ndarray:
    o, d, pix = camera_rays(cam)
    a = np.asarray(start, float)
    u = np.asarray(direction, float)
    u = u / np.linalg.norm(u)
    b = a + u * length
    mask = _ray_segment_angle(o, d, a, b) < band_px * pix
    # Floor reflection: rays going down hit y = 0 at o + s d; mirror the direction.
    down = d[..., 1] < -1e-6
    s = np.where(down, -o[1] / np.where(down, d[..., 1], -1.0), 0.0)
    p = o + s[..., None] * d
    m = d.copy()
    m[..., 1] *= -1
    ang = np.full(d.shape[:-1], np.inf)
    idx = np.nonzero(down)
    if len(idx[0]):
        ang[idx] = _ray_segment_angle(p[idx], m[idx], a, b)
    return mask | (down & (ang < reflect_rad))


def spot_mask(cam: dict, point, radius_px: float = 4.0) -> np.ndarray:
    """Pixels whose camera ray passes within `radius_px` pixel widths (as an angle) of `point`:
    where a laser ends on a wall, its spot (a few pixels that can hold most of an image's
    squared error)."""
    o, d, pix = camera_rays(cam)
    p = np.asarray(point, float)
    return _ray_segment_angle(o, d, p, p) < radius_px * pix
