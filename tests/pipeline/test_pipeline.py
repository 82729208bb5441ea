"""The pipeline: sweep expansion, references, the content-addressed cache (a second run skips
everything, a changed config reruns only what depends on it), --stage, and bad experiments."""
import json

import pytest

from conftest import ROOT, run_pipeline

from pipeline import experiment as experiment_mod


def write_experiment(env, name, doc):
    from pathlib import Path
    path = Path(env["PIPELINE_EXPERIMENTS"]) / f"{name}.json"
    path.write_text(json.dumps(doc))
    return path


TWO_MESHES = {
    "description": "two cuboids and a table",
    "results": "mesh",
    "stages": {
        "cube": {"tool": "mesher", "config": {"source": {"kind": "cuboid", "cells": [1, 1, 1], "size": [0.01, 0.01, 0.01]}},
                 "sweep": {"source.cells": [[1, 1, 1], [2, 1, 1]]}},
        "table": {"report": "pipeline.reports.meshes", "inputs": ["cube"], "params": {"order": ["cube"]}},
    },
}


def test_second_run_skips_everything_and_changed_config_reruns(pipeline_env):
    write_experiment(pipeline_env, "t", TWO_MESHES)
    first = run_pipeline(pipeline_env, "run", "t")
    assert first.returncode == 0, first.stdout + first.stderr
    assert "pipeline: 3 ran" in first.stdout
    second = run_pipeline(pipeline_env, "run", "t")
    assert "pipeline: 3 cached" in second.stdout, second.stdout
    doc = json.loads(json.dumps(TWO_MESHES))
    doc["stages"]["cube"]["sweep"]["source.cells"][1] = [3, 1, 1]
    write_experiment(pipeline_env, "t", doc)
    third = run_pipeline(pipeline_env, "run", "t")
    # cube#0 unchanged, cube#1 new, so the table reruns too.
    assert "cached cube#0" in third.stdout and "ran cube#1" in third.stdout and "ran table" in third.stdout


def test_stage_option_reruns_one_stage(pipeline_env):
    write_experiment(pipeline_env, "t", TWO_MESHES)
    run_pipeline(pipeline_env, "run", "t")
    r = run_pipeline(pipeline_env, "run", "t", "--stage", "table")
    assert "cached cube#0" in r.stdout and "ran table" in r.stdout


def test_results_and_manifest_written(pipeline_env):
    from pathlib import Path
    write_experiment(pipeline_env, "t", TWO_MESHES)
    run_pipeline(pipeline_env, "run", "t")
    results = Path(pipeline_env["PIPELINE_RESULTS"])
    assert (results / "mesh" / "meshes.md").exists()
    assert (results / "mesh" / "meshes.csv").exists()
    manifest = json.loads((results / "manifest.json").read_text())
    runs = manifest["experiments"]["t"]
    assert {r["run"] for r in runs} == {"cube#0", "cube#1", "table"}
    assert all(len(r["key"]) == 64 for r in runs)
    assert "REPORT.md" in {p.name for p in results.iterdir()}


def test_failed_run_is_reported_and_dependents_skipped(pipeline_env):
    doc = {"stages": {
        "bad": {"tool": "mesher", "config": {"source": {"kind": "cuboid", "cells": [1, 1, 1], "size": [1, -1, 1]}}},
        "table": {"report": "pipeline.reports.meshes", "inputs": ["bad"]}}}
    write_experiment(pipeline_env, "t", doc)
    r = run_pipeline(pipeline_env, "run", "t")
    assert r.returncode == 1
    assert "FAILED bad: exit 2" in r.stdout and "/source/size" in r.stdout
    assert "skipped table" in r.stdout


@pytest.mark.parametrize("doc,expected", [
    ({"stages": {}}, "/stages: expected a non-empty object"),
    ({"stages": {"a": {"tool": "mesher", "colour": 1}}}, "/stages/a/colour: unknown field"),
    ({"stages": {"a": {"tool": "mesher", "config": {"m": "@nope"}}}}, "reference @nope names no stage"),
    ({"stages": {"a": {"tool": "mesher", "config": {"m": "@b"}}, "b": {"tool": "mesher", "config": {"m": "@a"}}}}, "expected no cycle"),
    ({"stages": {"a": {"tool": "mesher", "sweep": {"x": []}}}}, "/stages/a/sweep/x: expected a non-empty list"),
    ({"stages": {"a": {"tool": "mesher", "python": "x"}}}, "expected exactly one of"),
    ({"stagse": {}}, "/stagse: unknown field"),
])
def test_bad_experiment_exit_2(pipeline_env, doc, expected):
    write_experiment(pipeline_env, "bad", doc)
    r = run_pipeline(pipeline_env, "run", "bad")
    assert r.returncode == 2
    assert expected in r.stderr, r.stderr


def test_sweep_cartesian_product_and_references(monkeypatch, tmp_path):
    monkeypatch.setattr(experiment_mod, "EXPERIMENTS", tmp_path)
    (tmp_path / "s.json").write_text(json.dumps({"stages": {
        "m": {"tool": "mesher", "config": {"a": {"b": 0}, "c": 0}, "sweep": {"a.b": [1, 2], "c": ["x", "y", "z"]}},
        "u": {"tool": "mesher", "config": {"mesh": "@m#4", "all": ["@m#0", "@m#1"]}},
        "r": {"report": "pipeline.reports.meshes", "inputs": ["u"]}}}))
    exp = experiment_mod.load("s")
    assert exp.stage_runs["m"] == [f"m#{k}" for k in range(6)]
    assert exp.runs["m#4"].config == {"a": {"b": 2}, "c": "y"}
    assert exp.runs["m#4"].sweep == {"a.b": 2, "c": "y"}
    assert sorted(exp.runs["u"].deps) == ["m#0", "m#1", "m#4"]
    assert experiment_mod.closure(exp, "u") == ["m#0", "m#1", "m#4", "u"]
    assert exp.runs["r"].deps == ["u"]


def test_every_shipped_experiment_loads():
    for name in experiment_mod.list_experiments():
        exp = experiment_mod.load(name)
        assert exp.runs, name


def test_content_hash_ignores_provenance_but_not_payload(tmp_path):
    """Downstream keys use the artifact's schema and payload: a new commit in the provenance
    must not rerun the pipeline, a changed payload must."""
    from pipeline.hashing import content_hash
    doc = {"schema": {"name": "x", "version": 1}, "provenance": {"git_commit": "a" * 40}, "payload": {"u": [1.0]}}
    a, b, c = tmp_path / "a.json", tmp_path / "b.json", tmp_path / "c.json"
    a.write_text(json.dumps(doc))
    b.write_text(json.dumps(dict(doc, provenance={"git_commit": "b" * 40})))
    c.write_text(json.dumps(dict(doc, payload={"u": [2.0]})))
    assert content_hash(a) == content_hash(b)
    assert content_hash(a) != content_hash(c)


def bench_json(tmp_path, times):
    path = tmp_path / "bench_dhd.json"
    path.write_text(json.dumps({"benchmarks": [{"name": n, "run_type": "iteration", "real_time": t}
                                               for n, t in times.items()]}))
    return path


def test_kernel_ratios_are_relative_to_tled_and_judge_the_target(tmp_path):
    from pipeline.bench import kernel_ratios
    text = "\n".join(kernel_ratios(bench_json(tmp_path, {
        "BM_NodalForces/partition:0": 100.0, "BM_NodalForces/partition:2": 45.0,
        "BM_LinearRowsMemoryFloor": 29.0, "BM_LinearRows/repeats:1/kernel:0": 42.0,
        "BM_LinearRowsSingleValues": 33.0, "BM_LinearRowsInLanes": 47.0})))
    assert "| linear, assembled rows (the engine's default) | 0.45 |" in text
    assert "| the assembled rows' product alone (without the nodal sums) | 0.42 |" in text
    assert 'single-precision stored values (the option solver.linear_precision "single") | 0.33 |' in text
    assert "with gathered displacements (a measured alternative, not used by the engine) | 0.47 |" in text
    assert "| memory floor of the assembled rows (reading their stored values once, no arithmetic) | 0.29 |" in text
    assert "Measured for the nodal forces: 0.45× — not met; reading the assembled rows once" in text
    assert "already costs 0.29×" in text
    met = "\n".join(kernel_ratios(bench_json(tmp_path, {
        "BM_NodalForces/partition:0": 100.0, "BM_NodalForces/partition:2": 30.0})))
    assert "0.3× — met" in met and "already costs" not in met
    assert kernel_ratios(tmp_path / "missing.json") == []


def test_held_nodes_lines_give_the_median_speed_up_of_each_partition(tmp_path):
    from pipeline.bench_held import held_nodes_lines
    path = tmp_path / "bench_dhd.json"
    runs = []
    for skip, times in ((0, [50.0, 40.0, 44.0]), (1, [36.0, 40.0, 30.0])):
        name = f"BM_HeldNodes/partition:2/skip:{skip}/real_time"
        runs += [{"name": name, "run_name": name, "run_type": "iteration", "real_time": 9.0, "cpu_time": t,
                  "ns_per_node": 10.0 - 3 * skip} for t in times]
    runs.append({"name": "BM_HeldNodes/partition:2/skip:0/real_time_mean", "run_name": "BM_HeldNodes/partition:2/skip:0/real_time",
                 "run_type": "aggregate", "real_time": 1.0, "cpu_time": 1.0})
    path.write_text(json.dumps({"benchmarks": runs}))
    text = "\n".join(held_nodes_lines(path))
    assert "| all linear (assembled rows) | 3 | 40 | 30 | 1.333 | 1.222 | 10 | 7 |" in text   # fastest, medians; no aggregates
    assert "all TLED" not in text                                           # not measured, no row
    assert held_nodes_lines(tmp_path / "missing.json") == []


def test_cpu_description_names_the_model_and_the_widest_vector_extension(tmp_path):
    from pipeline.bench import cpu_description
    info = tmp_path / "cpuinfo"
    for flags, expected in [("fpu avx2 fma avx512f avx512vl", "AVX-512"), ("fpu avx avx2 fma", "AVX2"),
                            ("fpu sse4_2 avx", "no AVX2"), ("fpu avx512f avx2 fma", "AVX2")]:
        info.write_text(f"processor\t: 0\nmodel name\t: Some CPU\nflags\t\t: {flags}\n\nprocessor\t: 1\n")
        assert cpu_description(str(info)) == f"Some CPU ({expected})"
    assert cpu_description(str(tmp_path / "missing")) == "CPU unknown"


# --------------------------------------------------------------------------- stages shared by reference
def _ref_experiments(tmp_path):
    (tmp_path / "a.json").write_text(json.dumps({
        "shared": {"cells": [2, 1, 1]},
        "stages": {
            "cube": {"tool": "mesher", "config": {"source": {"kind": "cuboid", "cells": {"shared": "cells"},
                                                            "size": [0.01, 0.01, 0.01]}}},
            "other": {"tool": "mesher", "config": {"source": {"kind": "cuboid", "cells": [1, 1, 1],
                                                             "size": [0.01, 0.01, 0.01]}}},
            "table": {"report": "pipeline.reports.meshes", "inputs": ["cube"], "params": {"order": ["cube"]}}}}))
    (tmp_path / "b.json").write_text(json.dumps({
        "results": "mesh_b",
        "stages": {
            "cube": {"ref": "a.cube", "description": "a's cube"},
            "table": {"report": "pipeline.reports.meshes", "inputs": ["cube"], "params": {"order": ["cube"]}}}}))


def test_a_stage_ref_is_the_other_experiments_stage_verbatim(monkeypatch, tmp_path):
    monkeypatch.setattr(experiment_mod, "EXPERIMENTS", tmp_path)
    _ref_experiments(tmp_path)
    a, b = experiment_mod.load("a"), experiment_mod.load("b")
    # The shared fragment is expanded in a's stage, and b's run of it is the same run.
    assert a.runs["cube"].config["source"]["cells"] == [2, 1, 1]
    assert b.runs["cube"].config == a.runs["cube"].config
    assert b.origins == {"cube": "a.cube"} and experiment_mod.origin(a, "cube") == "a.cube"
    assert [(e.name, s) for e, s in experiment_mod.sharing(a, "cube")] == [("b", "cube")]
    assert experiment_mod.sharing(a, "other") == []
    # --stage refreshes the reports built on the stage, not the stages beside it.
    assert experiment_mod.refresh(a, "cube") == ["cube", "table"]
    assert experiment_mod.refresh(a, "other") == ["other"]


@pytest.mark.parametrize("stage, expected", [
    ({"ref": "nope.cube"}, "/stages/x/ref: expected an experiment of experiments/, got 'nope'"),
    ({"ref": "a.missing"}, "/stages/x/ref: expected a stage of a.json, got 'missing'"),
    ({"ref": "a.table"}, "/stages/x/ref: expected a tool or python stage, a.table is not one"),
    ({"ref": "a"}, "/stages/x/ref: expected \"experiment.stage\", got 'a'"),
    ({"ref": "a.cube", "config": {}}, "/stages/x/config: unknown field for a stage declared by \"ref\""),
    ({"ref": "c.x"}, "expected no cycle of stage refs"),
    ({"tool": "mesher", "config": {"cells": {"shared": "nope"}}}, "/stages/x/config/cells/shared: expected the name"),
])
def test_bad_stage_refs_are_refused(monkeypatch, tmp_path, stage, expected):
    from pipeline.errors import ExperimentError
    monkeypatch.setattr(experiment_mod, "EXPERIMENTS", tmp_path)
    _ref_experiments(tmp_path)
    (tmp_path / "c.json").write_text(json.dumps({"stages": {"x": stage}}))
    with pytest.raises(ExperimentError) as e:
        experiment_mod.load("c")
    assert expected in str(e.value)


def test_stage_rerun_refreshes_its_reports_here_and_where_it_is_shared(pipeline_env):
    """A stage whose artifact changed under the same key (as a rerun of a tool with changed
    behaviour does): `--stage` reruns it and the reports built on it, in this experiment and in
    the experiments that include it by ref; REPORT.md says which command wrote it."""
    from pathlib import Path
    env_dir = Path(pipeline_env["PIPELINE_EXPERIMENTS"])
    _ref_experiments(env_dir)
    assert run_pipeline(pipeline_env, "run", "a").returncode == 0
    assert run_pipeline(pipeline_env, "run", "b").returncode == 0
    manifest = json.loads((Path(pipeline_env["PIPELINE_RESULTS"]) / "manifest.json").read_text())
    artifact = next(e["artifact"] for e in manifest["experiments"]["a"] if e["run"] == "cube")
    path = Path(artifact) if Path(artifact).is_absolute() else ROOT / artifact
    doc = json.loads(path.read_text())
    doc["payload"]["nodes"][0][0] += 1e-3       # the tables were built on this, stale, artifact
    path.write_text(json.dumps(doc))
    from pipeline import cache
    cache.record_artifact_hash(path)            # as its own run would have written it
    for name in ("a", "b"):
        assert "ran table" in run_pipeline(pipeline_env, "run", name).stdout
    r = run_pipeline(pipeline_env, "run", "a", "--stage", "cube")
    assert r.returncode == 0, r.stdout + r.stderr
    assert "[a 1/2] ran cube" in r.stdout and "[a 2/2] ran table" in r.stdout
    assert "[b 2/2] ran table" in r.stdout and "[b 1/2] cached cube" in r.stdout
    assert "other" not in r.stdout   # a stage beside the rerun one is not selected
    report = (Path(pipeline_env["PIPELINE_RESULTS"]) / "REPORT.md").read_text()
    assert "Last updated by `pipeline run a --stage cube`" in report and "make reproduce" not in report
