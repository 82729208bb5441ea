"""Executes the runs of experiments: cache lookup, tool/module invocation, parallel scheduling."""
import ast
import importlib
import importlib.util
import json
import subprocess
import threading
import time
from concurrent.futures import FIRST_COMPLETED, ThreadPoolExecutor, wait
from pathlib import Path
from typing import Dict, List, Optional

from pipeline import experiment as experiment_mod
from pipeline.artifacts import git_commit, write_json_atomic
from pipeline.context import ReportContext, RunView, StageContext
from pipeline.errors import RunFailed
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


class Outcome:
    def __init__(self, run, status: str, key: str, artifact: Optional[Path], seconds: float,
                 message: str = ""):
        self.run = run
        self.status = status          # ran | cached | failed | skipped
        self.key = key
        self.artifact = artifact
        self.seconds = seconds
        self.message = message


class Runner:
    def __init__(self, jobs: int = 1, force: bool = False, force_stages=(), echo=print, progress=None):
        self.jobs = max(1, jobs)
        self.force = force
        self.force_stages = set(force_stages)
        self.echo = echo
        # Anything with update(n) (a tqdm bar): told of every finished run, whatever its outcome.
        self.progress = progress
        self.outcomes: Dict[tuple, Outcome] = {}
        self.lock = threading.Lock()
        for d in (ARTIFACTS, CONFIGS, LOGS, STAMPS):
            d.mkdir(parents=True, exist_ok=True)

    # ---------------------------------------------------------------- keys
    def _code_hash(self, run) -> str:
        if run.kind == "tool":
            binary = BIN / run.target
            if not binary.exists():
                raise RunFailed(run.id, 2, f"no executable {rel(binary)} (run `make build`)")
            return file_hash(binary)
        module_file(run.target)  # a clear error when the module does not exist
        hashes = [file_hash(f) for f in pipeline_import_closure(run.target)]
        # A python stage that drives our executables names them in TOOLS: their binaries
        # belong to its key exactly like a tool stage's binary.
        if run.kind == "python":
            module = importlib.import_module(run.target)
            for tool in getattr(module, "TOOLS", ()):
                binary = BIN / tool
                if not binary.exists():
                    raise RunFailed(run.id, 2, f"no executable {rel(binary)} (run `make build`)")
                hashes.append(file_hash(binary))
            # Repository folders it reads (DATA): every file's path and content.
            for folder in getattr(module, "DATA", ()):
                for f in sorted(p for p in (ROOT / folder).rglob("*") if p.is_file()):
                    hashes.append([rel(f), file_hash(f)])
        return sha256_json(hashes)

    def _dep_outcome(self, exp, rid) -> Outcome:
        return self.outcomes[(exp.name, rid)]

    def key_of(self, exp, run) -> str:
        def by_hash(stage, idx):
            rid = stage if idx is None else f"{stage}#{idx}"
            return "content:" + content_hash(self._dep_outcome(exp, rid).artifact)

        material = {
            "kind": run.kind,
            "target": run.target,
            "code": self._code_hash(run),
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

    def _run_tool(self, exp, run, key: str, artifact: Path, log_path: Path) -> None:
        config_path = CONFIGS / f"{key}.json"
        write_json_atomic(config_path, self._resolved_config(exp, run))
        cmd = [str(BIN / run.target)]
        if run.mode:
            cmd.append(run.mode)
        cmd += run.args + ["--config", rel(config_path), "--out", rel(artifact)]
        with open(log_path, "w") as log:
            log.write("$ " + " ".join(cmd[0:1] and [rel(cmd[0])] + cmd[1:]) + "\n")
            log.flush()
            proc = subprocess.run(cmd, cwd=ROOT, stdout=log, stderr=subprocess.PIPE, text=True)
            log.write(proc.stderr)
        if proc.returncode != 0 or not artifact.exists():
            lines = [l for l in proc.stderr.strip().splitlines() if l.strip()]
            msg = lines[-1] if lines else "no message"
            if proc.returncode == 0:
                msg = "exited 0 but wrote no artifact"
            raise RunFailed(run.id, proc.returncode or 1, msg)

    def _run_python(self, exp, run, artifact: Path, log_path: Path) -> None:
        mod = importlib.import_module(run.target)
        ctx = StageContext(self._resolved_config(exp, run), artifact, run.id, exp.name)
        try:
            mod.run(ctx)
        except Exception as e:  # a python stage's failure is reported like a tool's
            if artifact.exists():
                artifact.unlink()
            log_path.write_text("\n".join(ctx.log_lines + [f"error: {e}"]) + "\n")
            raise RunFailed(run.id, 3 if isinstance(e, ArithmeticError) else 2, str(e)) from None
        log_path.write_text("\n".join(ctx.log_lines) + "\n")
        if not artifact.exists():
            raise RunFailed(run.id, 1, "python stage wrote no artifact")

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
        key = self.key_of(exp, run)
        forced = self.force or run.stage in self.force_stages
        log_path = LOGS / f"{exp.name}.{run.id.replace('#', '.')}.log"
        if run.kind == "report":
            stamp = STAMPS / f"{exp.name}.{run.stage}.json"
            if not forced and stamp.exists():
                old = json.loads(stamp.read_text())
                if old.get("key") == key and all((ROOT / p).exists() for p in old.get("outputs", [])):
                    return Outcome(run, "cached", key, stamp, time.time() - start)
            outputs = self._run_report(exp, run, key)
            write_json_atomic(stamp, {"key": key, "outputs": [rel(p) for p in outputs],
                                      "sha256": {rel(p): file_hash(p) for p in outputs if p.is_file()}})
            return Outcome(run, "ran", key, stamp, time.time() - start)
        artifact = ARTIFACTS / run.target.split(".")[-1] / f"{key[:32]}.json"
        artifact.parent.mkdir(parents=True, exist_ok=True)
        if artifact.exists() and not forced:
            return Outcome(run, "cached", key, artifact, time.time() - start)
        if run.kind == "tool":
            self._run_tool(exp, run, key, artifact, log_path)
        else:
            self._run_python(exp, run, artifact, log_path)
        return Outcome(run, "ran", key, artifact, time.time() - start)

    # ---------------------------------------------------------------- scheduling
    def run_experiment(self, exp, run_ids: List[str]) -> bool:
        """Runs the given runs of one experiment in dependency order; True when none failed."""
        pending = list(run_ids)
        total = len(pending)
        done_count = 0
        running = {}
        ok = True
        exclusive_running = False
        with ThreadPoolExecutor(max_workers=self.jobs) as pool:
            while pending or running:
                # Skip runs whose dependency failed.
                for rid in list(pending):
                    deps = exp.runs[rid].deps
                    if any(self.outcomes.get((exp.name, d)) and self.outcomes[(exp.name, d)].status
                           in ("failed", "skipped") for d in deps):
                        pending.remove(rid)
                        done_count += 1
                        self.outcomes[(exp.name, rid)] = Outcome(exp.runs[rid], "skipped", "", None, 0,
                                                                 "a dependency failed")
                        self._finished(f"[{exp.name} {done_count}/{total}] skipped {rid}: a dependency failed")
                ready = [rid for rid in pending
                         if all((exp.name, d) in self.outcomes for d in exp.runs[rid].deps)]
                for rid in ready:
                    run = exp.runs[rid]
                    if exclusive_running or len(running) >= self.jobs:
                        break
                    if run.exclusive and running:
                        break  # wait until the pool is empty
                    pending.remove(rid)
                    running[pool.submit(self._guarded, exp, run)] = rid
                    exclusive_running = run.exclusive
                if not running:
                    if pending:
                        # Only reachable if dependencies lie outside the selection: they were
                        # added by closure(), so this is a bug.
                        raise RuntimeError(f"cannot schedule {pending}")
                    break
                finished, _ = wait(list(running), return_when=FIRST_COMPLETED)
                for fut in finished:
                    rid = running.pop(fut)
                    outcome = fut.result()
                    if exp.runs[rid].exclusive:
                        exclusive_running = False
                    self.outcomes[(exp.name, rid)] = outcome
                    done_count += 1
                    if outcome.status == "failed":
                        ok = False
                        self._finished(f"[{exp.name} {done_count}/{total}] FAILED {rid}: {outcome.message}")
                    elif outcome.status == "cached":
                        self._finished(f"[{exp.name} {done_count}/{total}] cached {rid} (key {outcome.key[:12]})")
                    else:
                        self._finished(f"[{exp.name} {done_count}/{total}] ran {rid} "
                                       f"({exp.runs[rid].target}, {outcome.seconds:.1f} s)")
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
        except Exception as e:  # a report that raised: show it, keep going with the rest
            return Outcome(run, "failed", "", None, 0, f"{type(e).__name__}: {e}")

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


def write_manifest(runner: Runner, experiments, complete: bool = False) -> None:
    """results/manifest.json: every run's key, config and artifact hash. A run of a subset of
    the experiments keeps the other experiments' entries; a complete run starts afresh."""
    path = RESULTS / "manifest.json"
    manifest = {"git_commit": git_commit(), "experiments": {}}
    if path.exists() and not complete:
        try:
            manifest["experiments"] = json.loads(path.read_text()).get("experiments", {})
        except json.JSONDecodeError:
            pass
    for exp in experiments:
        entries = runner.manifest_entries(exp)
        if entries:
            manifest["experiments"][exp.name] = entries
    known = set(experiment_mod.list_experiments())
    manifest["experiments"] = dict(sorted((k, v) for k, v in manifest["experiments"].items() if k in known))
    write_json_atomic(path, manifest)
