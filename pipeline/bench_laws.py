"""`python3 -m pipeline.bench_laws`: what each tissue law costs per element and step in the explicit
engine, against the decoupled neo-Hookean element, from one run of bench_laws (every law, TLED and
ANP, repetitions interleaved at random so that a slow spell of a shared machine touches all alike),
and one and two threads from one run of bench_dhd's BM_StepsSampled -> results/bench/laws.{json,md}.
The CPU and the load average (before and after) are written beside the figures."""
import json
import statistics
import subprocess
import sys

from pipeline.bench import cpu_description
from pipeline.paths import BIN, RESULTS, ROOT
from pipeline.tables import fmt, markdown_table
from pipeline.artifacts import write_text_atomic

LAWS = {0: "decoupled neo-Hookean", 1: "Mooney–Rivlin", 2: "transversely isotropic, one fibre",
        3: "transversely isotropic, a fibre per element", 4: "decoupled neo-Hookean + 2 Prony terms",
        5: "Ogden, 1 term (α = 6.5)", 6: "Ogden, 3 terms", 7: "stable neo-Hookean", 8: "neo-Hookean, paper form"}
KINDS = {0: "TLED", 1: "ANP"}
SMALL_STRAIN = {2: "linear (assembled rows)", 3: "corotational"}
PARTITIONS = {0: "all TLED (paper form)", 15: "r = 0.5 (linear farthest from the top centre, TLED elsewhere)"}


def load_avg():
    try:
        return open("/proc/loadavg").read().split()[:3]
    except OSError:
        return ["?", "?", "?"]


def fastest(path, prefix, key):
    """{run_name: fastest repetition's `key`} of the benchmarks whose name starts with `prefix`
    (the fastest: other load only ever adds), with the repetition count."""
    runs = {}
    for b in json.loads(path.read_text()).get("benchmarks", []):
        if b["name"].startswith(prefix) and b.get("run_type") != "aggregate":
            runs.setdefault(b["run_name"], []).append(b[key])
    return {name: (min(v) if key != "steps_per_s" else max(v), statistics.median(v), len(v))
            for name, v in runs.items()}


def law_lines(path):
    ns = fastest(path, "BM_", "ns_per_element")
    ref = ns.get("BM_LawKernel/law:0/kind:0")
    if not ref:
        return []
    rows = []
    for law, label in LAWS.items():
        row = [label]
        for kind in KINDS:
            got = ns.get(f"BM_LawKernel/law:{law}/kind:{kind}")
            base = ns.get(f"BM_LawKernel/law:0/kind:{kind}")  # the same kind's neo-Hookean element
            row += [fmt(got[0]), fmt(got[0] / base[0]), fmt(got[1] / base[1])] if got and base else ["–"] * 3
        rows.append(row)
    for kind, label in SMALL_STRAIN.items():
        got = ns.get(f"BM_SmallStrainKernel/kind:{kind}")
        if got:
            rows.append([label, fmt(got[0]), fmt(got[0] / ref[0]), fmt(got[1] / ref[1]), "–", "–", "–"])
    reps = ref[2]
    return ["Element phase per element and step (`bench_laws`, paper mesh, 14,450 tets, all of one kind, one "
            f"thread; CPU time, fastest of {reps} interleaved repetitions, and the ratio of the medians beside it). "
            "Ratios are to the decoupled neo-Hookean element of the same kind; ANP includes its nodal-pressure "
            "pre-pass. The small-strain kinds, which do not depend on the law, are set against the TLED one:\n",
            markdown_table(["law", "TLED (ns)", "TLED / NH", "TLED / NH (medians)", "ANP (ns)", "ANP / NH ANP",
                            "ANP / NH ANP (medians)"], rows), ""]


def thread_lines(path):
    sps = fastest(path, "BM_StepsSampled/", "steps_per_s")
    rows = []
    for code, label in PARTITIONS.items():
        one = sps.get(f"BM_StepsSampled/partition:{code}/threads:1/real_time")
        two = sps.get(f"BM_StepsSampled/partition:{code}/threads:2/real_time")
        if one and two:
            rows.append([label, fmt(one[1]), fmt(two[1]), fmt(two[1] / one[1]), fmt(one[0]), fmt(two[0])])
    if not rows:
        return []
    return ["Whole explicit steps, one and two threads (`bench_dhd` BM_StepsSampled: 200 steps per iteration in "
            "ten runs of the thread team, as dhd_sim's runs end at each energy sample; wall time, medians of the "
            "interleaved repetitions, fastest beside them):\n",
            markdown_table(["partition", "1 thread (steps/s, median)", "2 threads (steps/s, median)", "2 / 1",
                            "1 thread (best)", "2 threads (best)"], rows), ""]


def run(exe, args, out):
    cmd = [str(BIN / exe), *args, f"--benchmark_out={out}", "--benchmark_out_format=json"]
    if subprocess.run(cmd, cwd=ROOT).returncode != 0 or not out.exists():
        return False
    data = json.loads(out.read_text())
    data.setdefault("context", {})["executable"] = exe
    write_text_atomic(out, json.dumps(data, indent=2) + "\n")
    return True


def main(argv=None):
    out_dir = RESULTS / "bench"
    out_dir.mkdir(parents=True, exist_ok=True)
    for exe in ("bench_laws", "bench_dhd"):
        if not (BIN / exe).exists():
            print(f"bench_laws: no {exe} in build/bin", file=sys.stderr)
            return 2
    before = load_avg()
    laws, threads = out_dir / "laws.json", out_dir / "threads.json"
    common = ["--benchmark_repetitions=5", "--benchmark_enable_random_interleaving=true"]
    if not run("bench_laws", [*common, "--benchmark_min_time=0.2"], laws):
        return 1
    if not run("bench_dhd", [*common, "--benchmark_filter=BM_StepsSampled", "--benchmark_min_time=1"], threads):
        return 1
    after = load_avg()
    text = ["# Tissue laws and threads\n",
            f"Machine: {cpu_description()}; load average (1, 5, 15 min) {' '.join(before)} before and "
            f"{' '.join(after)} after the runs. Compare figures as ratios within a table: each table is one run.\n"]
    text += law_lines(laws)
    text += thread_lines(threads)
    write_text_atomic(out_dir / "laws.md", "\n".join(text))
    print("\n".join(text))
    return 0


if __name__ == "__main__":
    sys.exit(main())
