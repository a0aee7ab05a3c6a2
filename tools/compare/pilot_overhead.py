"""The automatic pilots' overhead (issue 30: under 10 % of a 10 s render), scene by scene.

    python tools/compare/pilot_overhead.py [SCENE ...] [--brume target/release/brume] [--seed 3] [--repeats 3]

For each scene, its `[integrator]` table stripped as protocol.py strips it (brume's defaults):
a 1-pass render with the automatic settings, the same render with the choice that `--verbose`
prints pinned (q, forward rays, camera paths and, where the pilots chose it, radius_indirect:
no pilots then), and 3 passes pinned, each `--repeats` times interleaved; medians. The pilots'
time is the automatic 1-pass render minus the pinned one; a pass's time is half the difference
between the pinned 3-pass and 1-pass renders; the fixed cost (start-up, load and pilots) is the
automatic 1-pass render minus a pass. Run on an idle machine; prints one Markdown row per scene.
Without scenes: the eight protocol scenes of tools/compare/protocol.sh.
"""
from __future__ import annotations

import argparse
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from protocol_scene import strip_integrator  # noqa: E402

SCENES = [
    "scenes/fog-cube.toml",
    "tools/compare/scenes/height-fog.toml",
    "tools/compare/scenes/chromatic-cube.toml",
    "scenes/smoke-plume.toml",
    "scenes/chromatic-fog.toml",
    "tools/compare/scenes/fog-bank.toml",
    "scenes/valley-fog.toml",
    "scenes/fog-room-laser.toml",
]


def run(brume: str, args: list[str]) -> tuple[float, str]:
    t = time.perf_counter()
    r = subprocess.run([brume, *args], capture_output=True, text=True)
    wall = time.perf_counter() - t
    if r.returncode:
        raise SystemExit(f"{brume} {' '.join(args)}: {r.stderr.strip()}")
    return wall, r.stderr + r.stdout


def pinned(choice: str, radius: float) -> tuple[list[str], str]:
    """The --set options that pin the choice line's settings, and the choice in short."""
    q = re.search(r"q = \[([^\]]*)\]", choice).group(1)
    n = re.search(r"forward_rays = (\d+)", choice).group(1)
    c = re.search(r"camera_samples = (\d+)", choice).group(1)
    ri = re.search(r"radius_indirect = ([0-9.]+) x radius", choice)
    scale = float(ri.group(1)) if ri else 1.0
    sets = ["--set", f"integrator.q=[{q}]" if "," in q else f"integrator.q={q}"]
    sets += ["--set", f"integrator.forward_rays={n}", "--set", f"integrator.camera_samples={c}"]
    if scale != 1.0:
        sets += ["--set", f"integrator.radius_indirect={scale * radius}"]
    return sets, f"{q}, {n}, {c}, {scale:g}x"


def measure(brume: str, scene: Path, seed: int, repeats: int) -> str:
    # Beside the scene, so that its relative paths (spectra, meshes, textures) still resolve.
    with tempfile.NamedTemporaryFile("w", suffix=".toml", dir=scene.parent, prefix=".overhead-") as f:
        f.write(strip_integrator(scene.read_text())[0])
        f.flush()
        info = run(brume, ["info", f.name])[1]
        radius = float(re.search(r"^radius:\s+([0-9.e+-]+) m", info, re.M).group(1))
        out = Path(tempfile.mkdtemp())
        auto, one, three, short = [], [], [], ""
        common = ["--seed", str(seed), "--quiet"]
        for _ in range(repeats):
            w, text = run(brume, ["render", f.name, "--passes", "1", "--verbose", "-o", str(out / "a.exr"), "--seed", str(seed)])
            auto.append(w)
            choice = next(line for line in text.splitlines() if line.startswith("auto: chosen"))
            sets, short = pinned(choice, radius)
            one.append(run(brume, ["render", f.name, "--passes", "1", *common, "-o", str(out / "p1.exr"), *sets])[0])
            three.append(run(brume, ["render", f.name, "--passes", "3", *common, "-o", str(out / "p3.exr"), *sets])[0])
    m = statistics.median
    a_pass = (m(three) - m(one)) / 2
    pilots = m(auto) - m(one)
    fixed = m(auto) - a_pass
    return (f"| {scene.stem} | {short} | {a_pass:.2f} s | {pilots:.2f} s ({pilots / 10 * 100:.0f} % of 10 s) "
            f"| {fixed:.2f} s ({fixed / 10 * 100:.0f} % of 10 s) |")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scenes", nargs="*", default=SCENES)
    ap.add_argument("--brume", default="target/release/brume")
    ap.add_argument("--seed", type=int, default=3)
    ap.add_argument("--repeats", type=int, default=3)
    a = ap.parse_args()
    print("| scene (defaults) | the choice (q, forward rays, camera paths, radius for scattered light) | a pass | the pilots | start-up, load and pilots |")
    print("|---|---|---|---|---|")
    for s in a.scenes:
        print(measure(a.brume, Path(s), a.seed, a.repeats), flush=True)


if __name__ == "__main__":
    main()
