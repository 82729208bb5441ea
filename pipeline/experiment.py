"""Experiments: strict loading of experiments/<name>.json and expansion of sweeps into runs.

A stage is one of three kinds (see pipeline/EXPERIMENTS.md):
  tool    a C++ executable of build/bin        -> one artifact per run
  python  a module with run(ctx)               -> one artifact per run
  report  a module with report(ctx)            -> tables and plots in results/<results>/
A stage may instead be {"ref": "experiment.stage"}, another experiment's stage verbatim, and a
config may use {"shared": NAME}, a fragment of the experiment's "shared" block: one definition
for what several stages or experiments must agree on.
"""
import copy
import itertools
import json
import math
import os
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Dict, List, Optional

from pipeline import json_limits
from pipeline.errors import ExperimentError
from pipeline.paths import EXPERIMENTS

REF = re.compile(r"^@([A-Za-z0-9_\-]+)(?:#(\d+))?$")
TOP_KEYS = {"description", "results", "paper", "stages", "notes", "shared"}
STAGE_REF = re.compile(r"^([A-Za-z0-9_\-]+)\.([A-Za-z0-9_\-]+)$")
STAGE_KEYS = {
    "tool": {"tool", "config", "sweep", "mode", "args", "exclusive", "description"},
    "python": {"python", "config", "sweep", "exclusive", "description"},
    "report": {"report", "inputs", "params", "description"},
}


@dataclass
class Run:
    """One execution of a stage (a stage with a sweep has several)."""
    experiment: str
    stage: str
    kind: str                      # tool | python | report
    target: str                    # executable name or module
    index: Optional[int]           # position in the sweep, None when not swept
    config: Dict[str, Any]
    sweep: Dict[str, Any] = field(default_factory=dict)
    mode: Optional[str] = None
    args: List[str] = field(default_factory=list)
    exclusive: bool = False
    inputs: List[str] = field(default_factory=list)   # report: input stage names
    params: Dict[str, Any] = field(default_factory=dict)
    deps: List[str] = field(default_factory=list)     # run ids this run needs

    @property
    def id(self) -> str:
        return self.stage if self.index is None else f"{self.stage}#{self.index}"


@dataclass
class Experiment:
    name: str
    path: Path
    doc: Dict[str, Any]
    runs: Dict[str, Run]           # run id -> run, in file order
    stage_runs: Dict[str, List[str]]
    # stage -> "experiment.stage" it is defined by, for the stages declared {"ref": ...}
    origins: Dict[str, str] = field(default_factory=dict)

    @property
    def results_subdir(self) -> str:
        return self.doc.get("results", self.name)


def _fail(path, pointer, expected):
    raise ExperimentError(f"{path}: {pointer or '/'}: {expected}")


def _set_dotted(config: dict, dotted: str, value, path, pointer):
    keys = dotted.split(".")
    node = config
    for k in keys[:-1]:
        if isinstance(node, list) and k.isdigit() and int(k) < len(node):
            node = node[int(k)]
            continue
        if not isinstance(node, dict):
            _fail(path, pointer, f"a sweep path through objects, but {dotted!r} meets a non-object")
        node = node.setdefault(k, {})
    last = keys[-1]
    if isinstance(node, list) and last.isdigit() and int(last) < len(node):
        node[int(last)] = value
    elif isinstance(node, dict):
        node[last] = value
    else:
        _fail(path, pointer, f"a sweep path through objects, but {dotted!r} meets a non-object")


def find_refs(value) -> List[tuple]:
    """All (stage, index-or-None) references "@stage" / "@stage#k" inside a config."""
    out = []
    if isinstance(value, str):
        m = REF.match(value)
        if m:
            out.append((m.group(1), None if m.group(2) is None else int(m.group(2))))
    elif isinstance(value, dict):
        for v in value.values():
            out.extend(find_refs(v))
    elif isinstance(value, list):
        for v in value:
            out.extend(find_refs(v))
    return out


def substitute_refs(value, resolve):
    """Replaces every reference string by resolve(stage, index)."""
    if isinstance(value, str):
        m = REF.match(value)
        if m:
            return resolve(m.group(1), None if m.group(2) is None else int(m.group(2)))
        return value
    if isinstance(value, dict):
        return {k: substitute_refs(v, resolve) for k, v in value.items()}
    if isinstance(value, list):
        return [substitute_refs(v, resolve) for v in value]
    return value


# The most runs one stage's sweep may expand into: a sweep is a product of lists, so a few long
# lists make millions of runs before anything checks them. Raise it through the environment.
DEFAULT_MAX_SWEEP_RUNS = 10000


def max_sweep_runs() -> int:
    text = os.environ.get("PIPELINE_MAX_SWEEP_RUNS", "")
    if not text:
        return DEFAULT_MAX_SWEEP_RUNS
    if not text.isdigit() or int(text) < 1:
        raise ExperimentError(f"environment: PIPELINE_MAX_SWEEP_RUNS: expected a positive integer, got {text!r}")
    return int(text)


def list_experiments() -> List[str]:
    return sorted(p.stem for p in EXPERIMENTS.glob("*.json"))


def _read_doc(path: Path) -> dict:
    if not path.exists():
        known = ", ".join(list_experiments())
        raise ExperimentError(f"{path.name}: no such experiment (known: {known})")
    try:
        doc = json_limits.loads(path.read_text(), str(path))
    except json_limits.JsonLimitError as e:
        raise ExperimentError(str(e)) from None
    except json.JSONDecodeError as e:
        raise ExperimentError(f"{path}: invalid JSON: {e}") from None
    if not isinstance(doc, dict):
        _fail(path, "/", "expected an object")
    for k in doc:
        if k not in TOP_KEYS:
            _fail(path, f"/{k}", f"unknown field (expected one of {sorted(TOP_KEYS)})")
    stages = doc.get("stages")
    if not isinstance(stages, dict) or not stages:
        _fail(path, "/stages", "expected a non-empty object of stages")
    shared = doc.get("shared", {})
    if not isinstance(shared, dict):
        _fail(path, "/shared", "expected an object of named config fragments")
    return doc


def _expand_shared(value, shared: dict, path, pointer):
    """Replaces every {"shared": NAME} inside a config by a copy of the experiment's fragment
    shared[NAME]: one definition of settings several stages must agree on (pipeline/EXPERIMENTS.md)."""
    if isinstance(value, dict):
        if set(value) == {"shared"}:
            name = value["shared"]
            if not isinstance(name, str) or name not in shared:
                _fail(path, pointer + "/shared", f"expected the name of a fragment of /shared "
                      f"({', '.join(sorted(shared)) or 'none defined'}), got {name!r}")
            return copy.deepcopy(shared[name])
        return {k: _expand_shared(v, shared, path, f"{pointer}/{k}") for k, v in value.items()}
    if isinstance(value, list):
        return [_expand_shared(v, shared, path, f"{pointer}/{i}") for i, v in enumerate(value)]
    return value


def _with_shared(spec, shared: dict, path, pointer):
    if isinstance(spec, dict) and "config" in spec:
        spec = dict(spec, config=_expand_shared(spec["config"], shared, path, f"{pointer}/config"))
    return spec


def _resolve_stage_ref(spec: dict, path, pointer, chain=()):
    """The definition of a stage declared {"ref": "experiment.stage"}: that experiment's stage,
    verbatim (its "@stage" references then name stages of the experiment that includes it), with
    that experiment's shared fragments expanded; a chain of refs is followed. Returns
    (definition, "experiment.stage" of the definition)."""
    for k in spec:
        if k not in ("ref", "description"):
            _fail(path, f"{pointer}/{k}", "unknown field for a stage declared by \"ref\" (only \"description\")")
    target = spec["ref"]
    m = STAGE_REF.match(target) if isinstance(target, str) else None
    if not m:
        _fail(path, f"{pointer}/ref", f"expected \"experiment.stage\", got {target!r}")
    if target in chain:
        _fail(path, f"{pointer}/ref", "expected no cycle of stage refs, got " + " -> ".join(chain + (target,)))
    other_path = EXPERIMENTS / f"{m.group(1)}.json"
    if not other_path.exists():
        _fail(path, f"{pointer}/ref", f"expected an experiment of experiments/, got {m.group(1)!r}")
    other = _read_doc(other_path)
    if m.group(2) not in other["stages"]:
        _fail(path, f"{pointer}/ref", f"expected a stage of {other_path.name}, got {m.group(2)!r}")
    found = other["stages"][m.group(2)]
    if isinstance(found, dict) and "ref" in found:
        return _resolve_stage_ref(found, other_path, f"/stages/{m.group(2)}", chain + (target,))
    if not isinstance(found, dict) or "report" in found:
        _fail(path, f"{pointer}/ref", f"expected a tool or python stage, {target} is not one")
    return _with_shared(found, other.get("shared", {}), other_path, f"/stages/{m.group(2)}"), target


def load(name: str) -> Experiment:
    path = EXPERIMENTS / f"{name}.json"
    doc = _read_doc(path)
    shared = doc.get("shared", {})
    origins: Dict[str, str] = {}
    stages = {}
    for stage, spec in doc["stages"].items():
        if isinstance(spec, dict) and "ref" in spec:
            resolved, origins[stage] = _resolve_stage_ref(spec, path, f"/stages/{stage}")
            stages[stage] = dict(resolved, **({"description": spec["description"]} if "description" in spec else {}))
        else:
            stages[stage] = _with_shared(spec, shared, path, f"/stages/{stage}")

    runs: Dict[str, Run] = {}
    stage_runs: Dict[str, List[str]] = {}
    for stage, spec in stages.items():
        ptr = f"/stages/{stage}"
        if not re.match(r"^[A-Za-z0-9_\-]+$", stage):
            _fail(path, ptr, "expected a stage name of letters, digits, _ and -")
        if not isinstance(spec, dict):
            _fail(path, ptr, "expected an object")
        kinds = [k for k in STAGE_KEYS if k in spec]
        if len(kinds) != 1:
            _fail(path, ptr, "expected exactly one of \"tool\", \"python\", \"report\"")
        kind = kinds[0]
        for k in spec:
            if k not in STAGE_KEYS[kind]:
                _fail(path, f"{ptr}/{k}", f"unknown field for a {kind} stage")
        target = spec[kind]
        if not isinstance(target, str) or not target:
            _fail(path, f"{ptr}/{kind}", "expected a non-empty string")
        if kind == "report":
            inputs = spec.get("inputs", [])
            if not isinstance(inputs, list) or not all(isinstance(i, str) for i in inputs):
                _fail(path, f"{ptr}/inputs", "expected a list of stage names")
            for i, inp in enumerate(inputs):
                if inp not in stages:
                    _fail(path, f"{ptr}/inputs/{i}", f"expected a stage of this experiment, got {inp!r}")
            params = spec.get("params", {})
            if not isinstance(params, dict):
                _fail(path, f"{ptr}/params", "expected an object")
            run = Run(name, stage, kind, target, None, {}, inputs=list(inputs), params=params)
            runs[run.id] = run
            stage_runs[stage] = [run.id]
            continue
        config = spec.get("config", {})
        if not isinstance(config, dict):
            _fail(path, f"{ptr}/config", "expected an object")
        sweep = spec.get("sweep", {})
        if not isinstance(sweep, dict):
            _fail(path, f"{ptr}/sweep", "expected an object of dotted path -> list of values")
        for k, v in sweep.items():
            if not isinstance(v, list) or not v:
                _fail(path, f"{ptr}/sweep/{k}", "expected a non-empty list of values")
        mode = spec.get("mode")
        if mode is not None and not isinstance(mode, str):
            _fail(path, f"{ptr}/mode", "expected a string")
        args = spec.get("args", [])
        if not isinstance(args, list) or not all(isinstance(a, str) for a in args):
            _fail(path, f"{ptr}/args", "expected a list of strings")
        exclusive = spec.get("exclusive", False)
        if not isinstance(exclusive, bool):
            _fail(path, f"{ptr}/exclusive", "expected true or false")
        count = math.prod(len(v) for v in sweep.values())
        if count > max_sweep_runs():
            _fail(path, f"{ptr}/sweep", f"expected a sweep of at most {max_sweep_runs()} runs "
                  f"(PIPELINE_MAX_SWEEP_RUNS), got {' x '.join(str(len(v)) for v in sweep.values())} = {count}")
        combos = [dict(zip(sweep.keys(), values)) for values in itertools.product(*sweep.values())] \
            if sweep else [None]
        ids = []
        for idx, combo in enumerate(combos):
            cfg = copy.deepcopy(config)
            if combo:
                for dotted, value in combo.items():
                    _set_dotted(cfg, dotted, copy.deepcopy(value), path, f"{ptr}/sweep/{dotted}")
            run = Run(name, stage, kind, target, idx if combo is not None else None, cfg,
                      sweep=combo or {}, mode=mode, args=list(args), exclusive=exclusive)
            runs[run.id] = run
            ids.append(run.id)
        stage_runs[stage] = ids

    # Dependencies: references inside configs, and report inputs.
    for run in runs.values():
        if run.kind == "report":
            run.deps = [rid for s in run.inputs for rid in stage_runs[s]]
            continue
        for stage, idx in find_refs(run.config):
            if stage not in stage_runs:
                _fail(path, f"/stages/{run.stage}/config", f"reference @{stage} names no stage")
            if stages[stage].get("report"):
                _fail(path, f"/stages/{run.stage}/config", f"reference @{stage} names a report")
            ids = stage_runs[stage]
            if idx is None:
                if len(ids) != 1:
                    _fail(path, f"/stages/{run.stage}/config",
                          f"@{stage} is swept ({len(ids)} runs): name one as @{stage}#k")
                run.deps.append(ids[0])
            else:
                if idx >= len(ids) or stage_runs[stage][0] == stage:
                    _fail(path, f"/stages/{run.stage}/config", f"@{stage}#{idx} names no run")
                run.deps.append(f"{stage}#{idx}")
    _check_acyclic(path, runs)
    return Experiment(name, path, doc, runs, stage_runs, origins)


def _check_acyclic(path, runs: Dict[str, Run]):
    state: Dict[str, int] = {}

    def visit(rid, chain):
        if state.get(rid) == 2:
            return
        if state.get(rid) == 1:
            _fail(path, "/stages", "expected no cycle, got " + " -> ".join(chain + [rid]))
        state[rid] = 1
        for d in runs[rid].deps:
            visit(d, chain + [rid])
        state[rid] = 2

    for rid in runs:
        visit(rid, [])


def closure(exp: Experiment, stage: str) -> List[str]:
    """Run ids needed for `stage`: its runs and, transitively, their dependencies."""
    if stage not in exp.stage_runs:
        raise ExperimentError(f"{exp.path.name}: no stage {stage!r} (stages: {', '.join(exp.stage_runs)})")
    return closure_of_runs(exp, exp.stage_runs[stage])


def refresh(exp: Experiment, stage: str) -> List[str]:
    """Run ids of `pipeline run NAME --stage S`: the stage with what it needs (closure) and every
    run that depends on it, transitively, with what those need: the reports built on the stage
    are refreshed with it (each reruns only when its key, which holds its inputs' content, says so)."""
    needed = set(closure(exp, stage))
    changed = set(exp.stage_runs[stage])
    grew = True
    while grew:
        grew = False
        for rid, run in exp.runs.items():
            if rid not in changed and any(d in changed for d in run.deps):
                changed.add(rid)
                grew = True
    for rid in changed:
        needed.update(closure_of_runs(exp, [rid]))
    return [rid for rid in exp.runs if rid in needed]


def closure_of_runs(exp: Experiment, run_ids: List[str]) -> List[str]:
    needed, todo = set(), list(run_ids)
    while todo:
        rid = todo.pop()
        if rid in needed:
            continue
        needed.add(rid)
        todo.extend(exp.runs[rid].deps)
    return [rid for rid in exp.runs if rid in needed]


def origin(exp: Experiment, stage: str) -> str:
    """"experiment.stage" that defines `stage` of `exp`: itself, or what its ref names."""
    return exp.origins.get(stage, f"{exp.name}.{stage}")


def sharing(exp: Experiment, stage: str) -> List[tuple]:
    """The other experiments' stages defined by the same stage as `stage` of `exp` (through
    {"ref": ...}), as [(experiment, stage)]: rerunning one refreshes the others' reports."""
    want = origin(exp, stage)
    out = []
    for name in list_experiments():
        if name == exp.name:
            continue
        try:
            other = load(name)
        except ExperimentError:
            continue
        for s in other.stage_runs:
            if origin(other, s) == want:
                out.append((other, s))
    return out
