"""How well the automatic settings' pilots, which trace one pixel in four (every second row and
column), see the film's 4x4-binned variance (docs/performance.md, "The block model at the film's
scale").

    python tools/compare/lattice_bins.py SCENE --q Q --rays N --paths S --seeds 12 [--brume BIN]

Renders one pass of the fixed configuration per seed (1..SEEDS), then compares, over the seeds:
- the film's variance on 4x4 bins of the full image (what the protocol's binned error measures);
- the variance of the means of 2x2 blocks of lattice points (4 pixels' values in each 4x4
  area: what the tuner's block model measured until now);
- that block variance extrapolated to the film's bins, `1.25 VB - 0.25 V1` per block (V1 the
  block's points' mean variance): exact for white noise and for noise shared by a whole bin.
Each figure is the mean over bins (or blocks) of the per-bin variance across seeds, of the sum of
the image's channels. Needs numpy and OpenEXR (tools/compare/requirements.txt).
"""
from __future__ import annotations

import argparse
import subprocess
import tempfile
from pathlib import Path

import numpy as np

from compare import bin4, read_rgb


def lattice_estimates(stack: np.ndarray) -> dict:
    """Per-bin variances across the first axis of `stack` (seeds x height x width): the film's
    4x4 bins, the lattice's 2x2 blocks, and the blocks extrapolated to the film's bins."""
    n, h, w = stack.shape
    h4, w4 = h // 4 * 4, w // 4 * 4
    a = stack[:, :h4, :w4]

    def var(x):
        return x.var(axis=0, ddof=1)

    # The protocol's own 4x4 binning (compare.bin4), image by image.
    bins = np.stack([bin4(x)[..., 0] for x in a])
    lattice = a[:, ::2, ::2]
    blocks = lattice.reshape(n, h4 // 4, 2, w4 // 4, 2).mean(axis=(2, 4))
    points = var(lattice).reshape(h4 // 4, 2, w4 // 4, 2).mean(axis=(1, 3))
    return {
        "pixel": float(var(a).mean()),
        "film_bins": float(var(bins).mean()),
        "blocks": float(var(blocks).mean()),
        "extrapolated": float((1.25 * var(blocks) - 0.25 * points).mean()),
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene")
    ap.add_argument("--brume", default="target/release/brume")
    ap.add_argument("--q", required=True)
    ap.add_argument("--rays", required=True)
    ap.add_argument("--paths", required=True)
    ap.add_argument("--seeds", type=int, default=12)
    args = ap.parse_args()
    images = []
    with tempfile.TemporaryDirectory() as tmp:
        for seed in range(1, args.seeds + 1):
            out = Path(tmp) / f"s{seed}.exr"
            subprocess.run(
                [args.brume, "render", args.scene, "--passes", "1", "--seed", str(seed), "-q",
                 "-o", str(out), "--set", f"integrator.q={args.q}",
                 "--set", f"integrator.forward_rays={args.rays}",
                 "--set", f"integrator.camera_samples={args.paths}"],
                check=True,
            )
            images.append(read_rgb(out).sum(axis=2))
    e = lattice_estimates(np.stack(images))
    f = e["film_bins"]
    print(
        f"{args.scene} q={args.q} rays={args.rays} paths={args.paths}: pixel {e['pixel']:.4e}, "
        f"film bins {f:.4e}, blocks {e['blocks']:.4e} ({e['blocks'] / f:.2f}x), "
        f"extrapolated {e['extrapolated']:.4e} ({e['extrapolated'] / f:.2f}x)"
    )


if __name__ == "__main__":
    main()
