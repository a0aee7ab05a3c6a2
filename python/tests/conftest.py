"""Shared fixtures of the Python package's tests (python/tests).

The package is imported from the environment (tools/test-all.sh installs it with maturin); the
CLI it is compared with is BRUME_BIN (default target/debug/brume, relative to the repo root).
"""

import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SCENE = ROOT / "scenes" / "chromatic-fog.toml"
LAMP = ROOT / "examples" / "python" / "lamp-fog.toml"
# chromatic-fog at a test's size: a few thousand forward rays on 24 x 12 pixels.
SMALL = {"camera.width": 24, "camera.height": 12, "integrator.forward_rays": 2000}


def _bin():
    p = Path(os.environ.get("BRUME_BIN", "target/debug/brume"))
    return p if p.is_absolute() else ROOT / p


def cli_sets(sets):
    """A `set` dict as the CLI's `--set KEY=VALUE` arguments (numbers only here)."""
    out = []
    for k, v in sets.items():
        out += ["--set", f"{k}={v}"]
    return out


@pytest.fixture(scope="session")
def cli():
    exe = _bin()
    if not exe.exists():
        pytest.fail(f"brume binary not found at {exe} (build it or set BRUME_BIN)")

    def run(*args, cwd=None, check=True):
        r = subprocess.run([str(exe), *map(str, args)], capture_output=True, text=True,
                           timeout=300, cwd=cwd)
        if check and r.returncode != 0:
            raise AssertionError(f"brume {' '.join(map(str, args))} failed: {r.stderr}")
        return r

    run.exe = exe
    return run
