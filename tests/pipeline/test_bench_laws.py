"""pipeline.bench_laws' tables from Google Benchmark JSON: each law's cost is the fastest
repetition's over the decoupled neo-Hookean element's of the same kind, and the thread table divides the
two-thread steps/s by the one-thread steps/s."""
import json

from pipeline.bench_laws import law_lines, thread_lines


def bench(name, **counters):
    return {"name": name, "run_name": name, "run_type": "iteration", **counters}


def test_law_ratios_are_to_the_fastest_neo_hookean_repetition(tmp_path):
    path = tmp_path / "laws.json"
    path.write_text(json.dumps({"benchmarks": [
        bench("BM_LawKernel/law:0/kind:0", ns_per_element=10.0),
        bench("BM_LawKernel/law:0/kind:0", ns_per_element=12.0),
        bench("BM_LawKernel/law:5/kind:0", ns_per_element=17.0),
        bench("BM_LawKernel/law:5/kind:0", ns_per_element=30.0),
        bench("BM_LawKernel/law:5/kind:1", ns_per_element=25.0),
        bench("BM_LawKernel/law:0/kind:1", ns_per_element=20.0),
    ]}))
    table = "\n".join(law_lines(path))
    ogden = next(line for line in table.splitlines() if line.startswith("| Ogden, 1 term"))
    cells = [c.strip() for c in ogden.strip("|").split("|")]
    assert cells[1:4] == ["17", "1.7", "2.136"]  # fastest 17 / 10; medians 23.5 / 11
    assert cells[4:6] == ["25", "1.25"]  # ANP against the neo-Hookean ANP element


def test_thread_table_divides_two_threads_by_one(tmp_path):
    path = tmp_path / "threads.json"
    name = "BM_StepsSampled/partition:0/threads:%d/real_time"
    path.write_text(json.dumps({"benchmarks": [
        bench(name % 1, steps_per_s=1000.0), bench(name % 1, steps_per_s=1200.0),
        bench(name % 2, steps_per_s=1800.0), bench(name % 2, steps_per_s=2000.0)]}))
    row = next(line for line in "\n".join(thread_lines(path)).splitlines() if line.startswith("| all TLED"))
    cells = [c.strip() for c in row.strip("|").split("|")]
    assert cells[1:4] == ["1100", "1900", "1.727"]
    assert cells[4:6] == ["1200", "2000"]
