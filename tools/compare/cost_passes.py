"""Per-pass wall time and work counters of fixed-budget passes on the protocol scenes (each
stripped of its [integrator] table, at the q its automatic choice takes for seed 3), for
fitting the tuner's cost weights (`integrator::auto::COST_WEIGHTS`; cost_fit.py). A pass's time
is that of an 8-pass render minus a 2-pass one, over 6, so that start-up and loading cancel.
Each record also holds the image's pixels x spectral bins, which every pass pays for whatever
its budgets (its pass buffer, the splats' drain, the film's sums; cost_fit.py fits a weight for
it). Run on an idle machine. Output: JSON lines, one per (scene, forward rays, camera paths).

    python tools/compare/cost_passes.py target/release/brume passes.jsonl
"""
import json
import re
import subprocess
import sys
import time
import tomllib
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from protocol_scene import strip_integrator  # noqa: E402

SCENES = [
    ("fog-cube", "scenes/fog-cube.toml", []),
    ("fog-cube-09", "scenes/fog-cube.toml", ["media.fog.sigma_s=0.9", "media.fog.sigma_a=0.1"]),
    ("height-fog", "tools/compare/scenes/height-fog.toml", []),
    ("fog-bank", "tools/compare/scenes/fog-bank.toml", []),
    ("smoke-plume", "scenes/smoke-plume.toml", []),
    ("chromatic-cube", "tools/compare/scenes/chromatic-cube.toml", []),
    ("chromatic-fog", "scenes/chromatic-fog.toml", []),
    ("fog-room-laser", "scenes/fog-room-laser.toml", ['lights.3.spectrum="laser-532nm.csv"']),
]
# `brume render -v`'s work line: paths, volumes, rays, gather hits, forward segments.
WORK = re.compile(
    r"work: (\d+) camera paths, (\d+) volume records, (\d+) forward rays, (\d+) gather hits, "
    r"(\d+) forward segments"
)
Q = re.compile(r"q = \[([^\]]*)\]")


def run(brume, scene, sets, passes):
    cmd = [brume, "render", str(scene), "--seed", "3", "--passes", str(passes), "-o", "/tmp/cost.exr", "-v"]
    for s in sets:
        cmd += ["--set", s]
    t0 = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True)
    t = time.perf_counter() - t0
    if p.returncode:
        raise SystemExit(p.stderr)
    out = p.stderr + p.stdout
    return t, [int(x) for x in WORK.search(out).groups()], Q.search(out)


def main():
    brume, out_path = sys.argv[1], sys.argv[2]
    with open(out_path, "a") as out:
        for name, path, sets in SCENES:
            src = Path(path)
            text, _, _ = strip_integrator(src.read_text())
            desc = tomllib.loads(text)
            # Every protocol scene names its image's size and bins.
            pixel_bins = desc["camera"]["width"] * desc["camera"]["height"] * desc["film"]["bins"]
            tmp = src.parent / f".cost-{src.stem}.toml"
            tmp.write_text(text)
            try:
                _, _, q = run(brume, tmp, sets, 1)
                qs = q.group(1) if q else ""
                for rays in (12500, 50000, 200000):
                    for s in (1, 4):
                        cfg = sets + [f"integrator.forward_rays={rays}", f"integrator.camera_samples={s}"]
                        if qs:
                            cfg.append(f"integrator.q={qs.split(',')[0].strip()}")
                        t2, w2, _ = run(brume, tmp, cfg, 2)
                        t8, w8, _ = run(brume, tmp, cfg, 8)
                        rec = {"scene": name, "rays": rays, "samples": s, "q": qs,
                               "pixel_bins": pixel_bins,
                               "sec_per_pass": (t8 - t2) / 6,
                               "work_per_pass": [(a - b) / 6 for a, b in zip(w8, w2)]}
                        print(json.dumps(rec), file=out, flush=True)
            finally:
                tmp.unlink()


if __name__ == "__main__":
    main()
