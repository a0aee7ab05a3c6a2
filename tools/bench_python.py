"""Python against the CLI: the same scene, seed and passes rendered by `brume render` and by
`brume.load(...).render(...).save(...)`, each in a process of its own, alternately, RUNS times;
prints the wall and CPU seconds (user + system of the child, from its rusage) of each run and
checks the two EXRs are the same bytes. Used for docs/performance.md ("Python package").

    python tools/bench_python.py --brume target/release/brume --python .venv/bin/python \
        scenes/fog-cube.toml --passes 8 --seed 1 --runs 3
"""

import argparse
import os
import statistics
import subprocess
import tempfile
import time
from pathlib import Path


def timed(cmd):
    t0 = time.monotonic()
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(p.pid, 0)
    wall = time.monotonic() - t0
    p.returncode = os.waitstatus_to_exitcode(status)
    err = p.stderr.read().decode()
    if p.returncode != 0:
        raise SystemExit(f"{cmd[0]} failed: {err}")
    return wall, usage.ru_utime + usage.ru_stime


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scene", type=Path)
    ap.add_argument("--brume", type=Path, default=Path("target/release/brume"))
    ap.add_argument("--python", default=".venv/bin/python")
    ap.add_argument("--passes", type=int, required=True)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--runs", type=int, default=3)
    args = ap.parse_args()
    out = Path(tempfile.mkdtemp())
    cli = [str(args.brume), "render", str(args.scene), "--passes", str(args.passes),
           "--seed", str(args.seed), "-q", "-o", str(out / "cli.exr")]
    code = (f"import brume; brume.load({str(args.scene)!r}).render(passes={args.passes}, "
            f"seed={args.seed}, progress=False).save({str(out / 'py.exr')!r})")
    py = [args.python, "-c", code]
    times = {"cli": [], "python": []}
    for _ in range(args.runs):
        times["cli"].append(timed(cli))
        times["python"].append(timed(py))
    same = (out / "cli.exr").read_bytes() == (out / "py.exr").read_bytes()
    for name, t in times.items():
        walls, cpus = [w for w, _ in t], [c for _, c in t]
        print(f"{name:7s} wall {' '.join(f'{w:.2f}' for w in walls)} s (median "
              f"{statistics.median(walls):.2f}); CPU {' '.join(f'{c:.2f}' for c in cpus)} s "
              f"(median {statistics.median(cpus):.2f})")
    print(f"EXRs byte-identical: {same}")


if __name__ == "__main__":
    main()
