"""Reports that stay true for any config: a small variant of an experiment is run through the
pipeline with one scene parameter changed at a time, the report regenerated, and no statement of
the report may keep the old value; a sentence comparing two stages that no longer share the scene
says how they differ. A mutation check, not a grep for today's literals."""
import copy
import json
from pathlib import Path

import pytest

from conftest import ROOT, run_pipeline, tool

# A pipeline run per variant: about a minute in all on a shared machine.
pytestmark = pytest.mark.slow


def small_async_table():
    """experiments/async_table.json on a 12-node bar over 2 s, two primary sizes, two rates."""
    exp = json.loads((ROOT / "experiments" / "async_table.json").read_text())
    stages = exp["stages"]
    for name, stage in stages.items():
        cfg = stage.get("config")
        if not cfg:
            continue
        cfg["model"]["nodes"] = 12
        cfg["haptics"]["duration"] = 2
        cfg["timing_repeats"] = 1
        stage.pop("exclusive", None)
        sweep = stage.get("sweep", {})
        if "model.youngs_modulus" in sweep:
            sweep["model.youngs_modulus"] = [5000]
        if "async.primary.nodes" in sweep:
            sweep["async.primary.nodes"] = [3, 5]
        if "async.secondary.0.every" in sweep:
            sweep["async.secondary.0.every"] = [5, 20] if name == "sweep" else [20]
    return exp


def set_in(stages, path, value, only=None):
    for name, stage in stages.items():
        if stage.get("config") and (only is None or name == only):
            node = stage["config"]
            for key in path[:-1]:
                node = node[key]
            node[path[-1]] = value


def report_text(results: Path) -> str:
    return "\n".join(p.read_text() for p in sorted(results.rglob("*.md")))


def run_variant(pipeline_env, tmp_path, exp, name):
    env = dict(pipeline_env, PIPELINE_RESULTS=str(tmp_path / name))
    (Path(env["PIPELINE_EXPERIMENTS"]) / "async_table.json").write_text(json.dumps(exp))
    proc = run_pipeline(env, "run", "async_table", "-j", "1")
    assert proc.returncode == 0, proc.stderr[-2000:]
    return report_text(tmp_path / name)


# (config path, base value, changed value, phrase with the base value, phrase with the new one)
ASYNC_SCENE = [
    (("haptics", "probe_stiffness"), 10, 25, "probe spring 10 N/m", "probe spring 25 N/m"),
    (("input", "amplitude"), 0.001, 0.002, "chirp 1 mm", "chirp 2 mm"),
    (("input", "end_frequency"), 5, 3, "to 5 Hz", "to 3 Hz"),
    (("haptics", "duration"), 2, 3, "over 2 s", "over 3 s"),
    (("model", "nodes"), 12, 16, "bar of 12 nodes", "bar of 16 nodes"),
    (("haptics", "rate"), 1000, 500, "at 1 kHz", "at 0.5 kHz"),
]


def test_async_table_states_every_scene_value_from_its_runs(pipeline_env, tmp_path):
    tool("async_sim")
    base = small_async_table()
    text = run_variant(pipeline_env, tmp_path, base, "base")
    for _, _, _, old, _ in ASYNC_SCENE:
        assert old in text, f"the base report does not state {old!r}"
    assert "not the same scene" not in text
    for path, _, new_value, old, new in ASYNC_SCENE:
        exp = copy.deepcopy(base)
        set_in(exp["stages"], path, new_value)
        text = run_variant(pipeline_env, tmp_path, exp, "_".join(path))
        assert old not in text, f"{path}: a statement keeps {old!r}"
        assert new in text, f"{path}: no statement gives {new!r}"


def test_a_sentence_comparing_two_stages_says_when_their_scenes_differ(pipeline_env, tmp_path):
    tool("async_sim")
    exp = small_async_table()
    set_in(exp["stages"], ("haptics", "probe_stiffness"), 25, only="in_turn")
    text = run_variant(pipeline_env, tmp_path, exp, "in_turn_spring")
    assert "not the same scene (probe spring 25 N/m in the in-turn runs, probe spring 10 N/m in the sweep)" in text


# --------------------------------------------------------------------------- 000 Tables 2–3
def small_dhd_table2():
    """experiments/dhd_table2.json on a 4 × 4 × 3 cuboid, shares 0, 0.5 and 1, 300 steps."""
    exp = json.loads((ROOT / "experiments" / "dhd_table2.json").read_text())
    st = exp["stages"]
    st["mesh"]["config"]["source"].update(cells=[4, 4, 3], size=[0.04, 0.04, 0.03])
    loads = [[0, 0, -0.002], [0, 0, -0.003]]
    for name in ("sim_layer", "static", "sim_transient"):
        cfg = st[name]["config"]
        cfg["partition"]["operating_point"] = [0.02, 0.02, 0.03]
        cfg["boundary"]["prescribed"][0]["nearest"] = [0.02, 0.02, 0.03]
        if cfg["solver"]["kind"] == "explicit":
            cfg["solver"]["steps"] = 300
        else:
            cfg["solver"]["increments"] = 3
        sweep = st[name]["sweep"]
        sweep["boundary.prescribed.0.displacement"] = loads
        sweep["partition.linear_fraction"] = [0.0, 0.5] if name == "sim_transient" else \
            ([0.0, 1.0] if name == "static" else [0.0, 0.5, 1.0])
        if "damping.alpha" in sweep:
            sweep["damping.alpha"] = [0]
    exp["paper"]["table2"]["applied_displacement"] = 0.2
    exp["paper"]["table3"]["applied_displacement"] = 0.3
    return exp


def run_dhd_variant(pipeline_env, tmp_path, exp, name):
    env = dict(pipeline_env, PIPELINE_RESULTS=str(tmp_path / name))
    (Path(env["PIPELINE_EXPERIMENTS"]) / "dhd_table2.json").write_text(json.dumps(exp))
    proc = run_pipeline(env, "run", "dhd_table2", "-j", "1")
    assert proc.returncode == 0, proc.stderr[-2000:]
    return report_text(tmp_path / name)


def set_partition(exp, key, value):
    for name in ("sim_layer", "static", "sim_transient"):
        exp["stages"][name]["config"]["partition"][key] = value


def test_dhd_table2_names_the_split_its_runs_asked_for(pipeline_env, tmp_path):
    tool("dhd_sim")
    base = small_dhd_table2()
    text = run_dhd_variant(pipeline_env, tmp_path, base, "base")
    assert "layer split (the lowest elements linear, 000 Fig. 10)" in text
    assert "share of linear elements r" in text and "300 steps" in text
    assert " 0.2 cm" in text and "α = 0" in text and "distance split" not in text

    exp = copy.deepcopy(base)
    set_partition(exp, "distance", "euclidean")
    text = run_dhd_variant(pipeline_env, tmp_path, exp, "euclidean")
    assert "layer split" not in text
    assert "distance split (the elements farthest from the operating point (euclidean distance) linear)" in text

    exp = copy.deepcopy(base)
    set_partition(exp, "linear_element", "corotational")
    text = run_dhd_variant(pipeline_env, tmp_path, exp, "corotational")
    assert "lowest elements linear" not in text and "share of linear elements" not in text
    assert "lowest elements corotational" in text and "share of corotational elements r" in text
    assert "All-corotational (r = 100 %)" in text

    exp = copy.deepcopy(base)
    for name in ("sim_layer", "sim_transient"):
        exp["stages"][name]["config"]["solver"]["steps"] = 400
    text = run_dhd_variant(pipeline_env, tmp_path, exp, "steps")
    assert "300 steps" not in text and "400 steps" in text

    exp = copy.deepcopy(base)
    for name in ("sim_layer", "static", "sim_transient"):
        exp["stages"][name]["sweep"]["boundary.prescribed.0.displacement"] = [[0, 0, -0.0025], [0, 0, -0.003]]
    text = run_dhd_variant(pipeline_env, tmp_path, exp, "load")
    assert " 0.2 cm" not in text and "0.25 cm" in text

    exp = copy.deepcopy(base)
    exp["stages"]["sim_transient"]["sweep"]["damping.alpha"] = [2]
    text = run_dhd_variant(pipeline_env, tmp_path, exp, "alpha")
    assert "α = 0" not in text and "α = 2" in text
