"""The CalculiX contact reference's deck (the block's top faces as the slave surface, a positive
rigid sphere cap as the master) and strict config, and the contact_calculix and contact_search
reports' sentences following their runs."""
import numpy as np
import pytest

from pipeline.config_reader import ConfigError
from pipeline.reports import contact_calculix, contact_hertz, contact_search
from pipeline.stages import calculix_contact
from report_ctx import FakeContext, run

R, E, NU = 0.02, 5000.0, 0.35


def cube_mesh():
    """One unit cube of 5 tets, positively oriented, with bottom and top node sets."""
    nodes = [[x, y, z] for z in (0.0, 1.0) for y in (0.0, 1.0) for x in (0.0, 1.0)]
    tets = [[0, 1, 3, 5], [0, 3, 2, 6], [0, 5, 6, 4], [3, 6, 5, 7], [0, 3, 6, 5]]
    p = np.array(nodes)
    for t in tets:
        a, b, c, d = p[t]
        assert np.dot(np.cross(b - a, c - a), d - a) > 0
    return {"nodes": nodes, "tets": tets, "node_sets": {"bottom": [0, 1, 2, 3], "top": [4, 5, 6, 7]}}


def config(**changes):
    c = {"mesh": "m.json", "material": {"model": "neo_hookean_decoupled", "E": E, "nu": NU},
         "sphere": {"radius": 0.5, "lowest_point": [0.5, 0.5, 1.0], "depth": 0.1, "subdivisions": 2},
         "penalty": 1e9}
    c.update(changes)
    return c


def test_deck_has_the_top_faces_as_slave_and_a_positive_rigid_cap_as_master():
    mesh = cube_mesh()
    cfg = calculix_contact.read_config(config())
    nodes, tets = np.array(mesh["nodes"], float), np.array(mesh["tets"])
    deck, ref, cap = calculix_contact.build_deck(nodes, tets, mesh["node_sets"], cfg)
    lines = deck.splitlines()
    slave = lines[lines.index("*SURFACE, NAME=BLOCKTOP, TYPE=ELEMENT") + 1:lines.index("*SURFACE, NAME=SPHERESURF, TYPE=ELEMENT")]
    assert len(slave) == 2  # the top square's two triangles
    for entry in slave:
        e, face = entry.split(", ")
        corners = calculix_contact.C3D4_FACES[int(face[1:]) - 1]
        assert all(mesh["tets"][int(e) - 1][k] in mesh["node_sets"]["top"] for k in corners)
    # Every sphere tet is positive (CalculiX stops at a non-positive Jacobian).
    coords = {}
    for line in lines:
        parts = line.split(", ")
        if len(parts) == 4 and parts[0].isdigit() and "." in parts[1]:
            coords[int(parts[0])] = np.array([float(v) for v in parts[1:]])
    start = lines.index("*ELEMENT, TYPE=C3D4, ELSET=SPHERE") + 1
    for line in lines[start:start + cap]:
        a, b, c, d = (coords[int(v)] for v in line.split(", ")[1:])
        assert np.dot(np.cross(b - a, c - a), d - a) > 0
    assert f"*RIGID BODY, ELSET=SPHERE, REF NODE={ref}, ROT NODE={ref + 1}" in lines
    assert "*CONTACT PAIR, INTERACTION=TOUCH, TYPE=SURFACE TO SURFACE" in lines
    assert f"{ref}, 3, 3, -0.1" in lines


def test_config_is_strict():
    with pytest.raises(ConfigError, match="/sphere/radius"):
        calculix_contact.read_config(config(sphere={"radius": -1, "lowest_point": [0, 0, 0], "depth": 0.1}))
    with pytest.raises(ConfigError, match="/material"):
        calculix_contact.read_config(config(material={"model": "linear", "E": E, "nu": NU}))
    with pytest.raises(ConfigError, match="stiffness"):
        calculix_contact.read_config(config(stiffness=3))


def ours_run(mesh, scale):
    t = np.linspace(0.0, 1.2, 601)
    s = np.clip(t, 0, 1)
    depth = 0.002 * s * s * (3 - 2 * s)
    force = scale * contact_hertz.hertz_force(depth, R, E, NU)
    payload = {"tools": [{"time": t.tolist(), "force": [[0.0, 0.0, f] for f in force], "contacts": [9] * len(t)}]}
    cfg = {"mesh": mesh, "material": {"E": E, "nu": NU},
           "boundary": {"tools": [{"radius": R, "travel": [0, 0, -0.002], "ramp_time": 1.0, "ramp": "smooth"}]}}
    return run(payload, cfg)


def ccx_run(mesh, tets, scale):
    d = np.linspace(0, 0.002, 11)
    payload = {"depth": d.tolist(), "force": (scale * contact_hertz.hertz_force(d, R, E, NU)).tolist(),
               "element_count": tets, "ccx_version": "2.20", "sphere_cap_elements": 100, "penalty": 1e9,
               "analysis": {"increments_taken": 10, "iterations": 40}, "wall_time_s": 3.0}
    return run(payload, {"mesh": mesh})


def test_calculix_report_states_the_ratios_of_each_mesh(tmp_path):
    ctx = FakeContext(tmp_path, runs={"ours": [ours_run("b", 1.0), ours_run("a", 1.0)],
                                      "ccx": [ccx_run("a", 2500, 2.0), ccx_run("b", 20000, 1.25)]})
    contact_calculix.report(ctx)
    text = (tmp_path / "calculix_summary.md").read_text()
    assert "2500 tets: at 2 mm" in text and "ours / CalculiX = 0.5;" in text
    assert "20000 tets" in text and "ours / CalculiX = 0.8;" in text
    assert "goes from 0.5 on the coarsest mesh to 0.8 on the finest" in text
    assert (tmp_path / "calculix.png").exists()


def search_run(mode, contact_seconds, force):
    payload = {"timing": {"contact_seconds": contact_seconds, "steps": 1000, "steps_per_second": 500.0},
               "tools": [{"force": [[0, 0, 0], force], "nodes": 4000, "contacts": [0, 12]}], "mesh": {"tets": 12007}}
    return run(payload, sweep={"solver.contact_search": mode})


def test_search_report_says_whether_the_forces_agree(tmp_path):
    same = {"liver_press": [search_run("grid", 0.01, [0, 0, 0.5]), search_run("all", 0.05, [0, 0, 0.5])],
            "cuboid_press": [search_run("grid", 0.02, [0, 0, 0.1]), search_run("all", 0.02, [0, 0, 0.2])]}
    contact_search.report(FakeContext(tmp_path, runs=same))
    text = (tmp_path / "search_summary.md").read_text()
    assert "liver: 4000 boundary nodes, 12 in contact" in text
    assert "50 µs per step testing every node and 10 µs with the grid (5× less)" in text
    assert text.count("the same bit for bit") == 1 and "NOT the same" in text
