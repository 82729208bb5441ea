"""Executes the runs of experiments: keys, cache lookup, and the scheduling of every selected
run of every selected experiment in dependency order. Where a tool or python run executes is the
executor's business (pipeline/executors.py): this process's pool, or a Dask cluster."""
import ast
import importlib
import importlib.util
import json
import threading
import time
from concurrent.futures import FIRST_COMPLETED, ThreadPoolExecutor, wait
from pathlib import Path
from typing import Dict, List, Optional

from pipeline import experiment as experiment_mod
from pipeline.artifacts import git_commit, write_json_atomic
from pipeline.cache import cached_artifact_intact, record_artifact_hash
from pipeline.context import ReportContext, RunView
from pipeline.errors import RunFailed
from pipeline.execute import RunSpec
from pipeline.hashing import content_hash, file_hash, sha256_json
from pipeline.paths import ARTIFACTS, BIN, CONFIGS, LOGS, RESULTS, ROOT, STAMPS, rel

def module_file(module: str) -> Path:
    spec = importlib.util.find_spec(module)
    if spec is None or spec.origin is None:
        raise RunFailed(module, 2, f"no Python module {module!r}")
    return Path(spec.origin)


_AST_LOCK = threading.Lock()  # CPython's ast.parse is not safe across threads


def pipeline_import_closure(module: str) -> list:
    """The source files of `module` and of every pipeline.* module it imports, transitively:
    an edit to a shared helper (tables, plots, a *_common module) changes the key."""
    with _AST_LOCK:
        return _import_closure(module)


def _import_closure(module: str) -> list:
    seen, todo, files = set(), [module], []
    while todo:
        name = todo.pop()
        if name in seen:
            continue
        seen.add(name)
        try:
            path = module_file(name)
        except (RunFailed, ModuleNotFoundError):
            continue
        files.append(path)
        tree = ast.parse(path.read_text(), filename=str(path))
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and node.module and node.module.startswith("pipeline"):
                todo.append(node.module)
                todo.extend(f"{node.module}.{a.name}" for a in node.names)
            elif isinstance(node, ast.Import):
                todo.extend(a.name for a in node.names if a.name.startswith("pipeline"))
    return sorted(files)


def code_hash(kind: str, target: str) -> str:
    """The code part of a run's key: the tool's binary, or a python stage's or report's import
    closure within pipeline/ with the binaries it names in TOOLS and the files under its DATA
    folders. The client keys with it; a worker checks it sees the same before it runs."""
    if kind == "tool":
        binary = BIN / target
        if not binary.exists():
            raise RunFailed(target, 2, f"no executable {rel(binary)} (run `make build`)")
        return file_hash(binary)
    module_file(target)  # a clear error when the module does not exist
    hashes = [file_hash(f) for f in pipeline_import_closure(target)]
    # A python stage that drives our executables names them in TOOLS: their binaries
    # belong to its key exactly like a tool stage's binary.
    if kind == "python":
        module = importlib.import_module(target)
        for tool in getattr(module, "TOOLS", ()):
            binary = BIN / tool
            if not binary.exists():
                raise RunFailed(target, 2, f"no executable {rel(binary)} (run `make build`)")
            hashes.append(file_hash(binary))
        # Repository folders it reads (DATA): every file's path and content.
        for folder in getattr(module, "DATA", ()):
            for f in sorted(p for p in (ROOT / folder).rglob("*") if p.is_file()):
                hashes.append([rel(f), file_hash(f)])
    return sha256_json(hashes)


class Outcome:
    def __init__(self, run, status: str, key: str, artifact: Optional[Path], seconds: float,
                 message: str = ""):
        self.run = run
        self.status = status          # ran | cached | failed | skipped
        self.key = key
        self.artifact = artifact
        self.seconds = seconds        # wall time as the client saw it
        self.message = message
        self.exec_seconds = None      # ran: the run's own time where it executed
        self.where = ""               # ran: host:pid that executed it


class Runner:
    def __init__(self, jobs: int = 1, force: bool = False, force_stages=(), echo=print, progress=None,
                 executor=None):
        from pipeline.executors import LocalExecutor
        self.executor = executor if executor is not None else LocalExecutor(jobs)
        self.jobs = max(1, self.executor.slots)
        self.force = force
        self.force_stages = set(force_stages)   # (experiment name, stage) pairs
        self.echo = echo
        # Anything with update(n) (a tqdm bar): told of every finished run, whatever its outcome.
        self.progress = progress
        self.outcomes: Dict[tuple, Outcome] = {}
        for d in (ARTIFACTS, CONFIGS, LOGS, STAMPS):
            d.mkdir(parents=True, exist_ok=True)

    # ---------------------------------------------------------------- keys
    def _code_hash(self, run) -> str:
        try:
            return code_hash(run.kind, run.target)
        except RunFailed as e:
            raise RunFailed(run.id, e.code, e.message) from None

    def _dep_outcome(self, exp, rid) -> Outcome:
        return self.outcomes[(exp.name, rid)]

    def key_of(self, exp, run, code: Optional[str] = None) -> str:
        def by_hash(stage, idx):
            rid = stage if idx is None else f"{stage}#{idx}"
            return "content:" + content_hash(self._dep_outcome(exp, rid).artifact)

        material = {
            "kind": run.kind,
            "target": run.target,
            "code": code if code is not None else self._code_hash(run),
            "mode": run.mode,
            "args": run.args,
            "config": experiment_mod.substitute_refs(run.config, by_hash),
        }
        if run.kind == "report":
            material["experiment"] = exp.name
            material["results"] = exp.results_subdir
            material["params"] = run.params
            material["paper"] = exp.doc.get("paper")
            material["inputs"] = [(rid, content_hash(self._dep_outcome(exp, rid).artifact)) for rid in run.deps]
        return sha256_json(material)

    # ---------------------------------------------------------------- execution
    def _resolved_config(self, exp, run) -> dict:
        def by_path(stage, idx):
            rid = stage if idx is None else f"{stage}#{idx}"
            return rel(self._dep_outcome(exp, rid).artifact)

        return experiment_mod.substitute_refs(run.config, by_path)

    def _run_report(self, exp, run, key: str) -> List[Path]:
        views: Dict[str, List[RunView]] = {}
        for stage in run.inputs:
            views[stage] = [RunView(exp.runs[rid], self._dep_outcome(exp, rid).artifact)
                            for rid in exp.stage_runs[stage]]
        ctx = ReportContext(exp, run, views)
        mod = importlib.import_module(run.target)
        mod.report(ctx)
        return ctx.outputs

    def execute(self, exp, run) -> Outcome:
        start = time.time()
        code = self._code_hash(run)
        key = self.key_of(exp, run, code)
        forced = self.force or (exp.name, run.stage) in self.force_stages
        log_path = LOGS / f"{exp.name}.{run.id.replace('#', '.')}.log"
        if run.kind == "report":
            stamp = STAMPS / f"{exp.name}.{run.stage}.json"
            if not forced and stamp.exists():
                old = json.loads(stamp.read_text())
                if old.get("key") == key and all((ROOT / p).exists() for p in old.get("outputs", [])) \
                        and all((ROOT / p).is_file() and file_hash(ROOT / p) == h
                                for p, h in old.get("sha256", {}).items()):
                    return Outcome(run, "cached", key, stamp, time.time() - start)
            outputs = self._run_report(exp, run, key)
            write_json_atomic(stamp, {"key": key, "outputs": [rel(p) for p in outputs],
                                      "sha256": {rel(p): file_hash(p) for p in outputs if p.is_file()}})
            return Outcome(run, "ran", key, stamp, time.time() - start)
        artifact = ARTIFACTS / run.target.split(".")[-1] / f"{key[:32]}.json"
        artifact.parent.mkdir(parents=True, exist_ok=True)
        if artifact.exists() and not forced and cached_artifact_intact(artifact):
            return Outcome(run, "cached", key, artifact, time.time() - start)
        config = self._resolved_config(exp, run)
        config_path = None
        if run.kind == "tool":
            config_path = CONFIGS / f"{key}.json"
            write_json_atomic(config_path, config)
        spec = RunSpec(experiment=exp.name, run_id=run.id, kind=run.kind, target=run.target, key=key,
                       code_hash=code, artifact=str(artifact), log=str(log_path), config=config,
                       config_path=rel(config_path) if config_path else None, mode=run.mode,
                       args=list(run.args))
        result = self.executor.execute(spec, run.exclusive)
        if not result.ok:
            raise RunFailed(run.id, result.code, result.message)
        record_artifact_hash(artifact)
        outcome = Outcome(run, "ran", key, artifact, time.time() - start)
        outcome.exec_seconds, outcome.where = result.seconds, f"{result.host}:{result.pid}"
        return outcome

    # ---------------------------------------------------------------- scheduling
    def run_experiment(self, exp, run_ids: List[str]) -> bool:
        """Runs the given runs of one experiment in dependency order; True when none failed."""
        return self.run_all([(exp, run_ids)])

    def run_all(self, selected) -> bool:
        """Runs the selected runs of several experiments, [(experiment, run ids)], as one graph:
        a run starts once its dependencies are done, whatever experiment it belongs to, so
        independent experiments overlap and the pool does not idle at an experiment's tail. Ready
        runs start in experiment order, then file order (with one slot, experiments still run one
        after another). An `exclusive` run waits until nothing else runs, and runs alone.
        True when none failed."""
        pending = [(exp, rid) for exp, run_ids in selected for rid in run_ids]
        total = {exp.name: len(run_ids) for exp, run_ids in selected}
        done = {name: 0 for name in total}
        running = {}
        ok = True
        exclusive_running = False

        def finished(exp, line):
            done[exp.name] += 1
            self._finished(f"[{exp.name} {done[exp.name]}/{total[exp.name]}] {line}")

        def settled(exp, rid):
            return (exp.name, rid) in self.outcomes

        with ThreadPoolExecutor(max_workers=self.jobs) as pool:
            while pending or running:
                # Skip runs whose dependency failed.
                for exp, rid in list(pending):
                    if any(self.outcomes.get((exp.name, d)) and self.outcomes[(exp.name, d)].status
                           in ("failed", "skipped") for d in exp.runs[rid].deps):
                        pending.remove((exp, rid))
                        self.outcomes[(exp.name, rid)] = Outcome(exp.runs[rid], "skipped", "", None, 0,
                                                                 "a dependency failed")
                        finished(exp, f"skipped {rid}: a dependency failed")
                ready = [(exp, rid) for exp, rid in pending
                         if all(settled(exp, d) for d in exp.runs[rid].deps)]
                for exp, rid in ready:
                    run = exp.runs[rid]
                    if exclusive_running or len(running) >= self.jobs:
                        break
                    if run.exclusive and running:
                        break  # wait until the pool is empty
                    pending.remove((exp, rid))
                    running[pool.submit(self._guarded, exp, run)] = (exp, rid)
                    exclusive_running = run.exclusive
                if not running:
                    if pending:
                        # Only reachable if dependencies lie outside the selection: they were
                        # added by closure(), so this is a bug.
                        raise RuntimeError(f"cannot schedule {[f'{e.name}:{r}' for e, r in pending]}")
                    break
                finished_futures, _ = wait(list(running), return_when=FIRST_COMPLETED)
                for fut in finished_futures:
                    exp, rid = running.pop(fut)
                    outcome = fut.result()
                    if exp.runs[rid].exclusive:
                        exclusive_running = False
                    self.outcomes[(exp.name, rid)] = outcome
                    if outcome.status == "failed":
                        ok = False
                        finished(exp, f"FAILED {rid}: {outcome.message}")
                    elif outcome.status == "cached":
                        finished(exp, f"cached {rid} (key {outcome.key[:12]})")
                    else:
                        finished(exp, f"ran {rid} ({exp.runs[rid].target}, {outcome.seconds:.1f} s)")
        return ok

    def _finished(self, line: str) -> None:
        """One run is done: its log line, and one step of the progress."""
        self.echo(line)
        if self.progress is not None:
            self.progress.update(1)

    def _guarded(self, exp, run) -> Outcome:
        try:
            return self.execute(exp, run)
        except RunFailed as e:
            return Outcome(run, "failed", "", None, 0, f"exit {e.code}: {e.message}")
        except Exception as e:  # a report that raised, a lost worker: show it, keep going with the rest
            return Outcome(run, "failed", "", None, 0, f"{type(e).__name__}: {e}")

    def timings(self) -> List[dict]:
        """Every finished run's times: the client's wall time and, for a run that executed, its
        own time where it ran; the difference is what scheduling it cost."""
        return [{"experiment": name, "run": rid, "kind": o.run.kind, "target": o.run.target,
                 "status": o.status, "wall_s": round(o.seconds, 4),
                 "exec_s": None if o.exec_seconds is None else round(o.exec_seconds, 4), "where": o.where}
                for (name, rid), o in self.outcomes.items()]

    # ---------------------------------------------------------------- manifest
    def manifest_entries(self, exp) -> List[dict]:
        out = []
        for rid, run in exp.runs.items():
            o = self.outcomes.get((exp.name, rid))
            if o is None:
                continue
            entry = {"run": rid, "kind": run.kind, "target": run.target, "status": o.status,
                     "key": o.key}
            if run.kind != "report":
                entry["config"] = run.config
                if run.sweep:
                    entry["sweep"] = run.sweep
                if o.artifact is not None and o.artifact.exists():
                    entry["artifact"] = rel(o.artifact)
                    entry["sha256"] = file_hash(o.artifact)
            elif o.artifact is not None and o.artifact.exists():
                entry["outputs"] = json.loads(o.artifact.read_text()).get("sha256", {})
            out.append(entry)
        return out


def write_manifest(runner: Runner, experiments, complete: bool = False, command: str = "") -> None:
    """results/manifest.json: every run's key, config and artifact hash, and which command at
    which commit last ran each experiment ("last_run"; REPORT.md says whose results it shows). A
    run of a subset of the experiments keeps the other experiments' entries; a complete run
    starts afresh."""
    path = RESULTS / "manifest.json"
    commit = git_commit()
    manifest = {"git_commit": commit, "command": command, "complete": complete, "experiments": {},
                "last_run": {}}
    if path.exists() and not complete:
        try:
            old = json.loads(path.read_text())
            manifest["experiments"] = old.get("experiments", {})
            manifest["last_run"] = old.get("last_run", {})
        except json.JSONDecodeError:
            pass
    for exp in experiments:
        entries = runner.manifest_entries(exp)
        if entries:
            manifest["experiments"][exp.name] = entries
            manifest["last_run"][exp.name] = {"commit": commit, "command": command}
    known = set(experiment_mod.list_experiments())
    for block in ("experiments", "last_run"):
        manifest[block] = dict(sorted((k, v) for k, v in manifest[block].items() if k in known))
    write_json_atomic(path, manifest)
