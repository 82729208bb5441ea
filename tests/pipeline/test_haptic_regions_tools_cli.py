"""haptic_sim with linked regions and a rigid tool or a blade, end to end: the run completes and
reports how the regions followed the tool and reacted to the cuts; nonsense in the regions and
tool config ends in exit 2 with one line naming the member, and no artifact."""
import json

import pytest

from conftest import run_tool, write_json

SPHERE = {"shape": "sphere", "radius": 0.01, "position": [0, 0, 1]}


@pytest.fixture
def block(tmp_path):
    write_json(tmp_path / "m.json", {"source": {"kind": "cuboid", "cells": [6, 6, 3], "size": [0.06, 0.06, 0.03]}})
    assert run_tool("mesher", "--config", tmp_path / "m.json", "--out", tmp_path / "mesh.json").returncode == 0

    def config(tools=(SPHERE,), probe=None, regions=None, **extra):
        boundary = {"fixed": [{"set": "bottom"}]}
        if tools:
            boundary["tools"] = list(tools)
        c = {"model": {"mesh": str(tmp_path / "mesh.json"), "material": {"E": 5000, "nu": 0.35, "density": 1000},
                       "damping": {"alpha": 20}, "boundary": boundary},
             "frames": 300, "probe": probe or {"contact": "tool", "tool_offset": [0, 0, 0.01]},
             "input": {"kind": "press", "start": [0.03, 0.03, 0.04], "direction": [0, 0, -1], "depth": 0.004,
                       "ramp_time": 0.2},
             "regions": regions or {"radius": 0.012}}
        c.update(extra)
        return write_json(tmp_path / "h.json", c)

    return tmp_path, config


def test_regions_with_a_tool_and_a_blade_run_and_report(block):
    tmp, config = block
    config()
    r = run_tool("haptic_sim", "run", "--config", tmp / "h.json", "--out", tmp / "run.json")
    assert r.returncode == 0, r.stderr
    p = json.loads((tmp / "run.json").read_text())["payload"]
    assert p["solver"] == "regions" and p["regions"]["late_contacts"] == 0 and not p["events"]
    assert max(f[2] for f in p["force"]) > 0.01  # the tissue pushes the sphere back
    config(tools=(), probe={"stiffness": 100, "contact": "push"}, blade={"edge": [0, 0, 0.02]},
           input={"kind": "slide", "start": [0.02, 0.032, 0.04], "direction": [0, 0, -1], "depth": 0.005,
                  "ramp_time": 0.05, "slide_direction": [1, 0, 0], "speed": 0.05})
    r = run_tool("haptic_sim", "run", "--config", tmp / "h.json", "--out", tmp / "cut.json")
    assert r.returncode == 0, r.stderr
    p = json.loads((tmp / "cut.json").read_text())["payload"]
    topology = p["regions"]["topology"]
    assert p["cuts"] and topology["changes"] == len(p["cuts"])
    assert topology["local_updates"] + topology["rebuilds"] == topology["changes"]


@pytest.mark.parametrize("kwargs, pointer, words", [
    ({"probe": {"stiffness": 100}, "tools": (), "regions": {"radius": 0.012, "tool_margin": 0.001}},
     "/regions/tool_margin", "without probe.contact"),
    ({"regions": {"radius": 0.012, "tool_margin": -1}}, "/regions/tool_margin", ">= 0"),
    ({"probe": {"stiffness": 100}}, "/regions", "probe.contact \"tool\""),
    ({"tools": (SPHERE, SPHERE)}, "/regions", "one rigid tool"),
])
def test_regions_and_tool_nonsense_exit_2_with_one_line(block, kwargs, pointer, words):
    tmp, config = block
    config(**kwargs)
    r = run_tool("haptic_sim", "run", "--config", tmp / "h.json", "--out", tmp / "run.json")
    assert r.returncode == 2, r.stderr
    assert len(r.stderr.strip().splitlines()) == 1 and pointer in r.stderr and words in r.stderr, r.stderr
    assert not (tmp / "run.json").exists()
