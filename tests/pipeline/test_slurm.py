"""The SLURM recipe (pipeline/slurm/dask_pipeline.sbatch): valid bash, and a real run of it on
this machine with a stand-in for `srun` that starts its command here, as one node would."""
import json
import os
import subprocess
import uuid
from pathlib import Path

import pytest

from conftest import ROOT, tool

SCRIPT = ROOT / "pipeline" / "slurm" / "dask_pipeline.sbatch"
SRUN = """#!/usr/bin/env bash
# srun for one node: drop srun's own options, run the command here.
while [ $# -gt 0 ] && [[ "$1" == --* ]]; do shift; done
exec "$@"
"""


def test_recipe_is_valid_bash():
    r = subprocess.run(["bash", "-n", str(SCRIPT)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr


@pytest.mark.slow  # a real scheduler and workers, about 13 s
def test_recipe_runs_an_experiment_on_its_cluster(pipeline_env, tmp_path):
    pytest.importorskip("distributed")
    tool("mesher")
    doc = {"stages": {"cube": {"tool": "mesher", "config": {
        "source": {"kind": "cuboid", "cells": [1, 1, 1], "size": [0.01, 0.01, 0.01]}},
        "sweep": {"source.cells": [[1, 1, 1], [2, 1, 1]]}}}}
    (Path(pipeline_env["PIPELINE_EXPERIMENTS"]) / "t.json").write_text(json.dumps(doc))
    fake = tmp_path / "bin"
    fake.mkdir()
    (fake / "srun").write_text(SRUN)
    (fake / "srun").chmod(0o755)
    env = dict(pipeline_env, PATH=f"{fake}:{os.environ['PATH']}", REPO=str(ROOT), EXPERIMENT="t",
               SLURM_JOB_ID=f"test-{uuid.uuid4().hex[:8]}", SLURM_JOB_NUM_NODES="1", SLURM_CPUS_PER_TASK="2",
               TMPDIR=str(tmp_path))
    r = subprocess.run(["bash", str(SCRIPT)], cwd=tmp_path, env=env, capture_output=True, text=True, timeout=180)
    assert r.returncode == 0, r.stdout + r.stderr[-3000:]
    assert "Dask cluster" in r.stdout and "pipeline: 2 ran" in r.stdout, r.stdout
    assert not (ROOT / "build" / f"dask-scheduler-{env['SLURM_JOB_ID']}.json").exists()
