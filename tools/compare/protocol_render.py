"""Timed renders of the protocol (protocol.py): the machine's idleness, brume as a timed child
process, Mitsuba 3 as a warm in-process peer, and the pilot that picks Mitsuba's sampler."""

from __future__ import annotations

import hashlib
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

import mitsuba_scene
from compare import read_rgb

IDLE_LOAD = 0.5
# Seed ranges, disjoint so that no two images share samples (Mitsuba: base + chunk index).
M_PILOT, M_REF, M_RUN = 1_000_000, 10_000_000, 100_000_000
B_REF, B_FIXED = 900_001, 999_999

def cpu_busy(seconds: float = 1.0) -> float:
    """Share of all CPUs busy over `seconds` (this process sleeps meanwhile: it is the others)."""
    def snap():
        f = [int(x) for x in Path("/proc/stat").read_text().split("\n")[0].split()[1:]]
        return sum(f), f[3] + f[4]  # total, idle + iowait
    t0, i0 = snap()
    time.sleep(seconds)
    t1, i1 = snap()
    return 1.0 - (i1 - i0) / max(t1 - t0, 1)


def machine_state(settle: float) -> dict:
    """Wait up to `settle` s for the 1-min load average to fall to IDLE_LOAD (our own previous
    run raises it for about a minute), then record it and the CPUs' busy share."""
    t0 = time.perf_counter()
    while os.getloadavg()[0] > IDLE_LOAD and time.perf_counter() - t0 < settle:
        time.sleep(2.0)
    waited = time.perf_counter() - t0
    load = os.getloadavg()
    st = {"load_before": list(load), "busy_before": cpu_busy(), "waited_s": waited}
    st["idle"] = load[0] <= IDLE_LOAD
    if not st["idle"]:
        print(f"WARNING: NOT IDLE: 1-min load average {load[0]:.2f} > {IDLE_LOAD} at a run's start "
              f"(CPUs {100 * st['busy_before']:.0f} % busy): this run's timing is not a measurement",
              file=sys.stderr, flush=True)
    return st


def cpu_of(cpuinfo: str) -> dict:
    """The CPU's model name and its widest SIMD level, from /proc/cpuinfo's text."""
    model = next((line.split(":", 1)[1].strip() for line in cpuinfo.splitlines()
                  if line.startswith("model name")), None)
    flags = next((set(line.split(":", 1)[1].split()) for line in cpuinfo.splitlines()
                  if line.startswith("flags")), set())
    simd = next((level for level, flag in (("avx512", "avx512f"), ("avx2", "avx2"), ("avx", "avx"), ("sse4.2", "sse4_2"))
                 if flag in flags), None)
    return {"model": model, "simd": simd}


def host(drjit=None) -> dict:
    """The host a comparison ran on: Mitsuba's LLVM kernels gain from wide SIMD and brume's scalar
    code does not, so a ratio holds for its host only (docs/performance.md: on an AVX2 host
    Mitsuba rendered fog-cube at a third of the spp/s of the morning's host, brume at 0.6-0.8x).
    With `drjit` given, its LLVM target CPU as Dr.Jit chose it (None where the symbol is absent)."""
    try:
        rec = cpu_of(Path("/proc/cpuinfo").read_text())
    except OSError:
        rec = {"model": None, "simd": None}
    rec["cores"] = os.cpu_count()
    if drjit is not None:
        try:
            import ctypes

            lib = ctypes.CDLL(str(Path(drjit.__file__).parent / "libdrjit-core.so"))
            f = lib._Z19jit_llvm_target_cpuv  # jit_llvm_target_cpu(), a C++ symbol of Dr.Jit's core
            f.restype = ctypes.c_char_p
            rec["drjit_llvm_cpu"] = (f() or b"").decode() or None
        except (OSError, AttributeError):
            rec["drjit_llvm_cpu"] = None
    return rec


# ----------------------------------------------------------------------------- brume

def check_radiometric(path: Path) -> None:
    import OpenEXR

    with OpenEXR.File(str(path)) as f:
        units = f.header().get("brumeUnits")
    if units is not None and units != "radiometric":
        raise SystemExit(f"{path}: brumeUnits = {units}: Mitsuba's images are radiometric")


def brume_cmd(brume: str, scene: Path, seed: int, out: Path, sets: list[str], budget: list[str]) -> list[str]:
    cmd = [brume, "render", str(scene), "--seed", str(seed), "-o", str(out), "--quiet"] + budget
    for s in sets:
        cmd += ["--set", s]
    return cmd


def run_timed(cmd: list[str]) -> dict:
    """Run a child; its wall seconds (whole process) and CPU seconds (rusage, all threads)."""
    t0 = time.perf_counter()
    proc = subprocess.Popen(cmd)
    _, status, ru = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - t0
    if os.waitstatus_to_exitcode(status) != 0:
        raise SystemExit(f"failed: {' '.join(cmd)}")
    cpu = ru.ru_utime + ru.ru_stime
    return {"wall_s": wall, "cpu_s": cpu, "cpu_per_wall": cpu / wall, "cmd": cmd}


def brume_render(brume, scene, seconds, seed, out, sets) -> tuple[np.ndarray, dict]:
    rec = run_timed(brume_cmd(brume, scene, seed, out, sets, ["--time", f"{seconds:g}"]))
    check_radiometric(out)
    return read_rgb(out), rec


def brume_fixed_cost(brume, scene, out, sets) -> dict:
    """brume's cost outside its passes (process start, scene load, automatic pilots): a 1-pass
    run minus the per-pass cost from a 3-pass run; and `brume info` (start and load alone)."""
    r1 = run_timed(brume_cmd(brume, scene, B_FIXED, out, sets, ["--passes", "1"]))
    r3 = run_timed(brume_cmd(brume, scene, B_FIXED, out, sets, ["--passes", "3"]))
    per = (r3["wall_s"] - r1["wall_s"]) / 2
    info = [brume, "info", str(scene)] + [x for s in sets for x in ("--set", s)]
    t0 = time.perf_counter()
    subprocess.run(info, check=True, stdout=subprocess.DEVNULL)
    return {"fixed_wall_s": r1["wall_s"] - per, "per_pass_wall_s": per, "info_wall_s": time.perf_counter() - t0,
            "passes_1": r1, "passes_3": r3}


def file_sha(path: str) -> str:
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()[:16]


class Peer:
    """Mitsuba 3 with one sampler, JIT warm: images of a wall-clock budget in calls of `chunk` spp."""

    def __init__(self, mi, scene: Path, desc: dict, sampler: str, chunk: int, integrator: str, spot: str, floor: str):
        self.mi, self.chunk, self.sampler = mi, chunk, sampler
        d = mitsuba_scene.load(scene, chunk, floor=floor, integrator=integrator, spot_profile=spot,
                               sampler=sampler, desc=desc)
        self.scene = mi.load_dict(d)
        self.render(0.0, 0)  # warm-up: JIT compilation, not timed (seed 0 is in no other range)

    def _call(self, seed: int) -> np.ndarray:
        # np.asarray forces the evaluation, so the timer sees the whole render.
        return np.asarray(self.mi.render(self.scene, spp=self.chunk, seed=seed), dtype=np.float64)

    def render(self, seconds: float, seed0: int) -> tuple[np.ndarray, dict]:
        acc, n = None, 0
        w0, c0 = time.perf_counter(), time.process_time()
        while acc is None or time.perf_counter() - w0 < seconds:
            img = self._call(seed0 + n)
            acc = img if acc is None else acc + img
            n += 1
        wall, cpu = time.perf_counter() - w0, time.process_time() - c0
        rec = {"wall_s": wall, "cpu_s": cpu, "cpu_per_wall": cpu / wall, "spp": n * self.chunk,
               "calls": n, "first_seed": seed0, "sampler": self.sampler}
        return acc / n, rec


def pilot(make_peer, seconds: float) -> tuple[Peer, dict]:
    """Per sampler, two images of `seconds` each: RMSE = sqrt(mean((A - B)^2) / 2) relative to
    their mean, scaled to the budget. Returns the best sampler's peer and the table."""
    table, peers = {}, {}
    for i, name in enumerate(mitsuba_scene.SAMPLERS):
        peer = make_peer(name)
        a, ra = peer.render(seconds, M_PILOT + i * 100_000)
        b, rb = peer.render(seconds, M_PILOT + i * 100_000 + 50_000)
        t = 0.5 * (ra["wall_s"] + rb["wall_s"])
        bad = nonfinite(a) + nonfinite(b)
        # An image with NaN or inf pixels is unusable whatever its RMSE elsewhere (Mitsuba 3.9's
        # stratified and multijitter leave one NaN pixel per 64-spp call on smoke-plume).
        rmse = np.inf if bad else np.sqrt(np.mean((a - b) ** 2) / 2) / np.mean(0.5 * (a + b))
        table[name] = {"rel_rmse": float(rmse), "rel_rmse_nominal": float(rmse * np.sqrt(t / seconds)),
                       "nonfinite_pixels": bad, "wall_s": [ra["wall_s"], rb["wall_s"]], "spp": [ra["spp"], rb["spp"]]}
        why = f"DISQUALIFIED: {bad} NaN/inf pixels" if bad else f"rel RMSE {table[name]['rel_rmse_nominal']:.4g} at {seconds:g} s"
        print(f"pilot {name:12s}: {why} ({ra['spp']} spp per image)", flush=True)
        peers[name] = peer
    best = min(table, key=lambda k: table[k]["rel_rmse_nominal"])
    if not np.isfinite(table[best]["rel_rmse_nominal"]):
        raise SystemExit("pilot: every sampler's images have NaN/inf pixels")
    return peers[best], {"seconds": seconds, "samplers": table, "chosen": best}


def nonfinite(img: np.ndarray) -> int:
    return int((~np.isfinite(img).all(-1)).sum())


def chunk_ok(chunk: int) -> None:
    """stratified / multijitter want a square spp, ldsampler a power of two: 64 is both."""
    root = int(round(chunk ** 0.5))
    if chunk < 64 or root * root != chunk or chunk & (chunk - 1):
        raise SystemExit(f"--chunk-spp {chunk}: use >= 64, a square and a power of two (64, 256, 1024, ...)")
