"""Where runs execute: this machine's own pool (the default) or a Dask distributed cluster.

The runner decides what runs (keys, cache, order, skipping); an executor only carries a
RunSpec to pipeline.execute.run_spec somewhere and brings its RunResult back. Reports always
run here, on the client: they read artifacts and write results/.

Dask workers must see the client's repository, build/bin and cache at the same paths (a shared
filesystem); `DaskExecutor.check_workers` proves it at start-up, each run checks its code hash
again on its worker, and runs are published into the cache atomically (pipeline.cache)."""
import logging
import os
import threading
import uuid
from pathlib import Path
from typing import Dict, Iterable, Tuple

from pipeline import cache, paths
from pipeline.errors import ExperimentError
from pipeline.execute import RunResult, RunSpec, run_spec

# Resource a Dask worker offers when it may run `exclusive` (timing) runs; dask-local workers do.
EXCLUSIVE = "exclusive"
# Runs whose function raised (an I/O error on a shared filesystem, say) are resubmitted this many
# times; a worker that dies mid-run is handled by the scheduler itself, which moves the run to
# another worker (distributed.scheduler.allowed-failures, 3 by default).
RETRIES = 2


class ClusterMismatch(ExperimentError):
    """A worker that does not see the client's code or cache: refused (exit 2)."""


class LocalExecutor:
    """Runs in this process's threads (the runner's pool): the pipeline as it always was."""
    name = "local"

    def __init__(self, jobs: int = 1):
        self.slots = max(1, jobs)

    def describe(self) -> str:
        return f"local pool of {self.slots}"

    def check_workers(self, _code: Dict[Tuple[str, str], str]) -> None:
        pass

    def execute(self, spec: RunSpec, exclusive: bool = False) -> RunResult:
        return run_spec(spec, check_code=False)

    def clean_stale(self) -> Tuple[int, int]:
        return cache.clean_stale()

    def close(self) -> None:
        cache.release_staging_dir()


def worker_identity(code_keys: Iterable[Tuple[str, str]], token_path: str) -> dict:
    """Runs on a worker: what it sees of the repository, the code and the cache."""
    import socket
    from pipeline.runner import code_hash
    code = {}
    for kind, target in code_keys:
        try:
            code[f"{kind}:{target}"] = code_hash(kind, target)
        except Exception as e:  # a missing binary or module: reported, not raised
            code[f"{kind}:{target}"] = f"error: {e}"
    try:
        token = Path(token_path).read_text()
    except OSError:
        token = None
    return {"host": socket.gethostname(), "pid": os.getpid(), "root": str(paths.ROOT),
            "bin": str(paths.BIN), "cache": str(paths.CACHE), "token": token, "code": code}


def _clean_stale_here() -> Tuple[int, int]:
    return cache.clean_stale()


class DaskExecutor:
    """Runs on a Dask distributed cluster: an existing one (`address`: tcp://HOST:PORT or a
    scheduler file) or, with address None, a local cluster of `workers` processes."""
    name = "dask"

    def __init__(self, address: str = None, workers: int = 2, jobs: int = None, echo=print,
                 wait_s: float = 60):
        import distributed
        self.echo = echo
        self.cluster = None
        if address is None:
            self.cluster = distributed.LocalCluster(
                n_workers=max(1, workers), threads_per_worker=1, processes=True,
                resources={EXCLUSIVE: 1}, dashboard_address=None, scheduler_port=0,
                silence_logs=logging.CRITICAL)  # the pipeline reports failures itself
            self.client = distributed.Client(self.cluster)
        else:
            try:
                if "://" not in address and Path(address).is_file():
                    self.client = distributed.Client(scheduler_file=address, timeout="30s")
                else:
                    self.client = distributed.Client(address, timeout="30s")
            except (OSError, TimeoutError) as e:
                raise ClusterMismatch(f"--scheduler {address}: cannot reach the Dask scheduler ({e})") from None
        try:
            self.client.wait_for_workers(1, timeout=wait_s)
        except TimeoutError:
            self.close()
            raise ClusterMismatch(f"the Dask scheduler {self.address} has no worker after {wait_s:.0f} s") from None
        # A worker lost mid-run: the scheduler moves its runs to the other workers by itself; the
        # pipeline says so on the console when it happens and in each moved run's log once it
        # has run again (its log is rewritten by the new worker, so the note is added after).
        self._lost: Dict[str, str] = {}      # task key -> the lost worker that was running it
        self._specs: Dict[str, RunSpec] = {}
        self._noted = set()
        self._lock = threading.Lock()
        self._closing = False
        self.client.subscribe_topic("all", self._on_event)
        workers_info = self.client.scheduler_info()["workers"]
        self.name = "dask-local" if self.cluster is not None else "dask"
        self.slots = jobs or sum(w.get("nthreads", 1) for w in workers_info.values())
        self.exclusive_remote = any(w.get("resources", {}).get(EXCLUSIVE) for w in workers_info.values())

    @property
    def address(self) -> str:
        return self.client.scheduler.address

    def describe(self) -> str:
        n = len(self.client.scheduler_info()["workers"])
        kind = "local Dask cluster" if self.cluster is not None else "Dask cluster"
        return f"{kind} {self.address}, {n} worker{'s' if n != 1 else ''}, {self.slots} runs at a time"

    def check_workers(self, code: Dict[Tuple[str, str], str]) -> None:
        """Refuses the cluster unless every worker sees the client's repository, code and cache."""
        paths.CACHE.mkdir(parents=True, exist_ok=True)
        token_path = paths.CACHE / f".worker-check.{uuid.uuid4().hex}"
        token = uuid.uuid4().hex
        token_path.write_text(token)
        try:
            seen = self.client.run(worker_identity, list(code), str(token_path))
        finally:
            token_path.unlink(missing_ok=True)
        problems = []
        for address, ident in sorted(seen.items()):
            who = f"worker {address} (host {ident['host']})"
            if ident["token"] != token:
                problems.append(f"{who} does not see the client's cache folder {paths.CACHE} "
                                f"(its cache is {ident['cache']})")
                continue
            for (kind, target), mine in code.items():
                theirs = ident["code"].get(f"{kind}:{target}", "")
                if theirs != mine:
                    what = (f"executable {target} ({paths.rel(paths.BIN / target)})" if kind == "tool"
                            else f"python stage {target}")
                    problems.append(f"{who} sees a different {what}: hash {theirs[:16] or 'none'} "
                                    f"(its build: {ident['bin']}), the client {mine[:16]}")
        if problems:
            raise ClusterMismatch("refusing the Dask cluster, its workers must share the client's repository, "
                                  "build and cache (a shared filesystem, the same build):\n  " + "\n  ".join(problems))

    def _on_event(self, event) -> None:
        """The scheduler's event stream: a removed worker that was running runs."""
        _, msg = event
        if not isinstance(msg, dict) or msg.get("action") != "remove-worker" or self._closing:
            return
        keys = sorted(str(k) for k in msg.get("processing-tasks", ()))
        worker = msg.get("worker", "?")
        with self._lock:
            for key in keys:
                self._lost[key] = worker
        runs = ", ".join(_run_of_key(k) for k in keys) or "no run"
        self.echo(f"pipeline: lost Dask worker {worker} while it ran {runs}"
                  + ("; resubmitted to the other workers" if keys else ""))

    def _note_resubmitted(self, key: str, result: RunResult = None) -> None:
        """Adds to a resubmitted run's log that its first worker was lost (once)."""
        with self._lock:
            if key not in self._lost or key in self._noted or key not in self._specs:
                return
            self._noted.add(key)
            worker, spec = self._lost[key], self._specs[key]
        where = f" and ran again on {result.host} (pid {result.pid})" if result is not None else ""
        line = f"pipeline: worker {worker} was lost while running this; the run was resubmitted{where}"
        try:
            with open(spec.log, "a") as log:
                log.write(line + "\n")
        except OSError:
            pass
        if result is not None:
            self.echo(f"pipeline: {spec.experiment} {spec.run_id}: resubmitted after worker {worker} was lost, "
                      f"ran again on {result.host} (pid {result.pid})")

    def execute(self, spec: RunSpec, exclusive: bool = False) -> RunResult:
        if exclusive and not self.exclusive_remote:
            # No worker offers the `exclusive` resource: timings stay on this machine, alone.
            return run_spec(spec, check_code=False)
        key = f"{spec.experiment}.{spec.run_id}-{uuid.uuid4().hex[:8]}"
        with self._lock:
            self._specs[key] = spec
        future = self.client.submit(run_spec, spec, key=key, pure=False, retries=RETRIES,
                                    resources={EXCLUSIVE: 1} if exclusive else None)
        result = future.result()
        self._note_resubmitted(key, result)
        return result

    def clean_stale(self) -> Tuple[int, int]:
        count, size = cache.clean_stale()
        try:
            for c, s in self.client.run(_clean_stale_here).values():
                count, size = count + c, size + s
        except Exception:  # a worker going away meanwhile: the next start cleans again
            pass
        return count, size

    def close(self) -> None:
        # A loss reported after its run came back: noted in the run's log now.
        for key in list(self._lost):
            self._note_resubmitted(key)
        self._closing = True
        try:
            self.client.run(cache.release_staging_dir)
        except Exception:  # a worker gone meanwhile: its folder is stale, cleaned next time
            pass
        cache.release_staging_dir()
        self.client.close()
        if self.cluster is not None:
            self.cluster.close()


def _run_of_key(key: str) -> str:
    """'experiment run' of a task key 'experiment.run-xxxxxxxx' (DaskExecutor.execute)."""
    name = key.rsplit("-", 1)[0]
    experiment, _, run = name.partition(".")
    return f"{experiment} {run}" if run else name


def make_executor(kind: str, scheduler: str = None, jobs: int = None, echo=print):
    if scheduler:
        return DaskExecutor(scheduler, jobs=jobs, echo=echo)
    if kind == "dask-local":
        return DaskExecutor(None, workers=jobs or os.cpu_count() or 1, echo=echo)
    if kind == "dask":
        raise ExperimentError("command line: --executor dask needs --scheduler tcp://HOST:PORT (or a scheduler file)")
    return LocalExecutor(jobs or 1)
