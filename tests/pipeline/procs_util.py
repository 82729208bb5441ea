"""Looking at real processes from the tests: descendants by name, and waiting for a condition."""
import time
from pathlib import Path

from pipeline.procs import descendants, exited

gone = exited  # whether a process has exited (a zombie has)


def comm(pid: int) -> str:
    try:
        return Path(f"/proc/{pid}/comm").read_text().strip()
    except OSError:
        return ""


def children_named(pid: int, name: str) -> list:
    """Processes below `pid` (at any depth) whose command name is `name`."""
    return [p for p in descendants(pid) if comm(p) == name]


def wait_until(condition, timeout: float, step: float = 0.02):
    """condition()'s first truthy value within `timeout` seconds, else its last (falsy) one."""
    deadline = time.time() + timeout
    value = condition()
    while not value and time.time() < deadline:
        time.sleep(step)
        value = condition()
    return value


def parent_of(pid: int) -> int:
    text = Path(f"/proc/{pid}/stat").read_text()
    return int(text[text.rfind(")") + 2:].split()[1])


def signal_in_flight(proc, tool: str, sig, target=lambda proc, pids: pids[0]):
    """Waits until a `tool` process runs below `proc`, sends `sig` to target(proc, those pids),
    and waits for `proc` to end: (stdout, stderr, the tool pids seen)."""
    import os
    try:
        pids = wait_until(lambda: children_named(proc.pid, tool), timeout=60)
        assert pids, f"no {tool} started"
        os.kill(target(proc, pids), sig)
        stdout, stderr = proc.communicate(timeout=120)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.communicate()
    return stdout, stderr, pids
