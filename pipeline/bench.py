"""`pipeline bench`: runs every Google Benchmark executable and tabulates the figures."""
import json
import subprocess

from pipeline.paths import BIN, RESULTS, ROOT
from pipeline.tables import fmt, markdown_table
from pipeline.artifacts import write_text_atomic
from pipeline.stages.machine_load import busy_note, measure


def run_benchmarks(filter_regex: str = "") -> int:
    out_dir = RESULTS / "bench"
    out_dir.mkdir(parents=True, exist_ok=True)
    benches = sorted(BIN.glob("bench_*"))
    if not benches:
        print("bench: no benchmark executables in build/bin (is libbenchmark-dev installed?)")
        return 2
    sections = ["# Benchmarks\n",
                "Google Benchmark figures measured on this machine in one run per executable; "
                "compare rows of the same table as ratios (the machine is shared and noisy).\n"]
    status = 0
    for exe in benches:
        out = out_dir / f"{exe.name}.json"
        cmd = [str(exe), f"--benchmark_out={out}", "--benchmark_out_format=json"]
        if filter_regex:
            cmd.append(f"--benchmark_filter={filter_regex}")
        print("bench:", exe.name, flush=True)
        # The load, CPU steal and a calibration kernel around the run; a disturbed run is taken
        # once more, then flagged (pipeline.stages.machine_load).
        proc, machine = measure(lambda: subprocess.run(cmd, cwd=ROOT), log=lambda m: print("bench:", m, flush=True))
        if proc.returncode != 0 or not out.exists():
            status = 1
            continue
        data = json.loads(out.read_text())
        # The build folder's absolute path is this machine's business: keep it relative.
        data.setdefault("context", {})["executable"] = exe.name
        data["machine"] = machine
        write_text_atomic(out, json.dumps(data, indent=2) + "\n")
        rows = []
        for b in data.get("benchmarks", []):
            if b.get("run_type") == "aggregate" and b.get("aggregate_name") != "mean":
                continue
            counters = {k: v for k, v in b.items() if k not in {
                "name", "family_index", "per_family_instance_index", "run_name", "run_type",
                "repetitions", "repetition_index", "threads", "iterations", "real_time", "cpu_time",
                "time_unit", "aggregate_name", "aggregate_unit", "label"} and isinstance(v, (int, float))}
            rows.append([b["name"], b.get("iterations"), b.get("real_time"), b.get("cpu_time"),
                         b.get("time_unit"), ", ".join(f"{k}={fmt(v)}" for k, v in counters.items())])
        note = busy_note(machine)
        sections.append(f"## {exe.name}\n\n" + (f"All figures of this table were {note[1:-1]}.\n\n" if note else "")
                        + markdown_table(
            ["benchmark", "iterations", "real time", "cpu time", "unit", "counters"], rows))
    ctx = data.get("context", {}) if benches else {}
    machine = (f"{cpu_description()}, {ctx.get('num_cpus', '?')} CPUs at {ctx.get('mhz_per_cpu', '?')} MHz, "
               f"library build type {ctx.get('library_build_type', '?')}")
    sections.append(f"Machine: {machine}.\n")
    write_text_atomic(out_dir / "README.md", "\n".join(sections))
    summary = ["## Benchmarks\n", "Raw Google Benchmark tables: [bench/README.md](bench/README.md). "
               f"Machine: {machine}.\n"]
    summary += kernel_ratios(out_dir / "bench_dhd.json")
    from pipeline.bench_held import held_nodes_lines  # (it imports this module)
    summary += held_nodes_lines(out_dir / "bench_dhd.json")
    write_text_atomic(out_dir / "summary.md", "\n".join(summary))
    return status


def cpu_description(cpuinfo="/proc/cpuinfo"):
    """The CPU model and the widest vector extension it offers, which the default build
    (-march=native on the same machine) compiles the kernels for: the cost ratios below depend on
    both (AVX-512 halves the element kernels' instructions)."""
    try:
        text = open(cpuinfo).read()
    except OSError:
        return "CPU unknown"
    fields = {}  # of the first processor listed
    for line in text.splitlines():
        key, colon, value = line.partition(":")
        if colon:
            fields.setdefault(key.strip(), value.strip())
    model = fields.get("model name", "CPU unknown")
    flags = set(fields.get("flags", "").split())
    vector = "AVX-512" if {"avx512f", "avx512vl"} <= flags else "AVX2" if {"avx2", "fma"} <= flags else "no AVX2"
    return f"{model} ({vector})"


def kernel_ratios(path):
    """Cost per element of each kind relative to TLED, from one bench_dhd run (000's paper mesh,
    one thread): the issue's "linear ≤ 0.3× TLED", first for the complete nodal forces, then for
    the element phase alone with the memory floor of the per-element data path."""
    if not path.exists():
        return []
    doc = json.loads(path.read_text())
    times = {b["name"]: b["real_time"] for b in doc.get("benchmarks", []) if b.get("run_type") != "aggregate"}
    note = busy_note(doc.get("machine"))
    sections = []
    kinds = [("2", "linear, assembled rows (the engine's default)"), ("5", "linear, element by element"),
             ("1", "TLED, decoupled form"), ("4", "ANP (decoupled form, with its pre-pass)"), ("3", "corotational")]
    for family, title, extra in [
            ("BM_NodalForces", "Internal nodal forces from the displacements (element phase and the nodal sums of "
             "000 eq. 23)",
             [("BM_LinearRows/repeats:1/kernel:0", "the assembled rows' product alone (without the nodal sums)"),
              ("BM_LinearRowsSingleValues", "the same product with single-precision stored values (the "
               "option solver.linear_precision \"single\")"),
              ("BM_LinearRowsInLanes", "the same product vectorised eight rows at a time with gathered "
               "displacements (a measured alternative, not used by the engine)"),
              ("BM_LinearRowsMemoryFloor", "memory floor of the assembled rows (reading their stored values once, "
               "no arithmetic)")]),
            ("BM_Kernel", "Element phase alone (for assembled linear elements: the rows of every node)",
             [("BM_MemoryFloorKernel", "memory floor of the per-element path (same loads and stores, no mechanics)")])]:
        tled = times.get(f"{family}/partition:0")
        if not tled:
            continue
        names = [(f"{family}/partition:{code}", label) for code, label in kinds] + extra
        rows = [[label, fmt(times[name] / tled)] for name, label in names if name in times]
        sections += [f"{title} on the paper mesh, cost per element relative to TLED (paper form), "
                     "measured in one run of `bench_dhd`:\n", markdown_table(["kind", "× TLED"], rows)]
    sections += target_line(times, note)
    return sections


def target_line(times, note=""):
    """The issue's "linear ≤ 0.3× TLED" judged on the complete nodal forces of one run, with the
    memory floor of the assembled rows (no product of the stored matrix can beat it)."""
    tled, linear = times.get("BM_NodalForces/partition:0"), times.get("BM_NodalForces/partition:2")
    if not (tled and linear):
        return []
    ratio = linear / tled
    line = (f"Target of the engine (ours, not a paper's number): a linear element costs ≤ 0.3× a TLED element. "
            f"Measured for the nodal forces: {fmt(ratio, 2)}× — {'met' if ratio <= 0.3 else 'not met'}")
    floor = times.get("BM_LinearRowsMemoryFloor")
    if floor:
        line += f"; reading the assembled rows once, with no arithmetic, already costs {fmt(floor / tled, 2)}×"
    return [line + " (why: `cpp/apps/dhd_sim.md`, speed section)" + (f" {note}" if note else "") + ".\n"]
