"""dhd_sim through Python: the same numbers as the executable, bit for bit, and the physics of
the static solver (a patch test)."""
import json

import numpy as np
import pytest

from conftest import import_softsim, make_artifact, payload, run_tool, without_timing

softsim = import_softsim()

E, NU, DROP, H = 5000.0, 0.35, 0.0004, 0.02
MESH_CONFIG = {"source": {"kind": "cuboid", "cells": [3, 3, 2], "size": [0.03, 0.03, H]}}
MATERIAL = {"model": "neo_hookean_paper", "E": E, "nu": NU, "density": 1000}
PUSH = {"fixed": ["bottom"], "prescribed": [{"set": "top", "displacement": [0, 0, -0.001]}]}


@pytest.fixture(scope="module")
def mesh_path(tmp_path_factory):
    return make_artifact("mesher", MESH_CONFIG, tmp_path_factory.mktemp("mesh"))


def run_both(mesh_path, config, folder):
    """dhd_sim's payload and Python's (config file, mesh from it), with a config naming the mesh."""
    config = {"mesh": str(mesh_path), **config}
    cli = payload(make_artifact("dhd_sim", config, folder))
    path = folder / "python.config.json"
    path.write_text(json.dumps(config))
    return cli, path


def test_static_solution_equals_dhd_sims_bit_for_bit(mesh_path, tmp_path):
    config = {"material": MATERIAL, "boundary": PUSH, "solver": {"kind": "static", "increments": 3}}
    cli, path = run_both(mesh_path, config, tmp_path)
    from_file = softsim.solve_static(None, path)
    given_mesh = softsim.solve_static(softsim.load_mesh(mesh_path), config)  # no "mesh" key
    for s in (from_file, given_mesh):
        assert without_timing(s.payload) == without_timing(cli)
        assert np.array_equal(s.displacement, np.array(cli["displacement"]))
        assert np.array_equal(s.reactions, np.array([r["force"] for r in cli["reactions"]]))
        assert s.reaction_names == [r["name"] for r in cli["reactions"]]
        assert s.iterations == cli["solver"]["iterations"] and s.residual == cli["solver"]["residual"]
        assert s.strain_energy == cli["energies"]["strain"]
    assert max(from_file.iterations) > 1  # a nonlinear solve, not a trivial one


def test_explicit_run_equals_dhd_sims_bit_for_bit(mesh_path, tmp_path):
    config = {"material": MATERIAL, "damping": {"alpha": 5.0}, "boundary": PUSH,
              "partition": {"linear_fraction": 0.4, "linear_element": "corotational"},
              "solver": {"kind": "explicit", "steps": 300},
              "output": {"trajectories": [{"set": "top"}], "trajectory_interval": 50, "velocity": True}}
    cli, path = run_both(mesh_path, config, tmp_path)
    assert without_timing(softsim.run_dhd(None, path)) == without_timing(cli)
    assert without_timing(softsim.run_dhd(softsim.load_mesh(mesh_path), config)) == without_timing(cli)


@pytest.mark.parametrize("element", ["linear", "corotational"])
def test_patch_test_uniaxial_strain_is_uniform(element):
    """A linear material under uniform uniaxial compression with free lateral faces: the exact
    solution is a uniform strain (eps_zz = -DROP/H, eps_xx = eps_yy = -nu eps_zz), which linear
    tetrahedra represent exactly, so every node's displacement is linear in its coordinates to
    round-off; the top's reaction is the uniaxial stress E eps_zz times the area."""
    mesh = softsim.cuboid((3, 2, 4), (0.03, 0.02, H), origin=(0.01, 0.02, 0.03))
    config = {"material": {"model": "linear", "E": E, "nu": NU},
              "partition": {"kind": "uniform", "element": element},
              "boundary": {"fixed": [{"set": "bottom", "components": "z"}, {"set": "x_min", "components": "x"},
                                     {"set": "y_min", "components": "y"}],
                           "prescribed": [{"set": "top", "displacement": [0, 0, -DROP], "components": "z"}]},
              "solver": {"increments": 1}}
    s = softsim.solve_static(mesh, config)
    x = mesh.nodes - mesh.nodes.min(axis=0)
    eps_zz = -DROP / H
    expected = x * np.array([-NU * eps_zz, -NU * eps_zz, eps_zz])
    assert np.abs(s.displacement - expected).max() <= 1e-13 * DROP
    top = s.reactions[s.reaction_names.index("prescribed top")]
    assert top[2] == pytest.approx(E * eps_zz * 0.03 * 0.02, rel=1e-12)
    # Uniaxial stress: the symmetry planes carry no normal force.
    for plane, axis in (("fixed x_min", 0), ("fixed y_min", 1)):
        assert abs(s.reactions[s.reaction_names.index(plane)][axis]) <= 1e-12 * abs(top[2])


def test_solve_static_refuses_an_explicit_solver(mesh_path):
    config = {"mesh": str(mesh_path), "boundary": PUSH, "solver": {"kind": "explicit"}}
    with pytest.raises(softsim.InputError, match=r'^<dict>: /solver/kind: expected "static"'):
        softsim.solve_static(None, config)


def test_bad_key_names_dict_and_json_pointer(mesh_path):
    config = {"material": {"E": 5000, "poisson": 0.3}}
    with pytest.raises(softsim.InputError) as error:
        softsim.run_dhd(softsim.load_mesh(mesh_path), config)
    assert str(error.value) == "<dict>: /material/poisson: unknown field"


def test_step_above_the_limit_names_the_config_like_dhd_sim(mesh_path, tmp_path):
    """A member found at fault after reading (ConfigInputError) gets the config's name in front."""
    config = {"mesh": str(mesh_path), "boundary": PUSH, "solver": {"steps": 10, "dt": 1.0}}
    path = tmp_path / "c.json"
    path.write_text(json.dumps(config))
    r = run_tool("dhd_sim", "--config", path, "--out", tmp_path / "r.json")
    assert r.returncode == 2
    with pytest.raises(softsim.InputError) as from_file:
        softsim.run_dhd(None, path)
    assert "dhd_sim: error: " + str(from_file.value) == r.stderr.strip()
    with pytest.raises(softsim.InputError, match=r"^<dict>: /solver: requested time step"):
        softsim.run_dhd(None, config)


def test_forced_unstable_step_is_a_numerical_error(mesh_path, tmp_path):
    """Central differences above the critical step blow up: the energy check stops the run."""
    config = {"mesh": str(mesh_path), "material": MATERIAL, "boundary": PUSH}
    critical = softsim.run_dhd(None, {**config, "solver": {"steps": 0}})["solver"]["dt_critical"]
    unstable = {**config, "solver": {"steps": 2000, "dt": 3 * critical, "force_dt": True}}
    with pytest.raises(softsim.NumericalError) as error:
        softsim.run_dhd(None, unstable)
    assert isinstance(error.value, ArithmeticError)
    path = tmp_path / "c.json"
    path.write_text(json.dumps(unstable))
    r = run_tool("dhd_sim", "--config", path, "--out", tmp_path / "r.json")
    assert r.returncode == 3 and r.stderr.strip() == "dhd_sim: numerical failure: " + str(error.value)
