"""One run, executed wherever the executor sends it: this process, a Dask worker here or on
another machine. Everything it needs travels in a RunSpec (plain data, picklable); what it did
comes back as a RunResult. Keys, cache lookups and scheduling stay with the runner.

The worker refuses a run whose code it sees differently from the client (another binary or
module source at the same path): a clear failure instead of a wrong artifact under the
client's key."""
import importlib
import os
import socket
import subprocess
import time
import uuid
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Dict, List, Optional

from pipeline import cache, paths
from pipeline.context import StageContext
from pipeline.procs import run_child


@dataclass
class RunSpec:
    experiment: str
    run_id: str
    kind: str                  # tool | python
    target: str                # executable name or module
    key: str
    code_hash: str             # what the client hashed into the key
    artifact: str              # final path in the cache
    log: str
    config: Dict[str, Any]     # resolved (references are artifact paths)
    config_path: Optional[str] = None   # tool: the config file the client wrote
    mode: Optional[str] = None
    args: List[str] = field(default_factory=list)


@dataclass
class RunResult:
    ok: bool
    code: int = 0
    message: str = ""
    seconds: float = 0.0
    host: str = ""
    pid: int = 0


def run_spec(spec: RunSpec, check_code: bool = True) -> RunResult:
    """Executes one tool or python run and publishes its artifact atomically into the cache.
    check_code: first check that this process sees the code the client keyed the run with
    (needless where the client itself runs it)."""
    start = time.time()
    where = dict(host=socket.gethostname(), pid=os.getpid())
    from pipeline.runner import code_hash  # the same function the client keyed with
    seen = code_hash(spec.kind, spec.target) if check_code else spec.code_hash
    if seen != spec.code_hash:
        return RunResult(False, 2, f"this worker ({where['host']}, pid {where['pid']}) sees other code for "
                         f"{spec.target} than the client (code hash {seen[:12]} vs {spec.code_hash[:12]}): "
                         "workers must share the client's repository and build", **where)
    # Unique per call: the same key may run twice at once, in two experiments or two threads.
    staged = cache.staging_dir() / f"{uuid.uuid4().hex[:12]}.{Path(spec.artifact).name}"
    artifact = Path(spec.artifact)
    try:
        if spec.kind == "tool":
            code, message = _run_tool(spec, staged)
        else:
            code, message = _run_python(spec, staged)
        if code == 0:
            cache.publish(staged, artifact)
    finally:
        for leftover in staged.parent.glob(staged.name + "*"):
            leftover.unlink(missing_ok=True)
    return RunResult(code == 0, code, message, time.time() - start, **where)


def _run_tool(spec: RunSpec, staged: Path):
    cmd = [str(paths.BIN / spec.target)]
    if spec.mode:
        cmd.append(spec.mode)
    cmd += spec.args + ["--config", spec.config_path, "--out", str(staged)]
    with open(spec.log, "w") as log:
        log.write("$ " + " ".join([paths.rel(cmd[0])] + cmd[1:-1] + [paths.rel(spec.artifact)]) + "\n")
        log.flush()
        proc = run_child(cmd, cwd=paths.ROOT, stdout=log, stderr=subprocess.PIPE, text=True)
        log.write(proc.stderr)
    if proc.returncode != 0:
        lines = [l for l in proc.stderr.strip().splitlines() if l.strip()]
        return proc.returncode, lines[-1] if lines else "no message"
    if not staged.exists():
        return 1, "exited 0 but wrote no artifact"
    return 0, ""


def _run_python(spec: RunSpec, staged: Path):
    mod = importlib.import_module(spec.target)
    ctx = StageContext(spec.config, staged, spec.run_id, spec.experiment)
    log = Path(spec.log)
    try:
        mod.run(ctx)
    except Exception as e:  # a python stage's failure is reported like a tool's
        log.write_text("\n".join(ctx.log_lines + [f"error: {e}"]) + "\n")
        return (3 if isinstance(e, ArithmeticError) else 2), str(e)
    log.write_text("\n".join(ctx.log_lines) + "\n")
    if not staged.exists():
        return 1, "python stage wrote no artifact"
    return 0, ""
