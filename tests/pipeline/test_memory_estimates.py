"""Every size-setting member has a memory estimate checked before anything is built: a mesh
tool's triangles, a convergence study's finest block, a served session's frames. Over the limit
(SOFTSIM_MEMORY_LIMIT_MB, lowered here) the run is exit 2 with one line naming the member and
the estimate; the same input under the machine's own limit runs."""
import os
import struct
import subprocess

import numpy as np

from conftest import run_tool, tool, write_json

CUBOID = {"source": {"kind": "cuboid", "cells": [3, 3, 2], "size": [0.03, 0.03, 0.02]}}


def closed_sphere_stl(path, rings, segments, radius=0.005):
    """A binary STL of a closed UV sphere: 2 x segments x (rings - 1) triangles."""
    theta = np.linspace(0, np.pi, rings + 1)[1:-1]
    phi = np.linspace(0, 2 * np.pi, segments, endpoint=False)
    v = [(0, 0, radius)] + [(radius * np.sin(t) * np.cos(p), radius * np.sin(t) * np.sin(p), radius * np.cos(t))
                            for t in theta for p in phi] + [(0, 0, -radius)]
    v, last = np.array(v), len(v) - 1
    at = lambda i, j: 1 + i * segments + j % segments
    tris = [(0, at(0, j), at(0, j + 1)) for j in range(segments)]
    for i in range(rings - 2):
        for j in range(segments):
            tris += [(at(i, j), at(i + 1, j), at(i, j + 1)), (at(i, j + 1), at(i + 1, j), at(i + 1, j + 1))]
    tris += [(last, at(rings - 2, j + 1), at(rings - 2, j)) for j in range(segments)]
    rec = np.zeros(len(tris), dtype=[("n", "<f4", 3), ("v", "<f4", 9), ("a", "<u2")])
    rec["v"] = v[np.array(tris)].reshape(len(tris), 9)
    path.write_bytes(b"\0" * 80 + struct.pack("<I", len(tris)) + rec.tobytes())
    return len(tris)


def one_line(r):
    lines = [l for l in r.stderr.splitlines() if l.strip()]
    assert len(lines) == 1, r.stderr
    return lines[0]


def run_limited(limit_mb, *args):
    env = dict(os.environ, SOFTSIM_MEMORY_LIMIT_MB=str(limit_mb))
    return subprocess.run([str(tool(args[0])), *map(str, args[1:])], capture_output=True, text=True, env=env,
                          timeout=120)


def test_a_mesh_tools_triangles_are_estimated_before_the_tool_is_built(tmp_path):
    assert run_tool("mesher", "--config", write_json(tmp_path / "m.json", CUBOID), "--out", tmp_path / "mesh.json").returncode == 0
    triangles = closed_sphere_stl(tmp_path / "tool.stl", 100, 100)
    cfg = write_json(tmp_path / "c.json", {
        "mesh": str(tmp_path / "mesh.json"), "material": {"model": "neo_hookean_paper", "E": 5000, "nu": 0.35, "density": 1000},
        "boundary": {"fixed": ["bottom"], "tools": [{"shape": "mesh", "file": str(tmp_path / "tool.stl"),
                                                     "position": [0.015, 0.015, 0.03]}]},
        "solver": {"kind": "explicit", "steps": 2}})
    r = run_limited(5, "dhd_sim", "--config", cfg, "--out", tmp_path / "o.json")
    assert r.returncode == 2, r.stderr
    line = one_line(r)
    assert f"{cfg}: /boundary/tools/0/file: expected a size whose run fits the memory limit" in line
    assert f"({triangles} triangles)" in line
    assert not (tmp_path / "o.json").exists()
    assert run_tool("dhd_sim", "--config", cfg, "--out", tmp_path / "o.json").returncode == 0


def test_a_convergence_studys_finest_block_is_estimated(tmp_path):
    cfg = write_json(tmp_path / "c.json", {"nodes_per_edge": [3, 21]})
    r = run_limited(1000, "rpim_precompute", "convergence", "--config", cfg, "--out", tmp_path / "o.json")
    assert r.returncode == 2, r.stderr
    assert f"{cfg}: /nodes_per_edge: expected a size whose run fits the memory limit" in one_line(r)


def test_a_served_sessions_frames_are_estimated(tmp_path):
    assert run_tool("mesher", "--config", write_json(tmp_path / "m.json", CUBOID), "--out", tmp_path / "mesh.json").returncode == 0
    cfg = write_json(tmp_path / "h.json", {
        "model": {"mesh": str(tmp_path / "mesh.json"), "material": {"E": 5000, "nu": 0.35, "density": 1000},
                  "damping": {"alpha": 20}, "boundary": {"fixed": [{"set": "bottom"}]}},
        "probe": {"stiffness": 100}, "realtime": {"source": "stdin", "max_frames": 1000000},
        "input": {"kind": "press", "start": [0.015, 0.015, 0.02], "direction": [0, 0, -1], "depth": 0.004,
                  "ramp_time": 0.05}})
    r = run_limited(100, "haptic_sim", "serve", "--config", cfg, "--out", tmp_path / "o.json")
    assert r.returncode == 2, r.stderr
    assert f"{cfg}: /realtime/max_frames: expected a size whose run fits the memory limit" in one_line(r)
