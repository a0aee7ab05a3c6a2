"""Fits cost weights to cost_passes.py's records: seconds per camera path, volume record,
forward ray, forward segment and gather hit, and optionally per pixel and spectral bin of a pass
(records that hold `pixel_bins`) or a constant per pass, by least
squares on the relative error with non-negative weights. Prints each scene's predicted /
measured times and the rms log error of the predicted ratios between one scene's passes (what
the tuner's choice depends on), in-sample and leaving each scene out of its own fit.

    python tools/compare/cost_fit.py passes.jsonl
"""
import json
import sys

import numpy as np

NAMES = ["paths", "volumes", "rays", "segments", "hits", "const", "pixel_bins"]
CURRENT = [5.0e-6, 8.0e-7, 2.5e-6, 0.0, 3.0e-7, 0.0, 0.0]  # COST_WEIGHTS (no segments, no per-pass part)


def nnls(a, b):
    """Least squares with non-negative weights: drop the most negative column until none is."""
    cols = list(range(a.shape[1]))
    while True:
        x, *_ = np.linalg.lstsq(a[:, cols], b, rcond=None)
        if (x >= 0).all():
            out = np.zeros(a.shape[1])
            out[cols] = x
            return out
        cols.pop(int(np.argmin(x)))


def main():
    recs = [json.loads(line) for line in open(sys.argv[1])]
    # The work line's order is paths, volumes, rays, hits, segments.
    w = np.array([[r["work_per_pass"][i] for i in (0, 1, 2, 4, 3)] + [1.0, r.get("pixel_bins", 0.0)]
                  for r in recs])
    t = np.array([r["sec_per_pass"] for r in recs])
    scenes = list(dict.fromkeys(r["scene"] for r in recs))
    of = {sc: [i for i, r in enumerate(recs) if r["scene"] == sc] for sc in scenes}

    def fit(mask, use):
        x = nnls((w[:, use] / t[:, None])[mask], np.ones(int(mask.sum())))
        out = np.zeros(len(NAMES))
        out[use] = x
        return out

    def within(rel):
        errs = [np.log(rel[i] / rel[i].mean()) for i in of.values()]
        return float(np.sqrt(np.mean(np.square(np.concatenate(errs)))))

    def show(weights, label, loo=None):
        rel = (w @ weights) / t
        print(label, " ".join(f"{n}={v:.3g}" for n, v in zip(NAMES, weights)))
        for sc in scenes:
            print(f"  {sc:15s} " + " ".join(f"{x:.2f}" for x in rel[of[sc]]))
        print(f"  rms log error within scenes {within(rel):.3f}" + (f", leaving the scene out {loo:.3f}" if loo else ""))

    show(np.array(CURRENT), "current")
    fits = [([0, 1, 2, 4], "refit, 4 counters"), ([0, 1, 2, 3, 4], "with segments"),
            ([0, 1, 2, 3, 4, 5], "with segments and a constant")]
    if w[:, 6].all():
        fits += [([0, 1, 2, 4, 6], "4 counters and pixels x bins"),
                 ([0, 1, 2, 4, 5], "4 counters and a constant")]
        # The tuner's weights as they are (one scale for them all) and a pass part beside them.
        both = np.column_stack([w @ np.array(CURRENT), w[:, 6]])
        x = nnls(both / t[:, None], np.ones(len(t)))
        kept = np.array(CURRENT) * x[0]
        kept[6] = x[1]
        print(f"the tuner's weights and a pass part: {x[1] / x[0]:.3g} per pixel and bin in their units")
        show(kept, "  as seconds")
    for use, label in fits:
        rel_loo = np.zeros(len(t))
        for sc in scenes:
            m = np.array([r["scene"] != sc for r in recs])
            rel_loo[~m] = (w[~m] @ fit(m, use)) / t[~m]
        show(fit(np.ones(len(t), bool), use), label, within(rel_loo))


if __name__ == "__main__":
    main()
