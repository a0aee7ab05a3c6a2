"""Automatic budgets against a grid of fixed ones: efficiency per pixel and 4x4-binned.

Issue 30 asks that the automatic budgets (q, forward rays, camera paths "auto") come within 5 %
of the best hand-tuned efficiency on every protocol scene. This measures it for one scene:

1. The automatic choice for each seed (`--seeds`): one pass rendered with the scene's defaults,
   its resolved `q`, `forward_rays` and `camera_samples` read from the result.
2. A grid of fixed budgets (`--rays` x `--paths` x `--scales`, q the median of the seeds'
   choices, the radius for scattered light the seeds' median multiple of the radius unless
   `--scales` names them) and every seed's own choice, each rendered in chunks of consecutive passes, m and 2m in turn
   (`pass_range`, one process, one seed, m so that a chunk takes at least `--chunk-seconds`):
   K independent chunk means per configuration, the radius fixed at its first pass's. The configurations are rendered in rounds (a few chunks of every one, then
   again), so a drift of the machine's speed during the run is charged to all of them alike.
3. Per configuration, the variance of one pass from the chunks' spread (`pass_variance`) for
   each pixel's RGB and each 4 x 4 block's mean, averaged over pixels and channels, over the
   square of the image's mean; the seconds of one pass, the slope of a chunk's wall time over
   its passes (a render call's own fixed cost left out, as a long render pays it once);
   efficiency = 1 / (variance x seconds), per pixel and binned, with a standard error from a
   bootstrap over the chunks.

The automatic settings' steady-state efficiency is the equal-time one of their choices over the
seeds: 1 / mean(V_i t_i) (a user gets one seed's choice; the expected MSE at equal time is the
mean). Their pilots' fixed cost is measured apart (a 1-pass render with automatic settings
against the same with its choice pinned), and the efficiency at a budget of T seconds is the
steady one times (T - pilots) / T.

The best of a grid is the largest of noisy estimates, so it is biased up by about one to two of
its standard errors: "auto / best" below 1 by that much is within the measurement.

Needs the `brume` Python package (`pip install ./python`). Usage:

    python tools/compare/budget_grid.py SCENE [--set KEY=VALUE ...] --out grid.json
    python tools/compare/budget_grid.py --table grid1.json grid2.json ...   (a markdown table)
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import time
from pathlib import Path

import numpy as np

from compare import bin4  # the protocol's 4 x 4 binning (edges cut)
from protocol_scene import parse_value


def pass_variance(means: np.ndarray, m: np.ndarray) -> float:
    """Relative variance of one pass from chunk means (axis 0) of m_j passes each: with the
    pass-weighted mean mu, sum_j m_j (x_j - mu)^2 / (K - 1) is unbiased for one pass's variance
    (E (x_j - mu)^2 = V / m_j - V / M); averaged over elements, over the square of the mean."""
    w = m.reshape((-1,) + (1,) * (means.ndim - 1)).astype(np.float64)
    mu = (w * means).sum(axis=0) / w.sum()
    k = means.shape[0]
    mean = float(mu.mean())
    if mean == 0.0 or k < 2:
        return float("nan")
    return float((w * (means - mu) ** 2).sum(axis=0).mean() / (k - 1)) / mean**2


def pass_seconds(seconds: np.ndarray, m: np.ndarray) -> float:
    """Seconds of one more pass: the slope of a chunk's wall time over its passes (chunks of two
    sizes), so that a render call's own fixed cost (building the run, the first pass's
    allocations) is not charged to the passes."""
    if len(set(m.tolist())) < 2:
        return float(seconds.sum() / m.sum())
    slope = np.polyfit(m.astype(np.float64), seconds, 1)[0]
    return float(slope)


def efficiency(means: np.ndarray, seconds: np.ndarray, m: np.ndarray, rng: np.random.Generator, boots: int = 200):
    """Per-pixel and binned efficiency 1 / (V t) of a configuration from its chunks' images
    (`means`, each the mean of its m_j passes) and wall seconds, each with a bootstrap standard
    error over the chunks (the time's own spread included)."""
    binned = np.stack([bin4(p) for p in means])
    t = pass_seconds(seconds, m)
    k = means.shape[0]
    idxs = [rng.integers(0, k, k) for _ in range(boots)]
    idxs = [i for i in idxs if len(set(m[i].tolist())) == len(set(m.tolist())) and len(set(i.tolist())) > 2]
    times = [pass_seconds(seconds[i], m[i]) for i in idxs]
    out = {}
    for name, stack in (("pixel", means), ("binned", binned)):
        v = pass_variance(stack, m)
        draws = [1.0 / (pass_variance(stack[i], m[i]) * ti) for i, ti in zip(idxs, times)]
        out[name] = {"variance": v, "efficiency": 1.0 / (v * t), "se": float(np.std(draws, ddof=1))}
    out["seconds"] = t
    out["passes"] = int(m.sum())
    return out


def choice(scene, seed: int) -> dict:
    res = scene.render(passes=1, seed=seed, progress=False)
    s = res.settings
    q = s["q"]
    return {
        "q": [float(x) for x in (q if isinstance(q, (list, tuple)) else [q])],
        "forward_rays": int(s["forward_rays"]),
        "camera_samples": int(s["camera_samples"]),
        # the radius for scattered light over the radius (the pilots choose 1 or 2)
        "indirect_scale": round(float(s["radius_indirect"]) / float(s["radius"]), 6),
        "radius": float(s["radius"]),
    }


def pinned(cfg: dict) -> dict:
    """The overrides that pin a configuration (one q per medium, in the scene's order)."""
    return {
        "integrator.q": cfg["q"][0] if len(cfg["q"]) == 1 else cfg["q"],
        "integrator.forward_rays": cfg["forward_rays"],
        "integrator.camera_samples": cfg["camera_samples"],
        # the pilots' radius for scattered light, or the grid's multiple of the radius
        "integrator.radius_indirect": cfg["indirect_scale"] * cfg["radius"],
        # the radius of every pass the first one's: a long grid would otherwise shrink it
        # past the consistent schedule's first passes, and charge the long configurations
        "integrator.radius_schedule": "fixed",
    }


def key(cfg: dict) -> str:
    qs = "/".join(f"{q:.3g}" for q in cfg["q"])
    k = f"q={qs} rays={cfg['forward_rays']} paths={cfg['camera_samples']}"
    # grids measured before the radius for scattered light was pinned have no scale
    return k + (f" indirect={cfg['indirect_scale']:g}x" if "indirect_scale" in cfg else "")


def timed_wall(fn) -> float:
    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


def measure(scene, configs: dict, args) -> dict:
    """Every configuration's chunks, rendered in rounds, and its efficiencies."""
    # One pass of each sizes its chunks: m passes (at least --chunk-seconds) and 2m in turn, so
    # that the slope of their times is one pass's, whatever a render call costs by itself.
    state = {}
    for k, cfg in configs.items():
        sc = scene.with_set(pinned(cfg))
        sc.render(pass_range=(0, 1), seed=args.grid_seed, progress=False)
        w = timed_wall(lambda: sc.render(pass_range=(0, 2), seed=args.grid_seed, progress=False)) / 2
        m = max(1, int(np.ceil(args.chunk_seconds / w)))
        chunks = int(min(args.max_chunks, max(args.min_chunks, round(args.seconds / (w * 1.5 * m)))))
        state[k] = {"scene": sc, "m": m, "total": chunks + chunks % 2, "images": [], "seconds": [], "sizes": [], "next": 0}
    for r in range(args.rounds):
        for k, st in state.items():
            lo = len(st["images"])
            hi = st["total"] if r == args.rounds - 1 else min(st["total"], 2 * round(st["total"] * (r + 1) / args.rounds / 2))
            for j in range(lo, hi):
                m = st["m"] * (1 + j % 2)
                t0 = time.perf_counter()
                res = st["scene"].render(pass_range=(st["next"], st["next"] + m), seed=args.grid_seed, progress=False)
                st["seconds"].append(time.perf_counter() - t0)
                st["next"] += m
                st["sizes"].append(m)
                st["images"].append(np.asarray(res.rgb, dtype=np.float64))
        print(f"round {r + 1}/{args.rounds} done", flush=True)

    rng = np.random.default_rng(7)
    rows = {}
    for k, st in state.items():
        rows[k] = {"config": configs[k], "chunk_passes": [st["m"], 2 * st["m"]],
                   "chunk_seconds": [float(x) for x in st["seconds"]], "chunk_sizes": [int(x) for x in st["sizes"]],
                   **efficiency(np.stack(st["images"]), np.asarray(st["seconds"]), np.asarray(st["sizes"]), rng)}

    return rows


def main(argv=None) -> int:
    if argv is None:
        argv = sys.argv[1:]
    if argv[:1] == ["--table"]:
        table(argv[1:])
        return 0
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE")
    ap.add_argument("--seeds", default="1,2,3,4,5")
    ap.add_argument("--rays", default="12500,25000,50000,100000,200000")
    ap.add_argument("--paths", default="1,2,4,8")
    ap.add_argument("--scales", default="", help="radii for scattered light over the radius, as 1,2 (default: the seeds' choices')")
    ap.add_argument("--configs", default="", help="Q:RAYS:PATHS[:SCALE],... in place of the grid (Q per medium as Q1/Q2; SCALE the radius for scattered light over the radius, default the seeds' median)")
    ap.add_argument("--seconds", type=float, default=10.0, help="target seconds per configuration")
    ap.add_argument("--chunk-seconds", type=float, default=0.8, help="least seconds of the smaller chunk")
    ap.add_argument("--min-chunks", type=int, default=8)
    ap.add_argument("--max-chunks", type=int, default=64)
    ap.add_argument("--rounds", type=int, default=4)
    ap.add_argument("--grid-seed", type=int, default=101, help="seed of the grid's passes")
    ap.add_argument("--out", required=True)
    args = ap.parse_args(argv)

    import brume  # noqa: PLC0415 (the package is needed only to run, not to import the helpers)

    overrides = {}
    for kv in args.set:
        k, _, v = kv.partition("=")
        overrides[k] = parse_value(v)  # TOML, as `brume render --set` reads it
    scene = brume.load(args.scene, set=overrides or None)

    seeds = [int(s) for s in args.seeds.split(",")]
    choices = {}
    for seed in seeds:
        choices[seed] = choice(scene, seed)
        print(f"seed {seed}: {key(choices[seed])}", flush=True)

    # The pilots' fixed cost: a 1-pass auto render against the same choice pinned, median of 3.
    seed0 = seeds[len(seeds) // 2]
    pin0 = scene.with_set(pinned(choices[seed0]))
    auto_w, pin_w = [], []
    for _ in range(3):
        auto_w.append(timed_wall(lambda: scene.render(passes=1, seed=seed0, progress=False)))
        pin_w.append(timed_wall(lambda: pin0.render(passes=1, seed=seed0, progress=False)))
    pilots = statistics.median(auto_w) - statistics.median(pin_w)
    print(f"pilots: {pilots:.3f} s (auto 1 pass {statistics.median(auto_w):.3f} s, pinned {statistics.median(pin_w):.3f} s)", flush=True)

    qs = [c["q"] for c in choices.values()]
    q_med = [float(np.median([q[i] for q in qs])) for i in range(len(qs[0]))]
    # The radius is the scene's (automatic: the same for every seed); the grid's radius for
    # scattered light is the seeds' median choice unless --scales names the multiples.
    radius = choices[seed0]["radius"]
    scale_med = float(np.median([c["indirect_scale"] for c in choices.values()]))
    scales = [float(x) for x in args.scales.split(",")] if args.scales else [scale_med]
    configs = {}
    if args.configs:
        # Named configurations in place of the grid (a confirmation run of a grid's best ones,
        # on another --grid-seed so that the best is not the one its own noise picked).
        for c in args.configs.split(","):
            q, n, s, *sc = c.split(":")
            cfg = {"q": [float(x) for x in q.split("/")], "forward_rays": int(n), "camera_samples": int(s),
                   "indirect_scale": float(sc[0]) if sc else scale_med, "radius": radius}
            configs[key(cfg)] = cfg
    else:
        for sc in scales:
            for n in (int(x) for x in args.rays.split(",")):
                for s in (int(x) for x in args.paths.split(",")):
                    cfg = {"q": q_med, "forward_rays": n, "camera_samples": s, "indirect_scale": sc, "radius": radius}
                    configs[key(cfg)] = cfg
    for c in choices.values():
        configs.setdefault(key(c), dict(c))

    rows = measure(scene, configs, args)
    result = {"scene": args.scene, "set": args.set, "choices": {str(s): c for s, c in choices.items()},
              "pilots_seconds": pilots, "rows": rows}
    result["summary"] = summarize(result)
    with open(args.out, "w") as f:
        json.dump(result, f, indent=1)
    print_table(result)
    return 0


def summarize(result: dict) -> dict:
    """The automatic choice against the best configuration measured, per pixel, binned, and by
    the tuner's own criterion (the product of both variances times the cost squared: the
    geometric mean of the two efficiencies, "both")."""
    rows, pilots = result["rows"], result["pilots_seconds"]
    for r in rows.values():
        r["both"] = {
            "efficiency": float(np.sqrt(r["pixel"]["efficiency"] * r["binned"]["efficiency"])),
            # relative errors add in quadrature, halved by the square root (treated as independent)
            "se": 0.5 * float(np.hypot(r["pixel"]["se"] / r["pixel"]["efficiency"], r["binned"]["se"] / r["binned"]["efficiency"]))
            * float(np.sqrt(r["pixel"]["efficiency"] * r["binned"]["efficiency"])),
        }
    summary = {}
    for metric in ("pixel", "binned", "both"):
        best = max(rows, key=lambda k: rows[k][metric]["efficiency"])
        # The automatic choice's equal-time efficiency over the seeds: 1 / mean(1 / e_i) (the
        # expected MSE at equal time is the mean of the seeds' V_i t_i).
        es = [rows[key(c)][metric]["efficiency"] for c in result["choices"].values()]
        auto = 1.0 / float(np.mean([1.0 / e for e in es]))
        best_e = rows[best][metric]["efficiency"]
        summary[metric] = {
            "best": best, "best_efficiency": best_e, "best_se": rows[best][metric]["se"],
            "auto_efficiency": auto, "auto_over_best": auto / best_e,
            "auto_over_best_at_10s": auto / best_e * max(0.0, (10.0 - pilots) / 10.0),
            "auto_over_best_at_60s": auto / best_e * max(0.0, (60.0 - pilots) / 60.0),
        }
    return summary


def table(paths: list[str]) -> None:
    """One line per scene: auto / best per metric, and with the pilots' cost at 10 and 60 s."""
    print("| scene | choices (seeds) | pilots | per pixel: auto / best [best] | 4x4: auto / best [best] | both | both at 10 s / 60 s |")
    print("|---|---|---|---|---|---|---|")
    for p in paths:
        with open(p) as f:
            res = json.load(f)
        sm = summarize(res)
        ch = "; ".join(sorted({key(c) for c in res["choices"].values()}))
        cells = []
        for metric in ("pixel", "binned"):
            s = sm[metric]
            cells.append(f"{s['auto_over_best']:.2f} [{s['best'].replace('q=', 'q ').replace('rays=', '').replace('paths=', '')}, "
                         f"+-{s['best_se'] / s['best_efficiency']:.0%}]")
        b = sm["both"]
        print(f"| {Path(p).stem} | {ch} | {res['pilots_seconds']:.2f} s | {cells[0]} | {cells[1]} | "
              f"{b['auto_over_best']:.2f} | {b['auto_over_best_at_10s']:.2f} / {b['auto_over_best_at_60s']:.2f} |")


def print_table(result: dict) -> None:
    rows = result["rows"]
    print(f"{'configuration':44s} {'passes':>6s} {'s/pass':>7s} {'eff pixel':>14s} {'eff 4x4':>14s}")
    for k, r in sorted(rows.items(), key=lambda kv: -kv[1]["pixel"]["efficiency"]):
        print(f"{k:44s} {r['passes']:6d} {r['seconds']:7.3f} "
              f"{r['pixel']['efficiency']:8.4g} ±{r['pixel']['se']:.2g} {r['binned']['efficiency']:8.4g} ±{r['binned']['se']:.2g}")
    for metric, s in summarize(result).items():
        print(f"{metric}: best {s['best']} {s['best_efficiency']:.4g} ± {s['best_se']:.2g}; auto {s['auto_efficiency']:.4g}; "
              f"auto/best {s['auto_over_best']:.3f} (with the pilots: {s['auto_over_best_at_10s']:.3f} at 10 s, "
              f"{s['auto_over_best_at_60s']:.3f} at 60 s)")


if __name__ == "__main__":
    sys.exit(main())
