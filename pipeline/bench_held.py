"""`python3 -m pipeline.bench_held`: what leaving the held (fixed) nodes out of the explicit node
update saves, measured in one run of bench_dhd's BM_HeldNodes (the same solver with the skipping
off and on, repetitions interleaved at random so that a slow spell of a shared machine touches
both alike) -> results/bench/held_nodes.{json,md}. `pipeline bench` puts the same lines into
results/bench/summary.md from its own bench_dhd run."""
import json
import statistics
import subprocess
import sys

from pipeline.bench import cpu_description
from pipeline.paths import BIN, RESULTS, ROOT
from pipeline.tables import fmt, markdown_table
from pipeline.artifacts import write_text_atomic

PARTITIONS = {"2": "all linear (assembled rows)", "0": "all TLED (paper form)"}


def held_nodes_lines(path):
    """Markdown lines: steps/s with held nodes updated (skip 0) and skipped (skip 1), per partition,
    from the mean (or the only) run of each; [] when the benchmark is not in the file."""
    if not path.exists():
        return []
    runs, node_phase = {}, {}
    for b in json.loads(path.read_text()).get("benchmarks", []):
        if not b["name"].startswith("BM_HeldNodes/") or b.get("run_type") == "aggregate":
            continue
        runs.setdefault(b["run_name"], []).append(b["cpu_time"])
        if "ns_per_node" in b:
            node_phase.setdefault(b["run_name"], []).append(b["ns_per_node"])
    rows = []
    for code, label in PARTITIONS.items():
        name = f"BM_HeldNodes/partition:{code}/skip:%d/real_time"
        full, skip = runs.get(name % 0), runs.get(name % 1)
        if not (full and skip):
            continue
        nodes = [statistics.median(node_phase[name % k]) if node_phase.get(name % k) else None for k in (0, 1)]
        # One thread's CPU time: on a shared, overloaded machine the wall time mostly measures the
        # waits for a core. Other load still only ever adds (cache contention): the fastest
        # repetition is the least disturbed one; the medians are kept beside it.
        a, b = min(full), min(skip)
        rows.append([label, len(full), a, b, a / b, statistics.median(full) / statistics.median(skip), *nodes])
    if not rows:
        return []
    verdicts = []
    for label, _, _, _, best, median, n0, n1 in rows:
        step = (f"the step is {fmt(100 * (min(best, median) - 1), 2)}–{fmt(100 * (max(best, median) - 1), 2)} % faster"
                if min(best, median) > 1 else "the step-time difference is within the spread of this run")
        node = f"; the node phase {fmt(n0)} → {fmt(n1)} ns per node" if n0 and n1 else ""
        verdicts.append(f"- {label}: {step}{node}.")
    return ["Held nodes (the fixed bottom layer of the bench scene, 324 of 3564 nodes) left out of the explicit "
            "node update, `bench_dhd` BM_HeldNodes, one thread, 200 steps per iteration; CPU time, fastest of "
            "the repetitions of one run, interleaved:\n",
            markdown_table(["partition", "repetitions", "held nodes updated (ms CPU)", "held nodes skipped (ms CPU)",
                            "speed-up (×)", "speed-up of the medians (×)",
                            "node phase, held nodes updated (ns per node, median)",
                            "node phase, held nodes skipped (ns per node, median)"], rows)] + verdicts + [""]


def main(argv=None):
    out_dir = RESULTS / "bench"
    out_dir.mkdir(parents=True, exist_ok=True)
    out = out_dir / "held_nodes.json"
    exe = BIN / "bench_dhd"
    if not exe.exists():
        print(f"bench_held: no {exe.name} in build/bin", file=sys.stderr)
        return 2
    cmd = [str(exe), "--benchmark_filter=BM_HeldNodes", "--benchmark_repetitions=15",
           "--benchmark_enable_random_interleaving=true", "--benchmark_min_time=0.3",
           f"--benchmark_out={out}", "--benchmark_out_format=json"]
    if subprocess.run(cmd, cwd=ROOT).returncode != 0 or not out.exists():
        return 1
    data = json.loads(out.read_text())
    data.setdefault("context", {})["executable"] = exe.name
    write_text_atomic(out, json.dumps(data, indent=2) + "\n")
    text = ["# Held nodes out of the explicit node update\n",
            f"Machine: {cpu_description()}, shared with other work (the ratio is of one run, interleaved).\n"]
    text += held_nodes_lines(out)
    text.append("Results are unchanged bit for bit (`HeldNodes.*` in `tests/cpp/test_dynamics.cpp`); only the "
                "gather and the central-difference update of the held nodes are saved, not their elements.\n")
    write_text_atomic(out_dir / "held_nodes.md", "\n".join(text))
    print("\n".join(text))
    return 0


if __name__ == "__main__":
    sys.exit(main())
