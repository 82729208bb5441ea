"""Command line of the pipeline:
  run EXPERIMENT|papers|all [--stage NAME] [--force] [-j N] [--executor local|dask-local | --scheduler ADDRESS]
      [--timings FILE]
  list
  report
  diff [--against REF] [--restore]
  clean [--results | --stale]
  bench [--filter REGEX]
Exit codes: 0 ok, 1 a run failed (diff: real changes found), 2 a malformed experiment or command line."""
import argparse
import shutil
import sys
import time

from pipeline import experiment as experiment_mod
from pipeline import report_md
from pipeline.errors import ExperimentError
from pipeline.paths import CACHE, RESULTS

# `pipeline run papers` (make reproduce-quick): the experiments whose tables and figures stand
# beside the three papers' (and the meshes they use); without our own studies around them (the
# liver under DHD-FEA, CalculiX validation, the RPIM stiffness study) and the haptic scene,
# cutting, contact, stability and benchmark experiments, which take most of the hour.
PAPERS = ["meshes", "dhd_table1", "dhd_table2", "dhd_partition", "dhd_pareto", "dhd_fig9",
          "rpim_datasets", "rpim_fit", "rpim_liver", "async_table", "async_inputs", "async_adaptive",
          "async_solvers"]


def _experiment_names(which: str) -> list:
    if which == "all":
        return experiment_mod.list_experiments()
    if which == "papers":
        known = set(experiment_mod.list_experiments())
        return [n for n in PAPERS if n in known]
    return [which]


def _progress_echo(bar):
    """Plain lines on stdout, one per finished run (a log that reads well in CI and on a
    terminal); with a progress bar on the terminal, written above it instead of through it."""
    if bar.disable:
        return lambda line: print(line, flush=True)

    def echo(line):
        bar.write(line, file=sys.stdout)
        sys.stdout.flush()
    return echo


def progress_bar(total: int, stream=None):
    """The overall count of runs done out of `total`, with an ETA, on `stream` (stderr) when it
    is a terminal; disabled, it writes nothing (CI logs and pipes keep only the plain lines)."""
    from tqdm import tqdm
    stream = stream if stream is not None else sys.stderr
    return tqdm(total=total, desc="pipeline", unit="run", file=stream, disable=not stream.isatty(),
                dynamic_ncols=True)


def _code_of(selected) -> dict:
    """(kind, target) -> code hash of every tool and python stage the selection runs (what a
    Dask worker must see the same); one that cannot be hashed fails later, at its run."""
    from pipeline.errors import RunFailed
    from pipeline.runner import code_hash
    code = {}
    for exp, run_ids in selected:
        for rid in run_ids:
            run = exp.runs[rid]
            if run.kind != "report" and (run.kind, run.target) not in code:
                try:
                    code[(run.kind, run.target)] = code_hash(run.kind, run.target)
                except RunFailed:
                    pass
    return code


def _announce_sweeps(exp, run_ids) -> None:
    """Says how many runs the selected sweeps make before any starts (the limit is
    experiment.max_sweep_runs)."""
    chosen = set(run_ids)
    swept = [(stage, sum(1 for r in ids if r in chosen)) for stage, ids in exp.stage_runs.items()
             if exp.runs[ids[0]].index is not None]
    swept = [(stage, n) for stage, n in swept if n]
    if swept:
        print(f"pipeline: {exp.name}: {len(run_ids)} runs; sweeps: "
              + ", ".join(f"{stage} {n}" for stage, n in swept), flush=True)


def cmd_run(args) -> int:
    from pipeline import cache, procs
    from pipeline.executors import make_executor
    from pipeline.runner import Runner, write_manifest

    names = _experiment_names(args.experiment)
    if args.stage and args.experiment in ("all", "papers"):
        raise ExperimentError(f"command line: --stage needs one experiment, not {args.experiment}")
    experiments = [experiment_mod.load(n) for n in names]
    selected = [(exp, experiment_mod.refresh(exp, args.stage) if args.stage else list(exp.runs))
                for exp in experiments]
    # A rerun stage that other experiments include by {"ref": ...}: their reports on it are
    # refreshed too, once it has run (a second pass, so none of them reads it half-way).
    followers = [(other, experiment_mod.refresh(other, stage))
                 for other, stage in experiment_mod.sharing(experiments[0], args.stage)] if args.stage else []
    for exp, run_ids in selected:
        _announce_sweeps(exp, run_ids)
    # A stopped pipeline stops what it started (its tools, a local cluster's workers).
    procs.stop_with_children(on_stop=cache.clean_stale)
    started = time.time()
    executor = make_executor(args.executor, args.scheduler, args.jobs)
    try:
        if executor.name != "local":
            print(f"pipeline: {executor.describe()}", flush=True)
        executor.check_workers(_code_of(selected + followers))
        _report_stale(executor.clean_stale())
        ready = time.time()
        ok = True
        with progress_bar(sum(len(run_ids) for _, run_ids in selected + followers)) as bar:
            echo = _progress_echo(bar)
            executor.echo = echo  # what the cluster did (a lost worker) goes where the runs' lines go
            runner = Runner(force=args.force, force_stages=[(args.experiment, args.stage)] if args.stage else [],
                            echo=echo, progress=bar, executor=executor)
            ok = runner.run_all(selected)
            if followers:
                ok = runner.run_all(followers) and ok
        _report_stale(executor.clean_stale())
        ran = time.time()
    finally:
        executor.close()
    if args.timings:
        from pipeline.artifacts import write_json_atomic
        write_json_atomic(args.timings, {
            "executor": executor.name, "slots": executor.slots, "startup_s": round(ready - started, 3),
            "runs_s": round(ran - ready, 3), "total_s": round(time.time() - started, 3),
            "runs": runner.timings()})
    complete = args.experiment == "all" and not args.stage
    write_manifest(runner, experiments + [other for other, _ in followers], complete=complete,
                   command=_command_line(args))
    report_md.assemble()
    counts = {}
    for o in runner.outcomes.values():
        counts[o.status] = counts.get(o.status, 0) + 1
    print("pipeline: " + ", ".join(f"{n} {s}" for s, n in sorted(counts.items())), flush=True)
    from pipeline.results_diff import one_line
    changes = one_line()
    if changes:
        print(f"pipeline: {changes}", flush=True)
    return 0 if ok else 1


def _command_line(args) -> str:
    """How REPORT.md names the run that last wrote results (without executor options)."""
    return "pipeline run " + args.experiment + (f" --stage {args.stage}" if args.stage else "") + \
        (" --force" if args.force else "")


def _report_stale(counted) -> None:
    from pipeline.cache import describe
    if counted[0]:
        print(f"pipeline: removed {describe(*counted)}", flush=True)


def cmd_list(_args) -> int:
    for name in experiment_mod.list_experiments():
        try:
            exp = experiment_mod.load(name)
            stages = ", ".join((f"{s}({len(r)})" if len(r) > 1 else s)
                               + (f" = {exp.origins[s]}" if s in exp.origins else "")
                               for s, r in exp.stage_runs.items())
            print(f"{name:28s} {exp.doc.get('description', '')}\n{'':28s} stages: {stages}")
        except ExperimentError as e:
            print(f"{name:28s} INVALID: {e}")
    return 0


def cmd_clean(args) -> int:
    from pipeline import cache
    stale = cache.stale_entries()
    if stale:
        print(f"pipeline: the cache holds {cache.describe(len(stale), sum(n for _, n in stale))}:")
        for path, nbytes in stale:
            print(f"  {path} ({nbytes / 1e6:.1f} MB)")
    if args.stale:
        count, size = cache.clean_stale()
        print(f"pipeline: removed {cache.describe(count, size)}; kept the rest of the cache")
        return 0
    shutil.rmtree(CACHE, ignore_errors=True)
    print("pipeline: removed the run cache")
    if args.results:
        for p in RESULTS.glob("*"):
            if p.is_dir():
                shutil.rmtree(p)
            else:
                p.unlink()
        print("pipeline: removed results/")
    return 0


def cmd_report(_args) -> int:
    """REPORT.md assembled again from the summaries in results/ (nothing runs)."""
    report_md.assemble()
    print(f"pipeline: wrote {RESULTS / 'REPORT.md'}")
    return 0


def cmd_diff(args) -> int:
    from pipeline import results_diff
    found = results_diff.classify(args.against)
    print(results_diff.report(found, args.against))
    if args.restore:
        restored = results_diff.restore(found, args.against)
        print(f"pipeline: restored {len(restored)} file{'s' if len(restored) != 1 else ''} whose only changes "
              f"were timings, round-off or bookkeeping; git status now shows the real changes")
    return 1 if found["real"] else 0


def cmd_bench(args) -> int:
    from pipeline.bench import run_benchmarks
    status = run_benchmarks(args.filter)
    report_md.assemble()
    return status


def main(argv) -> int:
    parser = argparse.ArgumentParser(prog="pipeline", description="Run the papers' experiments.")
    sub = parser.add_subparsers(dest="command", required=True)
    p_run = sub.add_parser("run", help="run an experiment (or all)")
    p_run.add_argument("experiment", help="an experiment name (experiments/NAME.json), papers (the experiments "
                                          "behind the papers' tables) or all")
    p_run.add_argument("--stage", help="rerun this stage (its dependencies come from the cache, or run first) and "
                                       "refresh what depends on it: the reports built on it, here and in the "
                                       "experiments that include it by ref")
    p_run.add_argument("--force", action="store_true", help="rerun every selected run")
    p_run.add_argument("-j", "--jobs", type=int, default=None,
                       help="parallel runs (default 1); with --executor dask-local the number of worker "
                            "processes (default: the CPU count); with --scheduler at most this many runs "
                            "at a time (default: the cluster's worker threads)")
    p_run.add_argument("--executor", choices=["local", "dask-local", "dask"], default="local",
                       help="where runs execute: this process's pool (default), a local Dask cluster of -j "
                            "worker processes, or the Dask cluster of --scheduler")
    p_run.add_argument("--scheduler", metavar="ADDRESS",
                       help="a running Dask scheduler, tcp://HOST:PORT or its scheduler file: runs execute on "
                            "its workers, which must share this repository, build and cache")
    p_run.add_argument("--timings", metavar="FILE",
                       help="write every run's wall time and, where it executed, its own time (JSON)")
    p_run.set_defaults(func=cmd_run)
    p_list = sub.add_parser("list", help="list the experiments and their stages")
    p_list.set_defaults(func=cmd_list)
    p_report = sub.add_parser("report", help="assemble results/REPORT.md again from results/ (runs nothing)")
    p_report.set_defaults(func=cmd_report)
    p_diff = sub.add_parser("diff", help="compare results/ with the committed results: real changes apart "
                                         "from timing noise (exit 1 when there are real changes)")
    p_diff.add_argument("--against", default="HEAD", metavar="REF", help="the git revision to compare with")
    p_diff.add_argument("--restore", action="store_true",
                        help="check out again the files whose only changes are timings")
    p_diff.set_defaults(func=cmd_diff)
    p_clean = sub.add_parser("clean", help="remove the run cache")
    p_clean.add_argument("--results", action="store_true", help="also remove results/")
    p_clean.add_argument("--stale", action="store_true",
                         help="remove only the temporary files of dead writers, keep the cache")
    p_clean.set_defaults(func=cmd_clean)
    p_bench = sub.add_parser("bench", help="run the Google Benchmark executables")
    p_bench.add_argument("--filter", default="", help="benchmark name regex")
    p_bench.set_defaults(func=cmd_bench)
    args = parser.parse_args(argv)
    try:
        return args.func(args)
    except ExperimentError as e:
        print(f"pipeline: error: {e}", file=sys.stderr)
        return 2
    except OSError as e:  # a full disk while writing reports or the manifest: one line, not a traceback
        print(f"pipeline: error: {e.filename or ''}{': ' if e.filename else ''}{e.strerror or e}", file=sys.stderr)
        return 1
