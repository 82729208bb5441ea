"""The pipeline on Dask distributed, with real processes: a local cluster of 2 workers gives the
local pool's artifacts byte for byte and a second run skips everything; a worker killed in the
middle of a run costs nothing but time; a worker that sees another binary than the client is
refused, by name; a worker that matches runs the experiment through --scheduler."""
import hashlib
import json
import os
import shutil
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import ROOT, run_pipeline, tool
from procs_util import gone, parent_of, signal_in_flight, wait_until

pytest.importorskip("distributed")
# Each starts a real cluster (10-20 s apiece): run by `make test-ci` and `make test-all`.
pytestmark = pytest.mark.slow

SMALL = {"results": "mesh", "stages": {
    "cube": {"tool": "mesher", "config": {"source": {"kind": "cuboid", "cells": [1, 1, 1], "size": [0.01, 0.01, 0.01]}},
             "sweep": {"source.cells": [[1, 1, 1], [2, 1, 1], [2, 2, 1], [2, 2, 2]]}},
    "table": {"report": "pipeline.reports.meshes", "inputs": ["cube"], "params": {"order": ["cube"]}}}}
# Runs of about a second each: long enough to kill a worker in the middle of one.
SLOW = {"results": "mesh", "stages": {
    "cube": {"tool": "mesher", "config": {"source": {"kind": "cuboid", "cells": [30, 30, 30], "size": [0.01, 0.01, 0.01]}},
             "sweep": {"source.size": [[0.01, 0.01, 0.01], [0.02, 0.01, 0.01], [0.03, 0.01, 0.01]]}}}}


def env_for(tmp_path, name, doc):
    """An environment with the experiment `t` = doc and its own results and cache under tmp_path/name."""
    env = dict(os.environ)
    exps = tmp_path / "experiments"
    exps.mkdir(exist_ok=True)
    (exps / "t.json").write_text(json.dumps(doc))
    env.update(PIPELINE_EXPERIMENTS=str(exps), PIPELINE_RESULTS=str(tmp_path / name / "results"),
               PIPELINE_CACHE=str(tmp_path / name / "cache"))
    return env


def tree_hashes(folder: Path, skip=()) -> dict:
    return {str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file() and p.parent.name not in skip}


def outputs(env) -> dict:
    """sha256 of every artifact in the cache and every file in results/; of the manifest, every
    run's key and output hashes (it also names the cache folder, which differs)."""
    cache, results = Path(env["PIPELINE_CACHE"]), Path(env["PIPELINE_RESULTS"])
    files = tree_hashes(results)
    files.pop("manifest.json")
    manifest = json.loads((results / "manifest.json").read_text())["experiments"]["t"]
    runs = {r["run"]: (r["status"], r["key"], r.get("sha256"), sorted((r.get("outputs") or {}).values()))
            for r in manifest}
    return {"artifacts": tree_hashes(cache / "artifacts"), "results": files, "runs": runs}


def leftovers(env) -> list:
    """Anything half-written in the cache: temporary files, staged artifacts."""
    cache = Path(env["PIPELINE_CACHE"])
    return [str(p) for p in cache.rglob("*") if p.is_file() and (".tmp." in p.name or "staging" in p.parts)]


def local_run(tmp_path, doc):
    """The experiment through the local pool: the reference, and the environment of a second
    cache for the same experiment."""
    tool("mesher")
    local = env_for(tmp_path, "local", doc)
    r = run_pipeline(local, "run", "t", "-j", "2")
    assert r.returncode == 0, r.stdout + r.stderr
    return local, env_for(tmp_path, "dask", doc)


def test_local_cluster_gives_the_local_pool_artifacts_and_skips_on_second_run(tmp_path):
    local, dask = local_run(tmp_path, SMALL)
    first = run_pipeline(dask, "run", "t", "--executor", "dask-local", "-j", "2")
    assert first.returncode == 0, first.stdout + first.stderr
    assert "local Dask cluster" in first.stdout and "pipeline: 5 ran" in first.stdout, first.stdout
    assert outputs(dask) == outputs(local)
    assert len(outputs(dask)["artifacts"]) == 4 and len(outputs(dask)["runs"]) == 5
    # Per-run logs reach the client's cache as they do locally.
    logs = sorted(p.name for p in (Path(dask["PIPELINE_CACHE"]) / "logs").iterdir())
    assert logs == [f"t.cube.{i}.log" for i in range(4)]
    second = run_pipeline(dask, "run", "t", "--executor", "dask-local", "-j", "2")
    assert second.returncode == 0, second.stdout + second.stderr
    assert "pipeline: 5 cached" in second.stdout, second.stdout
    assert leftovers(dask) == []


def test_worker_killed_mid_run_is_retried_and_results_are_identical(tmp_path):
    local, dask = local_run(tmp_path, SLOW)
    proc = subprocess.Popen([sys.executable, "-m", "pipeline", "run", "t", "--executor", "dask-local", "-j", "2"],
                            cwd=ROOT, env=dask, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    # A mesher in flight: its parent is the worker process running it.
    stdout, stderr, meshers = signal_in_flight(proc, "mesher", signal.SIGKILL, lambda _, pids: parent_of(pids[0]))
    assert proc.returncode == 0, stdout + stderr
    assert "pipeline: 3 ran" in stdout, stdout
    # The console says which worker was lost with which run, and that the run ran again ...
    lost = [line for line in stdout.splitlines() if line.startswith("pipeline: lost Dask worker")]
    assert len(lost) == 1 and "while it ran t cube#" in lost[0] and "resubmitted" in lost[0], stdout
    moved = lost[0].split("while it ran t ")[1].split(";")[0]
    # ... and so does that run's log, written by the worker that ran it again.
    log = Path(dask["PIPELINE_CACHE"]) / "logs" / f"t.{moved.replace('#', '.')}.log"
    assert "was lost while running this; the run was resubmitted" in log.read_text(), log.read_text()
    # The killed worker's tool died with it (no orphan writing into the cache) ...
    assert wait_until(lambda: gone(meshers[0]), timeout=10)
    # ... nothing half-written stays, and the results equal a clean local run.
    assert leftovers(dask) == []
    assert outputs(dask) == outputs(local)


class Cluster:
    """A Dask scheduler and workers started the way a user starts them (dask-scheduler,
    dask-worker), meeting through a scheduler file."""

    def __init__(self, tmp_path):
        self.file = tmp_path / "scheduler.json"
        self.procs = []
        self.log = tmp_path / "cluster.log"
        self.start(["dask-scheduler", "--scheduler-file", str(self.file), "--port", "0",
                    "--dashboard-address", ":0", "--host", "127.0.0.1"], dict(os.environ))
        assert wait_until(lambda: self.file.exists() and self.file.stat().st_size > 0, timeout=60)

    def start(self, cmd, env):
        cmd = [sys.executable, "-m", "distributed.cli." + cmd[0].replace("-", "_")] + cmd[1:]
        with open(self.log, "a") as log:
            proc = subprocess.Popen(cmd, cwd=ROOT, env=env, stdout=log, stderr=log)
        self.procs.append(proc)
        return proc

    def worker(self, env):
        env = dict(env, PYTHONPATH=str(ROOT))
        return self.start(["dask-worker", "--scheduler-file", str(self.file), "--nthreads", "1",
                           "--nworkers", "1", "--no-nanny", "--host", "127.0.0.1",
                           "--dashboard-address", ":0"], env)

    def stop(self, proc):
        proc.terminate()
        try:
            proc.wait(timeout=20)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()

    def close(self):
        for p in reversed(self.procs):
            if p.poll() is None:
                self.stop(p)


def test_worker_with_another_binary_is_refused_and_a_matching_one_runs(tmp_path):
    mesher = tool("mesher")
    env = env_for(tmp_path, "dask", SMALL)
    # A build whose mesher differs from the client's by one byte.
    other_bin = tmp_path / "other_bin"
    other_bin.mkdir()
    shutil.copy2(mesher, other_bin / "mesher")
    with open(other_bin / "mesher", "ab") as f:
        f.write(b"\0")
    cluster = Cluster(tmp_path)
    try:
        bad = cluster.worker(dict(env, PIPELINE_BIN=str(other_bin)))
        r = run_pipeline(env, "run", "t", "--scheduler", str(cluster.file))
        assert r.returncode == 2, r.stdout + r.stderr
        assert "refusing the Dask cluster" in r.stderr and "executable mesher" in r.stderr, r.stderr
        assert "worker tcp://127.0.0.1:" in r.stderr and str(other_bin) in r.stderr, r.stderr
        assert not (Path(env["PIPELINE_CACHE"]) / "artifacts" / "mesher").exists() or \
            not any((Path(env["PIPELINE_CACHE"]) / "artifacts" / "mesher").iterdir())
        cluster.stop(bad)
        good = cluster.worker(env)
        # A timing run: this worker offers no `exclusive` resource, so it runs on the client.
        doc = json.loads(json.dumps(SMALL))
        doc["stages"]["timing"] = {"tool": "mesher", "exclusive": True, "config": {
            "source": {"kind": "cuboid", "cells": [3, 1, 1], "size": [0.01, 0.01, 0.01]}}}
        env = env_for(tmp_path, "dask", doc)
        address = json.loads(cluster.file.read_text())["address"]
        ok = run_pipeline(env, "run", "t", "--scheduler", address, "--timings", str(tmp_path / "t.json"))
        assert ok.returncode == 0, ok.stdout + ok.stderr + cluster.log.read_text()[-3000:]
        assert "pipeline: 6 ran" in ok.stdout, ok.stdout
        where = {r["run"]: int(r["where"].split(":")[-1]) for r in
                 json.loads((tmp_path / "t.json").read_text())["runs"] if r["kind"] == "tool"}
        assert {where[f"cube#{i}"] for i in range(4)} == {good.pid}
        assert where["timing"] != good.pid
    finally:
        cluster.close()
