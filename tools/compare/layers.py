"""Per-layer equal-time errors of brume and Mitsuba 3: the `medium` layer (light the media
scatter towards the camera) and the `surface` layer (the surfaces seen through the media), on a
scene with one homogeneous medium, grey or not, whose surfaces stand in vacuum (fog-cube,
chromatic-fog, fog-room-laser).

Mitsuba has no layer split, so its layers come from two renders of equal CPU time:
- the scene as it is (the whole image W), and
- the surface layer S alone, by `surface_layer.py`: each camera ray walks through null
  boundaries to its first surface, and Mitsuba's own integrator (volpath) gives the radiance
  leaving that surface towards the camera, times the transmittance of the media in front of it.
The medium layer is M = W - S. Each render gets half the budget, so Mitsuba's layers cost the
same CPU time as brume's one render, which writes both layers. (Spent on S alone, Mitsuba's
surface error would be smaller by sqrt(2); M needs both renders and carries the noise of both.)

Errors: brume against its reference's layers (compare.py's reference halves in --work, whose
difference is subtracted as the reference's own noise); Mitsuba against its own layered
reference (compare.py's `mitsuba-ref.exr` and a surface reference of the same CPU time rendered
here), its noise removed with the spp ratio (`compare.own_share`), except in a scene with a
laser, where Mitsuba is measured against brume's reference as compare.py does (its own misses
most of the beam's light). Relative RMSE = RMSE / the
layer reference's mean. Run compare.py first with --work DIR for the references. Mitsuba is
charged as compare.py charges it (a Python glossy floor as if native, `--calib-seconds`).
`--brume-only` prints brume's layer errors alone (a variant's with `--brume-set`), and with
`--pairs N` the per-pixel noise of each layer at N passes.

  DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM-19.so .venv/bin/python tools/compare/layers.py \
      scenes/fog-cube.toml --work /tmp/cube-work --variant llvm_ad_spectral --runs 3 --times 5 15 60 \
      --out docs/images/perf-fog-cube-layers
"""

import argparse
import csv
import json
import math
import statistics
import sys
import tomllib
from pathlib import Path

import numpy as np
import OpenEXR

sys.path.insert(0, str(Path(__file__).resolve().parent))
import compare  # noqa: E402
import mitsuba_scene  # noqa: E402

LAYERS = ("medium", "surface")


def read_layers(path: Path) -> dict[str, np.ndarray]:
    """brume's EXR component layers, RGB per pixel."""
    with OpenEXR.File(str(path)) as f:
        ch = f.channels()
        return {k: np.asarray(ch[k].pixels, dtype=np.float64) for k in LAYERS}


def medium_sigma_t(scene: Path, desc: dict):
    """Mitsuba's sigma_t of the scene's only medium (a float, or a spectrum dict for a chromatic
    one), as mitsuba_scene translates it."""
    media = desc.get("media", {})
    if len(media) != 1:
        raise SystemExit(f"layers.py: needs exactly one medium, the scene has {len(media)}")
    (m,) = media.values()
    return mitsuba_scene.medium(desc, scene.parent, m, mitsuba_scene.Grid(desc.get("film", {})))["sigma_t"]


def mitsuba_layers(whole: np.ndarray, surface: np.ndarray) -> dict[str, np.ndarray]:
    """Mitsuba's layers from the whole image and the surface layer."""
    return {"medium": whole - surface, "surface": surface}


class SurfaceMitsuba(compare.Mitsuba):
    """compare.Mitsuba rendering the surface layer: its integrator wrapped in surface_layer."""

    def _dict(self, scene, spp, floor, drop):
        d = super()._dict(scene, spp, floor, drop)
        # A fresh sigma_t each time: a load consumes the dicts it is given.
        st = medium_sigma_t(Path(scene), tomllib.loads(Path(scene).read_text()))
        d["integrator"] = {"type": "surface_layer", "inner": d["integrator"], "sigma_t": st}
        return d


def compare_default(key: str) -> str:
    """What compare.py wrote before refs.json recorded `key`: its only behaviour then."""
    return {"integrator": "volpath", "spot_profile": "ramp"}[key]


def rel(e: float, mean: float) -> float:
    return math.sqrt(max(e, 0.0)) / mean


def brume_variant(a, b_ref: dict, b_var: dict) -> None:
    """brume's layer errors at each budget (rescaled to exactly the budget by sqrt(CPU s /
    budget)), and with --pairs N the relative standard deviation per pixel of each layer from
    two N-pass renders of other seeds (sqrt(mean (A - B)^2 / 2) / the layer's mean)."""
    label = " ".join(a.brume_set) or "scene settings"
    for i, t in enumerate(a.times):
        for run in range(a.runs):
            out = a.work / f"layers-brume-only-{t:g}.exr"
            _, bt = compare.brume_render(a.brume, a.scene, t, 5000 + i + 100 * run, out, a.brume_set, "cpu")
            img = read_layers(out)
            f = math.sqrt(bt / t)
            errs = " ".join(f"{k} {rel(compare.mse(img[k], b_ref[k]) - b_var[k], b_ref[k].mean()) * f:.4f}" for k in LAYERS)
            print(f"{label}: t={t:g} run {run}: {bt:.1f} CPU s, at {t:g} s: {errs}", flush=True)
    if a.pairs:
        imgs = []
        for seed in (11, 12):
            out = a.work / f"layers-pair-{seed}.exr"
            cmd = [a.brume, "render", str(a.scene), "--seed", str(seed), "--passes", str(a.pairs), "-o", str(out), "--quiet"]
            for s_ in a.brume_set:
                cmd += ["--set", s_]
            compare.run_child_cpu(cmd)
            imgs.append(read_layers(out))
        sds = " ".join(f"{k} {rel(compare.mse(imgs[0][k], imgs[1][k]) / 2.0, b_ref[k].mean()):.4f}" for k in LAYERS)
        print(f"{label}: {a.pairs} passes, relative sd per pixel: {sds}", flush=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene", type=Path)
    ap.add_argument("--brume", default="target/release/brume")
    ap.add_argument("--variant", default="llvm_ad_spectral")
    ap.add_argument("--work", type=Path, required=True, help="compare.py's --work folder (its references)")
    ap.add_argument("--times", type=float, nargs="+", default=[5, 15, 60])
    ap.add_argument("--runs", type=int, default=1)
    ap.add_argument("--surface-ref-seconds", type=float, default=None, help="default: the whole reference's CPU s")
    ap.add_argument("--integrator", choices=list(mitsuba_scene.INTEGRATORS), default="volpath", help="Mitsuba's, as compare.py's")
    ap.add_argument("--spot-profile", choices=list(mitsuba_scene.SPOT_PROFILES), default="ramp", help="as compare.py's")
    ap.add_argument("--calib-seconds", type=float, default=10.0, help="as compare.py: a Python glossy floor's native cost")
    ap.add_argument("--chunk-spp", type=int, default=4)
    ap.add_argument("--out", type=Path, default=None, help="prefix of the CSV and JSON (not with --brume-only)")
    ap.add_argument("--brume-only", action="store_true", help="brume's layer errors only (with --brume-set: a variant's), printed")
    ap.add_argument("--brume-set", action="append", default=[], help="brume --set KEY=VALUE (repeatable), --brume-only")
    ap.add_argument("--pairs", type=int, default=None, help="--brume-only: also two renders of this many passes; their layers' relative sd")
    a = ap.parse_args()
    if not a.brume_only and a.out is None:
        ap.error("--out is needed (or --brume-only)")
    if a.brume_set and not a.brume_only:
        ap.error("--brume-set needs --brume-only (Mitsuba renders the scene as it is)")

    desc = tomllib.loads(a.scene.read_text())
    sigma_t = medium_sigma_t(a.scene, desc)
    lasers = any(light.get("type") == "laser" for light in desc.get("lights", []))
    meta = json.loads((a.work / "refs.json").read_text())
    if meta["mitsuba"].get("clock") != "cpu" or meta["brume"].get("clock") != "cpu":
        raise SystemExit("layers.py: the references must be timed on the cpu clock")

    # brume's reference layers and their noise (halves).
    ha, hb = read_layers(a.work / "brume-ref-a.exr"), read_layers(a.work / "brume-ref-b.exr")
    b_ref = {k: 0.5 * (ha[k] + hb[k]) for k in LAYERS}
    b_var = {k: compare.mse(ha[k], hb[k]) / 4.0 for k in LAYERS}

    if a.brume_only:
        brume_variant(a, b_ref, b_var)
        return
    # Mitsuba: the whole scene and its surface layer, each with its reference.
    kw = {"clock": "cpu", "integrator": a.integrator, "spot_profile": a.spot_profile}
    for key, want in (("integrator", a.integrator), ("spot_profile", a.spot_profile)):
        if meta["mitsuba"].get(key, compare_default(key)) != want:
            raise SystemExit(f"layers.py: the Mitsuba reference was rendered with {key} {meta['mitsuba'].get(key)}, not {want}")
    whole = compare.Mitsuba(a.scene, a.variant, a.chunk_spp, "exact", [], a.calib_seconds, None, **kw)
    import surface_layer  # after compare.Mitsuba has set mitsuba's variant

    surface_layer.register()
    surf = SurfaceMitsuba(a.scene, a.variant, a.chunk_spp, "exact", [], a.calib_seconds, None, **kw)
    whole.seed, surf.seed = 10**7, 2 * 10**7
    w_ref, w_ref_spp = compare.read_rgb(a.work / "mitsuba-ref.exr"), meta["mitsuba"]["spp"]
    s_path = a.work / "mitsuba-surface-ref.exr"
    if "mitsuba_surface" in meta and s_path.exists():
        s_ref, s_ref_spp = compare.read_rgb(s_path), meta["mitsuba_surface"]["spp"]
    else:
        s_ref, s_t, s_ref_spp = surf.render_wall(a.surface_ref_seconds or meta["mitsuba"]["seconds"])
        compare.write_rgb(s_path, s_ref)
        meta["mitsuba_surface"] = {"seconds": s_t, "spp": s_ref_spp, "clock": "cpu", "integrator": a.integrator}
        (a.work / "refs.json").write_text(json.dumps(meta, indent=2))
    m_ref = mitsuba_layers(w_ref, s_ref)
    # The decomposition checked on the references: each layer's mean, brume's over Mitsuba's,
    # and their relative RMSE after scaling Mitsuba's to brume's mean.
    agreement = {
        "sigma_t": sigma_t if isinstance(sigma_t, float) else "spectrum",
        **{
            f"{k}_mean_brume_over_mitsuba": float(b_ref[k].mean() / m_ref[k].mean())
            for k in LAYERS
        },
        **{
            f"{k}_rel_rmse_between_references": rel(
                compare.mse(b_ref[k], m_ref[k] * float(b_ref[k].mean() / m_ref[k].mean())), b_ref[k].mean()
            )
            for k in LAYERS
        },
        "surface_ref_spp": s_ref_spp,
        "whole_ref_spp": w_ref_spp,
    }
    print(json.dumps(agreement, indent=2), flush=True)

    rows = []
    for i, t in enumerate(a.times):
        for run in range(a.runs):
            out = a.work / f"layers-brume-{t:g}.exr"
            _, bt = compare.brume_render(a.brume, a.scene, t, 5000 + i + 100 * run, out, [], "cpu")
            img = read_layers(out)
            for k in LAYERS:
                e = compare.mse(img[k], b_ref[k]) - b_var[k]
                rows.append({"renderer": "brume", "run": run, "budget_s": t, "measured_s": bt, "layer": k,
                             "rel_rmse": rel(e, b_ref[k].mean())})
            w, wt, wspp = whole.render(t / 2)
            g, gt, gspp = surf.render(t / 2)
            lay = mitsuba_layers(w, g)
            share = {"surface": compare.own_share(gspp, s_ref_spp),
                     "medium": 0.5 * (compare.own_share(wspp, w_ref_spp) + compare.own_share(gspp, s_ref_spp))}
            for k in LAYERS:
                if lasers:
                    # As compare.py: Mitsuba's reference misses most of a laser's light, so its
                    # layers are measured against brume's (k = 1, the units'), whose noise is
                    # removed as for brume.
                    e, mean = compare.mse(lay[k], b_ref[k]) - b_var[k], b_ref[k].mean()
                else:
                    e, mean = compare.mse(lay[k], m_ref[k]) * share[k], m_ref[k].mean()
                rows.append({"renderer": "mitsuba", "run": run, "budget_s": t, "measured_s": wt + gt, "layer": k,
                             "rel_rmse": rel(e, mean), "spp": f"{wspp}+{gspp}"})
            print(f"run {run} t={t:g}: brume {bt:.1f} s, mitsuba {wt:.1f} + {gt:.1f} s ({wspp} + {gspp} spp)", flush=True)

    with (a.out.parent / (a.out.name + ".csv")).open("w", newline="") as f:
        wr = csv.DictWriter(f, fieldnames=["renderer", "run", "budget_s", "measured_s", "layer", "rel_rmse", "spp"])
        wr.writeheader()
        wr.writerows(rows)
    summary = {"agreement": agreement, "budgets": {}}
    for t in a.times:
        for k in LAYERS:
            b = [r for r in rows if r["renderer"] == "brume" and r["budget_s"] == t and r["layer"] == k]
            m = [r for r in rows if r["renderer"] == "mitsuba" and r["budget_s"] == t and r["layer"] == k]
            bs, ms = statistics.mean(r["measured_s"] for r in b), statistics.mean(r["measured_s"] for r in m)
            be, me = statistics.mean(r["rel_rmse"] for r in b), statistics.mean(r["rel_rmse"] for r in m)
            summary["budgets"].setdefault(f"{t:g}", {})[k] = {
                "brume_s": bs, "mitsuba_s": ms, "brume_rel_rmse": be, "mitsuba_rel_rmse": me,
                "brume_sd": statistics.stdev(r["rel_rmse"] for r in b) if len(b) > 1 else 0.0,
                "mitsuba_sd": statistics.stdev(r["rel_rmse"] for r in m) if len(m) > 1 else 0.0,
                "ratio": be / me, "ratio_equal_time": be / me * math.sqrt(bs / ms),
            }
    (a.out.parent / (a.out.name + "-summary.json")).write_text(json.dumps(summary, indent=2))
    print(json.dumps(summary["budgets"], indent=2))


if __name__ == "__main__":
    main()
