"""The artifact envelope on the Python side, identical in shape to cpp/softsim/io/artifact.cpp:
{"schema": {"name", "version"}, "provenance": {...}, "payload": {...}}, written atomically."""
import json
import math
import os
import threading
import subprocess
from pathlib import Path

from pipeline.hashing import file_hash
from pipeline.paths import ROOT


def git_commit() -> str:
    """The source tree's commit as the executables report it (cpp/softsim/io/git_commit.hpp):
    `git describe --always --dirty` of the repository root, "unknown" without git or a repository."""
    try:
        out = subprocess.run(["git", "-C", str(ROOT), "describe", "--always", "--dirty"],
                             capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"
    return out or "unknown"


def _check_finite(value, where=""):
    if isinstance(value, float) and not math.isfinite(value):
        raise ValueError(f"non-finite value at {where or '/'}")
    if isinstance(value, dict):
        for k, v in value.items():
            _check_finite(v, f"{where}/{k}")
    elif isinstance(value, (list, tuple)):
        for i, v in enumerate(value):
            _check_finite(v, f"{where}/{i}")


def write_atomic(path, write) -> None:
    """Calls write(tmp) on a temporary sibling of `path` and renames it into place: a reader sees
    the old file or the whole new one, never a torn one. A failed write (a full disk) removes the
    temporary and raises the OSError; `path` is left as it was."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    # The thread's id as well as the PID: two threads of one process may write the same file at
    # once (one key in two overlapping experiments); the name still ends in `.tmp.PID`, which is
    # what the stale-file cleaner reads.
    tmp = Path(path.with_name(f"{path.name}.{threading.get_ident()}.tmp.{os.getpid()}"))  # a plain Path
    try:
        write(tmp)
        os.replace(tmp, path)
    except BaseException as e:
        try:
            tmp.unlink()
        except FileNotFoundError:
            pass
        if isinstance(e, OSError) and e.errno is not None:  # named by the file meant, not the temporary
            raise OSError(e.errno, e.strerror, str(path)) from e
        raise


class ResultPath(type(Path())):
    """A path under results/ (what a report's ctx.out gives) whose write_text and write_bytes
    are atomic, so that a report writing `ctx.out("summary.md").write_text(text)` gets the same
    guarantee as write_text_atomic."""

    def write_text(self, data, encoding=None, errors=None, newline=None):
        write_atomic(self, lambda tmp: tmp.write_text(data, encoding, errors, newline))
        return len(data)

    def write_bytes(self, data):
        write_atomic(self, lambda tmp: tmp.write_bytes(data))
        return len(data)


def write_text_atomic(path, text: str) -> None:
    """Every report, table and summary under results/ goes through here (and plots through
    pipeline.plots.save): the old file or the whole new one, never a torn one."""
    write_atomic(path, lambda tmp: tmp.write_text(text))


def write_json_atomic(path, document) -> None:
    def write(tmp):
        with open(tmp, "w") as f:
            json.dump(document, f, allow_nan=False)
            f.write("\n")
    write_atomic(path, write)


def write_artifact(out_path, schema: str, version: int, tool: str, config: dict, payload: dict,
                   inputs=(), seed=None) -> None:
    """Writes an artifact; refuses NaN/Inf anywhere in the payload (a numerical failure upstream)."""
    _check_finite(payload)
    document = {
        "schema": {"name": schema, "version": version},
        "provenance": {
            "tool": tool,
            "version": "python",
            "git_commit": git_commit(),
            "config": config,
            "inputs": {str(p): file_hash(p) for p in inputs},
            "seed": seed,
        },
        "payload": payload,
    }
    write_json_atomic(out_path, document)


def read_artifact(path, schema=None) -> dict:
    with open(path) as f:
        doc = json.load(f)
    if schema is not None and doc.get("schema", {}).get("name") != schema:
        raise ValueError(f"{path}: expected schema {schema!r}, got {doc.get('schema')!r}")
    return doc
