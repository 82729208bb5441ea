"""Bad input, for every executable: the corpus in tests/bad_input/<tool>/ (see its README.md).

Each bad case must end with exit code 2, exactly one line on stderr that starts with
"<tool>: error:" and contains the case's expected fragments (the file, the JSON pointer, what
was expected), and no output file. Each tool's `good` cases run the baseline the bad cases
depart from, so a bad case fails for its stated reason and not because the baseline is broken.
A case with `known_issue` is a defect in the tool that is not fixed yet: while the tool still
ends with the recorded `known_exit` code the case is an expected failure; any other outcome
fails, including the right one (then the entry is stale and must go).
"""
import json
from pathlib import Path

import pytest

from conftest import ROOT, run_tool, write_json
from pipeline.stages.stability_bad_input import CORPUS, case_command, load_cases

APPS = ROOT / "cpp" / "apps"
CASES = load_cases()


def case_param(tool, name, case):
    return pytest.param(tool, name, case, id=f"{tool}/{name}")


# ----------------------------------------------------------------------------- inputs
# Valid artifacts the configs refer to through placeholders, made once per test run by the
# tools themselves (so they always have the current schema) and only when a case needs them.
class Inputs:
    MESHER = {"source": {"kind": "cuboid", "cells": [2, 2, 2], "size": [0.02, 0.02, 0.02]}}
    PLATE = {"nodes": [5, 5, 2], "background_cells": [4, 4, 1], "gauss_order": 3}

    def __init__(self, folder: Path):
        self.folder = folder
        self.made = {}

    def _tool(self, name, tool, config, mode=None):
        if name not in self.made:
            cfg = write_json(self.folder / f"{name}.config.json", config)
            out = self.folder / f"{name}.json"
            args = ([mode] if mode else []) + ["--config", cfg, "--out", out]
            r = run_tool(tool, *args)
            assert r.returncode == 0, f"making the valid input {name} with {tool} failed: {r.stderr}"
            self.made[name] = out
        return self.made[name]

    def mesh(self):
        return self._tool("mesh", "mesher", self.MESHER)

    def dataset(self, axis):
        return self._tool(f"dataset_{axis}", "rpim_precompute",
                          {"plate": self.PLATE, "rpim": {"polynomial": "linear"},
                           "dataset": {"kind": f"axis_{axis}", "count": 6}})

    def fit(self):
        return self._tool("fit", "marquardt_fit",
                          {"datasets": {"z": str(self.dataset("z"))}, "check_forces": [0.5],
                           "timing": {"evaluations": 0},
                           "orders": {"z": {"force": 1, "components": {
                               c: {"surface": {"model": "separable", "orders": [2, 2]}, "parameters": 1}
                               for c in "xyz"}}}},
                          mode="fit")

    def substitute(self, text: str) -> str:
        lazy = {"@MESH@": self.mesh, "@DATASET_X@": lambda: self.dataset("x"),
                "@DATASET_Y@": lambda: self.dataset("y"), "@DATASET_Z@": lambda: self.dataset("z"),
                "@FIT@": self.fit}
        for key, make in lazy.items():
            if key in text:
                text = text.replace(key, str(make()))
        return text


@pytest.fixture(scope="session")
def inputs(tmp_path_factory):
    return Inputs(tmp_path_factory.mktemp("bad_input_inputs"))


def run_case(tool, name, case, inputs, tmp_path):
    args, config, out = case_command(tool, name, case, inputs.substitute, tmp_path)
    return run_tool(tool, *args), config, out


# ----------------------------------------------------------------------------- tests
@pytest.mark.parametrize("tool,name,case", [case_param(*c) for c in CASES if not c[2].get("good")])
def test_bad_input_exit_2_one_line_no_output(tool, name, case, inputs, tmp_path):
    r, config, out = run_case(tool, name, case, inputs, tmp_path)
    known = case.get("known_issue")
    if known:
        assert r.returncode != 2, f"known issue fixed? remove known_issue from the case: {r.stderr.strip()}"
        assert r.returncode == case["known_exit"], f"exit {r.returncode}, recorded {case['known_exit']}: {r.stderr}"
        pytest.xfail(known)
    lines = [l for l in r.stderr.splitlines() if l.strip()]
    assert r.returncode == 2, f"{case['why']}: exit {r.returncode}, stderr: {r.stderr.strip()[-400:]}"
    assert len(lines) == 1, f"expected one line, got:\n{r.stderr}"
    line = lines[0]
    assert line.startswith(f"{tool}: error: "), line
    for fragment in case["expect"]:
        fragment = inputs.substitute(fragment.replace("@CONFIG@", str(config)))
        assert fragment in line, f"{fragment!r} not in {line!r}"
    assert not out.exists(), "an output file was left behind"


@pytest.mark.parametrize("tool,name,case", [case_param(*c) for c in CASES if c[2].get("good")])
def test_good_baseline_runs(tool, name, case, inputs, tmp_path):
    r, _, out = run_case(tool, name, case, inputs, tmp_path)
    assert r.returncode == 0, r.stderr
    assert json.loads(out.read_text())["provenance"]["tool"] == tool


def test_every_executable_has_a_corpus():
    """Each cpp/apps/<tool>.cpp has a corpus with a baseline and the common kinds of bad input."""
    tools = sorted(p.stem for p in APPS.glob("*.cpp"))
    by_tool = {}
    for tool, name, case in CASES:
        by_tool.setdefault(tool, []).append((name, case))
    for tool in tools:
        cases = by_tool.get(tool, [])
        assert any(c.get("good") for _, c in cases), f"{tool}: no good baseline in tests/bad_input/{tool}/"
        names = " ".join(n for n, c in cases if not c.get("good"))
        for kind in ("truncated", "unknown", "missing", "wrong_type", "nan"):
            assert kind in names, f"{tool}: no '{kind}' case in tests/bad_input/{tool}/cases.json"


def test_corpus_files_are_all_referenced():
    """Every file in a tool's corpus folder is used by a case (no stale inputs)."""
    for manifest in CORPUS.glob("*/cases.json"):
        folder = manifest.parent
        cases = json.loads(manifest.read_text())
        used = {c["config"] for c in cases.values() if c["config"]}
        text = "".join((folder / u).read_text() for u in used)
        for f in folder.rglob("*"):
            if f.is_file() and f.name != "cases.json":
                rel = str(f.relative_to(folder))
                assert rel in used or rel in text, f"{f.relative_to(ROOT)} is not used by any case"
        for u in used:
            assert (folder / u).exists(), f"{folder.name}: missing {u}"
