"""Distributed renders for real: Dask (a LocalCluster of 2 worker processes) and the Slurm
array script of docs/distributed.md, each merged and compared with one process."""

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

import brume
from conftest import ROOT, SCENE, SMALL

sys.path.insert(0, str(ROOT / "examples" / "python"))


def test_dask_farm_merges_into_the_single_process_film(tmp_path):
    distributed = pytest.importorskip("distributed")
    from dask_farm import render_on_dask

    parts = tmp_path / "parts"
    parts.mkdir()
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=None)
    try:
        with distributed.Client(cluster) as client:
            assert len(client.scheduler_info()["workers"]) == 2
            merged = render_on_dask(client, SCENE, passes=6, parts=3, folder=parts, seed=7,
                                    sets=SMALL)
    finally:
        cluster.close()
    assert sorted(p.name for p in parts.iterdir()) == [
        "part-0-2.brume", "part-2-4.brume", "part-4-6.brume"]
    single = brume.load(SCENE, set=SMALL).render(passes=6, seed=7, progress=False)
    single.save(tmp_path / "single.brume")
    merged.save(tmp_path / "merged.brume")
    assert (tmp_path / "single.brume").read_bytes() == (tmp_path / "merged.brume").read_bytes()
    # The images too, written from the films as `brume merge` writes them.
    brume.read_film(tmp_path / "single.brume").save(tmp_path / "single.exr")
    merged.save(tmp_path / "merged.exr")
    assert (tmp_path / "single.exr").read_bytes() == (tmp_path / "merged.exr").read_bytes()


def slurm_scripts():
    """The array script and the merge command of docs/distributed.md, as written there."""
    doc = (ROOT / "docs" / "distributed.md").read_text()
    section = doc[doc.index("### Slurm job array"):doc.index("### Kubernetes")]
    blocks = re.findall(r"```bash\n(.*?)```", section, re.S)
    assert len(blocks) == 2, "docs/distributed.md: expected the array script and merge.sh"
    return blocks


def test_the_slurm_array_script_runs_task_by_task_and_merges(cli, tmp_path):
    """Runs the documented array script with SLURM_ARRAY_TASK_ID = 0, 1, ... in a loop (no
    Slurm: the tasks run one after the other here), then the documented merge, and compares
    with one render of all passes. Scaled down: 4 tasks of 2 passes instead of 40 of 25, on
    chromatic-fog at a test's size."""
    array, merge = slurm_scripts()
    tasks = re.search(r"#SBATCH --array=0-(\d+)", array)
    assert tasks and re.search(r"^PER=25 ", array, re.M)
    script = array.replace("PER=25 ", "PER=2 ")
    (tmp_path / "scene.toml").write_text(SCENE.read_text())
    (tmp_path / "parts").mkdir()
    sets = [f"--set {k}={v}" for k, v in SMALL.items()]
    # The small scene's overrides ride on the documented command line.
    script = script.replace("brume render scene.toml", "brume render scene.toml " + " ".join(sets))
    env = {**os.environ, "PATH": f"{cli.exe.parent}{os.pathsep}{os.environ['PATH']}"}
    for task in range(4):
        subprocess.run(["bash", "-c", script], cwd=tmp_path, check=True, timeout=300,
                       env={**env, "SLURM_ARRAY_TASK_ID": str(task)})
    subprocess.run(["bash", "-c", merge], cwd=tmp_path, check=True, timeout=300, env=env)
    cli("render", "scene.toml", *" ".join(sets).split(), "--seed", 7,
        "--set", "integrator.max_gather_bytes=4000000000", "--passes", 8, "-q",
        "-o", "single.brume", cwd=tmp_path)
    # The images of the single run's film as `brume merge` writes them (a render's own images
    # are the same bytes too, the automatic settings' choice in the EXR header included:
    # tests/reliability_cli/auto_budgets.rs).
    cli("merge", "single.brume", "-o", "single.exr", "-o", "single.png", "-q", cwd=tmp_path)
    for ext in ("exr", "png"):
        assert (tmp_path / f"out.{ext}").read_bytes() == (tmp_path / f"single.{ext}").read_bytes()
