"""Shared fixtures: the repository root, the built executables, throw-away pipeline folders."""
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
BIN = Path(os.environ.get("PIPELINE_BIN", ROOT / "build" / "bin"))
if not BIN.is_absolute():
    BIN = ROOT / BIN
sys.path.insert(0, str(ROOT))


def pytest_configure(config):
    config.addinivalue_line("markers", "slow: runs the pipeline on several variants (about a minute)")


def tool(name: str) -> Path:
    path = BIN / name
    if not path.exists():
        pytest.fail(f"{path.relative_to(ROOT)} is missing: run `make build` first")
    return path


def run_tool(name, *args, cwd=ROOT):
    return subprocess.run([str(tool(name)), *map(str, args)], cwd=cwd, capture_output=True, text=True)


def write_json(path: Path, value) -> Path:
    path.write_text(json.dumps(value) if not isinstance(value, str) else value)
    return path


@pytest.fixture
def pipeline_env(tmp_path):
    """Environment for `python -m pipeline` with its own experiments, results and cache."""
    env = dict(os.environ)
    (tmp_path / "experiments").mkdir()
    env["PIPELINE_EXPERIMENTS"] = str(tmp_path / "experiments")
    env["PIPELINE_RESULTS"] = str(tmp_path / "results")
    env["PIPELINE_CACHE"] = str(tmp_path / "cache")
    return env


def run_pipeline(env, *args):
    return subprocess.run([sys.executable, "-m", "pipeline", *args], cwd=ROOT, env=env,
                          capture_output=True, text=True)
