"""The progress line of `pipeline run`: on a terminal (stderr a TTY) one overall count of runs
done out of all selected, with an ETA, that counts every run once whatever its outcome; anywhere
else (CI logs, pipes) nothing but the plain lines, one per run."""
import fcntl
import json
import os
import pty
import re
import struct
import subprocess
import sys
import termios
import threading
from pathlib import Path

from conftest import ROOT, run_pipeline

CUBES = {"stages": {
    "cube": {"tool": "mesher", "config": {"source": {"kind": "cuboid", "cells": [1, 1, 1], "size": [0.01, 0.01, 0.01]}},
             "sweep": {"source.cells": [[1, 1, 1], [2, 1, 1]]}},
    "table": {"report": "pipeline.reports.meshes", "inputs": ["cube"], "params": {"order": ["cube"]}}}}
# A run that fails (a negative size) and the report that depends on it, skipped.
FAILING = {"stages": {
    "bad": {"tool": "mesher", "config": {"source": {"kind": "cuboid", "cells": [1, 1, 1], "size": [1, -1, 1]}}},
    "table": {"report": "pipeline.reports.meshes", "inputs": ["bad"]}}}
PLAIN_LINE = re.compile(r"^\[\w+ \d+/\d+\] (ran|cached|FAILED|skipped) ")


def write_experiments(env, **docs):
    for name, doc in docs.items():
        (Path(env["PIPELINE_EXPERIMENTS"]) / f"{name}.json").write_text(json.dumps(doc))


def run_on_terminal(env, *args):
    """`pipeline ARGS` with stderr on a pseudo-terminal 100 columns wide and stdout on a pipe:
    (stdout, everything the terminal received)."""
    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 100, 0, 0))
    proc = subprocess.Popen([sys.executable, "-m", "pipeline", *args], cwd=ROOT, env=env,
                            stdout=subprocess.PIPE, stderr=slave, text=True)
    os.close(slave)
    received = []

    def drain():
        while True:
            try:
                chunk = os.read(master, 4096)
            except OSError:  # EIO: the terminal's last writer has gone
                break
            if not chunk:
                break
            received.append(chunk)
    reader = threading.Thread(target=drain)
    reader.start()
    stdout = proc.communicate(timeout=300)[0]
    reader.join(timeout=30)
    os.close(master)
    return stdout, b"".join(received).decode()


def test_not_a_terminal_no_progress_line(pipeline_env):
    write_experiments(pipeline_env, cubes=CUBES, failing=FAILING)
    r = run_pipeline(pipeline_env, "run", "all")
    assert r.returncode == 1, r.stdout + r.stderr
    assert r.stderr == ""
    lines = r.stdout.splitlines()
    assert "\r" not in r.stdout
    assert sum(bool(PLAIN_LINE.match(line)) for line in lines) == 5
    assert all(PLAIN_LINE.match(line) or line.startswith("pipeline: ") for line in lines), lines


def test_terminal_counts_every_run_once_with_an_eta(pipeline_env):
    """Five runs over two experiments: ran, a failure and the run it skips; the second time the
    cubes come from the cache. Each time the count climbs to exactly 5/5."""
    write_experiments(pipeline_env, cubes=CUBES, failing=FAILING)
    for outcome in ("ran", "cached"):
        stdout, terminal = run_on_terminal(pipeline_env, "run", "all")
        counts = [(int(done), int(total)) for done, total in re.findall(r"(\d+)/(\d+) \[", terminal)]
        assert counts, terminal
        assert all(total == 5 for _, total in counts), counts
        assert [done for done, _ in counts] == sorted(done for done, _ in counts), counts
        assert counts[-1] == (5, 5), counts
        assert re.search(r"\[\d\d:\d\d<\d\d:\d\d", terminal), terminal  # elapsed<remaining
        # The per-run lines stay on stdout, none lost to the bar.
        assert sum(bool(PLAIN_LINE.match(line)) for line in stdout.splitlines()) == 5, stdout
        assert f"{outcome} cube#0" in stdout and "FAILED bad" in stdout and "skipped table" in stdout


def test_async_sim_draws_frames_on_a_terminal_and_nothing_elsewhere(tmp_path):
    """async_sim's progress line counts the frames of every loop (timed repeats of whole and
    regions, then the reference) up to their total; off a terminal stderr has only its summary."""
    from conftest import tool, write_json
    cfg = json.loads((ROOT / "tests/bad_input/async_sim/good.json").read_text())
    cfg["haptics"]["duration"] = 20.0  # 20000 frames a loop: 3 loops, several reports
    path = write_json(tmp_path / "run.json", cfg)
    cmd = [str(tool("async_sim")), "--config", str(path), "--out", str(tmp_path / "o.json")]
    master, slave = pty.openpty()
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=slave)
    os.close(slave)
    received = b""
    while True:
        try:
            chunk = os.read(master, 4096)
        except OSError:
            break
        if not chunk:
            break
        received += chunk
    os.close(master)
    assert proc.wait(timeout=300) == 0
    frames = [int(m.group(1)) for m in re.finditer(rb"async_sim: frame (\d+) / 60000 \(t = ", received)]
    assert frames and frames[-1] == 60000 and frames == sorted(frames), received[-400:]
    quiet = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    assert quiet.returncode == 0 and "frame" not in quiet.stderr and len(quiet.stderr.splitlines()) == 1, quiet.stderr
