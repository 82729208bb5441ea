"""A failed run never takes an earlier run's files with it: a dhd_sim series whose run blows up
(exit 3) after writing snapshots of the same names as an earlier, finished series leaves the
earlier .pvd and every earlier snapshot byte for byte, and nothing of its own."""
from conftest import run_tool, write_json

CUBOID = {"source": {"kind": "cuboid", "cells": [2, 2, 2], "size": [0.02, 0.02, 0.02]}}


def series_config(tmp_path, mesh, dt, steps):
    return write_json(tmp_path / "run.json", {
        "mesh": str(mesh), "material": {"model": "neo_hookean_paper", "E": 5000, "nu": 0.35, "density": 1000},
        "boundary": {"fixed": ["bottom"], "prescribed": [{"set": "top", "displacement": [0, 0, -0.001]}]},
        "solver": {"kind": "explicit", "steps": steps, "dt": dt, "force_dt": True},
        "output": {"vtu": str(tmp_path / "sim.vtu"), "vtu_interval": 1}})


def files(folder):
    return {p.name: p.read_bytes() for p in folder.iterdir()}


def test_a_failed_series_keeps_the_earlier_series_of_the_same_name(tmp_path):
    mesh = tmp_path / "mesh.json"
    assert run_tool("mesher", "--config", write_json(tmp_path / "m.json", CUBOID), "--out", mesh).returncode == 0
    done = run_tool("dhd_sim", "--config", series_config(tmp_path, mesh, 1e-5, 5), "--out", tmp_path / "first.json")
    assert done.returncode == 0, done.stderr
    earlier = files(tmp_path)
    assert any(n.endswith(".pvd") for n in earlier) and sum(n.endswith(".vtu") for n in earlier) >= 2
    # Above the stability limit: the run writes snapshots over the earlier ones, then blows up.
    cfg = series_config(tmp_path, mesh, 0.05, 20000)
    failed = run_tool("dhd_sim", "--config", cfg, "--out", tmp_path / "second.json")
    assert failed.returncode == 3, failed.stderr
    now = files(tmp_path)
    del now["run.json"], earlier["run.json"]
    assert now == earlier
