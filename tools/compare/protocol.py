"""The fair equal-wall-time comparison of brume and Mitsuba 3 on one scene (issue 30, item 1).

Usage (from the repository root; the Mitsuba venv of tools/compare/requirements.txt):
  PY=/work/wt/cond-venv/bin/python
  $PY tools/compare/protocol.py scenes/fog-cube.toml --times 10 60 --runs 5 --out out/fog-cube
  $PY tools/compare/protocol.py scenes/fog-cube.toml --set media.fog.sigma_s=0.9 \
      --set media.fog.sigma_a=0.1 --times 10 60 --out out/fog-cube-a09
  $PY tools/compare/protocol.py scenes/fog-room-laser.toml --reference brume --times 10 --out out/room
tools/compare/protocol.sh is the full list the measurement runs.

The protocol, and why (issue 30's "Why": the project's earlier figures came from a harness that
favoured brume in several ways at once):
- ONE reference for both renderers, scale fixed at 1. Scoring each renderer against its own
  reference hides its bias (brume's blur over its radius, its spectral upsampling of textures):
  against an independent reference that bias is error, and it is what grows brume's ratio with
  time. The reference is Mitsuba's long render with its best sampler (--reference mitsuba), or
  brume's own long run where Mitsuba cannot converge (fog-room-laser's 2 mm laser, compare.py's
  docstring: --reference brume, with the scene's own settings), or two halves rendered
  elsewhere (--reference files --reference-halves A B: light_trace.py's independent light
  tracer, where Mitsuba reads high near chromatic-fog's spot and its `stratified` sampler
  reads a gradient on fog-cube). Each is rendered as two
  independent halves A, B (other seeds); the reference is their mean, and its own noise,
  E[(A - B)^2] / 4 per pixel, is subtracted from every MSE (recomputed on 4x4-binned images for
  the binned metric). Mitsuba's light spectra are in brume's units (mitsuba_scene.py), so the
  scale is 1; the ratio of sums ref / image (k) is printed only as a check. References live in
  the work folder with a JSON key (scene text, --set edits, source and its settings, renderer
  versions) and are reused only when the whole key matches: a reuse cannot mix sources.
- The wall clock on an idle machine, both renderers on all cores. CPU time per process charges
  contention unevenly on a busy machine and hides poor parallel efficiency; the wall clock is
  what a user waits. brume is timed as its whole process (`brume render --time T`: start-up,
  scene load and its automatic pilots included), Mitsuba around its mi.render calls only (scene
  load and JIT compilation excluded, after one untimed warm-up render): brume is charged more,
  the conservative side. brume's fixed cost (1 and 3 passes: w1 - (w3 - w1) / 2) is measured
  and printed. CPU seconds (brume: the child's rusage; Mitsuba: time.process_time, its LLVM
  threads run in this process) and CPU / wall are reported beside it. Both overrun T a little
  (brume renders whole passes, Mitsuba whole calls): RMSE is reported as measured and scaled to
  the nominal budget, RMSE * sqrt(t_actual / T) (error ~ 1 / sqrt(time)); the ratios use the
  scaled figures. The 1-minute load average is recorded before and after each run and a run
  that starts above 0.5 is flagged NOT IDLE (the harness first waits up to --settle seconds for
  the load its own previous run left to decay); the busy share of all CPUs over the second
  before each run (/proc/stat, while this process sleeps) is recorded too.
- The peer at its best: Mitsuba renders >= 64 samples per call (at 4 per call about 10 % of its
  time was single-threaded), and a pilot picks its sampler among independent, stratified,
  multijitter and ldsampler (stratified sampling was worth 1.33-1.36x in variance per sample on
  fog-cube). The pilot renders two images per sampler at --pilot-seconds on seeds no measured
  run uses; each sampler's per-pixel RMSE is sqrt(mean((A - B)^2) / 2), scaled to the pilot
  budget; the lowest wins and is named in every output. That scores noise alone, assuming every
  sampler unbiased, and on fog-cube `stratified` is not: against the independent light
  tracer it reads a gradient of +-0.5 % along the light (Mitsuba's `independent` and brume do
  not; docs/performance.md). A 4 s pilot cannot see a bias that small, so protocol.sh also
  measures `independent` in full (--sampler independent) wherever the reference is the tracer's. The integrator is volpathmis when a medium's coefficients vary with wavelength
  (spectral MIS), else volpath; spots get brume's exact soft edge; the glossy floor is brume's
  BSDF as a Python plugin, traced into Mitsuba's LLVM kernels (native speed, timed as is).
- brume with its DEFAULT settings: settings tuned on the very scene, reference and metric that
  is then reported overstate what a user gets. The scene's [integrator] table is stripped of
  every key but `max_depth` (the only one that defines the image rather than tunes the
  estimator: it truncates the transported light, and Mitsuba's max_depth mirrors it); the
  stripped scene is a temporary dot-file beside the scene (so relative paths still resolve),
  deleted at exit. --brume-settings scene keeps the table; --brume-set KEY=VALUE adds tuned
  values; both are labelled as tuned in every output.
- Metrics: per-pixel RMSE and 4x4-binned RMSE (brume's noise is low-frequency, since one
  pass's forward rays are shared by all pixels: the binned figure shows it), relative to the
  reference's mean, with the reference's noise removed; --runs (>= 5 for a measurement) with
  other seeds per budget; median and min-max, and the brume / Mitsuba ratio of the medians.
- --set KEY=VALUE edits the scene for BOTH renderers (brume: its own --set; Mitsuba: the parsed
  scene before translation), e.g. fog-cube at albedo 0.9.

Modules: protocol_scene.py (--set edits, the stripped [integrator], what cannot be mapped),
protocol_render.py (idleness, the host, timed brume and Mitsuba renders, the sampler pilot),
protocol_growth.py (the ratio's change over the budgets, with its interval), this file
(reference, scores, runs, outputs).

Outputs: <out>.json (everything: runs, pilot, reference, commands, loads, the host's CPU, SIMD
level and Dr.Jit's LLVM target, since a ratio holds for its host only; the ratio's growth),
<out>.md (table rows for docs/performance.md, the growth under them), a printed summary; EXRs
in the work folder (<out>-work by default).
Not mapped (refused with the reason, never approximated silently): a chromatic medium with a
density (Mitsuba's grid medium is grey: it needs one render per bin group, density_check.py, not
one timed render); a light with a spectral line (fog-room-laser's laser: protocol.sh gives both
renderers the 14 nm triangle instead, by --set); whatever mitsuba_scene.py refuses (it names the
key). A Mitsuba sampler whose images hold NaN or inf pixels is disqualified by the pilot (3.9.1's
stratified and multijitter leave about one NaN pixel per 64-spp call on smoke-plume).
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import mitsuba_scene  # noqa: E402
from compare import bin4, read_rgb, write_rgb  # noqa: E402
from protocol_render import (  # noqa: E402
    B_REF, M_REF, M_RUN, Peer, brume_fixed_cost, brume_render, chunk_ok, file_sha, host, machine_state, nonfinite, pilot,
)
from protocol_growth import growth, growth_line  # noqa: E402
from protocol_scene import check_mappable, edited_desc, spectral_media, strip_integrator  # noqa: E402

LLVM = "/usr/lib/x86_64-linux-gnu/libLLVM-19.so"


# ----------------------------------------------------------------------------- reference

def cached(folder: Path, key: dict, files: list[str]) -> dict | None:
    """The stored record of `folder` if its key is exactly `key` and its files exist."""
    meta = folder / "key.json"
    if not meta.exists():
        return None
    rec = json.loads(meta.read_text())
    if rec.get("key") != key or not all((folder / f).exists() for f in files):
        print(f"{folder}: stored for another key: rendering anew", flush=True)
        return None
    return rec


def store(folder: Path, key: dict, rec: dict) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    tmp = folder / "key.json.tmp"
    tmp.write_text(json.dumps({"key": key, **rec}, indent=2))
    tmp.replace(folder / "key.json")


def key_folder(work: Path, kind: str, key: dict) -> Path:
    h = hashlib.sha256(json.dumps(key, sort_keys=True).encode()).hexdigest()[:12]
    return work / f"{kind}-{h}"


def render_reference(source: str, seconds: float, peer: Peer | None, brume_ref, files=None) -> tuple[list, list]:
    """Two independent halves of `seconds` in all, or the two given files: (images, records)."""
    imgs, recs = [], []
    for h in range(2):
        if source == "files":
            img, rec = read_rgb(files[h]), {"file": str(files[h]), "sha256": file_sha(files[h]), "wall_s": 0.0}
        elif source == "mitsuba":
            img, rec = peer.render(seconds / 2, M_REF + h * 5_000_000)
        else:
            img, rec = brume_ref(seconds / 2, B_REF + h)
        imgs.append(img)
        recs.append(rec)
        print(f"reference half {h}: {source}, {rec['wall_s']:.1f} s", flush=True)
    return imgs, recs


def halves(a: np.ndarray, b: np.ndarray) -> dict:
    """A reference from two independent halves: their mean, and its noise per pixel and of 4x4
    bins, E[(A - B)^2] / 4, which `scores` subtracts."""
    return {"mean": 0.5 * (a + b), "var": float(np.mean((a - b) ** 2) / 4),
            "var_bin4": float(np.mean((bin4(a) - bin4(b)) ** 2) / 4)}


def reference(work: Path, key: dict, source: str, seconds: float, peer, brume_ref, files=None) -> dict:
    """The reference (mean of two halves) and its noise per metric, cached under its key."""
    folder = key_folder(work, "reference", key)
    names = ["half-a.exr", "half-b.exr"]
    rec = cached(folder, key, names)
    if rec is None:
        imgs, recs = render_reference(source, seconds, peer, brume_ref, files)
        folder.mkdir(parents=True, exist_ok=True)
        for img, n in zip(imgs, names):
            write_rgb(folder / n, img)
        rec = {"halves": recs}
        store(folder, key, rec)
    else:
        print(f"reference: reusing {folder}", flush=True)
    a, b = (read_rgb(folder / n) for n in names)
    if nonfinite(a) + nonfinite(b):
        raise SystemExit(f"{folder}: the reference has NaN/inf pixels")
    return {"key": key, **halves(a, b), "folder": str(folder), **rec}


def scores(img: np.ndarray, ref: dict, wall: float, budget: float) -> dict:
    """Relative RMSE per pixel and of 4x4 bins, the reference's noise removed, as measured and
    scaled to the nominal budget; and k = sum(ref) / sum(img), the scale check."""
    bad = nonfinite(img)
    if bad:
        # Counted as error, not hidden: such a run's scores are NaN and its record says why.
        print(f"WARNING: {bad} NaN/inf pixels in this image: its scores are NaN", file=sys.stderr, flush=True)
    m = float(ref["mean"].mean())
    nan = float("nan")
    mse = nan if bad else max(float(np.mean((img - ref["mean"]) ** 2)) - ref["var"], 0.0)
    mse4 = nan if bad else max(float(np.mean((bin4(img) - bin4(ref["mean"])) ** 2)) - ref["var_bin4"], 0.0)
    s = np.sqrt(wall / budget)
    r, r4 = np.sqrt(mse) / m, np.sqrt(mse4) / m
    return {"rel_rmse": r, "rel_rmse_bin4": r4, "rel_rmse_nominal": r * s, "rel_rmse_bin4_nominal": r4 * s,
            "k": float(ref["mean"].sum() / img.sum()), "nonfinite_pixels": bad}


# ----------------------------------------------------------------------------- runs

class Setup:
    """What one invocation compares: the brume scene and settings, the peer, the reference."""

    def __init__(self, a, desc: dict, brume_scene: Path, brume_info: dict):
        self.a, self.desc = a, desc
        self.brume_scene, self.brume_info = brume_scene, brume_info
        self.brume_sets = a.set + a.brume_set
        self.work = a.work or a.out.parent / (a.out.name + "-work")
        self.work.mkdir(parents=True, exist_ok=True)
        self.scene_sha = hashlib.sha256(a.scene.read_bytes()).hexdigest()[:16]

    def brume_ref(self, seconds: float, seed: int):
        """brume's reference half: the scene's own settings, plus --set and --brume-ref-set."""
        out = self.work / "brume-ref-half.exr"
        return brume_render(self.a.brume, self.a.scene, seconds, seed, out, self.a.set + self.a.brume_ref_set)

    def run(self, who: str, budget: float, i: int, run: int):
        if who == "brume":
            out = self.work / "brume-run.exr"
            return brume_render(self.a.brume, self.brume_scene, budget, 1 + i * 1000 + run, out, self.brume_sets)
        return self.peer.render(budget, M_RUN + i * 1_000_000 + run * 10_000)


def measure(s: Setup, ref: dict) -> list[dict]:
    """Every run at every budget; brume and Mitsuba alternate which goes first, so a slow drift
    in the machine's state is charged to both."""
    rows = []
    for i, t in enumerate(s.a.times):
        for run in range(s.a.runs):
            order = ("brume", "mitsuba") if run % 2 == 0 else ("mitsuba", "brume")
            for who in order:
                state = machine_state(s.a.settle)
                img, rec = s.run(who, t, i, run)
                rec.update(state, load_after=list(os.getloadavg()), renderer=who, budget_s=t, run=run)
                rec.update(scores(img, ref, rec["wall_s"], t))
                rows.append(rec)
                print(f"T={t:g} s run {run} {who:7s}: wall {rec['wall_s']:.2f} s, CPU {rec['cpu_s']:.2f} s, "
                      f"rel RMSE {rec['rel_rmse_nominal']:.4g} (4x4 {rec['rel_rmse_bin4_nominal']:.4g}), "
                      f"k {rec['k']:.4f}{'' if rec['idle'] else '  [NOT IDLE]'}", flush=True)
    return rows


STATS = ("rel_rmse_nominal", "rel_rmse_bin4_nominal", "rel_rmse", "rel_rmse_bin4", "wall_s", "cpu_s", "cpu_per_wall", "k")


def summarise(rows: list[dict], times: list[float]) -> dict:
    """Per budget and renderer: median, min and max over runs; brume / Mitsuba of the medians."""
    out = {}
    for t in times:
        per = {}
        for who in ("brume", "mitsuba"):
            mine = [r for r in rows if r["renderer"] == who and r["budget_s"] == t]
            per[who] = {k: {"median": float(np.median([r[k] for r in mine])), "min": float(np.min([r[k] for r in mine])),
                            "max": float(np.max([r[k] for r in mine]))} for k in STATS}
            per[who]["runs"] = len(mine)
            per[who]["not_idle_runs"] = sum(not r["idle"] for r in mine)
        per["ratio_brume_over_mitsuba"] = {
            k: per["brume"][k]["median"] / per["mitsuba"][k]["median"]
            for k in STATS[:4] if per["mitsuba"][k]["median"] > 0}
        out[f"{t:g}"] = per
    return out


def fmt(d: dict, digits: int = 4) -> str:
    return f"{d['median']:.{digits}g} [{d['min']:.{digits}g}-{d['max']:.{digits}g}]"


def markdown(label: str, brume_label: str, peer_label: str, summary: dict) -> str:
    head = ("| scene | T (s) | brume | Mitsuba 3 | brume rel. RMSE | Mitsuba rel. RMSE | ratio | brume 4x4 | "
            "Mitsuba 4x4 | ratio 4x4 | brume wall s / CPU s (CPU/wall) | Mitsuba wall s / CPU s (CPU/wall) | runs |\n"
            "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n")
    rows = []
    for t, per in summary.items():
        b, m, r = per["brume"], per["mitsuba"], per["ratio_brume_over_mitsuba"]
        clock = [f"{x['wall_s']['median']:.1f} / {x['cpu_s']['median']:.1f} ({x['cpu_per_wall']['median']:.2f})" for x in (b, m)]
        idle = "" if b["not_idle_runs"] + m["not_idle_runs"] == 0 else " (NOT IDLE)"
        rows.append(
            f"| {label} | {t} | {brume_label} | {peer_label} | {fmt(b['rel_rmse_nominal'])} | {fmt(m['rel_rmse_nominal'])} | "
            f"{r.get('rel_rmse_nominal', float('nan')):.2f}x | {fmt(b['rel_rmse_bin4_nominal'])} | "
            f"{fmt(m['rel_rmse_bin4_nominal'])} | {r.get('rel_rmse_bin4_nominal', float('nan')):.2f}x | "
            f"{clock[0]} | {clock[1]} | {b['runs']}{idle} |")
    return head + "\n".join(rows) + "\n"


# ----------------------------------------------------------------------------- main

def args() -> argparse.Namespace:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene", type=Path)
    ap.add_argument("--out", type=Path, required=True, help="prefix of <out>.json and <out>.md")
    ap.add_argument("--work", type=Path, default=None, help="cached references, pilots and EXRs (default <out>-work)")
    ap.add_argument("--brume", default="target/release/brume")
    ap.add_argument("--times", type=float, nargs="+", default=[10.0], help="wall-clock budgets, s")
    ap.add_argument("--runs", type=int, default=5, help="runs (other seeds) per budget")
    ap.add_argument("--set", action="append", default=[], help="KEY=VALUE edit of the scene for BOTH renderers (repeatable)")
    ap.add_argument("--reference", choices=["mitsuba", "brume", "files"], default="mitsuba",
                    help="source of the reference (brume: fog-room-laser; files: --reference-halves)")
    ap.add_argument("--reference-halves", type=Path, nargs=2, default=None, metavar=("A", "B"),
                    help="two independent halves rendered elsewhere (light_trace.py), in brume's units, of the scene as edited by --set")
    ap.add_argument("--ref-seconds", type=float, default=600.0, help="reference, wall s in all (two halves)")
    ap.add_argument("--brume-ref-set", action="append", default=[], help="brume --set for a brume reference only")
    ap.add_argument("--brume-settings", choices=["default", "scene"], default="default", help="brume's [integrator]: stripped (defaults) or the scene's (tuned)")
    ap.add_argument("--brume-set", action="append", default=[], help="brume --set for the measured runs: a tuned variant, reported as such")
    ap.add_argument("--variant", default="llvm_ad_spectral")
    ap.add_argument("--integrator", choices=["auto", *mitsuba_scene.INTEGRATORS], default="auto", help="auto: volpathmis for media whose coefficients vary with wavelength")
    ap.add_argument("--spot-profile", choices=list(mitsuba_scene.SPOT_PROFILES), default="exact")
    ap.add_argument("--floor", choices=["exact", "builtin"], default="exact", help="Mitsuba's glossy floor: brume's BSDF (Python, traced into the LLVM kernels) or roughplastic")
    ap.add_argument("--chunk-spp", type=int, default=64, help="Mitsuba samples per render call")
    ap.add_argument("--pilot-seconds", type=float, default=5.0, help="budget of each of the two pilot images per sampler")
    ap.add_argument("--sampler", choices=list(mitsuba_scene.SAMPLERS), default=None, help="skip the pilot (not the protocol: for tests)")
    ap.add_argument("--settle", type=float, default=90.0, help="max s to wait before a run for the 1-min load to fall to 0.5")
    ap.add_argument("--no-fixed-cost", action="store_true", help="skip measuring brume's start-up and pilot cost")
    a = ap.parse_args()
    chunk_ok(a.chunk_spp)
    if (a.reference == "files") != (a.reference_halves is not None):
        ap.error("--reference files and --reference-halves A B go together")
    return a


def brume_scene(a) -> tuple[Path, dict, Path | None]:
    """The scene file brume's measured runs read: the scene's own, or a stripped dot-copy beside
    it (relative paths resolve as in the scene). Returns (path, description, temp to delete)."""
    if a.brume_settings == "scene":
        return a.scene, {"settings": "scene", "brume_set": a.brume_set}, None
    text, kept, removed = strip_integrator(a.scene.read_text())
    tmp = a.scene.parent / f".protocol-{a.scene.stem}-{os.getpid()}.toml"
    tmp.write_text(text)
    info = {"settings": "default", "integrator_keys_kept": kept, "integrator_keys_removed": removed,
            "kept_because": "max_depth truncates the transported light (it defines the image; Mitsuba mirrors it)",
            "brume_set": a.brume_set}
    print(f"brume defaults: removed integrator keys {removed}, kept {kept}", flush=True)
    return tmp, info, tmp


def peer_settings(a, s: Setup, mi) -> dict:
    integ = a.integrator
    if integ == "auto":
        integ = "volpathmis" if spectral_media(s.desc, a.scene.parent) else "volpath"
    # The translation's light scale (mitsuba_scene.mitsuba_y_excess) is in the key: references
    # rendered before it were 0.1 % bright and must not be reused.
    return {"mitsuba": mi.__version__, "variant": a.variant, "integrator": integ, "spot_profile": a.spot_profile,
            "floor": a.floor, "chunk_spp": a.chunk_spp, "y_scale": round(1.0 / mitsuba_scene.mitsuba_y_excess(mi), 9)}


def choose_peer(a, s: Setup, mi, ps: dict) -> tuple[Peer, dict]:
    """The pilot (cached under its key), or --sampler for tests."""
    def make(name):
        return Peer(mi, a.scene, s.desc, name, a.chunk_spp, ps["integrator"], ps["spot_profile"], ps["floor"])
    if a.sampler:
        return make(a.sampler), {"chosen": a.sampler, "skipped": "--sampler given: NOT the protocol"}
    key = {"scene_sha": s.scene_sha, "sets": a.set, "pilot_seconds": a.pilot_seconds, **ps}
    folder = key_folder(s.work, "pilot", key)
    rec = cached(folder, key, [])
    if rec is not None:
        print(f"pilot: reusing {folder}: {rec['pilot']['chosen']}", flush=True)
        return make(rec["pilot"]["chosen"]), rec["pilot"]
    state = machine_state(a.settle)  # the pilot compares timed renders: it wants an idle machine too
    peer, result = pilot(make, a.pilot_seconds)
    result["machine_before"] = state
    store(folder, key, {"pilot": result})
    return peer, result


def reference_key(a, s: Setup, ps: dict) -> dict:
    key = {"scene": str(a.scene), "scene_sha": s.scene_sha, "sets": a.set, "source": a.reference, "seconds": a.ref_seconds}
    if a.reference == "files":
        return {**key, "seconds": None, "halves_sha256": [file_sha(p) for p in a.reference_halves]}
    if a.reference == "mitsuba":
        return {**key, **ps, "sampler": s.peer.sampler}
    return {**key, "brume_sha": file_sha(a.brume), "brume_settings": "scene", "brume_ref_set": a.brume_ref_set}


def labels(a, s: Setup, ps: dict) -> tuple[str, str, str]:
    scene = a.scene.stem + (f" ({', '.join(a.set)})" if a.set else "")
    brume = "defaults" if a.brume_settings == "default" else "scene settings (tuned)"
    if a.brume_set:
        brume += f" + {', '.join(a.brume_set)} (tuned)"
    peer = f"{ps['integrator']}, {s.peer.sampler}, {a.chunk_spp} spp/call"
    return scene, brume, peer


def report(a, s: Setup, ps: dict, ref: dict, pilot_rec: dict, fixed: dict | None, rows: list[dict]) -> None:
    summary = summarise(rows, a.times)
    change = growth(rows, a.times)
    scene, brume, peer = labels(a, s, ps)
    doc = {
        "command": sys.argv, "scene": str(a.scene), "sets": a.set, "brume": s.brume_info, "mitsuba": {**ps, "sampler": s.peer.sampler},
        "pilot": pilot_rec, "reference": {k: v for k, v in ref.items() if k not in ("mean",)},
        "host": host(sys.modules.get("drjit")),
        "brume_fixed_cost": fixed, "runs": rows, "summary": summary, "growth": change,
        "notes": ["brume's wall time is its whole process (start-up, scene load, automatic pilots); Mitsuba's "
                  "excludes scene load and JIT (one untimed warm-up): brume is charged more",
                  "*_nominal = RMSE * sqrt(t_actual / T): the error at exactly the nominal budget (error ~ t^-1/2); "
                  "ratios use it", "RMSE relative to the reference's mean, the reference's noise removed "
                  "(mean((A - B)^2) / 4 of its halves, per metric); k = sum(ref) / sum(image), a check (1 expected)"],
    }
    a.out.parent.mkdir(parents=True, exist_ok=True)
    a.out.with_name(a.out.name + ".json").write_text(json.dumps(doc, indent=2, default=float))
    h = doc["host"]
    print(f"host: {h['model']}, {h['cores']} cores, widest SIMD {h['simd']}, Dr.Jit's LLVM target "
          f"{h.get('drjit_llvm_cpu')}", flush=True)
    md = markdown(scene, brume, peer, summary)
    if change:
        md += "\n" + growth_line(change)
    a.out.with_name(a.out.name + ".md").write_text(md)
    print_summary(a, ref, fixed, summary, md)


def print_summary(a, ref: dict, fixed: dict | None, summary: dict, md: str) -> None:
    print(f"\nreference: {a.reference}, {sum(h['wall_s'] for h in ref['halves']):.0f} s in two halves "
          f"(its noise: rel RMSE {np.sqrt(ref['var']) / ref['mean'].mean():.3g} per pixel, "
          f"{np.sqrt(ref['var_bin4']) / ref['mean'].mean():.3g} 4x4, removed from every score)")
    if fixed:
        print(f"brume fixed cost (start-up, load, automatic pilots; in brume's wall time, not in Mitsuba's): "
              f"{fixed['fixed_wall_s']:.2f} s; per pass {fixed['per_pass_wall_s']:.3f} s; `brume info` {fixed['info_wall_s']:.2f} s")
    noise = np.sqrt(ref["var"]) / ref["mean"].mean()
    for t, per in summary.items():
        least = min(per[w]["rel_rmse"]["median"] for w in ("brume", "mitsuba"))
        if noise > 0.5 * least:
            # The subtraction is unbiased, but its own error grows with the noise it removes.
            print(f"WARNING: T = {t} s: the reference's noise ({noise:.3g}) is over half the smallest RMSE measured "
                  f"({least:.3g}): render a longer reference (--ref-seconds)", flush=True)
        print(f"T = {t} s: k (scale check) brume {per['brume']['k']['median']:.4f}, Mitsuba {per['mitsuba']['k']['median']:.4f}; "
              f"ratio brume / Mitsuba per pixel {per['ratio_brume_over_mitsuba'].get('rel_rmse_nominal', float('nan')):.3f}x, "
              f"4x4 {per['ratio_brume_over_mitsuba'].get('rel_rmse_bin4_nominal', float('nan')):.3f}x")
    print("RMSE scaled to the nominal budget: RMSE * sqrt(t_actual / T); medians [min-max] over runs\n")
    print(md, flush=True)


def main() -> None:
    a = args()
    os.environ.setdefault("DRJIT_LIBLLVM_PATH", LLVM)
    desc = edited_desc(a.scene, a.set)
    try:
        check_mappable(desc, a.scene.parent)
    except NotImplementedError as e:
        raise SystemExit(f"{a.scene}: not mapped to Mitsuba 3: {e}") from e
    path, info, tmp = brume_scene(a)
    try:
        run_all(a, desc, path, info)
    finally:
        if tmp is not None:
            tmp.unlink(missing_ok=True)


def run_all(a, desc: dict, path: Path, info: dict) -> None:
    import mitsuba as mi

    mi.set_variant(a.variant)
    s = Setup(a, desc, path, info)
    ps = peer_settings(a, s, mi)
    try:
        s.peer, pilot_rec = choose_peer(a, s, mi, ps)
    except NotImplementedError as e:
        raise SystemExit(f"{a.scene}: not mapped to Mitsuba 3: {e}") from e
    print(f"Mitsuba: {ps['integrator']}, sampler {s.peer.sampler}, {a.chunk_spp} spp per call", flush=True)
    ref = reference(s.work, reference_key(a, s, ps), a.reference, a.ref_seconds, s.peer, s.brume_ref, a.reference_halves)
    fixed = None
    if not a.no_fixed_cost:
        fixed = brume_fixed_cost(a.brume, path, s.work / "brume-fixed.exr", s.brume_sets)
    rows = measure(s, ref)
    report(a, s, ps, ref, pilot_rec, fixed, rows)


if __name__ == "__main__":
    main()
