"""A tuner's automatic choices scored on the budget grids of budget_grid.py, without rendering
the choices again: a quick screen for a change to the automatic budgets before the protocol
(docs/performance.md, "The block model at the film's scale").

    python tools/compare/grid_score.py --brume BIN [--brume BIN2 ...] --seeds 1,2,3,4,5 \
        fog-cube=scenes/.x-fog-cube.toml height-fog=tools/compare/scenes/.x-height-fog.toml ...

For each NAME=SCENE (SCENE with its [integrator] table stripped, as the protocol renders it) and
seed, `brume render SCENE --passes 1 --seed S --verbose` prints the choice (q, forward rays,
camera paths). Its efficiency is read off the screening grid docs/images/protocol/budget-grid/
NAME.json: interpolated linearly in log forward rays and log camera paths between the grid's
points (clamped at its edges), per pixel and 4x4-binned; the seeds' geometric mean over the
grid's best is printed, and "both" (the geometric mean of the two, the tuner's criterion). q is
not interpolated: the grid holds one q, the seeds' median when it was measured. The grid's
figures carry their own noise (about 7-15 % each), and its best is biased up by it: a screen,
not a measurement.
"""
from __future__ import annotations

import argparse
import json
import math
import re
import subprocess
import tempfile
from pathlib import Path

GRIDS = Path(__file__).resolve().parents[2] / "docs" / "images" / "protocol" / "budget-grid"
CHOSEN = re.compile(r"forward_rays = (\d+), camera_samples = (\d+)")


def load_grid(path: Path) -> dict:
    """(forward rays, camera paths) -> (per-pixel, binned efficiency) of a screening grid."""
    rows = json.loads(path.read_text())["rows"]
    out = {}
    for r in rows.values():
        c = r["config"]
        eff = [r[k]["efficiency"] if isinstance(r[k], dict) else r[k] for k in ("pixel", "binned")]
        out[(c["forward_rays"], c["camera_samples"])] = tuple(eff)
    return out


def _weights(axis: list, x: float) -> list:
    lx, l = [math.log(v) for v in axis], math.log(x)
    if l <= lx[0]:
        return [(axis[0], 1.0)]
    if l >= lx[-1]:
        return [(axis[-1], 1.0)]
    i = max(j for j in range(len(axis)) if lx[j] <= l)
    t = (l - lx[i]) / (lx[i + 1] - lx[i])
    return [(axis[i], 1.0 - t), (axis[i + 1], t)]


def efficiency(grid: dict, rays: float, paths: float) -> tuple:
    """The grid's efficiencies at (rays, paths), log-linear between its complete rows."""
    paths_axis = sorted({s for _, s in grid})
    rays_axis = sorted({n for n, _ in grid if all((n, s) in grid for s in paths_axis)})
    logs = [0.0, 0.0]
    for n, wn in _weights(rays_axis, rays):
        for s, ws in _weights(paths_axis, paths):
            for k in range(2):
                logs[k] += wn * ws * math.log(grid[(n, s)][k])
    return tuple(math.exp(v) for v in logs)


def best(grid: dict) -> tuple:
    return (
        max(v[0] for v in grid.values()),
        max(v[1] for v in grid.values()),
        max(math.sqrt(v[0] * v[1]) for v in grid.values()),
    )


def score(grid: dict, choices: list) -> tuple:
    """Per pixel, binned and both: the choices' geometric mean efficiency over the grid's best."""
    effs = [efficiency(grid, n, s) for n, s in choices]
    gm = [math.exp(sum(math.log(e[k]) for e in effs) / len(effs)) for k in range(2)]
    bp, bb, bboth = best(grid)
    return gm[0] / bp, gm[1] / bb, math.sqrt(gm[0] * gm[1]) / bboth


def choice(brume: str, scene: str, seed: int) -> tuple:
    with tempfile.TemporaryDirectory() as tmp:
        out = subprocess.run(
            [brume, "render", scene, "--passes", "1", "--seed", str(seed), "--verbose",
             "-o", str(Path(tmp) / "c.exr")],
            check=True, capture_output=True, text=True,
        )
    for line in (out.stdout + out.stderr).splitlines():
        m = CHOSEN.search(line)
        if "chosen" in line and m:
            return int(m.group(1)), int(m.group(2))
    raise SystemExit(f"{scene} seed {seed}: no automatic choice printed")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenes", nargs="+", help="NAME=SCENE")
    ap.add_argument("--brume", action="append", required=True)
    ap.add_argument("--seeds", default="1,2,3,4,5")
    ap.add_argument("--grids", default=str(GRIDS))
    args = ap.parse_args()
    seeds = [int(s) for s in args.seeds.split(",")]
    for item in args.scenes:
        name, scene = item.split("=", 1)
        grid = load_grid(Path(args.grids) / f"{name}.json")
        for brume in args.brume:
            cs = [choice(brume, scene, s) for s in seeds]
            p, b, both = score(grid, cs)
            listed = ", ".join(f"{n} x {s}" for n, s in cs)
            print(f"{name} [{brume}]: per pixel {p:.2f}, binned {b:.2f}, both {both:.2f} ({listed})")


if __name__ == "__main__":
    main()
