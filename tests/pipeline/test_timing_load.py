"""Timings that know when the machine was busy: the load record of a timing stage, the retake of
a disturbed measurement, and the reports' verdicts that carry the flag."""
import pytest

from pipeline.reports import dhd_common as common
from pipeline.reports.dhd_table1 import cheaper_or_dearer
from pipeline.stages import machine_load


@pytest.fixture
def machine(monkeypatch):
    """A machine whose load, steal counters and calibration time the test sets."""
    state = {"load": 0.1, "steal": 0, "total": 0, "calibration": [0.01]}

    def cpu_times(path="/proc/stat"):
        state["total"] += 1000
        return state["steal"], state["total"]

    def calibration():
        return state["calibration"].pop(0) if len(state["calibration"]) > 1 else state["calibration"][0]

    monkeypatch.setattr(machine_load, "load_average", lambda path="/proc/loadavg": state["load"])
    monkeypatch.setattr(machine_load, "cpu_times", cpu_times)
    monkeypatch.setattr(machine_load, "calibration_seconds", calibration)
    return state


def test_a_quiet_measurement_is_taken_once_and_not_flagged(machine):
    calls = []
    result, rec = machine_load.measure(lambda: calls.append(1) or 42, log=lambda m: None, cores=4)
    assert result == 42 and len(calls) == 1
    assert rec["flagged"] is False and rec["retaken"] is False and rec["disturbed"] == []
    assert machine_load.busy_note(rec) == ""


def test_a_busy_measurement_is_retaken_once_then_flagged_with_its_load(machine):
    machine["load"] = 3.2
    calls = []
    _, rec = machine_load.measure(lambda: calls.append(1), log=lambda m: None, cores=2)
    assert len(calls) == 2
    assert rec["flagged"] and rec["retaken"] and rec["disturbed"] == ["load"]
    note = machine_load.busy_note(rec)
    assert note.startswith("(timed on a busy machine: load 3.2 on 2 cores") and "so was the retake" in note


def test_load_below_cores_minus_one_is_not_disturbed_but_above_is(machine):
    machine["load"] = 2.9
    assert not machine_load.measure(lambda: None, log=lambda m: None, cores=4)[1]["flagged"]
    machine["load"] = 3.1
    assert machine_load.measure(lambda: None, log=lambda m: None, cores=4)[1]["flagged"]


def test_a_calibration_that_changes_during_the_measurement_disturbs_it(machine):
    # before 10 ms, after 13 ms (+30 %); the retake measures 10 ms both times.
    machine["calibration"] = [0.010, 0.013, 0.010, 0.010]
    calls = []
    _, rec = machine_load.measure(lambda: calls.append(1), log=lambda m: None, cores=8)
    assert len(calls) == 2 and rec["retaken"] and not rec["flagged"]


def test_steal_above_the_threshold_disturbs_the_measurement(machine, monkeypatch):
    def stolen(path="/proc/stat"):
        machine["total"] += 1000
        machine["steal"] += 100   # 10 % of the CPU time stolen
        return machine["steal"], machine["total"]
    monkeypatch.setattr(machine_load, "cpu_times", stolen)
    _, rec = machine_load.measure(lambda: None, log=lambda m: None, cores=8)
    assert rec["flagged"] and rec["disturbed"] == ["steal"] and machine_load.busy_note(rec) == "(timed on a disturbed machine: CPU steal 10 %; so was the retake)"


def test_a_timing_without_a_record_says_so():
    assert "not recorded" in machine_load.busy_note(None)


def test_the_real_proc_files_are_read():
    assert machine_load.load_average() is None or machine_load.load_average() >= 0
    times = machine_load.cpu_times()
    assert times is None or times[1] >= times[0] >= 0


T1 = {"c_ours": 1.13, "c_paper": 0.07, "ns_tled": 5.0, "ns_linear": 5.6, "node_ns": 11.0,
      "steps_per_second_tled": 5000.0, "speedup_50_paper": 40 / 22}


def test_the_summary_claims_a_faster_step_only_where_the_numbers_show_it():
    text = common.verdict({"table1": dict(T1, speedup_50_ours=0.94)})
    assert "make the explicit step faster" not in text
    assert "do not make our explicit step faster" in text and "slower than all-TLED (0.94 times its speed)" in text
    text = common.verdict({"table1": dict(T1, speedup_50_ours=1.0)})
    assert "make the explicit step faster" not in text and "as fast as all-TLED (1 times its speed)" in text
    text = common.verdict({"table1": dict(T1, speedup_50_ours=1.5)})
    assert "linear elements make the explicit step faster" in text


def test_every_speed_clause_of_the_summary_carries_the_busy_note():
    note = "(timed on a busy machine: load 3.2 on 2 cores)"
    text = common.verdict({"table1": dict(T1, speedup_50_ours=0.94, busy_note=note)})
    clauses = [c for line in text.splitlines() for c in line.split("; ")
               if any(w in c for w in ("faster", "as fast", "slower", "steps/s", "costs"))]
    assert clauses and all("(timed on a busy machine" in c for c in clauses)
    assert note in text   # the conditions in full at least once


def test_cost_ratios_are_worded_from_the_number():
    assert cheaper_or_dearer(1.13) == "linear elements 1.13× dearer"
    assert cheaper_or_dearer(0.5) == "linear elements 2× cheaper"
    assert cheaper_or_dearer(1.0) == "no measurable difference"


def test_the_benchmark_target_verdict_carries_the_busy_note(tmp_path):
    import json
    from pipeline.bench import kernel_ratios
    busy = {"cores": 2, "load_before": 3.2, "load_after": 3.2, "steal_percent": 0.0, "calibration_change": 0.0,
            "disturbed": ["load"], "flagged": True, "retaken": True}
    path = tmp_path / "bench_dhd.json"
    path.write_text(json.dumps({"machine": busy, "benchmarks": [
        {"name": "BM_NodalForces/partition:0", "run_type": "iteration", "real_time": 100.0},
        {"name": "BM_NodalForces/partition:2", "run_type": "iteration", "real_time": 113.0}]}))
    line = [l for l in kernel_ratios(path) if "Target of the engine" in l][0]
    assert "1.1× — not met" in line and "(timed on a busy machine: load 3.2 on 2 cores; so was the retake)" in line


def test_the_timing_stage_records_the_machine_beside_its_samples(pipeline_env):
    """dhd_timing through the real dhd_sim on a small cuboid: the artifact keeps the load record
    of the sitting and the load average after every sample."""
    import json
    from pathlib import Path
    from conftest import run_pipeline, tool
    tool("dhd_sim")
    sim = {"mesh": "@mesh", "material": {"model": "neo_hookean_paper", "E": 5000, "nu": 0.35, "density": 1000},
           "boundary": {"fixed": ["bottom"]}, "solver": {"kind": "explicit", "steps": 20, "safety_factor": 0.5}}
    doc = {"description": "timing with its load", "results": "t",
           "stages": {"mesh": {"tool": "mesher", "config": {"source": {"kind": "cuboid", "cells": [3, 3, 2],
                                                                      "size": [0.03, 0.03, 0.02]}}},
                      "timing": {"python": "pipeline.stages.dhd_timing",
                                 "config": {"sim": sim, "partitions": [{"kind": "uniform"},
                                                                       {"kind": "uniform", "element": "linear"}],
                                            "threads": [1], "repeats": 2}}}}
    (Path(pipeline_env["PIPELINE_EXPERIMENTS"]) / "tl.json").write_text(json.dumps(doc))
    proc = run_pipeline(pipeline_env, "run", "tl")
    assert proc.returncode == 0, proc.stdout + proc.stderr
    [path] = (Path(pipeline_env["PIPELINE_CACHE"]) / "artifacts" / "dhd_timing").glob("*.json")
    payload = json.loads(path.read_text())["payload"]
    machine = payload["machine"]
    assert machine["cores"] >= 1 and machine["calibration_before_s"] > 0 and machine["calibration_after_s"] > 0
    assert isinstance(machine["flagged"], bool) and isinstance(machine["retaken"], bool)
    assert machine["flagged"] == bool(machine["disturbed"])
    assert all(len(run["load_per_sample"]) == 2 for run in payload["runs"])
