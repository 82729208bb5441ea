"""The bad-input corpus (tests/bad_input/, see its README.md) run as an experiment ->
"stability_bad_input" v1: for every case the exit code, the number of stderr lines, whether the
expected fragments were named, and whether an output file was left behind. The pytest harness
(tests/pipeline/test_bad_input.py) asserts the same contract; this stage records it for
results/stability/ so the summary can say what each executable does with bad input.

Config: {"inputs": {"@MESH@": artifact, "@DATASET_X@": ..., "@FIT@": ...}}
"""
# Executables this stage runs: part of its cache key (pipeline/runner.py).
TOOLS = ("mesher", "dhd_sim", "rpim_precompute", "marquardt_fit", "async_sim", "haptic_sim")
# Repository folders this stage reads: part of its cache key too.
DATA = ("tests/bad_input",)

import json
import subprocess
import tempfile
from pathlib import Path

from pipeline.artifacts import write_artifact
from pipeline.paths import ROOT
from pipeline.stages.stability_common import tool_hashes, tool_path

SCHEMA = "stability_bad_input"
TOOL = "pipeline.stages.stability_bad_input"
CORPUS = ROOT / "tests" / "bad_input"


def load_cases():
    """(tool, case name, case) of every case of the corpus: tools in name order, cases in the
    order of their cases.json."""
    cases = []
    for manifest in sorted(CORPUS.glob("*/cases.json")):
        tool = manifest.parent.name
        for name, case in json.loads(manifest.read_text()).items():
            cases.append((tool, name, case))
    return cases


def case_command(tool, name, case, substitute, folder):
    """The arguments of one case's run -> (args, config path or None, output path). The case's
    config is written into `folder` after `substitute(text)` has replaced the placeholders of
    the input artifacts (@MESH@, ...) and @DIR@ became the tool's corpus folder."""
    args = []
    if case.get("mode"):
        args.append(case["mode"])
    args += case.get("args", [])
    config = None
    if case["config"] is not None:
        text = substitute((CORPUS / tool / case["config"]).read_text())
        text = text.replace("@DIR@", f"tests/bad_input/{tool}")
        config = Path(folder) / f"{tool}.{name}.json"
        config.write_text(text)
        args += ["--config", str(config)]
    out = Path(folder) / f"{tool}.{name}.out.json"
    args += ["--out", str(out)]
    return args, config, out


def machine_free(message, folder):
    """A tool's line as the results show it: the scratch folder and this checkout's location
    replaced by names, so the table reads the same on every machine."""
    return message.replace(str(folder), "<scratch folder>").replace(str(ROOT), "<repository>")


def run_case(tool, name, case, inputs, folder):
    def substitute(text):
        for key, path in inputs.items():
            text = text.replace(key, str(path))
        return text

    args, config, out = case_command(tool, name, case, substitute, folder)
    proc = subprocess.run([str(tool_path(tool))] + args, cwd=ROOT, capture_output=True, text=True, timeout=120)
    lines = [l for l in proc.stderr.splitlines() if l.strip()]
    named = all(substitute(f.replace("@CONFIG@", str(config))) in (lines[0] if lines else "")
                for f in case.get("expect", []))
    row = {"tool": tool, "case": name, "why": case["why"], "good": bool(case.get("good")), "exit": proc.returncode,
           "lines": len(lines), "message": machine_free((lines[-1] if lines else "").replace(str(folder) + "/", ""), folder),
           "named": named, "output_left": out.exists(), "known_issue": case.get("known_issue")}
    if out.exists():
        out.unlink()
    return row


def run(ctx):
    inputs = ctx.config["inputs"]
    with tempfile.TemporaryDirectory(prefix="bad_input_") as tmp:
        rows = [run_case(tool, name, case, inputs, tmp) for tool, name, case in load_cases()]
    # The corpus has one folder per executable in TOOLS: sorted, the order the rows give.
    write_artifact(ctx.out_path, SCHEMA, 1, TOOL, ctx.config, {"rows": rows, "tools": tool_hashes(sorted(TOOLS))})
