"""Steps per second of dhd_sim for several partitions, measured in one sitting so that their
ratios are comparable (000 Table 1): every partition is run `repeats` times, the partitions
interleaved (round robin, the order rotated each round), so a slow spell of a shared machine
touches all of them alike. The figure is the best of the repeats (the highest steps/s: other
load on the machine only ever adds time, so the fastest repeat is the least disturbed one); the
median is kept beside it.

Pipeline stage (mark it "exclusive": true so nothing else runs meanwhile):
    {"python": "pipeline.stages.dhd_timing", "exclusive": true,
     "config": {"engine": "@check",           # any dhd_sim artifact: reruns the timing when the
                                              # engine's results (hence usually its build) change
                "sim": {... a dhd_sim config with "mesh": "@mesh" and solver.steps ...},
                "partitions": [{"kind": "uniform"}, {"linear_fraction": 0.5}, ...],
                "threads": [1], "repeats": 3}}

Each measurement is one `dhd_sim` process (from the pipeline's bin folder) whose artifact's
"timing" block gives the stepping loop's steps/s (setup and file I/O excluded), the kernel time
per element of each kind and the node-phase time per node. The artifact ("dhd_timing" v1) keeps
every sample, the best and the median per partition, the element counts by kind name, the
engine's element-kind legend (from its artifacts), the binary's sha256 and the CPU, and the
"machine" block of pipeline.stages.machine_load: the load, CPU steal and calibration kernel around
the sitting (a disturbed sitting is taken once more, then flagged), with the load average after
every sample.
"""
# Executables this stage runs: part of its cache key (pipeline/runner.py).
TOOLS = ("dhd_sim",)

import json
import os
import platform
import statistics
import subprocess
import tempfile
from pathlib import Path

from pipeline.artifacts import read_artifact, write_artifact
from pipeline.hashing import file_hash
from pipeline.paths import BIN, ROOT
from pipeline.element_kinds import kind_counts, kind_legend
from pipeline.stages.machine_load import load_average, measure

TOOL = "pipeline.stages.dhd_timing"
SCHEMA = "dhd_timing"
KEYS = {"engine", "sim", "partitions", "threads", "repeats"}


class TimingConfigError(ValueError):
    """A bad stage config: names the key and what was expected."""


def schedule(n_partitions: int, threads, repeats: int):
    """(round, threads, partition index) in run order: rounds outermost, partitions rotated by
    one each round so no partition always runs first (right after a process start-up)."""
    order = []
    for rnd in range(repeats):
        for th in threads:
            for k in range(n_partitions):
                order.append((rnd, th, (k + rnd) % n_partitions))
    return order


def cpu_model() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def _check(cfg):
    unknown = sorted(set(cfg) - KEYS)
    if unknown:
        raise TimingConfigError(f"/{unknown[0]}: unknown key (expected one of {sorted(KEYS)})")
    if not isinstance(cfg.get("sim"), dict) or "mesh" not in cfg["sim"]:
        raise TimingConfigError("/sim: expected a dhd_sim config with a \"mesh\"")
    parts = cfg.get("partitions")
    if not isinstance(parts, list) or not parts or not all(isinstance(p, dict) for p in parts):
        raise TimingConfigError("/partitions: expected a non-empty list of dhd_sim partition objects")
    threads = cfg.get("threads", [1])
    if not isinstance(threads, list) or not threads or not all(isinstance(t, int) and t >= 1 for t in threads):
        raise TimingConfigError("/threads: expected a list of positive integers")
    repeats = cfg.get("repeats", 3)
    if not isinstance(repeats, int) or repeats < 1:
        raise TimingConfigError("/repeats: expected a positive integer")
    return parts, threads, repeats



def _sitting(cfg, parts, threads, repeats, binary, log):
    """Every partition `repeats` times, interleaved: (samples, details, legend)."""
    samples = {(th, k): [] for th in threads for k in range(len(parts))}
    details = {}
    legend = None
    with tempfile.TemporaryDirectory(prefix="dhd_timing_") as tmp:
        cfg_path, out_path = Path(tmp) / "run.json", Path(tmp) / "out.json"
        for rnd, th, k in schedule(len(parts), threads, repeats):
            # Only the timing is read: the displacement field stays out of the artifact.
            sim = dict(cfg["sim"], partition=parts[k], threads=th,
                       output=dict(cfg["sim"].get("output", {}), displacement=False))
            cfg_path.write_text(json.dumps(sim))
            proc = subprocess.run([str(binary), "--config", str(cfg_path), "--out", str(out_path)],
                                  cwd=ROOT, capture_output=True, text=True)
            if proc.returncode != 0:
                lines = [l for l in proc.stderr.strip().splitlines() if l.strip()]
                raise RuntimeError(f"dhd_sim failed (exit {proc.returncode}) for partition {parts[k]}: "
                                   f"{lines[-1] if lines else 'no message'}")
            payload = read_artifact(out_path)["payload"]
            timing = payload["timing"]
            samples[(th, k)].append(timing["steps_per_second"])
            record = {"ns_per_element": timing.get("ns_per_element", {}),
                      "node_phase_ns_per_node": timing.get("node_phase_ns_per_node"),
                      "load": load_average()}
            if not details.get((th, k)):
                legend = kind_legend(payload)
                record["counts"] = kind_counts(payload)
                record["dt"] = payload["solver"]["dt"]
                record["steps"] = payload["solver"]["steps"]
            details.setdefault((th, k), []).append(record)
            log(f"round {rnd} threads {th} partition {k}: {timing['steps_per_second']:.1f} steps/s")
    return samples, details, legend


def run(ctx):
    cfg = ctx.config
    parts, threads, repeats = _check(cfg)
    binary = BIN / "dhd_sim"
    if not binary.exists():
        raise TimingConfigError(f"no executable {binary} (build dhd_sim first)")
    (samples, details, legend), machine = measure(lambda: _sitting(cfg, parts, threads, repeats, binary, ctx.log),
                                                  ctx.log)
    runs = []
    for th in threads:
        for k, part in enumerate(parts):
            first = details[(th, k)][0]
            per_kind = {}
            for d in details[(th, k)]:
                for name, ns in d["ns_per_element"].items():
                    per_kind.setdefault(name, []).append(ns)
            node_ns = [d["node_phase_ns_per_node"] for d in details[(th, k)]
                       if d["node_phase_ns_per_node"] is not None]
            s = samples[(th, k)]
            runs.append({
                "partition": part, "threads": th, "samples": s,
                "load_per_sample": [d.get("load") for d in details[(th, k)]],
                "steps_per_second": max(s), "median": statistics.median(s), "min": min(s), "max": max(s),
                "counts": first["counts"], "dt": first["dt"], "steps": first["steps"],
                "ns_per_element": {name: statistics.median(v) for name, v in per_kind.items()},
                "node_phase_ns_per_node": statistics.median(node_ns) if node_ns else None,
            })
    payload = {"runs": runs, "element_kind_legend": legend, "repeats": repeats, "order": "interleaved round robin",
               "binary_sha256": file_hash(binary), "cpu": cpu_model(), "cpu_count": os.cpu_count(),
               "machine": machine}
    mesh = Path(ROOT / cfg["sim"]["mesh"])
    inputs = [mesh] + ([Path(ROOT / cfg["engine"])] if "engine" in cfg else [])
    write_artifact(ctx.out_path, SCHEMA, 1, TOOL, cfg, payload, inputs=inputs)
