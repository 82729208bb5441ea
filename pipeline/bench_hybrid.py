"""`python3 -m pipeline.bench_hybrid`: the hybrid's speed-up against all TLED (000 Table 1) at linear
shares r = 0, 0.25, 0.5, 0.75, 1, with the linear rows' values in double and in single precision,
from one run of bench_dhd's BM_HybridSpeedUp (one thread, repetitions interleaved at random so that a
slow spell of a shared machine touches all alike), and what single precision changes on the held
press of the Table 1 scene (dhd_sim, r = 0.5 and 1) -> results/bench/hybrid.{json,md}. The CPU and
the load average (before and after) are written beside the figures."""
import json
import math
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

from pipeline.artifacts import write_text_atomic
from pipeline.bench import cpu_description
from pipeline.bench_laws import load_avg, run
from pipeline.paths import BIN, RESULTS, ROOT
from pipeline.tables import fmt, markdown_table

SHARES = {100: 0.0, 125: 0.25, 150: 0.5, 175: 0.75, 200: 1.0}
STEPS_PER_ITERATION = 200  # bench_dhd's kStepsPerIteration


def paper_speed_ups():
    """{r: frame rate / the all-TLED one} of 000 Table 1 (experiments/dhd_table1.json's paper block)."""
    table = json.loads((ROOT / "experiments" / "dhd_table1.json").read_text())["paper"]["table1"]
    rates = dict(zip(table["linear_fraction_percent"], table["frame_rate_hz"]))
    return {p / 100: rate / rates[0] for p, rate in rates.items()}, rates


def step_times(path):
    """{(code, single): ([CPU s per step], [wall s per step])} over the repetitions."""
    out = {}
    for b in json.loads(path.read_text()).get("benchmarks", []):
        if not b["name"].startswith("BM_HybridSpeedUp/") or b.get("run_type") == "aggregate":
            continue
        parts = dict(p.split(":") for p in b["run_name"].split("/")[1:] if ":" in p)
        scale = {"ms": 1e-3, "us": 1e-6, "ns": 1e-9, "s": 1.0}[b.get("time_unit", "ms")]
        key = (int(parts["partition"]), int(parts["single"]))
        cpu, wall = out.setdefault(key, ([], []))
        cpu.append(b["cpu_time"] * scale / STEPS_PER_ITERATION)
        wall.append(b["real_time"] * scale / STEPS_PER_ITERATION)
    return out


def press_config(mesh, share, precision):
    """The Table 1 scene (experiments/dhd_table1.json): the top-centre node pushed 6 mm down over
    0.3 s and held, damped; 2000 steps of half the critical step (about 2 s, settled)."""
    return {"mesh": str(mesh),
            "material": {"model": "neo_hookean_paper", "E": 5000, "nu": 0.35, "density": 1000},
            "damping": {"alpha": 50},
            "partition": {"kind": "linear_fraction", "linear_fraction": share, "distance": "depth",
                          "operating_point": [0.085, 0.085, 0.1]},
            "boundary": {"fixed": ["bottom"],
                         "prescribed": [{"nearest": [0.085, 0.085, 0.1], "displacement": [0, 0, -0.006],
                                         "ramp_time": 0.3, "ramp": "smooth"}]},
            "solver": {"kind": "explicit", "steps": 2000, "safety_factor": 0.5, "linear_precision": precision},
            "threads": 1}


def press_differences():
    """[(r, max |u|, max |u_single − u_double|, the same relative, held-node reaction change relative)]."""
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        (tmp / "mesh.json").write_text(json.dumps(
            {"source": {"kind": "cuboid", "cells": [17, 17, 10], "size": [0.17, 0.17, 0.1]}}))
        subprocess.run([str(BIN / "mesher"), "--config", str(tmp / "mesh.json"), "--out", str(tmp / "mesh_art.json")],
                       check=True, stdout=subprocess.DEVNULL)
        for share in (0.5, 1.0):
            result = {}
            for precision in ("double", "single"):
                cfg, out = tmp / f"{precision}.json", tmp / f"{precision}_out.json"
                cfg.write_text(json.dumps(press_config(tmp / "mesh_art.json", share, precision)))
                subprocess.run([str(BIN / "dhd_sim"), "--config", str(cfg), "--out", str(out)], check=True,
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                result[precision] = json.loads(out.read_text())["payload"]
            ud, us = result["double"]["displacement"], result["single"]["displacement"]
            umax = max(math.dist(u, [0, 0, 0]) for u in ud)
            dmax = max(math.dist(a, b) for a, b in zip(ud, us))
            rd = result["double"]["reactions"][-1]["force"]
            rs = result["single"]["reactions"][-1]["force"]
            rows.append((share, umax, dmax, dmax / umax, math.dist(rd, rs) / math.dist(rd, [0, 0, 0])))
    return rows


def speed_lines(times):
    paper, rates = paper_speed_ups()
    ref = times.get((100, 0))
    if not ref:
        return []
    ref_cpu, ref_wall = statistics.median(ref[0]), statistics.median(ref[1])
    rows = []
    for code, share in SHARES.items():
        row = [fmt(share), fmt(paper[share]) if share in paper else "–"]
        for single in (0, 1):
            got = times.get((code, single)) or (times.get((code, 0)) if code == 100 else None)
            if got:
                cpu, wall = statistics.median(got[0]), statistics.median(got[1])
                row += [fmt(1 / cpu), fmt(ref_cpu / cpu), fmt(min(ref[0]) / min(got[0])), fmt(ref_wall / wall)]
            else:
                row += ["–"] * 4
        rows.append(row)
    reps = len(ref[0])
    return ["Explicit steps on one thread (`bench_dhd` BM_HybridSpeedUp, paper mesh, 3564 nodes, 14,450 tets, "
            "200 steps per iteration, the Table 1 push; the linear elements farthest from the top centre): steps per "
            f"CPU second (median of {reps} interleaved repetitions) and the speed-up against all TLED (r = 0) from "
            "the medians of CPU time, from the fastest repetitions, and from the medians of wall time. 000 Table 1's "
            "speed-up is its frame rate over the all-TLED one (" +
            ", ".join(f"{p} %: {h} Hz" for p, h in rates.items()) + "); it gives no share above 50 %:\n",
            markdown_table(["r", "000 Table 1", "double: steps/s", "double: speed-up", "(fastest)", "(wall)",
                            "single: steps/s", "single: speed-up", "(fastest)", "(wall)"], rows), ""]


def press_lines(rows):
    return ["Single against double precision rows on the held press (dhd_sim, the Table 1 scene: the top-centre "
            "node pushed 6 mm over 0.3 s and held, α = 50/s, 2000 steps of half the critical step, settled; one "
            "thread): the largest nodal displacement difference, relative to the largest displacement, and the "
            "change of the held node's reaction force:\n",
            markdown_table(["r", "max ‖u‖ (m)", "max ‖u_single − u_double‖ (m)", "relative", "reaction, relative"],
                           [[fmt(r), fmt(u), fmt(d), fmt(rel), fmt(rr)] for r, u, d, rel, rr in rows]), ""]


def main(argv=None):
    out_dir = RESULTS / "bench"
    out_dir.mkdir(parents=True, exist_ok=True)
    for exe in ("bench_dhd", "dhd_sim", "mesher"):
        if not (BIN / exe).exists():
            print(f"bench_hybrid: no {exe} in build/bin", file=sys.stderr)
            return 2
    before = load_avg()
    raw = out_dir / "hybrid.json"
    if not run("bench_dhd", ["--benchmark_repetitions=5", "--benchmark_enable_random_interleaving=true",
                             "--benchmark_filter=BM_HybridSpeedUp", "--benchmark_min_time=0.5"], raw):
        return 1
    after = load_avg()
    text = ["# The hybrid's speed-up (000 Table 1) and single-precision linear rows\n",
            f"Machine: {cpu_description()}; load average (1, 5, 15 min) {' '.join(before)} before and "
            f"{' '.join(after)} after the benchmark run. Compare figures as ratios within the table: it is one run.\n"]
    text += speed_lines(step_times(raw))
    text += press_lines(press_differences())
    write_text_atomic(out_dir / "hybrid.md", "\n".join(text))
    print("\n".join(text))
    return 0


if __name__ == "__main__":
    sys.exit(main())
