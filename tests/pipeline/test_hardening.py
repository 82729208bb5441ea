"""What an adversarial run of the tools and the pipeline must not break (issue: hardening):
outputs that are devices or inputs, a failed run's leftovers, memory estimates refused before
anything is allocated, stale temporaries of killed writers, an experiment nested too deep or
sweeping too far, and cached artifacts that no longer match what their run wrote."""
import json
import os
import stat
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import ROOT, run_pipeline, run_tool, tool, write_json

CUBOID = {"source": {"kind": "cuboid", "cells": [2, 2, 2], "size": [0.02, 0.02, 0.02]}}
QUICK = {"stages": {"cube": {"tool": "mesher", "config": {
    "source": {"kind": "cuboid", "cells": [1, 1, 1], "size": [0.01, 0.01, 0.01]}}}}}


def one_error_line(r):
    lines = [l for l in r.stderr.splitlines() if l.strip()]
    assert len(lines) == 1, r.stderr
    return lines[0]


def dead_pid():
    proc = subprocess.Popen(["true"])
    proc.wait()
    return proc.pid


def test_out_naming_a_device_is_refused_and_the_device_kept(tmp_path):
    cfg = write_json(tmp_path / "c.json", CUBOID)
    r = run_tool("mesher", "--config", cfg, "--out", "/dev/null")
    assert r.returncode == 2
    assert "--out /dev/null: expected a regular file or a new file name, got a device" in one_error_line(r)
    assert stat.S_ISCHR(os.stat("/dev/null").st_mode)


def test_out_through_a_link_to_a_device_is_refused(tmp_path):
    link = tmp_path / "out.json"
    link.symlink_to("/dev/null")
    r = run_tool("mesher", "--config", write_json(tmp_path / "c.json", CUBOID), "--out", link)
    assert r.returncode == 2 and "got a device" in one_error_line(r)
    assert link.is_symlink() and stat.S_ISCHR(os.stat("/dev/null").st_mode)


def test_vtu_naming_the_out_file_is_refused(tmp_path):
    out = tmp_path / "mesh.json"
    cfg = write_json(tmp_path / "c.json", {**CUBOID, "vtu": str(out)})
    r = run_tool("mesher", "--config", cfg, "--out", out)
    assert r.returncode == 2 and f"{cfg}: /vtu: expected a file other than the --out file" in one_error_line(r)
    assert not out.exists()


def test_a_failed_run_leaves_none_of_its_vtu_files(tmp_path):
    """A forced step above the stability limit blows up after some snapshots were written: exit
    3, and neither the snapshots, the .pvd series nor the artifact are left; an earlier run's
    artifact at --out, which this run did not create, stays as it was."""
    mesh = tmp_path / "mesh.json"
    assert run_tool("mesher", "--config", write_json(tmp_path / "m.json", CUBOID), "--out", mesh).returncode == 0
    keep = tmp_path / "notes.txt"
    keep.write_text("not the run's")
    cfg = write_json(tmp_path / "run.json", {
        "mesh": str(mesh), "material": {"model": "neo_hookean_paper", "E": 5000, "nu": 0.35, "density": 1000},
        "boundary": {"fixed": ["bottom"], "prescribed": [{"set": "top", "displacement": [0, 0, -0.001]}]},
        "solver": {"kind": "explicit", "steps": 20000, "dt": 0.05, "force_dt": True},
        "output": {"vtu": str(tmp_path / "sim.vtu"), "vtu_interval": 1}})
    earlier = tmp_path / "out.json"
    earlier.write_text('{"an": "earlier artifact"}')
    r = run_tool("dhd_sim", "--config", cfg, "--out", earlier)
    assert r.returncode == 3, r.stderr
    left = sorted(p.name for p in tmp_path.iterdir())
    assert left == ["m.json", "mesh.json", "notes.txt", "out.json", "run.json"], left
    assert earlier.read_text() == '{"an": "earlier artifact"}'


def test_memory_estimate_over_the_limit_is_refused_before_building(tmp_path):
    cfg = write_json(tmp_path / "c.json", {"source": {"kind": "cuboid", "cells": [60, 60, 60], "size": [1, 1, 1]}})
    env = dict(os.environ, SOFTSIM_MEMORY_LIMIT_MB="100")
    r = subprocess.run([str(tool("mesher")), "--config", str(cfg), "--out", str(tmp_path / "o.json")],
                       capture_output=True, text=True, env=env, timeout=60)
    assert r.returncode == 2
    line = one_error_line(r)
    assert f"{cfg}: /source/cells: expected a size whose run fits the memory limit" in line
    assert "MiB, the limit is 100.0 MiB (SOFTSIM_MEMORY_LIMIT_MB)" in line
    assert not (tmp_path / "o.json").exists()


def test_input_larger_than_the_limit_is_refused(tmp_path):
    cfg = tmp_path / "c.json"
    cfg.write_text(json.dumps(CUBOID) + " " * 2_000_000)
    env = dict(os.environ, SOFTSIM_MAX_INPUT_MB="1")
    r = subprocess.run([str(tool("mesher")), "--config", str(cfg), "--out", str(tmp_path / "o.json")],
                       capture_output=True, text=True, env=env, timeout=60)
    assert r.returncode == 2
    assert f"{cfg}: expected a file of at most 1.0 MiB (SOFTSIM_MAX_INPUT_MB)" in one_error_line(r)


def test_stale_temporary_of_a_dead_writer_is_removed_by_the_next_write(tmp_path):
    out = tmp_path / "o.json"
    dead, live = tmp_path / f"o.json.tmp.{dead_pid()}", tmp_path / f"o.json.tmp.{os.getpid()}"
    dead.write_bytes(b"x" * 1000)
    live.write_bytes(b"y")
    r = run_tool("mesher", "--config", write_json(tmp_path / "c.json", CUBOID), "--out", out)
    assert r.returncode == 0, r.stderr
    assert not dead.exists() and live.exists() and out.exists()


# ----------------------------------------------------------------------------- the pipeline
def write_experiment(env, name, text):
    (Path(env["PIPELINE_EXPERIMENTS"]) / f"{name}.json").write_text(text)


def test_experiment_nested_too_deep_is_one_line(pipeline_env):
    deep = '{"stages": {"cube": {"tool": "mesher", "config": {"x": ' + "[" * 30000 + "]" * 30000 + "}}}}"
    write_experiment(pipeline_env, "t", deep)
    r = run_pipeline(pipeline_env, "run", "t")
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stderr
    assert "t.json: /: expected arrays and objects nested at most 64 deep" in one_error_line(r)


def test_sweep_beyond_the_limit_is_refused_and_a_sweep_announced(pipeline_env):
    doc = json.loads(json.dumps(QUICK))
    doc["stages"]["cube"]["sweep"] = {"sliver_threshold_deg": list(range(1, 102)), "source.size": [[0.01] * 3] * 100}
    write_experiment(pipeline_env, "t", json.dumps(doc))
    r = run_pipeline(pipeline_env, "run", "t")
    assert r.returncode == 2
    assert "t.json: /stages/cube/sweep: expected a sweep of at most 10000 runs" in one_error_line(r)
    assert "got 101 x 100 = 10100" in r.stderr
    doc["stages"]["cube"]["sweep"] = {"sliver_threshold_deg": [4, 5]}
    write_experiment(pipeline_env, "t", json.dumps(doc))
    env = dict(pipeline_env, PIPELINE_MAX_SWEEP_RUNS="1")
    r = run_pipeline(env, "run", "t")
    assert r.returncode == 2 and "got 2 = 2" in one_error_line(r)
    tool("mesher")
    r = run_pipeline(pipeline_env, "run", "t")
    assert r.returncode == 0, r.stdout + r.stderr
    assert "pipeline: t: 2 runs; sweeps: cube 2" in r.stdout, r.stdout


def test_a_damaged_cached_artifact_is_run_again(pipeline_env):
    tool("mesher")
    write_experiment(pipeline_env, "t", json.dumps(QUICK))
    assert run_pipeline(pipeline_env, "run", "t").returncode == 0
    [artifact] = (Path(pipeline_env["PIPELINE_CACHE"]) / "artifacts").rglob("*.json")
    whole = artifact.read_bytes()
    assert "cached cube" in run_pipeline(pipeline_env, "run", "t").stdout
    artifact.write_bytes(whole[: len(whole) // 2])
    r = run_pipeline(pipeline_env, "run", "t")
    assert r.returncode == 0 and "ran cube" in r.stdout, r.stdout
    assert artifact.read_bytes() == whole


def test_playback_over_the_memory_limit_names_the_forces(tmp_path):
    from test_bad_input import Inputs
    fit = Inputs(tmp_path).fit()
    cfg = write_json(tmp_path / "play.json", {"fit": str(fit), "forces": [[0, 0, 0.5]] * 1000})
    out = tmp_path / "o.json"
    env = dict(os.environ, SOFTSIM_MEMORY_LIMIT_MB="0.1")
    r = subprocess.run([str(tool("marquardt_fit")), "play", "--config", str(cfg), "--out", str(out)],
                       capture_output=True, text=True, env=env, timeout=60)
    assert r.returncode == 2
    assert f"{cfg}: /forces: expected a size whose run fits the memory limit" in one_error_line(r)
    assert not out.exists()
    r = run_tool("marquardt_fit", "play", "--config", cfg, "--out", out)
    assert r.returncode == 0, r.stderr


# A full disk: every write of a report (Markdown, CSV, PNG, REPORT.md) gives up half-way with
# ENOSPC. Run in a child so that the patches stay there.
FULL_DISK = r'''
import errno, pathlib, sys
import matplotlib.figure

def full(path, data):
    with open(path, "wb") as f:
        f.write(data[: len(data) // 2])
    raise OSError(errno.ENOSPC, "No space left on device", str(path))

if sys.argv[1] in ("text", "all"):
    pathlib.Path.write_text = lambda self, text, *a, **k: full(self, text.encode())
if sys.argv[1] in ("png", "all"):
    matplotlib.figure.Figure.savefig = lambda self, path, *a, **k: full(path, b"\x89PNG" * 1000)
from pipeline.cli import main
sys.exit(main(sys.argv[2:]))
'''


def results_files(env):
    root = Path(env["PIPELINE_RESULTS"])
    return {p.relative_to(root): p.read_bytes() for p in root.rglob("*") if p.is_file()}


@pytest.mark.parametrize("failing", ["text", "png"])
def test_a_full_disk_while_writing_reports_is_one_line_and_keeps_the_old_reports(pipeline_env, failing):
    tool("mesher")
    doc = {**json.loads(json.dumps(QUICK))}
    doc["stages"]["table"] = {"report": "pipeline.reports.meshes", "inputs": ["cube"], "params": {"order": ["cube"]}}
    write_experiment(pipeline_env, "t", json.dumps(doc))
    assert run_pipeline(pipeline_env, "run", "t").returncode == 0
    before = results_files(pipeline_env)
    assert any(p.suffix == ".png" for p in before) and any(p.name == "REPORT.md" for p in before), before.keys()
    r = subprocess.run([sys.executable, "-c", FULL_DISK, failing, "run", "t", "--stage", "table"], cwd=ROOT,
                       env=pipeline_env, capture_output=True, text=True, timeout=300)
    assert r.returncode != 0 and "Traceback" not in r.stdout + r.stderr, r.stdout + r.stderr
    # The report's run fails in its one line; REPORT.md, written after the runs, in one more.
    [failed] = [l for l in r.stdout.splitlines() if "FAILED" in l]
    assert "FAILED table: OSError: [Errno 28] No space left on device" in failed, failed
    for line in r.stderr.splitlines():
        assert line.startswith("pipeline: error: ") and line.endswith("REPORT.md: No space left on device"), line
    assert len(r.stderr.splitlines()) == (1 if failing == "text" else 0), r.stderr
    after = results_files(pipeline_env)
    # Every report as it was and no temporary left. The manifest and REPORT.md, written whole
    # after the runs, record the failed report (REPORT.md only when its own write succeeds).
    rewritten = {"manifest.json"} | ({"REPORT.md"} if failing == "png" else set())
    assert {p: b for p, b in after.items() if p.name not in rewritten} == \
        {p: b for p, b in before.items() if p.name not in rewritten}
    assert b'"status": "failed"' in after[Path("manifest.json")]


def test_async_series_over_the_memory_limit_names_the_member_and_the_estimate(tmp_path):
    """A long async_sim series is refused from its config, naming the member whose share of the
    estimate is largest (the series, then the per-frame records), before any frame is run."""
    cfg = json.loads((ROOT / "tests/bad_input/async_sim/good.json").read_text())
    cfg["haptics"]["duration"] = 1000.0  # 1e6 frames
    cfg["series_every"] = 1
    path = write_json(tmp_path / "run.json", cfg)
    out = tmp_path / "o.json"
    env = dict(os.environ, SOFTSIM_MEMORY_LIMIT_MB="100")
    r = subprocess.run([str(tool("async_sim")), "--config", str(path), "--out", str(out)],
                       capture_output=True, text=True, env=env, timeout=60)
    assert r.returncode == 2, r.stderr
    line = one_error_line(r)
    assert f"{path}: /series_every: expected a size whose run fits the memory limit: the run (mostly the time " \
           "series in the artifact) would take about" in line, line
    assert "the limit is 100.0 MiB (SOFTSIM_MEMORY_LIMIT_MB)" in line
    del cfg["series_every"]
    r = subprocess.run([str(tool("async_sim")), "--config", str(write_json(path, cfg)), "--out", str(out)],
                       capture_output=True, text=True, env=dict(env, SOFTSIM_MEMORY_LIMIT_MB="10"), timeout=60)
    assert r.returncode == 2 and f"{path}: /haptics/duration: expected a size whose run fits" in one_error_line(r)
    assert not out.exists()


def test_a_report_writing_through_its_out_path_writes_atomically(tmp_path, monkeypatch):
    """ctx.out gives a path whose write_text is atomic: a report that writes
    `ctx.out("summary.md").write_text(text)` on a full disk leaves the earlier file whole."""
    import errno
    import pathlib
    from pipeline.artifacts import ResultPath
    out = ResultPath(tmp_path) / "summary.md"
    out.write_text("the earlier summary\n")

    def full(self, text, *args, **kwargs):
        pathlib.Path.write_bytes(self, text.encode()[:5])
        raise OSError(errno.ENOSPC, "No space left on device", str(self))
    monkeypatch.setattr(pathlib.Path, "write_text", full)
    try:
        out.write_text("a new summary, longer than the disk allows\n")
        raise AssertionError("the full disk went unnoticed")
    except OSError as e:
        assert e.errno == errno.ENOSPC and e.filename == str(out)
    assert out.read_text() == "the earlier summary\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["summary.md"]
