"""How far budgets alone can take brume on a scene: the automatic settings' own cost-variance model.

`brume render --verbose` prints the model its pilots fitted (docs/scene-format.md, "Automatic
settings"): a pass of s camera paths per pixel and N forward rays has variance
`a / s + b / N + c / (s N)` (camera-side noise, forward-ray noise shared by all pixels, and the
gather's noise, which both average) and costs `d s + e N + f s N` seconds (camera paths, forward
rays, and the gather hits between them). Equal-time error goes as the square root of the product
V C. By the Cauchy-Schwarz inequality, for every (s, N)

    V C >= (sqrt(a d) + sqrt(b e) + sqrt(c f))^2,

with equality when each variance term is in proportion to its cost term; the automatic choice
sits on that bound. So the error at equal time is the sum of three parts, sqrt(ad), sqrt(be) and
sqrt(cf), and no choice of budgets removes any of them: making one part cheaper or less noisy by
a factor m lowers the error by that part's share times (1 - 1/sqrt(m)). This prints, per seed,
the chosen budgets, V C, the bound and each part's share of the error.

    python tools/compare/auto_bound.py --brume target/release/brume SCENE --seeds 1,2,3,4,5 [--set K=V ...]

Renders one film pass per seed after the pilots (a few seconds each); the model's costs are
measured times, so run it on an idle machine.
"""
from __future__ import annotations

import argparse
import math
import re
import subprocess
import tempfile
from pathlib import Path

NUM = r"([0-9.eE+-]+)"
BUDGETS = re.compile(
    r"camera paths (\d+) and forward rays (\d+): variance per pass = " + NUM + r"/paths \+ " + NUM
    + r"/rays \+ " + NUM + r"/\(paths x rays\), cost = " + NUM + r" paths \+ " + NUM + r" rays \+ "
    + NUM + r" paths x rays"
)


def model(brume: str, scene: str, seed: int, sets: list[str]) -> tuple[float, ...]:
    """(s, N, a, b, c, d, e, f) from the pilots of one seed."""
    with tempfile.TemporaryDirectory() as tmp:
        cmd = [brume, "render", scene, "--passes", "1", "--seed", str(seed), "--verbose",
               "-o", str(Path(tmp) / "pass.exr")]
        for s in sets:
            cmd += ["--set", s]
        out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
    m = BUDGETS.search(out)
    if m is None:
        raise SystemExit(f"seed {seed}: no budget model in the output (are forward_rays and camera_samples automatic?)")
    return tuple(float(x) for x in m.groups())


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("scene")
    p.add_argument("--brume", default="brume")
    p.add_argument("--seeds", default="1,2,3,4,5")
    p.add_argument("--set", action="append", default=[], dest="sets")
    a = p.parse_args()
    shares = []
    for seed in (int(x) for x in a.seeds.split(",")):
        s, n, va, vb, vc, cd, ce, cf = model(a.brume, a.scene, seed, a.sets)
        v = va / s + vb / n + vc / (s * n)
        c = cd * s + ce * n + cf * s * n
        parts = [math.sqrt(va * cd), math.sqrt(vb * ce), math.sqrt(vc * cf)]
        total = sum(parts)
        shares.append([x / total for x in parts])
        print(f"seed {seed}: {s:.0f} camera paths, {n:.0f} forward rays; V C = {v * c:.4g}, bound "
              f"{total ** 2:.4g}; error shares: camera {parts[0] / total:.2f}, forward rays "
              f"{parts[1] / total:.2f}, gather {parts[2] / total:.2f}")
    mean = [sum(col) / len(col) for col in zip(*shares)]
    print(f"mean shares: camera {mean[0]:.2f}, forward rays {mean[1]:.2f}, gather {mean[2]:.2f}")


if __name__ == "__main__":
    main()
