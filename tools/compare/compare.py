"""Equal-time comparison of brume and Mitsuba 3 on one scene: error versus wall-clock time.

Usage (from the repository root, with the venv of tools/compare/requirements.txt):
  .venv/bin/python tools/compare/compare.py scenes/fog-cube.toml --brume target/release/brume \
      --ref-seconds 120 --times 2 5 15 60 --out docs/images/perf-fog-cube

Method:
- Each renderer renders a long reference (its own, --ref-seconds) and one image per ladder time
  with a different seed. brume: `brume render --time T` (whole passes, so the real time runs a
  little over T); Mitsuba: `mi.render` in chunks of spp, each with a new seed, until T has
  elapsed. The recorded time is the measured wall-clock time (brume: the whole process,
  including scene load; Mitsuba: rendering only, after one warm-up render, so scene loading
  and set-up are not charged to it).
- Error: relative RMSE = RMSE over pixels and linear-sRGB channels / mean of the reference. Each
  renderer is measured against its own reference, so a scale difference between the two does
  not enter; the reference's own noise is removed assuming variance proportional to 1/time:
  MSE_true = MSE_measured / (1 + t / t_ref).
- Agreement: the two references are compared after fitting one scalar k (least squares) to
  Mitsuba's; k, the relative RMSE between the references, and the means of a few regions are
  written to <out>-agreement.json.
"""

from __future__ import annotations

import argparse
import csv
import json
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import OpenEXR

sys.path.insert(0, str(Path(__file__).parent))
import mitsuba_scene  # noqa: E402


def read_rgb(path: Path) -> np.ndarray:
    with OpenEXR.File(str(path)) as f:
        ch = f.channels()
        if "RGB" in ch:
            return np.asarray(ch["RGB"].pixels, dtype=np.float64)
        return np.stack([np.asarray(ch[c].pixels, dtype=np.float64) for c in "RGB"], axis=-1)


def brume_render(
    brume: str, scene: Path, seconds: float, seed: int, out: Path, sets: list[str] = ()
) -> tuple[np.ndarray, float]:
    cmd = [brume, "render", str(scene), "--time", str(seconds), "--seed", str(seed), "-o", str(out), "--quiet"]
    for s in sets:
        cmd += ["--set", s]
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True)
    return read_rgb(out), time.perf_counter() - t0


class Mitsuba:
    def __init__(self, scene: Path, variant: str, chunk_spp: int):
        import mitsuba as mi

        mi.set_variant(variant)
        self.mi = mi
        self.scene = mi.load_dict(mitsuba_scene.load(scene, chunk_spp))
        self.chunk = chunk_spp
        self.seed = 0
        self.render(0.0)  # warm-up (not timed)

    def render(self, seconds: float) -> tuple[np.ndarray, float, int]:
        acc = None
        chunks = 0
        t0 = time.perf_counter()
        while acc is None or time.perf_counter() - t0 < seconds:
            self.seed += 1
            img = np.asarray(self.mi.render(self.scene, spp=self.chunk, seed=self.seed), dtype=np.float64)
            acc = img if acc is None else acc + img
            chunks += 1
        return acc / chunks, time.perf_counter() - t0, chunks * self.chunk


def rel_rmse(img: np.ndarray, ref: np.ndarray, t: float, t_ref: float) -> float:
    mse = float(np.mean((img - ref) ** 2)) / (1.0 + t / t_ref)
    return float(np.sqrt(mse) / np.mean(ref))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene", type=Path)
    ap.add_argument("--brume", default="target/release/brume")
    ap.add_argument("--variant", default="scalar_spectral")
    ap.add_argument("--chunk-spp", type=int, default=4)
    ap.add_argument("--ref-seconds", type=float, default=120.0)
    ap.add_argument("--times", type=float, nargs="+", default=[2, 5, 15, 60])
    ap.add_argument("--brume-set", action="append", default=[], help="brume --set override for the ladder (the reference keeps the scene's settings: only for settings that leave the expected image unchanged, e.g. integrator.q)")
    ap.add_argument("--out", type=Path, required=True, help="prefix of the CSV, plot and JSON")
    a = ap.parse_args()
    a.out.parent.mkdir(parents=True, exist_ok=True)
    work = a.out.parent / (a.out.name + "-work")
    work.mkdir(exist_ok=True)

    mit = Mitsuba(a.scene, a.variant, a.chunk_spp)
    b_ref, b_ref_t = brume_render(a.brume, a.scene, a.ref_seconds, 1000, work / "brume-ref.exr")
    m_ref, m_ref_t, m_ref_spp = mit.render(a.ref_seconds)
    mit.mi.util.write_bitmap(str(work / "mitsuba-ref.exr"), m_ref.astype(np.float32))
    print(f"references: brume {b_ref_t:.1f} s, mitsuba {m_ref_t:.1f} s ({m_ref_spp} spp)", flush=True)

    k = float(np.sum(b_ref * m_ref) / np.sum(m_ref * m_ref))
    h, w, _ = b_ref.shape
    regions = {
        "whole": (0, w, 0, h),
        "centre": (w * 3 // 8, w * 5 // 8, h * 3 // 8, h * 5 // 8),
        "top-left": (0, w // 4, 0, h // 4),
        "bottom-right": (w * 3 // 4, w, h * 3 // 4, h),
    }
    agreement = {
        "k_mitsuba_to_brume": k,
        "rel_rmse_between_references": rel_rmse(k * m_ref, b_ref, 0.0, 1.0),
        "region_means_linear_srgb": {
            name: {
                "brume": b_ref[y0:y1, x0:x1].mean((0, 1)).tolist(),
                "mitsuba_scaled": (k * m_ref[y0:y1, x0:x1]).mean((0, 1)).tolist(),
            }
            for name, (x0, x1, y0, y1) in regions.items()
        },
        "brume_ref_seconds": b_ref_t,
        "mitsuba_ref_seconds": m_ref_t,
        "mitsuba_ref_spp": m_ref_spp,
        "mitsuba_variant": a.variant,
    }
    (a.out.parent / (a.out.name + "-agreement.json")).write_text(json.dumps(agreement, indent=2))
    print(json.dumps(agreement, indent=2), flush=True)

    rows = []
    for i, t in enumerate(a.times):
        img, bt = brume_render(a.brume, a.scene, t, 1 + i, work / f"brume-{t:g}.exr", a.brume_set)
        rows.append(("brume", t, bt, "", rel_rmse(img, b_ref, bt, b_ref_t)))
        img, mt, spp = mit.render(t)
        rows.append(("mitsuba", t, mt, spp, rel_rmse(img, m_ref, mt, m_ref_t)))
        print(rows[-2], rows[-1], flush=True)
    csv_path = a.out.parent / (a.out.name + ".csv")
    with csv_path.open("w", newline="") as f:
        wr = csv.writer(f)
        wr.writerow(["renderer", "budget_s", "measured_s", "spp", "rel_rmse"])
        wr.writerows(rows)
    plot(rows, a.out.parent / (a.out.name + ".png"), a.scene.stem)


def plot(rows, path: Path, title: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(5, 3.6), dpi=110)
    for name in ("brume", "mitsuba"):
        pts = [(r[2], r[4]) for r in rows if r[0] == name]
        ax.loglog(*zip(*pts), "o-", label=name)
    ax.set_xlabel("wall-clock seconds (2 shared cores)")
    ax.set_ylabel("relative RMSE vs own reference")
    ax.set_title(f"{title}: error vs time")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path)


if __name__ == "__main__":
    main()
