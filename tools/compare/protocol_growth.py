"""The protocol's ratio over time: does brume's error fall as fast as the peer's (issue 30)?

Usage: python tools/compare/protocol_growth.py OUT.json... (or A.json+B.json: one scene's
budgets measured apart) prints, for each protocol output with two budgets or more, the change
of the brume / Mitsuba ratio from the shortest budget to the longest with a 90 % bootstrap
interval; tools/compare/protocol.py writes the same into its JSON ("growth") and under its
table. The bootstrap resamples medians of 5 runs, which take few distinct values: the interval
is a guide to the medians' spread, not an exact confidence interval.
"""
from __future__ import annotations

import json
import sys

import numpy as np


def growth(rows: list[dict], times: list[float], draws: int = 4000, seed: int = 1) -> dict:
    """The ratio's change from the shortest budget to the longest, per metric: (brume / Mitsuba at
    the longest) / (brume / Mitsuba at the shortest), medians over runs as in `summarise`, with a
    90 % bootstrap interval (each renderer's runs at each budget resampled with replacement; a fixed
    seed). Issue 30 asks that the ratio not grow with time: with 5 runs a budget the medians move by
    several per cent, and only an interval that excludes 1 says the ratio grew (or fell)."""
    if len(times) < 2:
        return {}
    t0, t1 = min(times), max(times)
    rng = np.random.default_rng(seed)
    out = {"from_s": t0, "to_s": t1}
    for k in ("rel_rmse_nominal", "rel_rmse_bin4_nominal"):
        groups = [np.array([r[k] for r in rows if r["renderer"] == who and r["budget_s"] == t])
                  for who in ("brume", "mitsuba") for t in (t0, t1)]
        if any(len(g) == 0 for g in groups) or any(np.median(g) <= 0 for g in groups):
            continue

        def change(b0, b1, m0, m1):
            return (np.median(b1) / np.median(m1)) / (np.median(b0) / np.median(m0))

        draws_ = [change(*(g[rng.integers(0, len(g), len(g))] for g in groups)) for _ in range(draws)]
        lo, hi = np.quantile(draws_, [0.05, 0.95])
        out[k] = {"growth": float(change(*groups)), "lo90": float(lo), "hi90": float(hi),
                  "brume_falls": float(np.median(groups[0]) / np.median(groups[1])),
                  "mitsuba_falls": float(np.median(groups[2]) / np.median(groups[3]))}
    return out


def growth_line(g: dict) -> str:
    """One line for the table's foot: the growth per metric with its interval."""
    parts = []
    for k, name in (("rel_rmse_nominal", "per pixel"), ("rel_rmse_bin4_nominal", "4x4")):
        if k in g:
            x = g[k]
            parts.append(f"{name} {x['growth']:.3f}x [{x['lo90']:.3f}-{x['hi90']:.3f}] (brume's error falls "
                         f"{x['brume_falls']:.3f}x, Mitsuba's {x['mitsuba_falls']:.3f}x)")
    if not parts:
        return ""
    return (f"The ratio from {g['from_s']:g} to {g['to_s']:g} s (90 % bootstrap interval over runs; "
            f"1 = no growth; sqrt of the budgets' ratio = {np.sqrt(g['to_s'] / g['from_s']):.3f}): " + "; ".join(parts) + "\n")


def table_row(arg: str, runs: list[dict]) -> str:
    """A markdown row: the ratios (brume / Mitsuba of the medians) per budget, per pixel and 4x4,
    then the growth per metric with its interval."""
    times = sorted({r["budget_s"] for r in runs})

    def ratio(t, k):
        med = [np.median([r[k] for r in runs if r["renderer"] == w and r["budget_s"] == t]) for w in ("brume", "mitsuba")]
        return med[0] / med[1]

    cells = [" / ".join(f"{ratio(t, k):.2f}x" for t in times) for k in ("rel_rmse_nominal", "rel_rmse_bin4_nominal")]
    g = growth(runs, times)
    grow = [f"{g[k]['growth']:.2f}x [{g[k]['lo90']:.2f}-{g[k]['hi90']:.2f}]" if k in g else "-"
            for k in ("rel_rmse_nominal", "rel_rmse_bin4_nominal")]
    name = " + ".join(p.split("/")[-1] for p in arg.split("+"))
    # The peer's speed on the host that measured it: hosts differ (wide SIMD helps Mitsuba's LLVM
    # kernels, not brume), so rows compare across hosts only with it beside them.
    spp = np.median([r["spp"] / r["wall_s"] for r in runs if r["renderer"] == "mitsuba" and "spp" in r] or [np.nan])
    return (f"| {name} | {' / '.join(f'{t:g}' for t in times)} | {cells[0]} | {cells[1]} | {grow[0]} | {grow[1]} "
            f"| {spp:.1f} |")


def main() -> None:
    # A+B: the runs of two outputs of one scene (its 10 s and its 60 s rows measured apart).
    # --table: one markdown row per argument instead of a sentence.
    table = "--table" in sys.argv[1:]
    if table:
        print("| output | T (s) | ratio per pixel | ratio 4x4 | growth per pixel [90 %] | growth 4x4 [90 %] | Mitsuba spp/s |")
        print("|---|---|---|---|---|---|---|")
    for arg in (a for a in sys.argv[1:] if a != "--table"):
        runs = [r for path in arg.split("+") for r in json.loads(open(path).read())["runs"]]
        times = sorted({r["budget_s"] for r in runs})
        if table:
            print(table_row(arg, runs))
        else:
            line = growth_line(growth(runs, times))
            why = "one budget only" if len(times) < 2 else "no budget with both renderers' runs"
            print(f"{arg}: {line.strip() or why}")


if __name__ == "__main__":
    main()
