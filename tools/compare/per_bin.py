"""brume's image of a chromatic scene rendered one film bin at a time: a check of its spectral
sampling that needs no other renderer.

    python tools/compare/per_bin.py SCENE --renders 8 --passes 64 --out DIR [--set KEY=VALUE ...]

Each render of bin i is the scene with `film.bins = 1` over bin i's wavelengths
(`film.lambda_min`, `film.lambda_max` from the scene's own bins): every medium is then grey, so
no path carries spectral weights (no channel picks, no ratios of per-bin transmittances). A
light's power is given for its whole spectrum, and a one-bin film would put all of it into that
bin, so each light's power key is scaled by the share of its spectrum in bin i (brume's bin
average over the sum of them, mitsuba_scene.light_spectrum). Lights, media and surfaces are
constant within a bin, so the bins' images add up to the spectral image exactly (in
expectation): DIR/brume-K.exr is render K's sum, for column_ratio.py or density_check.py check.

Lights must give their amount as radiant `power` or `irradiance` (the share of a photometric
amount would need the bins' luminous efficacy, a profile's its table; emitting shapes and
spectral lines are not split either: all refused, not approximated). The renders use the
scene's own [integrator] settings, render K the seed --seed + K.
"""
from __future__ import annotations

import argparse
import subprocess
import sys
import tomllib
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import mitsuba_scene  # noqa: E402
from compare import read_rgb, write_rgb  # noqa: E402
from density_check import LUMA  # noqa: E402

RADIANT = ("power", "irradiance")
OTHER = ("luminous_flux", "illuminance", "intensity", "profile")


def light_shares(desc: dict, base: Path, grid: mitsuba_scene.Grid) -> list[tuple[str, float, np.ndarray]]:
    """Per light: its amount's key, the amount, and its spectrum's share of each film bin."""
    out = []
    for k, light in enumerate(desc.get("lights", [])):
        keys = [key for key in light if key in RADIANT]
        if any(key in light for key in OTHER) or len(keys) != 1:
            raise SystemExit(f"lights.{k}: needs exactly one amount of {RADIANT} and no {OTHER} (has {sorted(light)})")
        shares = mitsuba_scene.light_spectrum(desc, base, light.get("spectrum"), grid) * grid.width
        out.append((keys[0], float(light[keys[0]]), shares))
    return out


def light_sets(shares: list[tuple[str, float, np.ndarray]], i: int) -> list[str]:
    """brume --set edits giving each light (of `light_shares`) its share of bin `i`."""
    return [f"lights.{k}.{key}={amount * float(s[i])!r}" for k, (key, amount, s) in enumerate(shares)]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene", type=Path)
    ap.add_argument("--out", type=Path, required=True)
    ap.add_argument("--renders", type=int, default=4)
    ap.add_argument("--passes", type=int, default=64)
    ap.add_argument("--seed", type=int, default=100)
    ap.add_argument("--brume", default="target/release/brume")
    ap.add_argument("--set", action="append", default=[], help="brume --set KEY=VALUE for every render")
    a = ap.parse_args()
    desc = tomllib.loads(a.scene.read_text())
    grid = mitsuba_scene.Grid(desc.get("film", {}))
    spectra = [light.get("spectrum") for light in desc.get("lights", [])]
    if any(isinstance(sp, dict) and ("line" in sp or "lines" in sp) for sp in spectra):
        raise SystemExit("spectral lines add bins of their own: not split here")
    if any("emit" in shape for shape in desc.get("shapes", [])):
        raise SystemExit("emitting shapes: not split here")
    shares = light_shares(desc, a.scene.parent, grid)
    a.out.mkdir(parents=True, exist_ok=True)
    for k in range(a.renders):
        total = None
        for i in range(grid.n):
            lo, hi = grid.edges[i], grid.edges[i + 1]
            out = a.out / f"bin-{i}.exr"
            cmd = [a.brume, "render", str(a.scene), "--seed", str(a.seed + k), "--passes", str(a.passes), "--quiet",
                   "-o", str(out), "--set", "film.bins=1", "--set", f"film.lambda_min={float(lo)!r}",
                   "--set", f"film.lambda_max={float(hi)!r}"]
            for s in a.set + light_sets(shares, i):
                cmd += ["--set", s]
            subprocess.run(cmd, check=True)
            img = read_rgb(out)
            total = img if total is None else total + img
        write_rgb(a.out / f"brume-{k}.exr", total)
        y = float((total @ LUMA).sum())
        print(f"render {k + 1}/{a.renders}: {grid.n} bins, image sum of Y {y:.6g}", flush=True)


if __name__ == "__main__":
    main()
