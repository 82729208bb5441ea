"""What a stopped or crashed run leaves behind, with real processes: a killed pipeline takes its
tools with it, a killed tool leaves nothing half-written in the cache, stale temporary files of
dead writers are removed (and `pipeline clean` names them), and independent experiments overlap."""
import json
import os
import signal
import socket
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import ROOT, run_pipeline, tool
from procs_util import gone, signal_in_flight, wait_until

# One mesher run of about a second.
SLOW = {"stages": {"cube": {"tool": "mesher", "config": {
    "source": {"kind": "cuboid", "cells": [30, 30, 30], "size": [0.01, 0.01, 0.01]}}}}}
# A simulation that would run for half a minute: only a kill ends it sooner.
LONG = {"stages": {
    "mesh": {"tool": "mesher", "config": {"source": {"kind": "cuboid", "cells": [2, 2, 2], "size": [0.04, 0.04, 0.03]}}},
    "sim": {"tool": "dhd_sim", "config": {
        "mesh": "@mesh", "material": {"model": "neo_hookean_paper", "E": 5000, "nu": 0.35, "density": 1000},
        "damping": {"alpha": 50}, "partition": {"kind": "linear_fraction", "linear_fraction": 0.0, "distance": "depth"},
        "boundary": {"fixed": ["bottom"]}, "solver": {"kind": "explicit", "steps": 30000000, "safety_factor": 0.5}}}}}
QUICK = {"stages": {"cube": {"tool": "mesher", "config": {
    "source": {"kind": "cuboid", "cells": [1, 1, 1], "size": [0.01, 0.01, 0.01]}}}}}


def write(env, name, doc):
    (Path(env["PIPELINE_EXPERIMENTS"]) / f"{name}.json").write_text(json.dumps(doc))


def start(env, *args):
    return subprocess.Popen([sys.executable, "-m", "pipeline", *args], cwd=ROOT, env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def half_written(env):
    cache = Path(env["PIPELINE_CACHE"])
    return [p for p in cache.rglob("*") if p.is_file() and (".tmp." in p.name or "staging" in p.parts)]


def dead_pid():
    proc = subprocess.Popen(["true"])
    proc.wait()
    return proc.pid


@pytest.mark.parametrize("sig", [signal.SIGKILL, signal.SIGTERM])
def test_stopped_pipeline_stops_its_tools(pipeline_env, sig):
    tool("dhd_sim")
    write(pipeline_env, "t", LONG)
    proc = start(pipeline_env, "run", "t")
    _, _, sims = signal_in_flight(proc, "dhd_sim", sig, lambda proc, _: proc.pid)
    # The tool does not outlive its leader (and so cannot write into the cache afterwards).
    assert wait_until(lambda: all(gone(p) for p in sims), timeout=3), sims
    if sig == signal.SIGTERM:
        assert proc.returncode == 128 + signal.SIGTERM
        assert half_written(pipeline_env) == []
    # Whatever a SIGKILL left is stale now, and the next run removes it before it runs.
    write(pipeline_env, "t", QUICK)
    again = run_pipeline(pipeline_env, "run", "t")
    assert again.returncode == 0, again.stdout + again.stderr
    assert half_written(pipeline_env) == []


def test_killed_tool_leaves_nothing_half_written(pipeline_env):
    tool("mesher")
    write(pipeline_env, "t", SLOW)
    proc = start(pipeline_env, "run", "t")
    stdout, stderr, _ = signal_in_flight(proc, "mesher", signal.SIGKILL)
    assert proc.returncode == 1 and "FAILED cube: exit -9" in stdout, stdout + stderr
    assert half_written(pipeline_env) == []
    assert not any((Path(pipeline_env["PIPELINE_CACHE"]) / "artifacts").rglob("*.json"))


def test_stale_temporary_files_are_reported_and_removed(pipeline_env):
    cache = Path(pipeline_env["PIPELINE_CACHE"])
    dead = dead_pid()
    # A tool killed while writing into the staging folder of a pipeline that is gone as well.
    staged = cache / "staging" / socket.gethostname() / str(dead)
    staged.mkdir(parents=True)
    (staged / "abc.json.tmp.12345").write_bytes(b"x" * 3_000_000)
    # A live process's staging folder is left alone.
    live = cache / "staging" / socket.gethostname() / str(os.getpid())
    live.mkdir(parents=True)
    (live / "def.json.tmp.1").write_bytes(b"y")
    # The pipeline's own atomic write, interrupted long ago, outside the staging folders.
    old = cache / "configs" / f"k.json.tmp.{dead}"
    old.parent.mkdir(parents=True)
    old.write_text("{")
    os.utime(old, (1, 1))
    # A fresh one may belong to a writer on another machine sharing the cache: kept.
    fresh = cache / "configs" / f"f.json.tmp.{dead}"
    fresh.write_text("{")
    report = run_pipeline(pipeline_env, "clean", "--stale")
    assert report.returncode == 0, report.stderr
    assert "2 stale temporary files of dead writers (3.0 MB)" in report.stdout, report.stdout
    assert str(staged) in report.stdout and str(old) in report.stdout
    assert not staged.exists() and not old.exists()
    assert (live / "def.json.tmp.1").exists() and fresh.exists()
    (live / "def.json.tmp.1").unlink()
    live.rmdir()
    # `pipeline clean` names them before it removes the whole cache.
    staged.mkdir(parents=True)
    (staged / "abc.json.tmp.12345").write_bytes(b"x" * 1000)
    full = run_pipeline(pipeline_env, "clean")
    assert "1 stale temporary file of dead writers" in full.stdout and "removed the run cache" in full.stdout
    assert not cache.exists()


def run_two(env, a, b):
    """Experiments a and b, both at once (-j 2)."""
    tool("mesher")
    write(env, "a", a)
    write(env, "b", b)
    r = run_pipeline(env, "run", "all", "-j", "2")
    assert r.returncode == 0, r.stdout + r.stderr
    return r


def test_independent_experiments_overlap(pipeline_env):
    r = run_two(pipeline_env, SLOW, QUICK)
    lines = [l for l in r.stdout.splitlines() if l.startswith("[")]
    # b's quick run started beside a's slow one, so it finished first.
    assert lines[0].startswith("[b 1/1] ran cube") and lines[1].startswith("[a 1/1] ran cube"), r.stdout
    # With one slot they run one after another, in name order.
    r = run_pipeline(pipeline_env, "run", "all", "--force")
    lines = [l for l in r.stdout.splitlines() if l.startswith("[")]
    assert lines[0].startswith("[a 1/1]") and lines[1].startswith("[b 1/1]"), r.stdout


def test_same_key_in_two_experiments_at_once_leaves_one_valid_entry(pipeline_env):
    r = run_two(pipeline_env, SLOW, SLOW)
    assert "[a 1/1] ran cube" in r.stdout and "[b 1/1] ran cube" in r.stdout, r.stdout
    entries = list((Path(pipeline_env["PIPELINE_CACHE"]) / "artifacts").rglob("*.json"))
    assert len(entries) == 1 and json.loads(entries[0].read_text())["schema"]["name"]
    assert half_written(pipeline_env) == []
