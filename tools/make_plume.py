"""Writes scenes/smoke-plume.vol: a smoke plume as a Mitsuba `.vol` density grid, for
scenes/smoke-plume.toml and for the cost benchmark of sparse media.

What it makes: a plume rising from a round source near the bottom of its box, whose radius grows
linearly with height (a turbulent plume's cone) while its density falls (the smoke spreads over
a wider section), with deterministic turbulence. Values are >= 0 and the largest is exactly 1.
The plume occupies `--occupancy` of the box's volume (voxels whose density exceeds 1 % of the
maximum): the radius scale is solved by bisection until it does, so the grid stays as sparse as
the benchmark needs whatever the noise does.

How: in the box's metres (x, z across, y up; the source at height `--source-height` in the middle
of the floor), at height s above the source
- radius R(s) = f (R0 + spread s), f the solved scale;
- amplitude (R0 / R)^thinning (1 would keep the density x area constant, lower keeps the upper
  plume visible);
- the axis drifts sideways with height by a 1-D smooth noise, and the point is displaced by a
  3-D smooth noise before its distance d to the axis is taken (domain warping: the edge folds),
  both growing with s (the flow gets more turbulent as it rises);
- profile 1 - (d/R)^2 for d < R (compact: no long tails spending occupancy on thin smoke);
- times a clumpiness factor max(0, 1 + clump * n(x)), n a 3-D noise;
- a smooth onset over 4 cm at the source and a fade over the top 15 % of the box.
The noises are value noise: independent uniform values in [-1, 1] on a coarse lattice from
numpy's default_rng(seed), interpolated with smoothstep weights, summed over octaves (lattice
twice as fine, amplitude halved each time) and divided by the sum of amplitudes. Nothing else is
random, so the same arguments give the same bytes.

File layout (Mitsuba 3 `.vol`, read by brume's `density = { type = "grid", ... }` too): 'VOL',
version byte 3, int32 encoding 1 (float32), int32 nx, ny, nz, int32 channels 1, 6 float32 bbox
(xmin, ymin, zmin, xmax, ymax, zmax), then float32 data[((z ny + y) nx + x)], little-endian.
Sample (i, j, k) is the value at the centre of cell (i, j, k) of the bbox.

Command (from the repository root; the defaults make the committed file, 48 x 96 x 48, 885 KB):
    python3 tools/make_plume.py            # writes scenes/smoke-plume.vol, prints the occupancy
Parameters: --res NX NY NZ, --size X Y Z (m), --min X Y Z (the bbox's lower corner in the scene,
written into the file), --seed, --occupancy (fraction of the box, default 0.05), --out.
"""

from __future__ import annotations

import argparse
import struct
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]


def smoothstep(t: np.ndarray) -> np.ndarray:
    return t * t * (3.0 - 2.0 * t)


def value_noise(rng: np.random.Generator, cells: tuple[int, ...], coords: list[np.ndarray]) -> np.ndarray:
    """One octave of value noise: random values in [-1, 1] at the nodes of a lattice of `cells`
    cells per axis over [0, 1] of each coordinate, interpolated with smoothstep weights (any
    number of axes; `coords` in [0, 1], broadcastable)."""
    lattice = rng.uniform(-1.0, 1.0, size=tuple(c + 1 for c in cells))
    idx, wts = [], []
    for c, u in zip(cells, coords):
        x = np.clip(u, 0.0, 1.0) * c
        i = np.minimum(np.floor(x).astype(int), c - 1)
        idx.append(i)
        wts.append(smoothstep(x - i))
    out = 0.0
    for corner in range(1 << len(cells)):
        w, where = 1.0, []
        for a in range(len(cells)):
            bit = (corner >> a) & 1
            w = w * (wts[a] if bit else 1.0 - wts[a])
            where.append(idx[a] + bit)
        out = out + w * lattice[tuple(where)]
    return out


def fbm(rng: np.random.Generator, base: tuple[int, ...], octaves: int, coords: list[np.ndarray]) -> np.ndarray:
    """Octaves of value noise, lattice doubling and amplitude halving; normalised to [-1, 1]."""
    total, amp, norm = 0.0, 1.0, 0.0
    for o in range(octaves):
        total = total + amp * value_noise(rng, tuple(b << o for b in base), coords)
        norm += amp
        amp *= 0.5
    return total / norm


def plume(res, size, seed: int, scale: float, p: dict) -> np.ndarray:
    """Density at the voxel centres, shape (nz, ny, nx) (x fastest in memory), unnormalised."""
    nx, ny, nz = res
    sx, sy, sz = size
    rng = np.random.default_rng(seed)
    # Voxel centres in metres; broadcast as (z, y, x).
    x = ((np.arange(nx) + 0.5) / nx * sx)[None, None, :]
    y = ((np.arange(ny) + 0.5) / ny * sy)[None, :, None]
    z = ((np.arange(nz) + 0.5) / nz * sz)[:, None, None]
    u = [x / sx, y / sy, z / sz]
    s = np.maximum(y - p["source_height"], 0.0)
    rise = s / (sy - p["source_height"])  # 0 at the source, 1 at the top
    # The axis drifts with height (1-D noise of height only), more as it rises.
    drift_x = 0.18 * sx * rise * fbm(rng, (3,), 3, [y / sy])
    drift_z = 0.18 * sz * rise * fbm(rng, (3,), 3, [y / sy])
    # Domain warp: 3-D noise displacing the point across, growing with height.
    lat = (3, 6, 3)
    warp = (0.02 + 0.16 * rise) * sx
    wx = warp * fbm(rng, lat, 3, u)
    wz = warp * fbm(rng, lat, 3, u)
    dx = x + wx - (0.5 * sx + drift_x)
    dz = z + wz - (0.5 * sz + drift_z)
    d = np.sqrt(dx * dx + dz * dz)
    r0 = p["r0"]
    radius = scale * (r0 + p["spread"] * s)
    amp = (r0 / (r0 + p["spread"] * s)) ** p["thinning"]
    q = np.clip(1.0 - (d / radius) ** 2, 0.0, None)
    clumps = np.maximum(0.0, 1.0 + p["clump"] * fbm(rng, (4, 8, 4), 3, u))
    onset = smoothstep(np.clip((y - p["source_height"]) / 0.04 + 1.0, 0.0, 1.0))
    fade = smoothstep(np.clip((1.0 - y / sy) / 0.15, 0.0, 1.0))
    return (amp * q * clumps * onset * fade).astype(np.float64)


def occupancy(rho: np.ndarray) -> float:
    return float((rho > 0.01 * rho.max()).mean())


def write_vol(path: Path, rho: np.ndarray, lo, hi) -> None:
    nz, ny, nx = rho.shape
    head = b"VOL" + bytes([3]) + struct.pack("<iiiii", 1, nx, ny, nz, 1) + struct.pack("<6f", *lo, *hi)
    path.write_bytes(head + np.ascontiguousarray(rho, dtype="<f4").tobytes())


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--res", type=int, nargs=3, default=[48, 96, 48])
    ap.add_argument("--size", type=float, nargs=3, default=[1.0, 2.0, 1.0], help="box size, m")
    ap.add_argument("--min", type=float, nargs=3, default=[-0.5, 0.001, -0.5], help="box's lower corner in the scene (smoke-plume.toml: 1 mm above the floor), m")
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--occupancy", type=float, default=0.05)
    ap.add_argument("--out", type=Path, default=REPO / "scenes" / "smoke-plume.vol")
    a = ap.parse_args()
    params = {"source_height": 0.12, "r0": 0.06, "spread": 0.12, "thinning": 0.5, "clump": 0.5}
    # Occupancy grows with the radius scale: bisect on it (40 halvings: far below a voxel).
    lo, hi = 0.05, 4.0
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        if occupancy(plume(a.res, a.size, a.seed, mid, params)) < a.occupancy:
            lo = mid
        else:
            hi = mid
    rho = plume(a.res, a.size, a.seed, hi, params)
    rho /= rho.max()
    box_lo = np.array(a.min, dtype=float)
    write_vol(a.out, rho, box_lo, box_lo + np.array(a.size))
    occ = occupancy(rho)
    print(f"{a.out}: {a.res[0]} x {a.res[1]} x {a.res[2]}, {a.out.stat().st_size} bytes, radius scale {hi:.4f}")
    print(f"occupied (rho > 0.01 max): {occ:.4f} of the box ({int(round(occ * rho.size))} of {rho.size} voxels); "
          f"rho > 0.1: {(rho > 0.1).mean():.4f}; mean rho {rho.mean():.4f}, max {rho.max():.3f}")


if __name__ == "__main__":
    main()
