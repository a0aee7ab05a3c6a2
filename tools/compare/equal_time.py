"""brume against itself at equal wall time: variants of one scene (other binaries, other --set
edits), each rendered `brume render SCENE --time T --seed S` for every seed, the variants in
turn (reversed on every other seed, so that a drift of the machine is charged to all alike).

    python tools/compare/equal_time.py SCENE --time 10 --seeds 1,2,3,4 \
        --variant auto=target/release/brume \
        --variant ri2=target/release/brume:integrator.radius_indirect=0.02344 \
        [--reference-halves A.exr B.exr]

With --reference-halves each image is scored as protocol.py scores it (relative RMSE per pixel
and of 4x4 bins against the halves' mean, their own noise removed, scaled to the nominal time):
noise and bias. Without, each variant's noise is the standard deviation across the seeds'
images (per pixel and of 4x4 bins, relative to the images' mean, times sqrt(median wall / T)):
noise only, for scenes without an independent reference. The first variant is the baseline of
the printed ratios. No Mitsuba here: the peer's figure comes from protocol.py.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from compare import bin4, read_rgb  # noqa: E402
from protocol import halves, scores  # noqa: E402
from protocol_render import brume_cmd, run_timed  # noqa: E402


def seed_noise(images: list[np.ndarray], walls: list[float], budget: float) -> tuple[float, float]:
    """Relative noise across seeds (per pixel, 4x4-binned), scaled to the nominal budget."""
    a = np.array(images, dtype=np.float64)
    m = float(a.mean())
    s = np.sqrt(float(np.median(walls)) / budget)
    per_pixel = np.sqrt(np.mean(a.var(axis=0, ddof=1))) / m
    b = np.array([bin4(x) for x in a])
    return float(per_pixel * s), float(np.sqrt(np.mean(b.var(axis=0, ddof=1))) / m * s)


def scored(img: np.ndarray, ref: dict, wall: float, budget: float) -> tuple[float, float]:
    """protocol.py's relative RMSE per pixel and 4x4, the reference's noise removed, at the
    nominal budget."""
    s = scores(img, ref, wall, budget)
    return s["rel_rmse_nominal"], s["rel_rmse_bin4_nominal"]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene", type=Path)
    ap.add_argument("--time", type=float, required=True)
    ap.add_argument("--seeds", default="1,2,3,4")
    ap.add_argument("--variant", action="append", required=True, help="LABEL=BINARY[:KEY=V,KEY=V]")
    ap.add_argument("--reference-halves", nargs=2, type=Path)
    ap.add_argument("--work", type=Path, default=Path("/tmp"))
    a = ap.parse_args()
    variants = []
    for v in a.variant:
        label, _, rest = v.partition("=")
        binary, _, sets = rest.partition(":")
        variants.append((label, binary, [s for s in sets.split(",") if s]))
    ref = halves(*(read_rgb(p) for p in a.reference_halves)) if a.reference_halves else None
    seeds = [int(s) for s in a.seeds.split(",")]
    images = {label: [] for label, _, _ in variants}
    walls = {label: [] for label, _, _ in variants}
    for i, seed in enumerate(seeds):
        for label, binary, sets in variants if i % 2 == 0 else variants[::-1]:
            out = a.work / f"equal-time-{label}.exr"
            rec = run_timed(brume_cmd(binary, a.scene, seed, out, sets, ["--time", f"{a.time:g}"]))
            img = read_rgb(out)
            walls[label].append(rec["wall_s"])
            images[label].append(scored(img, ref, rec["wall_s"], a.time) if ref else img)
            extra = " rel RMSE %.5g (4x4 %.5g)" % images[label][-1] if ref else ""
            print(f"seed {seed} {label}: wall {rec['wall_s']:.2f} s{extra}", flush=True)
    figures = {}
    for label in images:
        if ref:
            r = np.array(images[label])
            figures[label] = (float(np.median(r[:, 0])), float(np.median(r[:, 1])))
        else:
            figures[label] = seed_noise(images[label], walls[label], a.time)
    base = figures[variants[0][0]]
    what = "median rel RMSE" if ref else "noise across seeds"
    for label, (p, b) in figures.items():
        print(f"{label}: {what} {p:.5g} / {b:.5g} (per pixel / 4x4), ratio {p / base[0]:.3f} / {b / base[1]:.3f}")


if __name__ == "__main__":
    main()
