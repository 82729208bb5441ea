"""Processes the pipeline starts, and what becomes of them when it stops.

A tool run is a child process. Without care it outlives a killed pipeline: it keeps running and
writing into the cache after its leader is gone. Two measures stop that:
  - every child asks the kernel for SIGKILL when its parent dies (prctl PR_SET_PDEATHSIG), which
    also covers a leader killed with SIGKILL, where no handler runs;
  - the leader's handler for SIGTERM, SIGINT and SIGHUP kills every descendant (the tools of the
    python stages too, which start their own children) before it exits.
"""
import ctypes
import ctypes.util
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

_PR_SET_PDEATHSIG = 1
try:
    _LIBC = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6", use_errno=True)
    _PRCTL = _LIBC.prctl
except (OSError, AttributeError):  # not Linux: no parent-death signal, the handler still works
    _PRCTL = None


def _die_with_parent() -> None:
    # Runs in the child between fork and exec: nothing but one prepared C call.
    if _PRCTL is not None:
        _PRCTL(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)


def run_child(cmd, **kwargs) -> subprocess.CompletedProcess:
    """subprocess.run for a tool: the child is killed when the process (strictly, the thread)
    that started it dies, so a killed pipeline or Dask worker leaves no orphan behind."""
    return subprocess.run(cmd, preexec_fn=_die_with_parent, **kwargs)


def pid_alive(pid: int) -> bool:
    """Whether a process with this id exists on this machine (a zombie counts as alive)."""
    if pid <= 0:
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # someone else's process
        return True
    return True


def _children_map() -> dict:
    children = {}
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            text = stat.read_text()
        except OSError:
            continue
        # pid (comm) state ppid ...: comm may hold spaces and parentheses, so split after the last ')'.
        fields = text[text.rfind(")") + 2:].split()
        children.setdefault(int(fields[1]), []).append(int(stat.parent.name))
    return children


def descendants(pid: int) -> list:
    """Every process below `pid`, parents before their children."""
    children = _children_map()
    out, todo = [], list(children.get(pid, []))
    while todo:
        p = todo.pop(0)
        out.append(p)
        todo.extend(children.get(p, []))
    return out


def kill_descendants(grace: float = 2.0) -> list:
    """SIGTERM to every descendant of this process, SIGKILL to those still there after `grace`
    seconds; returns the pids it signalled."""
    pids = descendants(os.getpid())
    for sig in (signal.SIGTERM, signal.SIGKILL):
        for p in pids:
            try:
                os.kill(p, sig)
            except (ProcessLookupError, PermissionError):
                pass
        deadline = time.time() + grace
        while sig == signal.SIGTERM and time.time() < deadline and not all(exited(p) for p in pids):
            time.sleep(0.05)
    return pids


def exited(pid: int) -> bool:
    """Whether the process has exited (a zombie, waiting for its parent to reap it, has)."""
    try:
        text = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return True
    return text[text.rfind(")") + 2:].split()[0] == "Z"


def stop_with_children(on_stop=None) -> None:
    """Installs the leader's handler: on SIGTERM, SIGINT or SIGHUP it kills every descendant,
    calls on_stop() (cleaning what the killed writers left), and exits 128 + the signal."""
    def handler(signum, _frame):
        for s in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP):
            signal.signal(s, signal.SIG_IGN)
        print(f"pipeline: stopped by signal {signum}: stopping the runs it started", file=sys.stderr, flush=True)
        kill_descendants()
        if on_stop is not None:
            try:
                on_stop()
            except Exception:  # best effort: the next start cleans again
                pass
        os._exit(128 + signum)

    for s in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP):
        signal.signal(s, handler)
