"""The --out file of every executable (app.cpp): --out must not name the config, an input or a
directory (success would overwrite the user's file); a failed run removes only what it wrote and
leaves an earlier run's artifact at --out as it was. Such an --out,
an --out or --config given twice, or a --config naming a directory, is bad input (exit 2, one
line) and leaves every file as it was."""
import json

from conftest import run_tool, write_json

CUBOID = {"source": {"kind": "cuboid", "cells": [1, 1, 1], "size": [0.01, 0.01, 0.01]}}
BROKEN = {"source": {"kind": "cuboid", "cells": [1, 1, 1]}}  # no size: fails after reading


def assert_refused(r, *fragments):
    lines = [l for l in r.stderr.splitlines() if l.strip()]
    assert r.returncode == 2, r.stderr
    assert len(lines) == 1, r.stderr
    for f in fragments:
        assert f in lines[0], lines[0]


def test_out_same_as_config_keeps_the_config(tmp_path):
    for config in (CUBOID, BROKEN):
        cfg = write_json(tmp_path / "c.json", config)
        r = run_tool("mesher", "--config", cfg, "--out", cfg)
        assert_refused(r, f"--out {cfg}: expected a file other than the --config file")
        assert json.loads(cfg.read_text()) == config


def test_out_through_a_link_to_the_config_keeps_the_config(tmp_path):
    cfg = write_json(tmp_path / "c.json", BROKEN)
    link = tmp_path / "link.json"
    link.symlink_to(cfg)
    assert_refused(run_tool("mesher", "--config", cfg, "--out", link), "expected a file other than the --config file")
    assert json.loads(cfg.read_text()) == BROKEN


def test_out_naming_a_directory_keeps_the_directory(tmp_path):
    folder = tmp_path / "empty"
    folder.mkdir()
    for config in (CUBOID, BROKEN):
        cfg = write_json(tmp_path / "c.json", config)
        assert_refused(run_tool("mesher", "--config", cfg, "--out", folder), f"--out {folder}: expected a file name, got a directory")
        assert folder.is_dir()


def test_out_naming_an_input_keeps_the_input(tmp_path):
    mesh = tmp_path / "mesh.json"
    assert run_tool("mesher", "--config", write_json(tmp_path / "m.json", CUBOID), "--out", mesh).returncode == 0
    before = mesh.read_bytes()
    cfg = write_json(tmp_path / "run.json", {"mesh": str(mesh), "solver": {"steps": 1}})
    assert_refused(run_tool("dhd_sim", "--config", cfg, "--out", mesh),
                   f"{cfg}: /mesh: expected a file other than the --out file {mesh}")
    assert mesh.read_bytes() == before


def test_a_failed_run_leaves_an_earlier_output_untouched(tmp_path):
    """The run did not create the file at --out, so failing must not remove or change it: the
    exit code says the run failed, the earlier artifact stays the earlier run's."""
    out = tmp_path / "out.json"
    out.write_text("an artifact of an earlier run")
    r = run_tool("mesher", "--config", write_json(tmp_path / "c.json", BROKEN), "--out", out)
    assert_refused(r, "/source/size: missing required field")
    assert out.read_text() == "an artifact of an earlier run"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["c.json", "out.json"]


def test_out_or_config_given_twice(tmp_path):
    cfg = write_json(tmp_path / "c.json", CUBOID)
    a, b = tmp_path / "a.json", tmp_path / "b.json"
    assert_refused(run_tool("mesher", "--config", cfg, "--out", a, "--out", b), "command line: --out given twice")
    assert_refused(run_tool("mesher", "--config", cfg, "--config", cfg, "--out", a), "command line: --config given twice")
    assert not a.exists() and not b.exists()


def test_config_naming_a_directory_says_so(tmp_path):
    folder = tmp_path / "configs"
    folder.mkdir()
    out = tmp_path / "out.json"
    assert_refused(run_tool("mesher", "--config", folder, "--out", out), f"{folder}: expected a JSON file, got a directory")
    assert not out.exists() and folder.is_dir()
