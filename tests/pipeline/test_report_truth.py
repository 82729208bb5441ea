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
