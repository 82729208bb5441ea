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
    (out_dir / "summary.md").write_text("\n".join(summary))
    return status
