"""A renderer's bias against a reference, its own noise and the reference's removed.

    python tools/compare/bias.py --renders A.exr B.exr --reference-halves R1.exr R2.exr
    python tools/compare/bias.py --renders A.exr B.exr --paired C.exr D.exr

A and B are long renders of one configuration with independent seeds; R1 and R2 the reference's
independent halves. With M = (A + B) / 2 and R = (R1 + R2) / 2, E (M - R)^2 is the squared bias
plus M's noise, E (A - B)^2 / 4, plus R's, E (R1 - R2)^2 / 4: subtracting both leaves the squared
bias, per pixel and of 4x4 bins (the protocol's metrics, tools/compare/protocol.py), printed as
an RMS relative to the reference's mean with the noise terms beside it. A radius's blur, for
one, is a bias of this kind: it becomes the error floor of long renders, which no number of
passes removes. Where the squared bias is below two of its standard errors (a bootstrap over
pixel blocks) it is printed as unresolved.

`--paired C D`: the difference of two configurations' biases instead, C and D rendered with
A's and B's seeds (a radius and twice it, say). Renders of one seed share their random numbers,
so neither pair is a reference for the other; the seeds' differences A - C and B - D are
independent, and the squared mean difference less its noise, E ((A - C) - (B - D))^2 / 4, is
the squared difference of the biases. Much sharper than two biases against a reference whose
own noise is larger than either.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))
from compare import bin4, read_rgb  # noqa: E402


def squared_bias(a: np.ndarray, b: np.ndarray, r1: np.ndarray, r2: np.ndarray, mean: float | None = None) -> dict:
    """The squared bias of the renders (a, b) against the reference halves (r1, r2), per pixel
    and binned, relative to `mean` squared (default the reference's mean), and the noise terms
    removed."""
    m, r = 0.5 * (a + b), 0.5 * (r1 + r2)
    mean = float(r.mean()) if mean is None else mean
    out = {"mean": mean}
    for name, f in (("pixel", lambda x: x), ("binned", bin4)):
        mse = float(np.mean((f(m) - f(r)) ** 2))
        noise = float(np.mean((f(a) - f(b)) ** 2) / 4)
        ref_noise = float(np.mean((f(r1) - f(r2)) ** 2) / 4)
        out[name] = {"bias2": (mse - noise - ref_noise) / mean**2, "mse": mse / mean**2,
                     "noise": noise / mean**2, "reference_noise": ref_noise / mean**2}
    return out


def paired_difference(a, b, c, d) -> dict:
    """The squared difference of the biases of (a, b) and (c, d), rendered pairwise with the
    same seeds, relative to the mean of c and d squared: `squared_bias` of the seeds'
    differences against a reference of zeros (which has no noise)."""
    zero = np.zeros_like(a)
    return squared_bias(a - c, b - d, zero, zero, mean=float((0.5 * (c + d)).mean()))


def bootstrap_se(a, b, r1, r2, block: int = 8, boots: int = 200, seed: int = 1, paired: bool = False) -> dict:
    """Standard errors of the squared biases from a bootstrap over square blocks of pixels
    (the noise is correlated over a few pixels; blocks of 8 hold the 4x4 bins whole)."""
    h, w = a.shape[:2]
    hb, wb = h // block, w // block

    def tiles(x):
        x = x[: hb * block, : wb * block]
        return x.reshape(hb, block, wb, block, -1).swapaxes(1, 2).reshape(hb * wb, block, block, -1)

    t = [tiles(x) for x in (a, b, r1, r2)]
    rng = np.random.default_rng(seed)
    draws = {"pixel": [], "binned": []}
    for _ in range(boots):
        idx = rng.integers(0, hb * wb, hb * wb)
        # the tiles side by side in one row: bin4 then sees whole 4x4 bins of each tile
        draw = [np.concatenate(list(x[idx]), axis=1) for x in t]
        s = paired_difference(*draw) if paired else squared_bias(*draw)
        for k in draws:
            draws[k].append(s[k]["bias2"])
    return {k: float(np.std(v)) for k, v in draws.items()}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--renders", nargs=2, required=True, metavar=("A", "B"))
    group = ap.add_mutually_exclusive_group(required=True)
    group.add_argument("--reference-halves", nargs=2, metavar=("R1", "R2"))
    group.add_argument("--paired", nargs=2, metavar=("C", "D"), help="another configuration's renders of A's and B's seeds")
    ap.add_argument("--json", help="write the figures here too")
    args = ap.parse_args(argv)
    paired = args.paired is not None
    imgs = [read_rgb(Path(p)) for p in (*args.renders, *(args.paired or args.reference_halves))]
    res = paired_difference(*imgs) if paired else squared_bias(*imgs)
    se = bootstrap_se(*imgs, paired=paired)
    what = "the biases differ by" if paired else "bias"
    for k in ("pixel", "binned"):
        s = res[k]
        res[k]["bias2_se"] = se[k]
        rms = f"{np.sqrt(max(s['bias2'], 0.0)):.3%}"
        resolved = "" if s["bias2"] > 2 * se[k] else " (unresolved: under 2 standard errors)"
        print(f"{k}: {what} {rms} of the mean{resolved}; squared {s['bias2']:.3e} +- {se[k]:.1e}, "
              f"of an MSE {s['mse']:.3e} less the renders' noise {s['noise']:.3e} and the "
              f"reference's {s['reference_noise']:.3e}")
    if args.json:
        Path(args.json).write_text(json.dumps(res, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
