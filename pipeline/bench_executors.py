"""The local pool against a local Dask cluster on the same experiments, each from an empty cache:
wall time, start-up, and the scheduling overhead per run (the client's wall time of a run minus
the run's own time where it executed). From these, an estimate of a large sweep on N workers.

    /usr/bin/python3 -m pipeline.bench_executors [-j 2] [--repeat 1] EXPERIMENT...

writes results/bench/executors.csv and executors.md."""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

from pipeline import experiment as experiment_mod
from pipeline.paths import RESULTS, ROOT
from pipeline.artifacts import write_text_atomic

EXECUTORS = {"local pool": ["--executor", "local"], "dask-local": ["--executor", "dask-local"]}
WORKERS = (2, 8, 16, 32)


def measure(name: str, flags, jobs: int) -> dict:
    with tempfile.TemporaryDirectory() as tmp:
        env = dict(os.environ, PIPELINE_CACHE=f"{tmp}/cache", PIPELINE_RESULTS=f"{tmp}/results")
        timings = Path(tmp) / "timings.json"
        proc = subprocess.run([sys.executable, "-m", "pipeline", "run", name, "-j", str(jobs), *flags,
                               "--timings", str(timings)], cwd=ROOT, env=env, capture_output=True, text=True)
        if proc.returncode != 0:
            raise SystemExit(f"bench_executors: {name} {' '.join(flags)} failed:\n{proc.stdout[-2000:]}{proc.stderr[-2000:]}")
        return json.loads(timings.read_text())


def summarise(doc: dict) -> dict:
    runs = [r for r in doc["runs"] if r["status"] == "ran" and r["exec_s"] is not None]
    overhead = [r["wall_s"] - r["exec_s"] for r in runs]
    return {"total_s": doc["total_s"], "startup_s": doc["startup_s"], "runs_s": doc["runs_s"],
            "runs": len(runs), "exec_mean_s": statistics.mean(r["exec_s"] for r in runs),
            "exec_sum_s": sum(r["exec_s"] for r in runs),
            "overhead_mean_ms": 1000 * statistics.mean(overhead),
            "overhead_median_ms": 1000 * statistics.median(overhead)}


def largest_sweep(exclusive: bool = False):
    """(experiment, stage, runs) of the largest swept stage; exclusive=False: of those that may
    run in parallel (an `exclusive` timing sweep runs one run at a time on any executor)."""
    best = ("", "", 0)
    for name in experiment_mod.list_experiments():
        exp = experiment_mod.load(name)
        for stage, ids in exp.stage_runs.items():
            run = exp.runs[ids[0]]
            if len(ids) > best[2] and run.kind != "report" and run.exclusive == exclusive:
                best = (name, stage, len(ids))
    return best


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="pipeline.bench_executors")
    parser.add_argument("experiments", nargs="+")
    parser.add_argument("-j", "--jobs", type=int, default=2)
    parser.add_argument("--repeat", type=int, default=1)
    parser.add_argument("--report-only", action="store_true",
                        help="rewrite executors.md from executors.csv without measuring")
    args = parser.parse_args(argv)
    out = RESULTS / "bench"
    if args.report_only:
        import csv
        with open(out / "executors.csv") as f:
            rows = [{k: (v if k in ("experiment", "executor", "load") else float(v)) for k, v in r.items()}
                    for r in csv.DictReader(f)]
        write_text_atomic(out / "executors.md", report(rows, args.jobs))
        return 0
    rows = []
    for name in args.experiments:
        for rep in range(args.repeat):
            for label, flags in EXECUTORS.items():
                load = os.getloadavg()[0]
                s = summarise(measure(name, flags, args.jobs))
                load = f"{load:.1f}-{os.getloadavg()[0]:.1f}"
                rows.append({"experiment": name, "executor": label, "repeat": rep + 1, "load": load, **s})
                print(f"{name} {label} #{rep + 1}: {s['total_s']:.1f} s, overhead {s['overhead_mean_ms']:.0f} ms/run",
                      flush=True)
    out.mkdir(parents=True, exist_ok=True)
    keys = ["experiment", "executor", "repeat", "load", "runs", "total_s", "startup_s", "runs_s", "exec_sum_s",
            "exec_mean_s", "overhead_mean_ms", "overhead_median_ms"]
    write_text_atomic(out / "executors.csv", "".join(
        ",".join(f"{r[k]:.3f}" if isinstance(r[k], float) else str(r[k]) for k in keys) + "\n"
        for r in [dict(zip(keys, keys))] + rows))
    # (load: the machine's 1-minute load average before and after the measurement)
    write_text_atomic(out / "executors.md", report(rows, args.jobs))
    return 0


def report(rows, jobs: int) -> str:
    lines = [f"# The pipeline's executors: local pool vs. a local Dask cluster ({jobs} workers)", "",
             "Measured by `/usr/bin/python3 -m pipeline.bench_executors " + " ".join(sorted({r['experiment'] for r in rows}))
             + f"`: each experiment from an empty cache, `-j {jobs}`, through the local pool and through "
             f"`--executor dask-local -j {jobs}` ({jobs} worker processes of one thread). Overhead of a run = "
             "its wall time as the client saw it minus its own time where it executed (the worker's "
             "`run_spec`: tool start to artifact published). Start-up = from the command's start to the "
             "first run (the Dask cluster's start and the workers' check).", "",
             "| experiment | executor | load avg | runs | wall s | start-up s | runs s | Σ run time s | mean run s | overhead/run ms (mean, median) |",
             "| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for r in rows:
        lines.append(f"| {r['experiment']} | {r['executor']} | {r.get('load', '')} | {r['runs']:.0f} | {r['total_s']:.1f} | {r['startup_s']:.1f} | "
                     f"{r['runs_s']:.1f} | {r['exec_sum_s']:.1f} | {r['exec_mean_s']:.2f} | "
                     f"{r['overhead_mean_ms']:.0f}, {r['overhead_median_ms']:.0f} |")
    dask = [r for r in rows if r["executor"] == "dask-local"]
    local = [r for r in rows if r["executor"] == "local pool"]
    exp, stage, count = largest_sweep()
    x_exp, x_stage, x_count = largest_sweep(exclusive=True)
    measured = ", ".join(sorted({r["experiment"] for r in rows}))
    t_run = statistics.mean(r["exec_mean_s"] for r in rows)
    o_dask = statistics.mean(r["overhead_mean_ms"] for r in dask) / 1000
    o_local = statistics.mean(r["overhead_mean_ms"] for r in local) / 1000
    startup = statistics.mean(r["startup_s"] for r in dask)
    lines += ["", "The machine is shared (the load average column: 2 cores, other work beside ours), so the "
              "wall times carry that noise: compare the overhead per run, which is measured run by run, "
              "more than the totals.", "",
              "## Estimate for a cluster (an estimate, not a measurement)", "",
              f"The largest sweep that may run in parallel is `{exp}`/`{stage}`: {count} independent runs "
              f"(the larger `{x_exp}`/`{x_stage}`, {x_count} runs, is an `exclusive` timing sweep: one run at "
              "a time on any executor, so a cluster does not shorten it). Taking the mean run time measured "
              f"on {measured} (both executors) as its run time, t = {t_run:.2f} s, and the Dask overhead o = {1000 * o_dask:.0f} ms per run (local pool: "
              f"{1000 * o_local:.0f} ms), N workers of one core take about ⌈{count}/N⌉·(t + o) + start-up "
              f"({startup:.1f} s here; on a cluster the workers are already running, so it is the check alone). "
              "This assumes the cluster's cores run a run as fast as this machine's, runs of equal length "
              "and a shared filesystem that keeps up; reports and key hashing stay on the client and are "
              "not in it.", "",
              "| workers N | estimated sweep time s (runs only) | speed-up over the 2-core local pool |", "| ---: | ---: | ---: |"]
    base = math.ceil(count / 2) * (t_run + o_local)
    for n in sorted(set(WORKERS) | {count}):
        est = math.ceil(count / n) * (t_run + o_dask)
        lines.append(f"| {n} | {est:.1f} | {base / est:.1f} × |")
    lines += ["", f"Beyond N = {count} workers this sweep gains nothing: each run is one process on one core. "
              "The overhead matters when runs are short: at a run time t it costs o/(t + o) of the throughput "
              f"({100 * o_dask / (t_run + o_dask):.0f} % here).", ""]
    return "\n".join(lines)


if __name__ == "__main__":
    sys.exit(main())
