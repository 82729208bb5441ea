"""The CalculiX reference stages against analytic solutions.

Tet runner (pipeline.stages.calculix) on a 2 × 2 × 2-cell cuboid from the mesher:
  * linear uniaxial stretch with the lateral faces free: the homogeneous solution lies in the
    space of linear tetrahedra, so CalculiX must reproduce it to its print precision;
  * decoupled neo-Hookean uniaxial compression (NLGEOM) against the homogeneous analytic
    solution of W = mu/2 (Ibar1 - 3) + K/2 (J - 1)^2 with traction-free lateral faces;
  * force control with the reactions of a displacement-controlled solve gives the same field;
  * bad input and a non-converging solve fail clearly and write no artifact.
Plate runner (pipeline.stages.calculix_plate): equilibrium, mirror symmetry of the response to
a vertical force, and the energy ordering of the three support variants.
"""
import json
import shutil

import numpy as np
import pytest

from conftest import run_tool, write_json
from pipeline.stages.calculix import reaction_force, run_calculix, solve_tet_mesh
from pipeline.stages.calculix_analytic import uniaxial_neo_hookean_decoupled
from pipeline.config_reader import ConfigError
from pipeline.stages.calculix_ccx import CalculixNumericalError, fmt, parse_dat
from pipeline.stages.calculix_plate import PlateMesh, solve_plate

pytestmark = pytest.mark.skipif(shutil.which("ccx") is None,
                                reason="CalculiX (`ccx`, Debian calculix-ccx) is not installed")

SIZE = 0.01  # edge of the cube (m)


@pytest.fixture(scope="module")
def cube(tmp_path_factory):
    """2 × 2 × 2 cells of 5 tets, 1 cm cube: (artifact path, payload)."""
    d = tmp_path_factory.mktemp("cube")
    cfg = write_json(d / "mesh.json",
                     {"source": {"kind": "cuboid", "cells": [2, 2, 2], "size": [SIZE] * 3}})
    out = d / "cube.json"
    r = run_tool("mesher", "--config", cfg, "--out", out)
    assert r.returncode == 0, r.stderr
    return out, json.loads(out.read_text())["payload"]


def node_index(mesh, point):
    x = np.asarray(mesh["nodes"])
    i = int(np.argmin(np.linalg.norm(x - np.asarray(point), axis=1)))
    assert np.linalg.norm(x[i] - point) < 1e-12
    return i


def uniaxial_boundary(mesh, top_uz):
    """Bottom slides on z = 0, top moves by top_uz, lateral faces free; two point constraints
    at the bottom remove the in-plane rigid motions without restraining the lateral strain."""
    return {
        "fixed": [{"set": "bottom", "components": "z"},
                  {"nearest": [0, 0, 0], "components": "xy"},
                  {"nearest": [SIZE, 0, 0], "components": "y"}],
        "prescribed": [{"set": "top", "displacement": [0, 0, top_uz], "components": "z"}]}


def test_linear_uniaxial_stretch_is_exact(cube, tmp_path):
    path, mesh = cube
    E, nu, strain = 5000.0, 0.35, 0.01
    config = {"mesh": str(path),
              "material": {"model": "linear", "E": E, "nu": nu},
              "boundary": uniaxial_boundary(mesh, strain * SIZE)}
    out = tmp_path / "r.json"
    payload = run_calculix(config, out)
    x = np.asarray(mesh["nodes"])
    exact = np.column_stack([-nu * strain * x[:, 0], -nu * strain * x[:, 1], strain * x[:, 2]])
    u = np.asarray(payload["displacement"])
    assert u.shape == x.shape
    # The .dat file prints 7 significant digits.
    assert np.max(np.abs(u - exact)) < 1e-6 * strain * SIZE
    force = E * strain * SIZE**2  # sigma_zz * area
    assert reaction_force(payload, "prescribed top")[2] == pytest.approx(force, rel=1e-5)
    assert reaction_force(payload, "fixed bottom")[2] == pytest.approx(-force, rel=1e-5)
    assert np.allclose(reaction_force(payload, f"fixed node {node_index(mesh, [0, 0, 0])}"),
                       0, atol=1e-6 * force)
    doc = json.loads(out.read_text())
    assert doc["schema"] == {"name": "calculix_result", "version": 1}
    assert doc["provenance"]["config"] == config
    assert payload["element_type"] == "C3D4" and payload["ccx_version"] != "unknown"


def test_neo_hookean_uniaxial_compression_matches_analytic(cube, tmp_path):
    path, mesh = cube
    E, nu, stretch = 5000.0, 0.45, 0.75
    mu, K = E / (2 * (1 + nu)), E / (3 * (1 - 2 * nu))
    payload = run_calculix(
        {"mesh": str(path),
         "material": {"model": "neo_hookean_decoupled", "E": E, "nu": nu},
         "boundary": uniaxial_boundary(mesh, (stretch - 1) * SIZE),
         "analysis": {"increments": 5}},
        tmp_path / "r.json")
    lt, sigma, _ = uniaxial_neo_hookean_decoupled(mu, K, stretch)
    # The finite-strain answer differs clearly from the small-strain one (lt = 1 + nu * 0.25).
    assert abs((lt - 1) - nu * (1 - stretch)) > 0.01
    x = np.asarray(mesh["nodes"])
    exact = x * np.array([lt - 1, lt - 1, stretch - 1])
    u = np.asarray(payload["displacement"])
    assert np.max(np.abs(u - exact)) < 1e-5 * (1 - stretch) * SIZE
    force = sigma * (lt * SIZE) ** 2  # Cauchy stress on the deformed area
    assert reaction_force(payload, "prescribed top")[2] == pytest.approx(force, rel=1e-5)
    assert payload["analysis"]["nlgeom"] and payload["analysis"]["increments_taken"] >= 5
    assert payload["material"]["C10"] == pytest.approx(mu / 2)
    assert payload["material"]["D1"] == pytest.approx(2 / K)


@pytest.mark.parametrize("material", [
    {"model": "mooney_rivlin", "C10": 600.0, "C01": 300.0, "K": 6000.0},
    {"model": "ogden", "mu": [700.0, 30.0, -100.0], "alpha": [1.3, 5.0, -2.0], "K": 6000.0},
    # Two equal terms are one term of twice the modulus: catches a misread higher D_i.
    {"model": "ogden", "mu": [400.0, 300.0], "alpha": [1.3, 1.3], "K": 6000.0},
])
def test_mooney_rivlin_and_ogden_uniaxial_match_the_closed_form(cube, material, tmp_path):
    from pipeline.reports.validation_laws import uniaxial_force
    path, mesh = cube
    stretch = 0.8
    payload = run_calculix(
        {"mesh": str(path), "material": material,
         "boundary": uniaxial_boundary(mesh, (stretch - 1) * SIZE), "analysis": {"increments": 5}},
        tmp_path / "r.json")
    force = uniaxial_force(material, stretch, SIZE * SIZE)  # dW/dλ < 0 in compression
    assert reaction_force(payload, "prescribed top")[2] == pytest.approx(force, rel=1e-5)
    # The law's energy is the neo-Hookean one where it reduces to it (C01 = 0 / one term, alpha = 2).
    mu, K = 1000.0, 6000.0
    _, sigma, _ = uniaxial_neo_hookean_decoupled(mu, K, stretch)
    for law in ({"model": "mooney_rivlin", "C10": mu / 2, "C01": 0.0, "K": K},
                {"model": "ogden", "mu": [mu], "alpha": [2.0], "K": K}):
        lt = uniaxial_neo_hookean_decoupled(mu, K, stretch)[0]
        assert uniaxial_force(law, stretch, 1.0) == pytest.approx(sigma * lt * lt, rel=1e-7)


def test_pipeline_entry_point_resolves_the_mesh_from_the_root(cube, tmp_path):
    """run(ctx) as the pipeline calls it (config, out_path, root, log): a root-relative mesh
    path, an artifact at out_path, and the mesh's hash in the provenance."""
    from types import SimpleNamespace

    from pipeline.artifacts import read_artifact
    from pipeline.hashing import file_hash
    from pipeline.stages import calculix

    path, _ = cube
    log = []
    ctx = SimpleNamespace(
        config={"mesh": path.name,
                "material": {"model": "linear", "E": 1e3, "nu": 0.3},
                "boundary": {"fixed": ["bottom"],
                             "prescribed": [{"set": "top", "displacement": [0, 0, 1e-4]}]}},
        out_path=tmp_path / "out.json", root=path.parent, log=log.append)
    calculix.run(ctx)
    doc = read_artifact(tmp_path / "out.json", "calculix_result")
    assert list(doc["provenance"]["inputs"].values()) == [file_hash(path)]
    assert len(doc["payload"]["displacement"]) == 27
    assert any("C3D4" in line for line in log)


def test_force_control_reproduces_displacement_control(cube):
    """Loading the top nodes with their reactions from a displacement-controlled solve (and
    keeping the bottom fixed) must give back the same displacement field; the per-node
    reactions come from one-node constraints that override the set's."""
    _, mesh = cube
    material = {"model": "linear", "E": 3000.0, "nu": 0.3}
    motion = [2e-4, -1e-4, -3e-4]
    top = mesh["node_sets"]["top"]
    shear = solve_tet_mesh(mesh, material, {
        "fixed": ["bottom"],
        "prescribed": [{"set": "top", "displacement": motion}]
        + [{"nodes": [n], "displacement": motion} for n in top]})
    # Every top component is owned by the later one-node entries.
    assert reaction_force(shear, "prescribed top") == [0.0, 0.0, 0.0]
    forces = [{"nodes": [n], "force": r["force"]}
              for n, r in zip(top, shear["reactions"][2:])]
    loaded = solve_tet_mesh(mesh, material, {"fixed": ["bottom"], "forces": forces})
    a, b = np.asarray(shear["displacement"]), np.asarray(loaded["displacement"])
    assert np.linalg.norm(a - b) < 1e-5 * np.linalg.norm(a)


def test_bad_input_is_rejected_before_running(cube):
    _, mesh = cube
    lin = {"model": "linear", "E": 1e3, "nu": 0.3}
    fixed = {"fixed": ["bottom"]}
    with pytest.raises(ConfigError, match="/material/nu"):
        solve_tet_mesh(mesh, {**lin, "nu": 0.5}, fixed)
    with pytest.raises(ConfigError, match="no CalculiX counterpart"):
        solve_tet_mesh(mesh, {**lin, "model": "neo_hookean_paper"}, fixed)
    with pytest.raises(ConfigError, match="stiffness"):
        solve_tet_mesh(mesh, {**lin, "stiffness": 1}, fixed)
    with pytest.raises(ConfigError, match="node set of the mesh"):
        solve_tet_mesh(mesh, lin, {"fixed": ["lid"]})
    with pytest.raises(ConfigError, match="/boundary/prescribed/0: expected exactly one node"):
        solve_tet_mesh(mesh, lin, {"fixed": ["bottom"], "prescribed": [
            {"set": "top", "nodes": [1], "displacement": [0, 0, 1e-3]}]})
    with pytest.raises(ConfigError, match="gravity"):
        solve_tet_mesh(mesh, lin, {"fixed": ["bottom"], "gravity": [0, 0, -9.81]})
    with pytest.raises(ConfigError, match="constrained component"):
        solve_tet_mesh(mesh, lin, {"fixed": ["bottom"],
                                   "forces": [{"set": "bottom", "force": [0, 0, 1]}]})
    flipped = dict(mesh, tets=[[t[0], t[2], t[1], t[3]] for t in mesh["tets"]])
    with pytest.raises(ConfigError, match="positively oriented"):
        solve_tet_mesh(flipped, lin, fixed)


def test_failed_solves_are_numerical_errors_and_write_nothing(cube, tmp_path):
    path, mesh = cube
    out = tmp_path / "never.json"
    # mu = 2000 Pa, K = 20000 Pa
    material = {"model": "neo_hookean_decoupled", "E": 5806.451612903225, "nu": 0.4516129032258065}

    def squeeze(uz, analysis):
        return {"mesh": str(path), "material": material, "analysis": analysis,
                "boundary": {"fixed": ["bottom"], "prescribed": [
                    {"set": "top", "displacement": [0, 0, uz], "components": "z"}]}}

    # 98 % compression in one increment with no room to cut back: ccx gives up.
    with pytest.raises(CalculixNumericalError, match="increment size smaller than minimum"):
        run_calculix(squeeze(-0.98 * SIZE, {"increments": 1, "min_increment": 0.5}), out)
    # The top pushed through the bottom: every element must turn inside out.
    with pytest.raises(CalculixNumericalError, match="inverted element"):
        run_calculix(squeeze(-1.2 * SIZE, {"increments": 2}), out)
    assert not list(tmp_path.iterdir())


def test_deck_numbers_fit_calculix_fields_and_results_parse():
    """CalculiX reads 20 characters of a field and drops the rest without a word."""
    for x in (3.7500000000000033e-07, -1.2345678901234567e-100, 0.0048000000000000004,
              53691.275167785236, 1.0 / 3.0, -0.0, 1e300):
        text = fmt(x)
        assert len(text) <= 20
        assert float(text) == pytest.approx(x, rel=1e-12, abs=0)  # >= 13 digits
    blocks = parse_dat(" displacements (vx,vy,vz) for set NALL and time  0.1000000E+01\n\n"
                       "         7  1.000000E-03 -2.500000-101  0.000000E+00\n")
    assert blocks[0]["time"] == 1.0 and blocks[0]["rows"][7] == [1e-3, -2.5e-101, 0.0]


# --------------------------------------------------------------------------- plate runner
PLATE = {"size": [0.048, 0.048, 0.006], "divisions": [10, 10, 2],
         "material": {"model": "linear", "E": 0.32e6, "nu": 0.49}}


def test_plate_grid_maps_to_mesh_nodes():
    mesh = PlateMesh(PLATE["size"], [10, 10, 2], "C3D20R")
    assert mesh.node_at([0.024, 0.024, 0.006]) is not None
    assert mesh.node_at([0.0024, 0.0, 0.006]) is not None  # an edge midpoint
    assert mesh.node_at([0.0024, 0.0024, 0.006]) is None    # a face centre: not a C3D20 node
    coarse = PlateMesh(PLATE["size"], [4, 4, 1], "C3D8")
    assert coarse.node_at([0.0048, 0.0, 0.006]) is None
    assert len(coarse.positions) == 5 * 5 * 2 and len(coarse.elements) == 16


def test_plate_vertical_force_is_balanced_and_mirror_symmetric():
    p = solve_plate({**PLATE, "support": "vertical_corner_edges", "force": [0.0, 0.0, -0.2]})
    assert np.allclose(p["support_reaction_total"], [0, 0, 0.2], atol=1e-6)
    g = p["top_grid"]
    assert all(g["on_mesh"]) and len(g["displacement"]) == 121
    u = np.asarray(g["displacement"]).reshape(11, 11, 3)  # [j, i, component]
    scale = np.abs(u).max()
    # Mirror x -> 48 mm - x: ux changes sign, uy and uz do not; the diagonal swaps ux and uy.
    assert np.allclose(u[:, ::-1, 0], -u[:, :, 0], atol=1e-5 * scale)
    assert np.allclose(u[:, ::-1, 2], u[:, :, 2], atol=1e-5 * scale)
    assert np.allclose(u.transpose(1, 0, 2)[:, :, 2], u[:, :, 2], atol=1e-5 * scale)
    assert np.allclose(u.transpose(1, 0, 2)[:, :, 0], u[:, :, 1], atol=1e-5 * scale)
    centre = p["top_centre"]["displacement"]
    assert centre == g["displacement"][60] and centre[2] < 0


def test_plate_more_support_means_less_work():
    """Clamping every lateral face adds constraints to either edge support, so the work of the
    same force (f . u at the loaded node) must be smaller (minimum potential energy)."""
    force = [0.9, -0.7, -0.22]
    work = {}
    for support in ("side_faces", "bottom_edges", "vertical_corner_edges"):
        p = solve_plate({**PLATE, "support": support, "force": force})
        work[support] = float(np.dot(force, p["top_centre"]["displacement"]))
        assert work[support] > 0
    assert work["side_faces"] < work["bottom_edges"]
    assert work["side_faces"] < work["vertical_corner_edges"]


def test_plate_rejects_a_mesh_without_a_centre_node():
    with pytest.raises(ConfigError, match="/divisions"):
        solve_plate({**PLATE, "divisions": [5, 5, 2], "element_type": "C3D8",
                     "support": "side_faces", "force": [0, 0, -0.1]})
