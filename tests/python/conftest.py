"""Shared by the Python API tests: the softsim package, the executables it is compared with,
and valid input artifacts made by those executables.

Run: PYTHONPATH=<build>/python /usr/bin/python3 -m pytest -q tests/python (ctest's python_api
does this). Without the package the tests are skipped with the reason, except under ctest
(SOFTSIM_BIN set), where a package that does not import is a failure.
"""
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
BIN = Path(os.environ.get("SOFTSIM_BIN", ROOT / "build" / "bin"))
sys.path.insert(0, str(ROOT))  # the pipeline package: the bad-input corpus helpers

# Artifacts of the executables and of Python are compared byte for byte, so both must record the
# same commit (git_commit() reads this once per process, before any git call).
os.environ.setdefault("SOFTSIM_GIT_COMMIT", "0123456789abcdef0123456789abcdef01234567")


def import_softsim():
    """The softsim package; a skip naming what is missing when it was not built."""
    try:
        import softsim
    except ImportError as error:
        why = (f"the softsim Python module is not importable ({error}): build the target softsim_python "
               "and run with PYTHONPATH=<build>/python")
        if "SOFTSIM_BIN" in os.environ:
            pytest.fail(why, pytrace=False)
        pytest.skip(why, allow_module_level=True)
    return softsim


def tool(name):
    path = BIN / name
    if not path.exists():
        pytest.fail(f"{path} is missing: build the executables first")
    return path


def run_tool(name, *args):
    """Runs an executable from the repository root, as the pipeline does."""
    return subprocess.run([str(tool(name)), *map(str, args)], cwd=ROOT, capture_output=True, text=True)


def make_artifact(name, config, folder, mode=None):
    """Runs `name` on `config` (a dict) in `folder` -> the artifact's path."""
    folder = Path(folder)
    cfg = folder / f"{name}.{mode or 'run'}.config.json"
    cfg.write_text(json.dumps(config))
    out = folder / f"{name}.{mode or 'run'}.json"
    r = run_tool(name, *([mode] if mode else []), "--config", cfg, "--out", out)
    assert r.returncode == 0, f"{name} failed: {r.stderr}"
    return out


def payload(path):
    return json.loads(Path(path).read_text())["payload"]


def without_timing(p):
    """A payload without its wall-clock members (the one thing two runs do not share): the
    "timing" block, and the wall times of each cut event."""
    out = {k: v for k, v in p.items() if k != "timing"}
    if isinstance(out.get("cuts"), list):
        out["cuts"] = [{k: v for k, v in c.items() if not k.endswith("_seconds")} for c in out["cuts"]]
    return out


# The placeholders of the bad-input corpus (tests/bad_input/README.md) and the valid inputs they
# stand for, as its harness makes them: (tool, mode, config); a config may name other placeholders.
PLATE = {"nodes": [5, 5, 2], "background_cells": [4, 4, 1], "gauss_order": 3}
RECIPES = {
    "@MESH@": ("mesher", None, {"source": {"kind": "cuboid", "cells": [2, 2, 2], "size": [0.02, 0.02, 0.02]}}),
    **{f"@DATASET_{a.upper()}@": ("rpim_precompute", "dataset",
                                   {"plate": PLATE, "rpim": {"polynomial": "linear"},
                                    "dataset": {"kind": f"axis_{a}", "count": 6}}) for a in "xyz"},
    "@FIT@": ("marquardt_fit", "fit",
              {"datasets": {"z": "@DATASET_Z@"}, "check_forces": [0.5], "timing": {"evaluations": 0},
               "orders": {"z": {"force": 1, "components": {
                   c: {"surface": {"model": "separable", "orders": [2, 2]}, "parameters": 1} for c in "xyz"}}}}),
}


class CorpusInputs:
    """Makes each placeholder's artifact once, when a text first names it."""

    def __init__(self, folder):
        self.folder = Path(folder)
        self.paths = {}

    def substitute(self, text):
        for key, (name, mode, config) in RECIPES.items():
            if key in text:
                if key not in self.paths:
                    folder = self.folder / key.strip("@").lower()
                    folder.mkdir()
                    resolved = json.loads(self.substitute(json.dumps(config)))
                    self.paths[key] = make_artifact(name, resolved, folder, mode)
                text = text.replace(key, str(self.paths[key]))
        return text


@pytest.fixture(scope="session")
def corpus_inputs(tmp_path_factory):
    return CorpusInputs(tmp_path_factory.mktemp("corpus_inputs"))
