"""The bad-input corpus of the executables (tests/bad_input/) through Python: every config case
of mesher, dhd_sim, rpim_precompute and marquardt_fit's play mode must end in Python as it ends
in the executable - InputError or NumericalError with the message of the executable's error line
(the file, JSON pointer and expectation), or, for the good baselines, the payload it writes."""
import json
from functools import partial

import pytest

from conftest import ROOT, import_softsim, run_tool, without_timing
from pipeline.stages.stability_bad_input import case_command, load_cases

softsim = import_softsim()

# How Python runs each tool's config (a path, as the executable gets it), by mode.
CALLS = {
    ("mesher", None): lambda path: softsim.mesh_from_config(path),
    ("dhd_sim", None): lambda path: softsim.run_dhd(None, path),
    ("rpim_precompute", None): partial(softsim.rpim_precompute, mode="dataset"),
    **{("rpim_precompute", mode): partial(softsim.rpim_precompute, mode=mode)
       for mode in ("dataset", "stability", "convergence")},
    ("marquardt_fit", "play"): lambda path: softsim.play_fit(path),
}
# A case about the command line (flags, --out) has no Python counterpart.
CASES = [pytest.param(tool, name, case, id=f"{tool}/{name}") for tool, name, case in load_cases()
         if (tool, case.get("mode")) in CALLS and case["config"] is not None and not case.get("args")]


@pytest.fixture(autouse=True)
def from_the_root(monkeypatch):
    """Paths in the corpus configs are relative to the repository root, where the tools run."""
    monkeypatch.chdir(ROOT)


def test_the_corpus_reaches_every_bound_tool():
    assert {c.values[0] for c in CASES} == {"mesher", "dhd_sim", "rpim_precompute", "marquardt_fit"}
    assert len(CASES) >= 140


@pytest.mark.parametrize("tool,name,case", CASES)
def test_python_ends_as_the_executable(tool, name, case, corpus_inputs, tmp_path):
    args, config, out = case_command(tool, name, case, corpus_inputs.substitute, tmp_path)
    r = run_tool(tool, *args)
    call = CALLS[(tool, case.get("mode"))]
    if r.returncode == 0:
        result = call(config)
        if tool == "mesher":
            result.save(tmp_path / "python.json")
            assert (tmp_path / "python.json").read_bytes() == out.read_bytes()
        else:
            assert without_timing(result) == without_timing(json.loads(out.read_text())["payload"])
        return
    kinds = {2: (softsim.InputError, "error"), 3: (softsim.NumericalError, "numerical failure")}
    assert r.returncode in kinds, r.stderr
    error, label = kinds[r.returncode]
    with pytest.raises(error) as raised:
        call(config)
    assert f"{tool}: {label}: {raised.value}" == r.stderr.strip()
