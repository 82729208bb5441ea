"""Writing into the run cache safely when many processes (and machines) share it, and cleaning
what killed writers left behind.

A run never writes its artifact in place. The tool (or python stage) writes into a staging
folder of its own, build/cache/staging/<host>/<pid>/, and the finished artifact is renamed into
build/cache/artifacts/: a rename within one filesystem is atomic, so two runs of the same key on
two workers leave one complete entry (the later rename wins, and both are the same result),
never a torn one. A writer killed mid-run leaves its staging folder (with the tool's own
`*.tmp.PID`, possibly hundreds of MB); it is stale once that process is gone, which only its own
machine can tell: each machine cleans its own host's folders, at start-up and at the end of a run.
"""
import os
import shutil
import socket
import time
from pathlib import Path
from typing import List, Tuple

from pipeline import paths
from pipeline.procs import pid_alive

STAGING = "staging"
# A `*.tmp.PID` outside the staging folders (the pipeline's own small atomic writes) is stale
# when its PID is gone from this machine and it has not changed for this long: on a shared
# cache the writer may live on another machine, where this PID means nothing.
FOREIGN_GRACE_S = 600


def host() -> str:
    return socket.gethostname() or "localhost"


def staging_dir() -> Path:
    """This process's own staging folder (created)."""
    d = paths.CACHE / STAGING / host() / str(os.getpid())
    d.mkdir(parents=True, exist_ok=True)
    return d


def publish(staged: Path, final: Path) -> None:
    """Moves a finished artifact into the cache atomically."""
    final.parent.mkdir(parents=True, exist_ok=True)
    os.replace(staged, final)


def _tmp_pid(name: str):
    """The writer's PID of a `NAME.tmp.PID` file, or None."""
    head, sep, tail = name.rpartition(".tmp.")
    return int(tail) if sep and head and tail.isdigit() else None


def release_staging_dir() -> None:
    """Removes this process's staging folder when it is empty (at the end of a run)."""
    try:
        (paths.CACHE / STAGING / host() / str(os.getpid())).rmdir()
    except OSError:
        pass


def _size(path: Path) -> int:
    if path.is_file():
        return path.stat().st_size
    return sum(p.stat().st_size for p in path.rglob("*") if p.is_file())


def stale_entries(cache: Path = None, now: float = None) -> List[Tuple[Path, int]]:
    """(path, bytes) of every leftover of a dead writer in the cache that this machine can judge:
    its own host's staging folders whose process is gone, and `*.tmp.PID` files elsewhere whose
    PID is gone here and which have not changed for FOREIGN_GRACE_S."""
    cache = Path(cache or paths.CACHE)
    now = time.time() if now is None else now
    out = []
    mine = cache / STAGING / host()
    if mine.is_dir():
        for d in mine.iterdir():
            if d.name.isdigit() and not pid_alive(int(d.name)):
                out.append((d, _size(d)))
    if not cache.is_dir():
        return out
    for root, dirs, files in os.walk(cache):
        if Path(root) == cache and STAGING in dirs:
            dirs.remove(STAGING)
        for name in files:
            pid = _tmp_pid(name)
            if pid is None:
                continue
            p = Path(root) / name
            try:
                st = p.stat()
            except FileNotFoundError:
                continue
            if not pid_alive(pid) and now - st.st_mtime >= FOREIGN_GRACE_S:
                out.append((p, st.st_size))
    return out


def clean_stale(cache: Path = None) -> Tuple[int, int]:
    """Removes stale leftovers (stale_entries); returns (how many, bytes)."""
    count = size = 0
    for path, nbytes in stale_entries(cache):
        try:
            if path.is_dir():
                leftovers = sum(1 for p in path.rglob("*") if p.is_file())
                shutil.rmtree(path)
            else:
                leftovers = 1
                path.unlink()
        except FileNotFoundError:
            continue
        count += leftovers  # a dead writer's empty staging folder is tidied, not counted
        size += nbytes
    return count, size


def describe(count: int, size: int) -> str:
    return f"{count} stale temporary file{'s' if count != 1 else ''} of dead writers ({size / 1e6:.1f} MB)"


# ----------------------------------------------------------------------------- verification
# A cached artifact is used only if it is the file its run wrote: the run records the artifact's
# sha256 (cache/hashes/<tool>/<artifact>.sha256, apart from the artifacts), and a cache hit checks it. A truncated or edited artifact
# is run again instead of being reported as cached and failing every run downstream of it.

HASHES = "hashes"


def _hash_record(artifact: Path) -> Path:
    return artifact.parent.parent.parent / HASHES / artifact.parent.name / (artifact.name + ".sha256")


def record_artifact_hash(artifact) -> None:
    from pipeline.artifacts import write_atomic
    from pipeline.hashing import file_hash
    artifact = Path(artifact)
    digest = file_hash(artifact)
    write_atomic(_hash_record(artifact), lambda tmp: tmp.write_text(digest + "\n"))


def cached_artifact_intact(artifact) -> bool:
    """Whether a cached artifact matches its recorded hash. An artifact cached before hashes were
    recorded is accepted when it parses as an artifact, and its hash recorded then."""
    from pipeline import json_limits
    from pipeline.hashing import file_hash
    artifact = Path(artifact)
    record = _hash_record(artifact)
    try:
        if record.is_file():
            return record.read_text().strip() == file_hash(artifact)
        doc = json_limits.loads(artifact.read_text(), str(artifact))
        if not (isinstance(doc, dict) and {"schema", "provenance", "payload"} <= doc.keys()):
            return False
    except (OSError, ValueError):
        return False
    record_artifact_hash(artifact)
    return True
