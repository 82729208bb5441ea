"""The cache's keys do not depend on where the cache is: a cache inside the repository and one
outside it (an absolute path elsewhere) give every run the same key, so a cache can be moved or
shared without rerunning anything."""
import json
import os
import shutil
from pathlib import Path

from conftest import ROOT, run_pipeline, tool

CHAIN = {
    "results": "mesh",
    "stages": {
        "cube": {"tool": "mesher", "config": {"source": {"kind": "cuboid", "cells": [2, 2, 2], "size": [0.02, 0.02, 0.02]}}},
        "press": {"tool": "dhd_sim", "config": {
            "mesh": "@cube",
            "material": {"model": "neo_hookean_paper", "E": 5000, "nu": 0.35, "density": 1000},
            "boundary": {"fixed": ["bottom"], "prescribed": [{"set": "top", "displacement": [0, 0, -0.001]}]},
            "solver": {"kind": "static"}}},
        # A stage whose payload names the artifact it read (a path into the cache), and one after it.
        "recorded": {"python": "tests.pipeline.stage_records_input", "config": {"input": "@cube"}},
        "after": {"python": "tests.pipeline.stage_records_input", "config": {"input": "@recorded"}},
        "table": {"report": "pipeline.reports.meshes", "inputs": ["cube"], "params": {"order": ["cube"]}},
    },
}


def keys(env) -> dict:
    manifest = json.loads((Path(env["PIPELINE_RESULTS"]) / "manifest.json").read_text())
    return {r["run"]: r["key"] for r in manifest["experiments"]["t"]}


def test_a_cache_outside_the_repository_gives_the_keys_of_one_inside(pipeline_env, tmp_path):
    tool("mesher"), tool("dhd_sim")
    (Path(pipeline_env["PIPELINE_EXPERIMENTS"]) / "t.json").write_text(json.dumps(CHAIN))
    outside = dict(pipeline_env, PIPELINE_CACHE=str(tmp_path / "cache"))
    inside_dir = ROOT / "build" / f"cache-location-test-{os.getpid()}"
    inside = dict(pipeline_env, PIPELINE_CACHE=str(inside_dir), PIPELINE_RESULTS=str(tmp_path / "results-inside"))
    try:
        for env in (outside, inside):
            r = run_pipeline(env, "run", "t")
            assert r.returncode == 0, r.stdout + r.stderr
        assert keys(outside) == keys(inside)
        assert set(keys(inside)) == {"cube", "press", "recorded", "after", "table"}
    finally:
        shutil.rmtree(inside_dir, ignore_errors=True)
