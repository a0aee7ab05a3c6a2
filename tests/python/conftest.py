"""Shared fixtures for brume's Python reference checks.

brume is located by BRUME_BIN (default target/release/brume) and the colour chart example by
BRUME_COLOUR_CHART (default target/release/examples/colour_chart), relative to the repo root.
"""

import json
import os
import subprocess
import warnings
from pathlib import Path

import pytest

warnings.filterwarnings("ignore")  # colour-science warns about optional packages it lacks

ROOT = Path(__file__).resolve().parents[2]


def _exe(env, default):
    p = Path(os.environ.get(env, default))
    return p if p.is_absolute() else ROOT / p


BRUME = _exe("BRUME_BIN", "target/release/brume")
CHART = _exe("BRUME_COLOUR_CHART", "target/release/examples/colour_chart")


def run_brume(*args, check=True):
    # A guard against a hang, not a time limit (those belong in benchmarks): a debug build's
    # 128-pass render with automatic budgets can take over a minute on 2 busy cores.
    r = subprocess.run([str(BRUME), *map(str, args)], capture_output=True, text=True, timeout=600)
    if check and r.returncode != 0:
        raise AssertionError(f"brume {' '.join(map(str, args))} failed: {r.stderr}")
    return r


def brume_json(*args):
    return json.loads(run_brume(*args, "--json").stdout)


@pytest.fixture(scope="session")
def brume():
    if not BRUME.exists():
        pytest.fail(f"brume binary not found at {BRUME} (build it or set BRUME_BIN)")
    return BRUME


@pytest.fixture(scope="session")
def chart_bin():
    if not CHART.exists():
        pytest.fail(f"colour_chart example not found at {CHART} (set BRUME_COLOUR_CHART)")
    return CHART
