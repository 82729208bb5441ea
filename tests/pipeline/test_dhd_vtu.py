"""dhd_sim's ParaView output read by independent readers (meshio, and vtu_arrays for raw appended
data): the stress and strain cell fields of a homogeneous uniaxial state equal the closed-form
solution, the three encodings hold the same numbers bit for bit, and the .pvd series lists every
snapshot at its simulated time."""
import json
import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from conftest import run_tool, write_json
from vtu_arrays import read_arrays

E, NU = 5000.0, 0.35
MU, LAM = E / (2 * (1 + NU)), E * NU / ((1 + NU) * (1 - 2 * NU))
HEIGHT, STRETCH = 0.02, 1.1


def mesh(tmp_path):
    cfg = {"source": {"kind": "cuboid", "cells": [2, 2, 2], "size": [0.02, 0.02, HEIGHT]}}
    r = run_tool("mesher", "--config", write_json(tmp_path / "mesh_cfg.json", cfg), "--out", tmp_path / "mesh.json")
    assert r.returncode == 0, r.stderr
    return tmp_path / "mesh.json"


def uniaxial_paper(a):
    """Uniaxial stress of 000 eq. 14's neo-Hookean law: the lateral stretch t (t² the positive
    root of λ a² s² + (μ − λ a) s − μ = 0, from a free lateral face) and the axial Cauchy stress."""
    b = MU - LAM * a
    s = (-b + math.sqrt(b * b + 4 * LAM * a * a * MU)) / (2 * LAM * a * a)
    J = s * a
    nominal = MU * (a - 1 / a) + LAM * J * (J - 1) / a
    return math.sqrt(s), nominal / s


def run_static(tmp_path, vtu_format):
    vtu = tmp_path / f"static_{vtu_format}.vtu"
    cfg = {"mesh": str(mesh(tmp_path)),
           "material": {"model": "neo_hookean_paper", "E": E, "nu": NU},
           "boundary": {"fixed": [{"set": "bottom", "components": "z"}, {"set": "x_min", "components": "x"},
                                  {"set": "y_min", "components": "y"}],
                        "prescribed": [{"set": "top", "displacement": [0, 0, (STRETCH - 1) * HEIGHT],
                                        "components": "z"}]},
           "solver": {"kind": "static", "increments": 4},
           "output": {"vtu": str(vtu), "vtu_format": vtu_format}}
    r = run_tool("dhd_sim", "--config", write_json(tmp_path / f"static_{vtu_format}.json", cfg),
                 "--out", tmp_path / f"static_{vtu_format}_out.json")
    assert r.returncode == 0, r.stderr
    return vtu


def test_uniaxial_stress_and_strain_fields_equal_the_closed_form(tmp_path):
    meshio = pytest.importorskip("meshio")
    m = meshio.read(run_static(tmp_path, "base64"))
    t, sigma = uniaxial_paper(STRETCH)
    stress = m.cell_data_dict["cauchy_stress"]["tetra"]
    strain = m.cell_data_dict["green_lagrange_strain"]["tetra"]
    von_mises = m.cell_data_dict["von_mises_stress"]["tetra"]
    assert stress.shape == (40, 6) and strain.shape == (40, 6)
    # Components xx yy zz xy yz xz; the static solve is exact to its tolerance (1e-9 of the forces).
    np.testing.assert_allclose(stress, np.tile([0, 0, sigma, 0, 0, 0], (40, 1)), atol=1e-6 * sigma)
    np.testing.assert_allclose(strain, np.tile([(t * t - 1) / 2, (t * t - 1) / 2, (STRETCH ** 2 - 1) / 2, 0, 0, 0],
                                               (40, 1)), atol=1e-9)
    np.testing.assert_allclose(von_mises, sigma, rtol=1e-6)
    assert (m.cell_data_dict["element_kind"]["tetra"] == 1).all()  # TLED


def test_three_encodings_hold_the_same_numbers(tmp_path):
    arrays = {f: read_arrays(run_static(tmp_path, f)) for f in ("ascii", "base64", "raw")}
    names = {"Points", "displacement", "velocity", "element_kind", "region", "cauchy_stress",
             "green_lagrange_strain", "von_mises_stress", "connectivity", "offsets", "types"}
    assert set(arrays["raw"]) == names
    for f in ("ascii", "base64"):
        for name in names:
            assert arrays[f][name].dtype == arrays["raw"][name].dtype, (f, name)
            assert np.array_equal(arrays[f][name], arrays["raw"][name]), (f, name)
    assert arrays["raw"]["cauchy_stress"].shape == (40, 6)
    meshio = pytest.importorskip("meshio")  # and an independent reader agrees on the text encodings
    for f in ("ascii", "base64"):
        m = meshio.read(tmp_path / f"static_{f}.vtu")
        assert np.array_equal(m.cell_data_dict["cauchy_stress"]["tetra"], arrays["raw"]["cauchy_stress"]), f


def test_snapshot_series_lists_every_snapshot_at_its_time(tmp_path):
    meshio = pytest.importorskip("meshio")
    cfg = {"mesh": str(mesh(tmp_path)),
           "boundary": {"fixed": ["bottom"], "prescribed": [{"set": "top", "displacement": [0, 0, -0.001]}]},
           "solver": {"steps": 30},
           "output": {"vtu": str(tmp_path / "run.vtu"), "vtu_interval": 10}}
    r = run_tool("dhd_sim", "--config", write_json(tmp_path / "run.json", cfg), "--out", tmp_path / "out.json")
    assert r.returncode == 0, r.stderr
    dt = json.loads((tmp_path / "out.json").read_text())["payload"]["solver"]["dt"]
    datasets = ET.parse(tmp_path / "run.pvd").getroot().find("Collection").findall("DataSet")
    assert [d.get("file") for d in datasets] == [f"run_{s:06d}.vtu" for s in (0, 10, 20, 30)]
    assert [float(d.get("timestep")) for d in datasets] == [s * dt for s in (0, 10, 20, 30)]
    # The last snapshot is the final state.
    last = meshio.read(tmp_path / datasets[-1].get("file"))
    final = meshio.read(tmp_path / "run.vtu")
    assert np.array_equal(last.point_data["displacement"], final.point_data["displacement"])
    assert np.abs(final.point_data["displacement"]).max() > 0
