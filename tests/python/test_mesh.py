"""Meshes through Python: the cuboid of 000 §2.2.1, imports, and the tet_mesh artifact, which
must be mesher's byte for byte."""
import gc
import json

import numpy as np
import pytest

from conftest import ROOT, import_softsim, run_tool

softsim = import_softsim()

CELLS, SIZE, ORIGIN = (3, 4, 5), (0.06, 0.08, 0.05), (0.01, -0.02, 0.0)


def tet_volumes(nodes, tets):
    x = nodes[tets]
    return np.linalg.det(np.stack([x[:, 1] - x[:, 0], x[:, 2] - x[:, 0], x[:, 3] - x[:, 0]], axis=1)) / 6


def test_cuboid_nodes_tets_and_volume():
    m = softsim.cuboid(CELLS, SIZE, origin=ORIGIN)
    nx, ny, nz = CELLS
    assert (m.num_nodes, m.num_tets) == ((nx + 1) * (ny + 1) * (nz + 1), 5 * nx * ny * nz)
    assert m.nodes.dtype == np.float64 and m.nodes.shape == (m.num_nodes, 3)
    assert m.tets.dtype == np.int32 and m.tets.shape == (m.num_tets, 4)
    # Node (i, j, k) has index i + (nx+1)(j + (ny+1)k) and sits on the regular grid.
    k, j, i = np.meshgrid(np.arange(nz + 1), np.arange(ny + 1), np.arange(nx + 1), indexing="ij")
    grid = np.stack([i, j, k], axis=-1).reshape(-1, 3) * (np.array(SIZE) / CELLS) + ORIGIN
    np.testing.assert_allclose(m.nodes, grid, rtol=0, atol=1e-15)
    # Every tet positively oriented; together they fill the box exactly once.
    v = tet_volumes(m.nodes, m.tets)
    assert (v > 0).all()
    assert v.sum() == pytest.approx(np.prod(SIZE), rel=1e-12)
    top = m.node_sets["top"]
    assert np.array_equal(top, np.flatnonzero(np.isclose(m.nodes[:, 2], ORIGIN[2] + SIZE[2])))
    assert set(m.element_tags["layer"]) == set(range(nz))


def test_arrays_are_read_only_views_that_keep_the_mesh_alive():
    m = softsim.cuboid((2, 2, 2), (1.0, 1.0, 1.0))
    nodes, tets = m.nodes, m.tets
    assert np.shares_memory(nodes, m.nodes) and np.shares_memory(tets, m.tets)  # views, not copies
    with pytest.raises(ValueError):
        nodes[0, 0] = 5.0
    expected_nodes, expected_tets, expected_top = nodes.copy(), tets.copy(), m.node_sets["top"].copy()
    top = m.node_sets["top"]
    del m
    gc.collect()
    assert np.array_equal(nodes, expected_nodes) and np.array_equal(tets, expected_tets)
    assert np.array_equal(top, expected_top)


def test_save_writes_meshers_artifact_byte_for_byte(tmp_path):
    config = {"source": {"kind": "cuboid", "cells": list(CELLS), "size": list(SIZE), "origin": list(ORIGIN)},
              "sliver_threshold_deg": 12.5}
    path = tmp_path / "mesher.json"
    path.write_text(json.dumps(config))
    assert run_tool("mesher", "--config", path, "--out", tmp_path / "cli.json").returncode == 0
    softsim.mesh_from_config(config).save(tmp_path / "dict.json")
    softsim.mesh_from_config(path).save(tmp_path / "file.json")
    cli = (tmp_path / "cli.json").read_bytes()
    assert (tmp_path / "dict.json").read_bytes() == cli
    assert (tmp_path / "file.json").read_bytes() == cli


def test_cuboid_keywords_are_meshers_config(tmp_path):
    config = {"source": {"kind": "cuboid", "cells": [2, 3, 1], "size": [0.1, 0.1, 0.02]}}
    (tmp_path / "c.json").write_text(json.dumps(config))
    assert run_tool("mesher", "--config", tmp_path / "c.json", "--out", tmp_path / "cli.json").returncode == 0
    softsim.cuboid(np.array([2, 3, 1]), (0.1, 0.1, 0.02)).save(tmp_path / "py.json")
    assert (tmp_path / "py.json").read_bytes() == (tmp_path / "cli.json").read_bytes()


def test_imported_gmsh_file_and_its_artifact_round_trip(tmp_path):
    msh = "tests/bad_input/mesher/files/good.msh"  # relative to the root, as mesher records it
    config = {"source": {"kind": "file", "path": msh, "scale": 0.01}}
    (tmp_path / "c.json").write_text(json.dumps(config))
    assert run_tool("mesher", "--config", tmp_path / "c.json", "--out", tmp_path / "cli.json").returncode == 0
    cli = tmp_path / "cli.json"
    loaded = softsim.load_mesh(cli)
    loaded.save(tmp_path / "again.json")  # a loaded artifact keeps the provenance of its run
    assert (tmp_path / "again.json").read_bytes() == cli.read_bytes()
    imported = softsim.load_mesh(ROOT / msh, scale=0.01)
    assert np.array_equal(imported.nodes, loaded.nodes) and np.array_equal(imported.tets, loaded.tets)
    assert (tet_volumes(imported.nodes, imported.tets) > 0).all()


def test_closed_obj_surface_is_filled_in_memory(tmp_path, monkeypatch):
    # Gmsh runs inside the module (as in mesher): the unit cube scaled to 1 cm is filled exactly,
    # every tet positive, and nothing is left in the temporary folder.
    monkeypatch.setenv("TMPDIR", str(tmp_path))
    m = softsim.load_mesh(ROOT / "tests/bad_input/mesher/files/cube.obj", scale=0.01)
    v = tet_volumes(m.nodes, m.tets)
    assert (v > 0).all()
    assert v.sum() == pytest.approx(1e-6, rel=1e-12)
    assert list(tmp_path.iterdir()) == []


def test_bad_cuboid_names_the_call_and_pointer():
    with pytest.raises(softsim.InputError, match=r"^softsim\.cuboid\(\): /source/cells: expected cell counts "
                                                 r"between 1 and 400"):
        softsim.cuboid((0, 1, 1), (1, 1, 1))
    with pytest.raises(ValueError):  # InputError is a ValueError
        softsim.cuboid((1, 1, 1), (1, -1, 1))


def test_unknown_key_in_a_dict_config_names_dict_and_pointer():
    config = {"source": {"kind": "cuboid", "cells": [1, 1, 1], "size": [1, 1, 1], "colour": "red"}}
    with pytest.raises(softsim.InputError) as error:
        softsim.mesh_from_config(config)
    assert str(error.value) == "<dict>: /source/colour: unknown field"


def test_a_value_json_cannot_hold_is_refused_with_its_pointer():
    config = {"source": {"kind": "cuboid", "cells": [1, 1, object()], "size": [1, 1, 1]}}
    with pytest.raises(softsim.InputError, match=r"^<dict>: /source/cells/2: expected a JSON value"):
        softsim.mesh_from_config(config)
