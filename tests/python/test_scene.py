"""softsim.Scene, the step-by-step engine from Python: the same engine as dhd_sim (stepped in
pieces it equals the executable's run bit for bit), a probe moved between steps settles on the
static equilibrium of the same tip position, state reads are in place where asked, errors carry
the executables' messages, and stepping releases the GIL."""
import threading

import numpy as np
import pytest
from conftest import import_softsim, make_artifact, payload

softsim = import_softsim()


def block_config(mesh_path="m", steps=120):
    return {
        "mesh": mesh_path,
        "material": {"model": "neo_hookean_decoupled", "E": 5000, "nu": 0.35, "density": 1000},
        "damping": {"alpha": 8.0},
        "partition": {"linear_fraction": 0.4},
        "boundary": {
            "fixed": ["bottom"],
            "prescribed": [{"set": "top", "displacement": [0.0005, 0, -0.002], "ramp_time": 0.04, "ramp": "smooth"}],
            "gravity": [0, 0, -9.81],
        },
        "solver": {"kind": "explicit", "steps": steps, "energy_interval": 25},
        "output": {"velocity": True},
    }


@pytest.fixture(scope="module")
def block(tmp_path_factory):
    mesh = softsim.cuboid(cells=[4, 3, 3], size=[0.04, 0.03, 0.03])
    path = tmp_path_factory.mktemp("scene") / "mesh.json"
    mesh.save(str(path))
    return mesh, path


def test_stepped_in_pieces_equals_dhd_sim(block, tmp_path):
    mesh, mesh_path = block
    config = block_config(str(mesh_path))
    artifact = payload(make_artifact("dhd_sim", config, tmp_path))
    scene = softsim.Scene(config)  # the mesh loaded from the artifact the config names
    for n in (1, 30, 0, 44, 45):
        scene.step(n)
    assert scene.steps_done == 120
    assert np.array_equal(scene.displacement(), np.array(artifact["displacement"]))
    assert np.array_equal(scene.velocity(), np.array(artifact["velocity"]))
    reactions = scene.reactions()
    for item in artifact["reactions"]:
        assert np.array_equal(reactions[item["name"]], np.array(item["force"]))
    energies = scene.energies()
    assert np.array_equal(energies["strain"], np.array(artifact["energies"]["strain"]))
    # A Mesh object instead of the path: the same scene.
    same = softsim.Scene({k: v for k, v in config.items() if k != "mesh"}, mesh)
    same.step(120)
    assert np.array_equal(same.displacement(), scene.displacement())


def test_element_kinds_are_the_artifacts_legend(block, tmp_path):
    """softsim.ELEMENT_KIND_LEGEND is the dhd_result artifact's legend (one table in the engine),
    and Scene.element_kind uses its codes."""
    mesh, mesh_path = block
    config = block_config(str(mesh_path), steps=2)
    artifact = payload(make_artifact("dhd_sim", config, tmp_path))
    assert softsim.ELEMENT_KIND_LEGEND == artifact["element_kind_legend"]
    names = [k["name"] for k in softsim.ELEMENT_KIND_LEGEND]
    assert "anp" in names and len(set(names)) == len(names)
    scene = softsim.Scene(config)
    assert np.array_equal(scene.element_kind, np.array(artifact["element_kind"]))
    for code, name in enumerate(names):
        assert f"{code} {name}" in softsim.Scene.element_kind.__doc__
        assert artifact["element_counts"][name] == int((scene.element_kind == code).sum())


def test_probe_moved_between_steps_settles_on_the_static_solution(block):
    """Dynamic relaxation: a tip moved to its place over many 1 ms frames in a damped body ends
    at the Newton equilibrium of the same tip position (000 eq. 24), force included."""
    mesh, _ = block
    probe = {"nearest": [0.02, 0.015, 0.03], "stiffness": 30.0, "displacement": [0, 0, 0]}
    config = {
        "material": {"model": "neo_hookean_decoupled", "E": 5000, "nu": 0.35, "density": 1000},
        "damping": {"alpha": 60.0},
        "boundary": {"fixed": ["bottom"], "probe": probe},
        "solver": {"kind": "explicit"},
    }
    scene = softsim.Scene(config, mesh)
    start = scene.probe_position.copy()
    target = start + np.array([0.0, 0.0, -0.004])
    frame_steps = max(1, int(round(1e-3 / scene.dt)))
    depth_force = []
    for k in range(400):
        scene.probe_position = start + min(1.0, k / 200) * (target - start)
        scene.step(frame_steps)
        depth_force.append(-scene.probe_force()[2])
    scene.step(4000)
    static = softsim.solve_static(mesh, dict(config, boundary={"fixed": ["bottom"],
                                                               "probe": dict(probe, displacement=[0, 0, -0.004])},
                                             solver={"kind": "static", "increments": 4}))
    scale = np.abs(static.displacement).max()
    assert np.abs(scene.displacement() - static.displacement).max() < 1e-6 * scale
    force_gap = np.linalg.norm(scene.probe_force() - static.probe_force)
    assert force_gap < 1e-5 * np.linalg.norm(static.probe_force)
    # Pressing deeper never pulls the tool in: the force on it grows along the press.
    assert depth_force[199] > depth_force[100] > depth_force[20] > 0


def test_displacement_view_is_in_place_and_read_only(block):
    mesh, _ = block
    scene = softsim.Scene({k: v for k, v in block_config().items() if k != "mesh"}, mesh)
    scene.step(10)
    view = scene.displacement(copy=False)
    copy = scene.displacement()
    assert not view.flags.writeable
    assert not np.shares_memory(view, copy) and np.array_equal(view, copy)
    assert np.shares_memory(view, scene.displacement(copy=False))
    with pytest.raises(ValueError):
        view[0, 0] = 1.0
    scene.step(1)
    assert not np.array_equal(scene.displacement(), copy)


def test_errors_carry_the_executables_messages(block):
    mesh, _ = block
    bad = {k: v for k, v in block_config().items() if k != "mesh"}
    bad["solver"] = dict(bad["solver"], stepz=3)
    with pytest.raises(softsim.InputError, match=r"<dict>.*/solver/stepz"):
        softsim.Scene(bad, mesh)
    scene = softsim.Scene({k: v for k, v in block_config().items() if k != "mesh"}, mesh)
    with pytest.raises(softsim.InputError, match="no constraint named"):
        scene.set_prescribed_displacement("nowhere", [0, 0, 0])
    unstable = {k: v for k, v in block_config().items() if k != "mesh"}
    unstable["solver"] = {"kind": "explicit", "dt": 50 * scene.critical_dt, "force_dt": True, "energy_interval": 5}
    blowing = softsim.Scene(unstable, mesh)
    with pytest.raises(softsim.NumericalError, match="explicit step"):
        blowing.step(2000)
    static = dict(unstable, solver={"kind": "static"})
    with pytest.raises(softsim.InputError, match="static"):
        softsim.Scene(static, mesh).step(1)


def test_stepping_releases_the_gil(block):
    """Another Python thread runs while a long step() is in C++."""
    mesh, _ = block
    scene = softsim.Scene({k: v for k, v in block_config().items() if k != "mesh"}, mesh)
    worker = threading.Thread(target=scene.step, args=(60000,))
    ticks = 0
    worker.start()
    while worker.is_alive():
        ticks += 1
    worker.join()
    assert scene.steps_done == 60000
    # With the GIL held for the whole step the loop above could not run while it lasted.
    assert ticks > 1000


def test_the_press_liver_walkthrough_runs(tmp_path):
    """The README's walkthrough script: the liver pressed 1 cm, force against depth plotted."""
    import os
    import subprocess
    import sys
    from pathlib import Path

    root = Path(__file__).resolve().parents[2]
    out = tmp_path / "press.png"
    r = subprocess.run([sys.executable, str(root / "cpp/python/examples/press_liver.py"), str(out)], cwd=root,
                       capture_output=True, text=True, env=dict(os.environ), timeout=600)
    assert r.returncode == 0, r.stderr
    assert out.stat().st_size > 0
    held = float(r.stdout.split("force at 1 cm:")[1].split()[0])
    assert held > 0  # the tissue pushes back on the tool
