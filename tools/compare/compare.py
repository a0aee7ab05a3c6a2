"""Equal-time comparison of brume and Mitsuba 3 on one scene: error versus time (wall-clock or CPU).

Usage (from the repository root, with the venv of tools/compare/requirements.txt):
  .venv/bin/python tools/compare/compare.py scenes/fog-cube.toml --brume target/release/brume \
      --ref-seconds 120 --times 5 15 60 --out docs/images/perf-fog-cube
  .venv/bin/python tools/compare/compare.py scenes/fog-room-laser.toml --brume target/release/brume \
      --ref-seconds 600 --mitsuba-ref-seconds 600 --times 5 15 60 --out docs/images/perf-room

  DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM-19.so .venv/bin/python tools/compare/compare.py \
      scenes/fog-cube.toml --variant llvm_ad_spectral --clock cpu --runs 3 --times 5 15 60 \
      --ref-seconds 120 --out docs/images/perf-fog-cube-llvm

  DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM-19.so .venv/bin/python tools/compare/compare.py \
      scenes/chromatic-fog.toml --integrator volpathmis --spot-profile exact --variant llvm_ad_spectral \
      --clock cpu --runs 3 --times 5 15 60 --ref-seconds 120 --out docs/images/perf-chromatic-fog

Mitsuba's integrator and spots:
- --integrator volpath (default) or volpathmis. Mitsuba's volpath draws free-flight distances
  from the extinction of the first wavelength a path carries alone, which is noisy when the
  extinction varies with wavelength (chromatic-fog); volpathmis combines all of them (spectral
  MIS). Grey media give both the same image. The choice is written to refs.json (a reused
  Mitsuba reference must have been rendered with it), -agreement.json, -summary.json,
  -rungs.jsonl and the CSV (column mitsuba_integrator, Mitsuba's rows).
- --spot-profile ramp (default: Mitsuba's own soft edge, linear in the angle, as the grey scenes
  were always compared) or exact (brume's edge, linear in cos theta, through a projected
  texture; see mitsuba_scene.spot_profile_texture). The ramp emits 0.3 % less than brume for
  fog-room-laser's 35 deg spots with 5 deg edges, 1.3 % less for chromatic-fog's 4 deg spot with
  a 1 deg edge: use exact there, or the agreement check reads that deficit as k.

Clocks (--clock):
- wall (default): wall-clock seconds, as below.
- cpu: each renderer is charged the CPU seconds of its own process (user + system, all threads),
  which a busy machine disturbs much less than wall time. brume: the child's rusage (os.wait4),
  the whole process including scene load; brume render has only a wall-clock budget, so the
  pass count for a CPU budget T is chosen from a calibration (CPU of 1 and 3 passes of the same
  settings: load + N x per-pass cost = T) and the CPU actually used is what is reported.
  Mitsuba: time.process_time() around its mi.render calls (the LLVM backend's worker threads run
  inside this Python process, so they are counted), chunks until the budget is spent.
- --runs K repeats the ladder with other seeds (the references are shared), so the CSV has K rows
  per renderer and budget; the summary prints mean +- sd over runs, the brume / Mitsuba ratio of
  mean relative RMSE per budget, and the least-squares slope of log RMSE against log time.

Method:
- Each renderer renders a long reference and one image per ladder time with a different seed.
  brume: `brume render --time T` (whole passes, so the real time runs a little over T; the time
  is the whole process, scene load included); Mitsuba: `mi.render` in chunks of spp with a new
  seed each, after one untimed warm-up render.
- Mitsuba's light spectra are brume's, in brume's units (mitsuba_scene.py), so the two images
  should agree with scale k = 1; k is fitted between the references (ratio of their sums away
  from the beam: least squares is pulled to 0 by fireflies) as a check.
- Scenes without a laser (fog-cube): each renderer's error is against its own reference, with
  the reference's own noise removed. brume's reference is rendered as two halves with different
  seeds; E[(A - B)^2] / 4 is the per-pixel variance of their mean, subtracted from every MSE
  (per metric: whole, away, beam, 4x4 bins), which holds whatever the reference's settings (a
  smaller radius than the ladder's is noisier per second). References stored before the halves
  existed fall back to MSE_true = MSE_measured / (1 + t / t_ref) (variance ~ 1 / time, same
  settings) or, with --brume-set, to the variance a same-settings run stored in refs.json.
  Mitsuba's reference noise is removed by the spp formula (same estimator as its ladder).
- Scenes with a laser (fog-room-laser): Mitsuba's laser is a point spot with a 2 mm cone; next-event
  estimation reaches it only from path vertices inside that cone, so Mitsuba's reference does not
  converge on the beam nor on the light the beam scatters into the rest of the room (it is
  unbiased, but the variance sits in rare huge samples). The trustworthy reference for the whole
  image is brume's, so both renderers are measured against brume's reference (Mitsuba's image
  times k); brume's reference noise is removed from both with the variance brume's own ladder
  measures. The CSV also holds, for each renderer, the error outside and inside the beam mask
  (beam_mask.py), and Mitsuba's error against its own reference outside the mask (its noise
  only, blind to the light it misses).
- Glossy floor (room): Mitsuba renders brume's exact BSDF (brume_glossy.py, a Python plugin,
  `--floor exact`). Python costs ~5x Mitsuba's native speed, which would be unfair to Mitsuba,
  so Mitsuba's time is charged as spp x (seconds per spp of the same scene with the built-in
  `roughplastic` floor), measured once before the ladder: the cost of a native floor BSDF.
  `--floor builtin` renders with `roughplastic` instead and charges wall-clock time.
- Outputs: <out>.csv, <out>.png (error vs time), <out>-agreement.json (k, region means, relative
  RMSE between the references against what their noise predicts), <out>-refs.png (brume's
  reference | Mitsuba's | the beam mask), <out>-work/ (the EXRs).
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import subprocess
import sys
import time
import tomllib
from pathlib import Path

import numpy as np
import OpenEXR

sys.path.insert(0, str(Path(__file__).parent))
import beam_mask  # noqa: E402
import mitsuba_scene  # noqa: E402


def read_rgb(path: Path) -> np.ndarray:
    with OpenEXR.File(str(path)) as f:
        ch = f.channels()
        if "RGB" in ch:
            return np.asarray(ch["RGB"].pixels, dtype=np.float64)
        return np.stack([np.asarray(ch[c].pixels, dtype=np.float64) for c in "RGB"], axis=-1)


def write_rgb(path: Path, rgb: np.ndarray) -> None:
    """A float32 RGB EXR (written beside and renamed, so a crash leaves no half file)."""
    tmp = path.with_name(path.name + ".tmp.exr")
    with OpenEXR.File({"compression": OpenEXR.ZIP_COMPRESSION}, {"RGB": np.ascontiguousarray(rgb, dtype=np.float32)}) as f:
        f.write(str(tmp))
    tmp.replace(path)


def clock_fn(clock: str):
    """The timer a clock reads: wall-clock, or this process's CPU seconds (all threads)."""
    return time.perf_counter if clock == "wall" else time.process_time


def run_child_cpu(cmd: list[str]) -> float:
    """Run cmd; return its CPU seconds (user + system, all threads) from its rusage."""
    proc = subprocess.Popen(cmd)
    _, status, ru = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    if proc.returncode != 0:
        raise subprocess.CalledProcessError(proc.returncode, cmd)
    return ru.ru_utime + ru.ru_stime


_PASS_COST: dict[tuple, tuple[float, float]] = {}


def brume_pass_cost(brume: str, scene: Path, sets: tuple, out: Path) -> tuple[float, float]:
    """(load CPU s, CPU s per pass) of brume with these settings: from runs of 1 and 3 passes."""
    key = (brume, str(scene), sets)
    if key not in _PASS_COST:
        base = [brume, "render", str(scene), "--seed", "999", "-o", str(out), "--quiet"]
        for s in sets:
            base += ["--set", s]
        c1 = run_child_cpu(base + ["--passes", "1"])
        c3 = run_child_cpu(base + ["--passes", "3"])
        per = max((c3 - c1) / 2.0, 1e-3)
        _PASS_COST[key] = (max(c1 - per, 0.0), per)
        print(f"brume: {per:.3f} CPU s per pass, {max(c1 - per, 0.0):.2f} s load ({' '.join(sets) or 'scene settings'})", flush=True)
    return _PASS_COST[key]


def brume_render(
    brume: str, scene: Path, seconds: float, seed: int, out: Path, sets: list[str] = (), clock: str = "wall"
) -> tuple[np.ndarray, float]:
    """brume's image for a budget and the seconds charged on the clock."""
    cmd = [brume, "render", str(scene), "--seed", str(seed), "-o", str(out), "--quiet"]
    for s in sets:
        cmd += ["--set", s]
    if clock == "cpu":
        load, per = brume_pass_cost(brume, scene, tuple(sets), out)
        passes = max(1, round((seconds - load) / per))
        cpu = run_child_cpu(cmd + ["--passes", str(passes)])
        return read_rgb(out), cpu
    t0 = time.perf_counter()
    subprocess.run(cmd + ["--time", str(seconds)], check=True)
    return read_rgb(out), time.perf_counter() - t0


class Mitsuba:
    def __init__(
        self, scene: Path, variant: str, chunk_spp: int, floor: str, drop: list[int], calib_s: float, laser_r: float | None,
        clock: str = "wall", integrator: str = "volpath", spot_profile: str = "ramp",
    ):
        import mitsuba as mi

        mi.set_variant(variant)
        self.mi = mi
        self.integrator = integrator
        self.spot_profile = spot_profile
        desc = tomllib.loads(scene.read_text())
        glossy = any(m.get("type") == "glossy" for m in desc.get("materials", {}).values())
        self.laser_r = laser_r
        self.scene = mi.load_dict(self._dict(scene, chunk_spp, floor, drop))
        self.chunk = chunk_spp
        self.seed = 0
        self.now = clock_fn(clock)
        self.render_wall(0.0)  # warm-up (not timed)
        # Seconds per spp of a native floor BSDF, when the rendered one is the Python plugin.
        self.s_per_spp = None
        if floor == "exact" and glossy:
            fast = mi.load_dict(self._dict(scene, chunk_spp, "builtin", drop))
            mi.render(fast, spp=chunk_spp, seed=10**6)
            n, t0 = 0, self.now()
            while n == 0 or self.now() - t0 < calib_s:
                mi.render(fast, spp=chunk_spp, seed=10**6 + 1 + n)
                n += 1
            self.s_per_spp = (self.now() - t0) / (n * chunk_spp)
            print(f"mitsuba: native-floor cost {self.s_per_spp:.3f} s/spp ({n * chunk_spp} spp)", flush=True)

    def _dict(self, scene, spp, floor, drop):
        d = mitsuba_scene.load(
            scene, spp, floor=floor, laser_radius=self.laser_r, integrator=self.integrator, spot_profile=self.spot_profile
        )
        for i in drop:
            d.pop(f"light{i}", None)
        return d

    def _chunk(self) -> np.ndarray:
        self.seed += 1
        return np.asarray(self.mi.render(self.scene, spp=self.chunk, seed=self.seed), dtype=np.float64)

    def render_wall(self, seconds: float) -> tuple[np.ndarray, float, int]:
        """Chunks of spp until `seconds` are spent on the comparison's clock (wall or CPU)."""
        acc, chunks, t0 = None, 0, self.now()
        while acc is None or self.now() - t0 < seconds:
            img = self._chunk()
            acc = img if acc is None else acc + img
            chunks += 1
        return acc / chunks, self.now() - t0, chunks * self.chunk

    def render(self, seconds: float) -> tuple[np.ndarray, float, int]:
        """An image for a time budget on the clock, or spp-equivalent to a native floor BSDF."""
        if self.s_per_spp is None:
            return self.render_wall(seconds)
        chunks = max(1, round(seconds / (self.s_per_spp * self.chunk)))
        acc = sum(self._chunk() for _ in range(chunks))
        spp = chunks * self.chunk
        return acc / chunks, spp * self.s_per_spp, spp


def mse(a: np.ndarray, b: np.ndarray, m: np.ndarray | None = None) -> float:
    d = (a - b) ** 2
    return float(d[m].mean()) if m is not None else float(d.mean())


def own_share(effort: float, ref_effort: float) -> float:
    """Share of an image's measured MSE against a reference that is the image's own noise, when
    both come from the same estimator and variance falls as 1 / effort (time or spp): the
    reference adds Var / ref_effort to the image's Var / effort."""
    return 1.0 / (1.0 + effort / ref_effort)


def bin4(a: np.ndarray) -> np.ndarray:
    """4 x 4 box average: the error at a scale where brume's radius blur (a few pixels) and
    single-pixel speckle matter less."""
    h, w = a.shape[0] // 4 * 4, a.shape[1] // 4 * 4
    return a[:h, :w].reshape(h // 4, 4, w // 4, 4, -1).mean((1, 3))


def errors(img: np.ndarray, ref: np.ndarray, away: np.ndarray, beam: np.ndarray, spot: np.ndarray) -> tuple:
    """MSE over the whole image, away from the beam, in the beam, of 4 x 4 bins, and over the
    whole image but the lasers' wall spots."""
    return (
        mse(img, ref),
        mse(img, ref, away),
        mse(img, ref, beam) if beam.any() else 0.0,
        mse(bin4(img), bin4(ref)),
        mse(img, ref, ~spot),
    )


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene", type=Path)
    ap.add_argument("--brume", default="target/release/brume")
    ap.add_argument("--variant", default="scalar_spectral")
    ap.add_argument("--integrator", choices=list(mitsuba_scene.INTEGRATORS), default="volpath", help="Mitsuba's integrator: volpath, or volpathmis (spectral MIS, for media whose extinction varies with wavelength)")
    ap.add_argument("--spot-profile", choices=list(mitsuba_scene.SPOT_PROFILES), default="ramp", help="Mitsuba's spot edges: its own ramp (linear in angle) or brume's (linear in cos theta, by a projected texture)")
    ap.add_argument("--chunk-spp", type=int, default=4)
    ap.add_argument("--ref-seconds", type=float, default=120.0, help="brume reference (and Mitsuba's, unless --mitsuba-ref-seconds)")
    ap.add_argument("--mitsuba-ref-seconds", type=float, default=None, help="Mitsuba reference, wall-clock")
    ap.add_argument("--times", type=float, nargs="+", default=[2, 5, 15, 60])
    ap.add_argument("--clock", choices=["wall", "cpu"], default="wall", help="charge wall-clock seconds, or each renderer's process CPU seconds (brume: child rusage; Mitsuba: time.process_time)")
    ap.add_argument("--runs", type=int, default=1, help="repeat the ladder with other seeds (shared references); the summary gives mean +- sd")
    ap.add_argument("--brume-set", action="append", default=[], help="brume --set KEY=VALUE for the ladder (repeatable); the reference keeps the scene's settings (plus --brume-ref-set)")
    ap.add_argument("--brume-ref-set", action="append", default=[], help="brume --set KEY=VALUE for the reference only (repeatable)")
    ap.add_argument("--floor", choices=["exact", "builtin"], default="exact", help="Mitsuba's glossy floor: brume's BSDF as a Python plugin (timed as native) or roughplastic")
    ap.add_argument("--calib-seconds", type=float, default=10.0, help="time spent measuring Mitsuba's native-floor cost per spp")
    ap.add_argument("--drop-light", type=int, action="append", default=[], help="remove light N (0-based) in both renderers, e.g. the laser for a lamps-only agreement check")
    ap.add_argument("--mitsuba-laser-radius", type=float, default=None, help="Mitsuba only: widen the laser's cone to this radius (m) at the far wall (an agreement check of the beam's scattered light; not the scene)")
    ap.add_argument("--k", type=float, default=None, help="scale applied to Mitsuba's images against brume's reference (default: fitted without a laser; 1.0, the value the units give, with one)")
    ap.add_argument("--brume-only", action="store_true", help="skip Mitsuba's ladder (pilots of brume settings against stored references; with --reuse-refs)")
    ap.add_argument("--work", type=Path, default=None, help="folder of the EXRs and references (default <out>-work)")
    ap.add_argument("--reuse-refs", action="store_true", help="reuse the references in <out>-work/ if present (same scene and settings!)")
    ap.add_argument("--out", type=Path, required=True, help="prefix of the CSV, plot and JSON")
    a = ap.parse_args()
    a.out.parent.mkdir(parents=True, exist_ok=True)
    work = a.work or a.out.parent / (a.out.name + "-work")
    work.mkdir(parents=True, exist_ok=True)
    desc = tomllib.loads(a.scene.read_text())
    drop_sets = [f"lights.{i}.power=1e-12" for i in a.drop_light]
    lights = desc.get("lights", [])
    lasers = [(i, l) for i, l in enumerate(lights) if l["type"] == "laser" and i not in a.drop_light]

    if a.brume_only and not a.reuse_refs:
        ap.error("--brume-only needs --reuse-refs")
    mit = None if a.brume_only else Mitsuba(
        a.scene, a.variant, a.chunk_spp, a.floor, a.drop_light, a.calib_seconds, a.mitsuba_laser_radius, a.clock,
        a.integrator, a.spot_profile,
    )

    # References (cached with their times for --reuse-refs).
    meta_path = work / "refs.json"
    meta = json.loads(meta_path.read_text()) if a.reuse_refs and meta_path.exists() else {}
    for who in ("brume", "mitsuba"):
        if who in meta and meta[who].get("clock", "wall") != a.clock:
            ap.error(f"--reuse-refs: the stored {who} reference was timed on the {meta[who].get('clock', 'wall')} clock, not {a.clock}")
    if "mitsuba" in meta and not a.brume_only:
        for key, want, old in (("integrator", a.integrator, "volpath"), ("spot_profile", a.spot_profile, "ramp")):
            # refs.json written before these options existed: their only behaviour was the default.
            if meta["mitsuba"].get(key, old) != want:
                ap.error(f"--reuse-refs: the stored Mitsuba reference was rendered with {key} {meta['mitsuba'].get(key, old)}, not {want}")
    halves = (work / "brume-ref-a.exr", work / "brume-ref-b.exr")
    if "brume" in meta:
        b_ref, b_ref_t = read_rgb(work / "brume-ref.exr"), meta["brume"]["seconds"]
    else:
        # Two independent halves: their difference measures the reference's own noise, whatever
        # its settings (a smaller radius than the ladder's is noisier per second).
        sets = drop_sets + a.brume_ref_set
        ra, ta = brume_render(a.brume, a.scene, a.ref_seconds / 2, 1000, halves[0], sets, a.clock)
        rb, tb = brume_render(a.brume, a.scene, a.ref_seconds / 2, 1001, halves[1], sets, a.clock)
        b_ref, b_ref_t = 0.5 * (ra + rb), ta + tb
        write_rgb(work / "brume-ref.exr", b_ref)
        meta["brume"] = {"seconds": b_ref_t, "sets": sets, "clock": a.clock, "halves": True}
    if "mitsuba" in meta:
        m_ref, m_ref_t, m_ref_spp = read_rgb(work / "mitsuba-ref.exr"), meta["mitsuba"]["seconds"], meta["mitsuba"]["spp"]
    else:
        m_ref, m_ref_t, m_ref_spp = mit.render_wall(a.mitsuba_ref_seconds or a.ref_seconds)
        mit.mi.util.write_bitmap(str(work / "mitsuba-ref.exr"), m_ref.astype(np.float32))
        meta["mitsuba"] = {
            "seconds": m_ref_t, "spp": m_ref_spp, "floor": a.floor, "clock": a.clock, "variant": a.variant,
            "integrator": a.integrator, "spot_profile": a.spot_profile,
        }
    if mit is not None and "mitsuba" in meta and mit.seed < 10**7:
        # A reused reference was rendered with seeds 2, 3, ... of an earlier process: start the
        # ladder's chunks far beyond them, or its images would share samples with the reference.
        mit.seed = 10**7
    meta_path.write_text(json.dumps(meta, indent=2))
    print(f"references: brume {b_ref_t:.1f} s, mitsuba {m_ref_t:.1f} s ({m_ref_spp} spp)", flush=True)

    h, w, _ = b_ref.shape
    beam = np.zeros((h, w), dtype=bool)
    for _, l in lasers:
        length = mitsuba_scene.beam_length(l["position"], l["direction"], desc)
        beam |= beam_mask.beam_mask(desc["camera"], l["position"], l["direction"], length)
    away = ~beam
    # Where each laser ends on a wall: its spot, inside the beam mask.
    spot = np.zeros((h, w), dtype=bool)
    for _, l in lasers:
        length = mitsuba_scene.beam_length(l["position"], l["direction"], desc)
        u = np.asarray(l["direction"], float)
        end = np.asarray(l["position"], float) + u / np.linalg.norm(u) * length
        spot |= beam_mask.spot_mask(desc["camera"], end)
    # The reference's variance per pixel (whole, away, beam, 4x4 bins) from its two halves:
    # E[(A - B)^2] = 4 Var[(A + B) / 2].
    halves_var = None
    if meta["brume"].get("halves") and all(h_.exists() for h_ in halves):
        halves_var = tuple(x / 4.0 for x in errors(read_rgb(halves[0]), read_rgb(halves[1]), away, beam, spot))
        meta["brume_var_ref_halves"] = list(halves_var)
    # Ratio of sums, not least squares: with heavy-tailed noise (fireflies in Mitsuba's image)
    # least squares is pulled towards 0 by the largest samples.
    k = float(b_ref[away].sum() / m_ref[away].sum())
    k_rgb = (b_ref[away].sum(0) / m_ref[away].sum(0)).tolist()
    k_lsq = float(np.sum(b_ref[away] * m_ref[away]) / np.sum(m_ref[away] ** 2))
    k_fit = k
    if a.k is not None or lasers:
        # With a laser, Mitsuba's reference misses most of the beam's scattered light even away
        # from the beam, which biases the fit; the units make k = 1 (checked lamps-only).
        k = a.k if a.k is not None else 1.0

    # Ladder.
    mean_ref = float(b_ref.mean())
    rows = []
    img_m = {}  # Mitsuba's ladder images by row index
    b_var_ref = []  # estimates of brume's reference variance per pixel (whole image)
    same_settings = not a.brume_set
    stored_var = None if same_settings else meta.get("brume_var_ref")
    # Every run's short budgets before any long one, so an interrupted ladder has all its runs
    # at the budgets it reached; each rung's raw errors go to <out>-rungs.jsonl as they come.
    ladder = [(run, i, t) for i, t in enumerate(a.times) for run in range(a.runs)]
    rungs = (a.out.parent / (a.out.name + "-rungs.jsonl")).open("w")
    for run, i, t in ladder:
        img, bt = brume_render(
            a.brume, a.scene, t, 1 + i + 100 * run, work / f"brume-{t:g}.exr", drop_sets + a.brume_set, a.clock
        )
        f = own_share(bt, b_ref_t)
        e = errors(img, b_ref, away, beam, spot)
        b_var_ref.append(tuple(x * (1 - f) for x in e))
        if halves_var is not None:
            own = tuple(max(x - v, 0.0) for x, v in zip(e, halves_var))
        elif stored_var is not None:
            # Other settings than the reference's: their variance per time differs, so remove the
            # reference's variance measured by the run with the reference's own settings.
            own = tuple(max(x - v, 0.0) for x, v in zip(e, stored_var))
        else:
            own = tuple(x * f for x in e)
        rows.append({
            "renderer": "brume", "run": run, "budget_s": t, "measured_s": bt, "spp": "",
            "_mse": own,
            "own_away": np.sqrt(own[1]) / b_ref[away].mean(),
        })
        if a.brume_only:
            print(f"run {run} t={t:g}: brume {bt:.1f} s", flush=True)
            continue
        img, mt, spp = mit.render(t)
        ff = own_share(spp, m_ref_spp)
        rungs.write(json.dumps({
            "run": run, "budget_s": t, "brume_s": bt, "brume_mse_own": own, "mitsuba_s": mt, "mitsuba_spp": spp,
            "mitsuba_mse_own_ref": errors(img, m_ref, away, beam, spot), "mitsuba_own_share": ff,
            "brume_ref_mean": float(b_ref.mean()), "mitsuba_ref_mean": float(m_ref.mean()),
            "mitsuba_integrator": a.integrator, "mitsuba_spot_profile": a.spot_profile,
        }) + "\n")
        rungs.flush()
        img_m[len(rows)] = img
        rows.append({
            "renderer": "mitsuba", "run": run, "budget_s": t, "measured_s": mt, "spp": spp,
            "mitsuba_integrator": a.integrator,
            "_raw": errors(k * img, b_ref, away, beam, spot),
            "own_away": np.sqrt(mse(img, m_ref, away) * ff) / m_ref[away].mean(),
        })
        print(f"run {run} t={t:g}: brume {bt:.1f} s, mitsuba {mt:.1f} s ({spp} spp) [{a.clock}]", flush=True)
    rungs.close()
    var_ref = np.mean(np.array(b_var_ref), axis=0)
    if same_settings:
        meta["brume_var_ref"] = var_ref.tolist()
        meta_path.write_text(json.dumps(meta, indent=2))
    elif stored_var is not None:
        var_ref = np.array(stored_var)
    if halves_var is not None:
        var_ref = np.array(halves_var)
    for i, r in enumerate(rows):
        if r["renderer"] == "mitsuba":
            if lasers:
                r["_mse"] = tuple(max(x - v, 0.0) for x, v in zip(r["_raw"], var_ref))
            else:
                # No laser: Mitsuba's own reference is trustworthy; measure it against that.
                r["rel_rmse"] = r["rel_rmse_away"] = r["own_away"]
                r["rel_rmse_beam"] = r["rel_rmse_nospot"] = ""
                e = errors(img_m[i], m_ref, away, beam, spot)
                r["rel_rmse_bin4"] = np.sqrt(e[3] / (1.0 + r["spp"] / m_ref_spp)) / m_ref.mean()
                continue
        whole, aw, bm, b4 = r["_mse"][:4]
        # Stored variances from before the spot metric have 4 entries: no spot figure then.
        r["rel_rmse_nospot"] = np.sqrt(r["_mse"][4]) / b_ref[~spot].mean() if lasers and len(r["_mse"]) > 4 else ""
        r["rel_rmse_bin4"] = np.sqrt(b4) / mean_ref
        r["rel_rmse"] = np.sqrt(whole) / mean_ref
        r["rel_rmse_away"] = np.sqrt(aw) / b_ref[away].mean()
        r["rel_rmse_beam"] = np.sqrt(bm) / b_ref[beam].mean() if beam.any() else ""

    # Agreement between the references, away from the beam.
    regions = {}
    for ty in range(3):
        for tx in range(4):
            y0, y1, x0, x1 = ty * h // 3, (ty + 1) * h // 3, tx * w // 4, (tx + 1) * w // 4
            m = np.zeros((h, w), dtype=bool)
            m[y0:y1, x0:x1] = True
            m &= away
            if m.sum() < 0.5 * (y1 - y0) * (x1 - x0):
                continue
            regions[f"tile r{ty} c{tx} (x {x0}-{x1}, y {y0}-{y1})"] = {
                "brume": b_ref[m].mean(0).tolist(),
                "mitsuba_times_k": (k * m_ref[m]).mean(0).tolist(),
            }
    between = np.sqrt(mse(k * m_ref, b_ref, away)) / b_ref[away].mean()
    # Noise of each reference, away from the beam, from the ladders (own-reference errors).
    b_noise = np.sqrt(var_ref[1]) / b_ref[away].mean()
    m_rows = [r for r in rows if r["renderer"] == "mitsuba"]
    m_noise = float(np.mean([r["own_away"] * np.sqrt(r["spp"] / m_ref_spp) for r in m_rows])) if m_rows else float("nan")
    agreement = {
        "k_mitsuba_to_brume_fitted_away_from_beam": k_fit,
        "k_used_for_errors": k,
        "k_per_channel_linear_srgb": k_rgb,
        "k_least_squares": k_lsq,
        "k_expected": 1.0,
        "beam_mask_pixels": int(beam.sum()),
        "rel_rmse_between_references_away_from_beam": float(between),
        "predicted_from_reference_noise": float(np.hypot(b_noise, m_noise)),
        "brume_ref_noise_rel": float(b_noise),
        "mitsuba_ref_noise_rel_own": m_noise,
        "region_means_linear_srgb_away_from_beam": regions,
        "whole_image_means": {"brume": b_ref.mean((0, 1)).tolist(), "mitsuba_times_k": (k * m_ref).mean((0, 1)).tolist()},
        "brume_ref_seconds": b_ref_t,
        "mitsuba_ref_seconds": m_ref_t,
        "mitsuba_ref_spp": m_ref_spp,
        "mitsuba_variant": a.variant,
        "mitsuba_integrator": a.integrator,
        "mitsuba_spot_profile": a.spot_profile,
        "mitsuba_floor": a.floor,
        "mitsuba_native_floor_s_per_spp": mit.s_per_spp if mit else None,
        "brume_set": a.brume_set,
        "brume_ref_set": a.brume_ref_set,
        "dropped_lights": a.drop_light,
        "mitsuba_laser_radius": a.mitsuba_laser_radius,
        "error_reference": "brume reference (Mitsuba x k), brume's reference noise removed" if lasers else "own reference",
    }
    if lasers:
        import beam_line_check

        for who, ref in (("brume", b_ref), ("mitsuba", m_ref)):
            tot, mean, se, n = beam_line_check.check(a.scene, ref)
            agreement[f"beam_line_check_{who}_ref"] = {
                "image_over_single_scattering_sum": tot,
                "per_column_mean": mean,
                "per_column_std_error": se,
                "columns": n,
            }
    (a.out.parent / (a.out.name + "-agreement.json")).write_text(json.dumps(agreement, indent=2))
    print(json.dumps({x: y for x, y in agreement.items() if x != "region_means_linear_srgb_away_from_beam"}, indent=2), flush=True)

    cols = ["renderer", "run", "budget_s", "measured_s", "spp", "rel_rmse", "rel_rmse_bin4", "rel_rmse_away", "rel_rmse_beam", "rel_rmse_nospot", "own_away"]
    csv_path = a.out.parent / (a.out.name + ".csv")
    with csv_path.open("w", newline="") as f:
        wr = csv.writer(f)
        wr.writerow(cols[:-1] + ["rel_rmse_away_vs_own_ref", "mitsuba_integrator"])
        for r in rows:
            wr.writerow([f"{r[c]:.5g}" if isinstance(r[c], float) else r[c] for c in cols] + [r.get("mitsuba_integrator", "")])
    for r in rows:
        print(", ".join(f"{c}={r[c]:.4g}" if isinstance(r[c], float) else f"{c}={r[c]}" for c in cols), flush=True)
    summary = summarise(rows, a.clock)
    summary["mitsuba_integrator"] = a.integrator
    summary["mitsuba_spot_profile"] = a.spot_profile
    (a.out.parent / (a.out.name + "-summary.json")).write_text(json.dumps(summary, indent=2))
    print(json.dumps(summary, indent=2), flush=True)
    plot(rows, a.out.parent / (a.out.name + ".png"), a.scene.stem, bool(lasers), a.clock)
    side_by_side(b_ref, k * m_ref, beam, a.out.parent / (a.out.name + "-refs.png"))


def summarise(rows, clock: str) -> dict:
    """Per renderer and budget: mean +- sd over runs of the charged seconds and of the errors;
    the brume / Mitsuba ratio of the means; the slope of log RMSE against log seconds (all runs)."""
    out = {"clock": clock, "budgets": {}, "slope": {}}
    keys = ("measured_s", "rel_rmse", "rel_rmse_bin4", "rel_rmse_away", "rel_rmse_beam", "rel_rmse_nospot")
    for r in rows:
        b = out["budgets"].setdefault(f"{r['budget_s']:g}", {}).setdefault(r["renderer"], {k: [] for k in keys})
        for k in keys:
            if isinstance(r[k], float):
                b[k].append(r[k])
    for per in out["budgets"].values():
        for who, d in per.items():
            per[who] = {k: {"mean": float(np.mean(v)), "sd": float(np.std(v, ddof=1)) if len(v) > 1 else 0.0, "runs": len(v)} for k, v in d.items() if v}
        if "brume" in per and "mitsuba" in per:
            per["ratio_brume_over_mitsuba"] = {
                k: per["brume"][k]["mean"] / per["mitsuba"][k]["mean"]
                for k in ("rel_rmse", "rel_rmse_bin4", "rel_rmse_away", "rel_rmse_beam", "rel_rmse_nospot")
                if k in per["brume"] and k in per["mitsuba"] and per["mitsuba"][k]["mean"] > 0
            }
    for who in ("brume", "mitsuba"):
        pts = [(r["measured_s"], r["rel_rmse"], r["rel_rmse_bin4"]) for r in rows if r["renderer"] == who]
        if len({round(p[0], 3) for p in pts}) > 1:
            lt = np.log([p[0] for p in pts])
            out["slope"][who] = {
                "rel_rmse": float(np.polyfit(lt, np.log([p[1] for p in pts]), 1)[0]),
                "rel_rmse_bin4": float(np.polyfit(lt, np.log([p[2] for p in pts]), 1)[0]),
            }
    return out


def side_by_side(b: np.ndarray, m: np.ndarray, beam: np.ndarray, path: Path) -> None:
    """brume's reference | Mitsuba's (times k) | brume's with the beam mask tinted, one exposure."""
    from PIL import Image

    s = 0.35 / max(float(np.median(b)), 1e-12)

    def enc(x):
        x = np.clip(np.maximum(x * s, 0.0), 0.0, 1.0)
        return np.where(x <= 0.0031308, 12.92 * x, 1.055 * x ** (1 / 2.4) - 0.055)

    tint = enc(b)
    tint[beam] = 0.5 * tint[beam] + np.array([0.5, 0.0, 0.0])
    row = np.concatenate([enc(b), enc(m), tint], axis=1)
    Image.fromarray((row * 255 + 0.5).astype(np.uint8)).save(path)


def plot(rows, path: Path, title: str, laser: bool, clock: str = "wall") -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(5, 3.6), dpi=110)
    for name, colour in (("brume", "C0"), ("mitsuba", "C1")):
        for run in sorted({r["run"] for r in rows if r["renderer"] == name}):
            mine = [r for r in rows if r["renderer"] == name and r["run"] == run]
            first = run == min(r["run"] for r in rows)
            ax.loglog([r["measured_s"] for r in mine], [r["rel_rmse"] for r in mine], "o-", color=colour, label=name if first else None)
            if laser:
                ax.loglog(
                    [r["measured_s"] for r in mine], [r["rel_rmse_away"] for r in mine], "s--", color=colour, alpha=0.6,
                    label=f"{name}, away from beam" if first else None,
                )
    ax.set_xlabel("CPU seconds (2 shared cores)" if clock == "cpu" else "seconds (2 shared cores)")
    ax.set_ylabel("relative RMSE vs brume's reference" if laser else "relative RMSE vs own reference")
    ax.set_title(f"{title}: error vs time")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path)


if __name__ == "__main__":
    main()
