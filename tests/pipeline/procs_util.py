"""Looking at real processes from the tests: descendants by name, and waiting for a condition."""
import time
from pathlib import Path

from pipeline.procs import descendants


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
