"""The README's five-line example (and docs/python.md's copy of it) runs as written."""

import os
import re
import subprocess
import sys

from conftest import ROOT


def example(doc):
    blocks = re.findall(r"```python\n(.*?)```", (ROOT / doc).read_text(), re.S)
    assert blocks, f"{doc}: no python example"
    return blocks[0]


def test_the_readme_example_runs_as_written(tmp_path):
    code = example("README.md")
    assert len(code.strip().splitlines()) == 5
    assert code == example("docs/python.md")
    # From a folder like the repository's root: `scenes/` beside it, the output written there.
    os.symlink(ROOT / "scenes", tmp_path / "scenes")
    r = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True,
                       text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    assert r.stdout.startswith("(32, 64, 32) ")
    assert (tmp_path / "fog.exr").stat().st_size > 0
