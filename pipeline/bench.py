"""`pipeline bench`: runs every Google Benchmark executable and tabulates the figures."""
import json
import subprocess

from pipeline.paths import BIN, RESULTS, ROOT
from pipeline.tables import fmt, markdown_table


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
        proc = subprocess.run(cmd, cwd=ROOT)
        if proc.returncode != 0 or not out.exists():
            status = 1
            continue
        data = json.loads(out.read_text())
        # The build folder's absolute path is this machine's business: keep it relative.
        data.setdefault("context", {})["executable"] = exe.name
        out.write_text(json.dumps(data, indent=2) + "\n")
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
        sections.append(f"## {exe.name}\n\n" + markdown_table(
            ["benchmark", "iterations", "real time", "cpu time", "unit", "counters"], rows))
    ctx = data.get("context", {}) if benches else {}
    sections.append(f"Machine: {ctx.get('num_cpus', '?')} CPUs at {ctx.get('mhz_per_cpu', '?')} MHz, "
                    f"library build type {ctx.get('library_build_type', '?')}.\n")
    (out_dir / "README.md").write_text("\n".join(sections))
    summary = ["## Benchmarks\n", "Raw Google Benchmark tables: [bench/README.md](bench/README.md).\n"]
    summary += kernel_ratios(out_dir / "bench_dhd.json")
    (out_dir / "summary.md").write_text("\n".join(summary))
    return status


def kernel_ratios(path):
    """Element-kernel cost per element relative to the TLED kernel, from one bench_dhd run (000's
    paper mesh, one thread): the issue's "linear ≤ 0.3× TLED" and the memory floor that bounds it."""
    if not path.exists():
        return []
    times = {b["name"]: b["real_time"] for b in json.loads(path.read_text()).get("benchmarks", [])
             if b.get("run_type") != "aggregate"}
    tled = times.get("BM_Kernel/partition:0")
    if not tled:
        return []
    names = [("BM_Kernel/partition:2", "linear"), ("BM_MemoryFloorKernel", "memory floor (same loads and stores, no mechanics)"),
             ("BM_Kernel/partition:1", "TLED, decoupled form"), ("BM_Kernel/partition:4", "ANP (decoupled form, with its pre-pass)"),
             ("BM_Kernel/partition:3", "corotational")]
    rows = [[label, fmt(times[name] / tled)] for name, label in names if name in times]
    return ["Element kernels on the paper mesh, cost per element relative to the TLED kernel (paper form), "
            "measured in one run of `bench_dhd`:\n", markdown_table(["kernel", "× TLED"], rows)]
