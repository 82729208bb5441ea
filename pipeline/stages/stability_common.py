"""Shared plumbing of the stability stages: run an executable on a config and keep the outcome
whatever it is (a stability map needs the failures as data, so a run that ends with exit 3 is a
result here, not an error of the stage).

A stage that calls executables names them in TOOLS (their binaries are part of its cache key) and
records their sha256 in its artifact (`tools`): which binaries made it.
"""
import json
import re
import os
import subprocess
import tempfile
from pathlib import Path

import numpy as np

from pipeline.hashing import file_hash
from pipeline.paths import BIN, ROOT, rel


class Outcome:
    """What one run of an executable gave: exit code, the artifact's payload (exit 0 only) and the
    last line of stderr (the one-line error for exit 2/3)."""

    def __init__(self, code, payload, message, seconds):
        self.code = code
        self.payload = payload
        self.message = message
        self.seconds = seconds

    @property
    def ok(self):
        return self.code == 0

    def as_json(self):
        return {"exit": self.code, "message": self.message, "seconds": self.seconds}


def tool_path(name: str) -> Path:
    path = BIN / name
    if not path.exists():
        raise ValueError(f"no executable {rel(path)} (run `make build`)")
    return path


def tool_hashes(names):
    return {n: file_hash(tool_path(n)) for n in names}


def run_tool(name, config, mode=None, args=(), timeout=600):
    """Runs BIN/name on `config` (a dict) from the repository root; never raises for exit 2/3."""
    import time
    with tempfile.TemporaryDirectory(prefix="stability_") as tmp:
        cfg = Path(tmp) / "config.json"
        out = Path(tmp) / "out.json"
        cfg.write_text(json.dumps(config))
        cmd = [str(tool_path(name))] + ([mode] if mode else []) + list(args) + ["--config", str(cfg), "--out", str(out)]
        env = dict(os.environ, OMP_NUM_THREADS="1")
        start = time.time()
        proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=timeout, env=env)
        seconds = time.time() - start
        lines = [l for l in proc.stderr.splitlines() if l.strip()]
        # Temporary folders are this machine's business: keep them out of the results.
        message = re.sub(r"/tmp/[^/\s]+/", "<temp>/", lines[-1]) if lines else ""
        if proc.returncode not in (0, 2, 3):
            raise RuntimeError(f"{name} ended with exit {proc.returncode}: {message}")
        payload = None
        if proc.returncode == 0:
            if not out.exists():
                raise RuntimeError(f"{name} exited 0 but wrote no artifact")
            payload = json.loads(out.read_text())["payload"]
        elif out.exists():
            raise RuntimeError(f"{name} exited {proc.returncode} but left an artifact behind")
        return Outcome(proc.returncode, payload, message, seconds)


def read_payload(path):
    with open(ROOT / path) as f:
        return json.load(f)["payload"]


def total_energy(payload):
    """Kinetic + strain energy samples of a dhd_result (J)."""
    e = payload["energies"]
    return [k + s for k, s in zip(e["kinetic"], e["strain"])]


# Mesh geometry of the scenes: X is the nodes' array (n × 3, m).
def extent(X):
    """The lower and upper corners of the nodes' bounding box and its height (z extent)."""
    lo, hi = X.min(axis=0), X.max(axis=0)
    return lo, hi, float(hi[2] - lo[2])


def distance_to_top_centre(X):
    """Each node's distance to the centre of the bounding box's top face."""
    lo, hi, _ = extent(X)
    top = np.array([(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, hi[2]])
    return np.linalg.norm(X - top, axis=1)


def top_centre_node(X):
    """The node nearest to the centre of the top face (the lowest index on a tie)."""
    return int(np.argmin(distance_to_top_centre(X)))


def nodes_at_or_below(X, z):
    """Indices of the nodes with a z coordinate ≤ z, in order."""
    return [int(i) for i in np.flatnonzero(X[:, 2] <= z)]
