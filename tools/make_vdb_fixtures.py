#!/usr/bin/python3
"""Writes the OpenVDB test fixtures of src/medium/density/grid/vdb.rs into tests/data/.

Made with the real OpenVDB library through its Python binding: Debian 12's package
`python3-openvdb` 10.0.1-2 (OpenVDB 10.0.1, module `pyopenvdb`), installed with
`apt-get install python3-openvdb` and run with Debian's own /usr/bin/python3 (3.11):

    /usr/bin/python3 tools/make_vdb_fixtures.py

pyopenvdb.write uses OpenVDB's default file compression (Blosc + active mask, as Houdini's
default files), so every fixture here is Blosc-compressed; tools/make_vdb_compression_fixtures.cpp
writes the zip and uncompressed ones. The files carry a random UUID, so they differ from run to
run in those bytes only. Files written:

- vdb_density.vdb: float grid "density", active index box i 3..=7, j -2..=1, k 5..=7
  (5 x 4 x 3), value 0.1 * (a + 2b + 3c) + 1 with (a, b, c) = (i - 3, j + 2, k - 5), except a
  hole at (5, -1, 6) made inactive with the stored value 9 (the reader must use the background,
  0); transform: voxel size 0.5, translation (1, -2, 0.25) (UniformScaleTranslateMap).
- vdb_grids.vdb: several grids, for name look-up and the other cases:
  "tiles": float, fill of (0,0,0)..(15,7,7) with 0.5 (two active 8^3 tiles, no leaves) plus
  voxel (16, 0, 0) = 2; voxel size 2 (UniformScaleMap).
  "temperature": float, background 0.25, voxels (0,0,0) = 1.5, (1,1,0) = 3.0; transform
  diag(0.5, 0.25, 2) + translation (1, 2, 3) (ScaleTranslateMap).
  "half": "temperature" saved as half floats (saveFloatAsHalf), which vdb-rs 0.6 misreads.
  "tiles_instance": a shallow copy of "tiles", written as an instance of it (no tree of its own).
  "velocity": a vec3s grid with one voxel (not a float grid).
  "empty": a float grid with no active voxel.
- vdb_bad.vdb: float grids "negative" ((1,2,3) = -0.5), "nan" ((0,0,1) = NaN) and
  "inf" ((2,0,0) = +inf), each next to ordinary voxels of value 1.
- vdb_far.vdb: float grid "density" with voxels (0,0,0) and (100000,100000,100000): dense
  samples would need 4 * 100001^3 bytes.
- vdb_transforms.vdb: float grids "rotated" (voxel size 0.5 then a 30 degree rotation about
  z: an AffineMap), "mirrored" (scale (-1, 1, 1) and translation (1, 0, 0): a
  ScaleTranslateMap with a negative voxel size on x) and "scale_only" (scale (1, 2, 3), no
  translation: a ScaleMap, which vdb-rs 0.6 cannot read).
"""

import math
import os

import pyopenvdb as vdb

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "data")


def float_grid(name, voxels, transform=None, background=0.0):
    grid = vdb.FloatGrid(background)
    grid.name = name
    acc = grid.getAccessor()
    for ijk, value in voxels:
        acc.setValueOn(ijk, value)
    if transform is not None:
        grid.transform = transform
    return grid


def density():
    voxels = []
    for k in range(5, 8):
        for j in range(-2, 2):
            for i in range(3, 8):
                a, b, c = i - 3, j + 2, k - 5
                voxels.append(((i, j, k), 0.1 * (a + 2 * b + 3 * c) + 1.0))
    t = vdb.createLinearTransform(0.5)
    t.translate((1.0, -2.0, 0.25))
    grid = float_grid("density", voxels, t)
    grid.getAccessor().setValueOff((5, -1, 6), 9.0)
    return [grid]


def grids():
    tiles = vdb.FloatGrid(0.0)
    tiles.name = "tiles"
    tiles.fill((0, 0, 0), (15, 7, 7), 0.5, True)
    tiles.getAccessor().setValueOn((16, 0, 0), 2.0)
    tiles.transform = vdb.createLinearTransform(2.0)
    m = [[0.5, 0, 0, 0], [0, 0.25, 0, 0], [0, 0, 2.0, 0], [1.0, 2.0, 3.0, 1]]
    temp = float_grid(
        "temperature",
        [((0, 0, 0), 1.5), ((1, 1, 0), 3.0)],
        vdb.createLinearTransform(m),
        background=0.25,
    )
    half = temp.deepCopy()
    half.name = "half"
    half.saveFloatAsHalf = True
    velocity = vdb.Vec3SGrid()
    velocity.name = "velocity"
    velocity.getAccessor().setValueOn((0, 0, 0), (1.0, 0.0, 0.0))
    empty = vdb.FloatGrid()
    empty.name = "empty"
    instance = tiles.copy()
    instance.name = "tiles_instance"
    return [tiles, instance, temp, half, velocity, empty]


def bad():
    ones = [((0, 0, 0), 1.0), ((3, 3, 3), 1.0)]
    return [
        float_grid("negative", ones + [((1, 2, 3), -0.5)]),
        float_grid("nan", ones + [((0, 0, 1), math.nan)]),
        float_grid("inf", ones + [((2, 0, 0), math.inf)]),
    ]


def far():
    return [float_grid("density", [((0, 0, 0), 1.0), ((100000,) * 3, 1.0)])]


def transforms():
    rot = vdb.createLinearTransform(0.5)
    rot.rotate(math.radians(30.0), vdb.Axis.Z)
    mirror = vdb.createLinearTransform(1.0)
    mirror.scale((-1.0, 1.0, 1.0))
    mirror.translate((1.0, 0.0, 0.0))
    scale = vdb.createLinearTransform(1.0)
    scale.scale((1.0, 2.0, 3.0))
    voxels = [((0, 0, 0), 1.0), ((1, 0, 0), 2.0)]
    return [
        float_grid("rotated", voxels, rot),
        float_grid("mirrored", voxels, mirror),
        float_grid("scale_only", voxels, scale),
    ]


def main():
    os.makedirs(OUT, exist_ok=True)
    files = {
        "vdb_density.vdb": density(),
        "vdb_grids.vdb": grids(),
        "vdb_bad.vdb": bad(),
        "vdb_far.vdb": far(),
        "vdb_transforms.vdb": transforms(),
    }
    for name, file_grids in files.items():
        path = os.path.join(OUT, name)
        vdb.write(path, grids=file_grids)
        kinds = ", ".join(f"{g.name} ({g.transform.typeName})" for g in file_grids)
        print(f"{path}: {os.path.getsize(path)} bytes: {kinds}")


if __name__ == "__main__":
    main()
