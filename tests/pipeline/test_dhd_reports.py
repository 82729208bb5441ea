"""The Python logic of the DHD-FEA experiments on small synthetic data: the error metric, the
Pareto front, the split bookkeeping (what a run asked for against what it realised, the
all-TLED reference of each load), the cost model and the timing schedule, the placement of the
paper's points, node-set selection, the cut-open picture, the summary, and the consistency of the
experiment files that share runs through the cache."""
import json
from types import SimpleNamespace

import numpy as np
import pytest

from conftest import ROOT
from pipeline.config_reader import ConfigError
from pipeline.reports import dhd_common as common
from pipeline.stages import dhd_node_sets as node_sets
from report_ctx import FakeContext, run


# --------------------------------------------------------------------------- a small cuboid
def cuboid(nx=4, ny=4, nz=3, h=0.01):
    """The paper's 5-tet split (alternating with the parity of i + j + k), built here
    independently of the mesher, with the "layer" tag and the boundary triangles."""
    idx = lambda i, j, k: i + (nx + 1) * (j + (ny + 1) * k)
    nodes = np.array([[i * h, j * h, k * h] for k in range(nz + 1) for j in range(ny + 1)
                      for i in range(nx + 1)], dtype=float)
    tets, layer = [], []
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                c = [idx(i + a, j + b, k + d) for d in (0, 1) for b in (0, 1) for a in (0, 1)]
                # corners: 0 (000) 1 (100) 2 (010) 3 (110) 4 (001) 5 (101) 6 (011) 7 (111)
                if (i + j + k) % 2 == 0:
                    cells = [(0, 1, 2, 4), (1, 3, 2, 7), (1, 4, 5, 7), (2, 4, 7, 6), (1, 2, 4, 7)]
                else:
                    cells = [(0, 1, 3, 5), (0, 3, 2, 6), (0, 5, 4, 6), (3, 5, 6, 7), (0, 3, 5, 6)]
                for t in cells:
                    tet = [c[q] for q in t]
                    x = nodes[tet]
                    if np.linalg.det(np.stack([x[1] - x[0], x[2] - x[0], x[3] - x[0]], 1)) < 0:
                        tet[1], tet[2] = tet[2], tet[1]
                    tets.append(tet)
                    layer.append(k)
    tets = np.array(tets)
    faces = {}
    for t in tets:
        for f in ((t[1], t[2], t[3]), (t[0], t[2], t[3]), (t[0], t[1], t[3]), (t[0], t[1], t[2])):
            faces.setdefault(tuple(sorted(f)), []).append(f)
    boundary = [v[0] for v in faces.values() if len(v) == 1]
    # Orient outward: the normal points away from the box centre.
    centre = nodes.mean(axis=0)
    oriented = []
    for f in boundary:
        p = nodes[list(f)]
        n = np.cross(p[1] - p[0], p[2] - p[0])
        f = [int(v) for v in f]
        oriented.append(f if n @ (p.mean(axis=0) - centre) > 0 else [f[0], f[2], f[1]])
    return {"nodes": nodes.tolist(), "tets": tets.tolist(), "boundary": oriented,
            "node_sets": {}, "element_tags": {"layer": layer}, "units": "m"}


@pytest.fixture(scope="module")
def mesh():
    return cuboid()


# --------------------------------------------------------------------------- error metric
def test_error_metric_is_zero_for_identical_fields_and_scale_free():
    rng = np.random.default_rng(1)
    u_ref = rng.normal(size=(50, 3))
    assert common.displacement_error(u_ref, u_ref)["rel_mean"] == 0.0
    u = u_ref + 0.1 * rng.normal(size=(50, 3))
    e1 = common.displacement_error(u, u_ref, applied=1.0)
    e2 = common.displacement_error(7.0 * u, 7.0 * u_ref, applied=7.0)   # another length unit
    for key in ("rel_mean", "rel_applied", "rel_rms", "rel_max", "rel_per_node"):
        assert e1[key] == pytest.approx(e2[key], rel=1e-12)


def test_error_metric_matches_hand_computation_and_ignores_fixed_nodes():
    u_ref = np.array([[0, 0, -1.0], [0, 0, -0.5], [0, 0, 0]])
    u = np.array([[0, 0, -0.9], [0.0, 0.2, -0.5], [0, 0, 0]])
    e = common.displacement_error(u, u_ref, applied=1.0)
    assert e["rel_mean"] == pytest.approx((0.1 + 0.2) / 1.5)
    assert e["rel_applied"] == pytest.approx(0.1)          # mean |Δu| = 0.3 / 3 nodes
    assert e["rel_per_node"] == pytest.approx((0.1 / 1.0 + 0.2 / 0.5) / 2)   # fixed node excluded
    # Adding more fixed nodes (zero in both fields) leaves the primary metric unchanged.
    pad = np.zeros((10, 3))
    e_pad = common.displacement_error(np.vstack([u, pad]), np.vstack([u_ref, pad]))
    assert e_pad["rel_mean"] == pytest.approx(e["rel_mean"])


def test_error_metric_rejects_a_zero_reference_and_mismatched_shapes():
    with pytest.raises(ValueError):
        common.displacement_error(np.ones((3, 3)), np.zeros((3, 3)))
    with pytest.raises(ValueError):
        common.displacement_error(np.ones((3, 3)), np.ones((4, 3)))


# --------------------------------------------------------------------------- Pareto front
def test_pareto_front_keeps_exactly_the_non_dominated_points():
    times = [1.0, 2.0, 3.0, 1.5, 2.5, 3.0, 0.5]
    errors = [0.5, 0.3, 0.1, 0.6, 0.3, 0.2, 0.9]
    front = common.pareto_front(times, errors)
    assert front == [6, 0, 1, 2]
    # Brute force: a point is on the front iff no other point is ≤ in both and < in one.
    for i in range(len(times)):
        dominated = any(times[j] <= times[i] and errors[j] <= errors[i]
                        and (times[j] < times[i] or errors[j] < errors[i]) for j in range(len(times)))
        assert (i in front) == (not dominated)


def test_pareto_front_of_a_monotone_trade_off_is_everything():
    t = np.linspace(1, 2, 6)
    assert common.pareto_front(t, 1.0 / t) == list(range(6))


# --------------------------------------------------------------------------- split bookkeeping
# A legend of the artifact's shape. Its order differs from the engine's on purpose: the reports
# must take every name from the artifact, not from codes they know.
LEGEND = [{"name": "tled", "small_strain": False, "description": "TLED"},
          {"name": "linear", "small_strain": True, "description": "linear"},
          {"name": "anp", "small_strain": False, "description": "average nodal pressure"},
          {"name": "corotational", "small_strain": True, "description": "corotational"}]
LIN, TLED, ANP, COROT = 1, 0, 2, 3


def sim_payload(kinds, **more):
    return dict({"element_kind": list(kinds), "element_kind_legend": LEGEND}, **more)


def fake_run(partition, kinds, applied=(0, 0, -0.006), steps_per_second=1000.0, u=None, stage="sim"):
    config = {"partition": partition,
              "boundary": {"fixed": ["bottom"], "prescribed": [{"nearest": [0, 0, 0], "displacement": list(applied)}]}}
    payload = sim_payload(kinds, timing={"steps_per_second": steps_per_second},
                          displacement=(u if u is not None else np.zeros((3, 3))).tolist())
    return SimpleNamespace(config=config, payload=payload, sweep={}, stage=stage)


@pytest.mark.parametrize("partition, strategy, r, cheap", [
    ({"linear_fraction": 0.3}, "distance", 0.3, "linear"),
    ({"kind": "linear_fraction", "linear_fraction": 0.3, "distance": "depth"}, "layer", 0.3, "linear"),
    ({"kind": "strain", "linear_fraction": 0.2, "linear_element": "corotational"}, "strain", 0.2, "corotational"),
    ({"kind": "uniform", "element": "linear"}, "uniform", 1.0, "linear"),
    ({"kind": "uniform", "element": "corotational"}, "uniform", 1.0, "corotational"),
    ({"kind": "uniform", "element": "anp"}, "uniform", 0.0, "linear"),
    ({}, "uniform", 0.0, "linear"),
    ({"kind": "layers", "nonlinear_layers": 3}, "layers", None, "linear"),
])
def test_describe_partition_reads_the_engine_config(partition, strategy, r, cheap):
    d = common.describe_partition(partition, ["linear", "corotational"])
    assert (d["strategy"], d["requested_r"], d["cheap_kind"]) == (strategy, r, cheap)


def test_split_record_counts_and_checks_the_realised_share():
    kinds = [LIN] * 3 + [TLED] * 7
    rec = common.split_record(fake_run({"linear_fraction": 0.3}, kinds).config, sim_payload(kinds))
    assert (rec["cheap_elements"], rec["tled_elements"], rec["elements"]) == (3, 7, 10)
    assert rec["r"] == pytest.approx(0.3)
    # round(r · m) with halves up: r = 0.25 of 10 elements is 3 cheap elements, not 2.
    with pytest.raises(ValueError):
        common.split_record({"partition": {"linear_fraction": 0.25}}, sim_payload([LIN] * 2 + [TLED] * 8))
    common.split_record({"partition": {"linear_fraction": 0.25}}, sim_payload(kinds))
    # A corotational run must not contain linear elements, and the other way round.
    with pytest.raises(ValueError):
        common.split_record({"partition": {"linear_fraction": 0.3, "linear_element": "corotational"}},
                            sim_payload(kinds))
    rec = common.split_record({"partition": {"linear_fraction": 0.3, "linear_element": "corotational"}},
                              sim_payload([COROT] * 3 + [TLED] * 7))
    assert rec["counts"] == {"linear": 0, "tled": 7, "corotational": 3, "anp": 0}


def test_split_record_counts_anp_elements_by_the_legend():
    # ANP is the nonlinear kind here: counted under its name, never dropped, never cheap.
    kinds = [LIN] * 4 + [ANP] * 6
    partition = {"linear_fraction": 0.4, "nonlinear_element": "anp"}
    rec = common.split_record({"partition": partition}, sim_payload(kinds))
    assert rec["counts"] == {"tled": 0, "linear": 4, "anp": 6, "corotational": 0}
    assert (rec["cheap_elements"], rec["tled_elements"], rec["elements"]) == (4, 6, 10)
    assert rec["r"] == pytest.approx(0.4) and rec["nonlinear_kind"] == "anp"
    # A uniform ANP run is an all-nonlinear reference (r = 0), not an all-cheap one.
    rec = common.split_record({"partition": {"kind": "uniform", "element": "anp"}}, sim_payload([ANP] * 5))
    assert (rec["r"], rec["cheap_elements"], rec["nonlinear_kind"]) == (0.0, 0, "anp")
    # ANP elements in a run that asked for TLED ones are a mismatch, not silently ignored.
    with pytest.raises(ValueError, match="anp"):
        common.split_record({"partition": {"linear_fraction": 0.4}}, sim_payload(kinds))
    # Each element's name comes from the legend; a code beyond it is an error.
    assert list(common.element_kind_names(sim_payload([ANP, LIN, COROT, TLED]))) == \
        ["anp", "linear", "corotational", "tled"]
    with pytest.raises(ValueError, match="legend"):
        common.kind_counts(sim_payload([0, 4]))
    with pytest.raises(ValueError, match="element_kind_legend"):
        common.kind_counts({"element_kind": [0, 1]})


def test_the_engine_artifact_legend_names_every_kind_and_reports_read_it(tmp_path):
    """dhd_sim's own artifact: an ANP run realises its split under the legend's names."""
    from conftest import run_tool, write_json
    cfg = {"source": {"kind": "cuboid", "cells": [2, 2, 2], "size": [0.02, 0.02, 0.02]}}
    r = run_tool("mesher", "--config", write_json(tmp_path / "m.json", cfg), "--out", tmp_path / "mesh.json")
    assert r.returncode == 0, r.stderr
    sim = {"mesh": str(tmp_path / "mesh.json"),
           "partition": {"kind": "linear_fraction", "linear_fraction": 0.5, "nonlinear_element": "anp",
                         "linear_element": "corotational"},
           "boundary": {"fixed": ["bottom"], "prescribed": [{"set": "top", "displacement": [0, 0, -0.001]}]},
           "solver": {"steps": 3}}
    r = run_tool("dhd_sim", "--config", write_json(tmp_path / "s.json", sim), "--out", tmp_path / "out.json")
    assert r.returncode == 0, r.stderr
    payload = json.loads((tmp_path / "out.json").read_text())["payload"]
    names = common.kind_names(payload)
    assert set(names) >= {"linear", "tled", "corotational", "anp"}
    assert len(set(names)) == len(names)
    rec = common.split_record(sim, payload)
    assert rec["counts"]["anp"] == rec["tled_elements"] == 20 and rec["counts"]["corotational"] == 20
    assert rec["r"] == pytest.approx(0.5)
    assert payload["element_counts"] == dict(rec["counts"], linear_fraction=0.5)


def test_errors_are_taken_against_the_all_tled_run_of_the_same_load():
    rng = np.random.default_rng(3)
    u06, u10 = rng.normal(size=(3, 3)), rng.normal(size=(3, 3))
    rows = []
    for applied, u_ref in (((0, 0, -0.006), u06), ((0, 0, -0.01), u10)):
        for r, kinds, du, sps in ((0.0, [TLED] * 10, 0.0, 1000.0), (0.5, [LIN] * 5 + [TLED] * 5, 0.1, 1500.0)):
            run = fake_run({"linear_fraction": r}, kinds, applied, sps, u_ref + du)
            rows.append(dict(common.split_record(run.config, run.payload), run=run, stage="sim",
                             applied=common.applied_length(run.config)))
    by_load = common.errors_against_reference(rows)
    assert sorted(by_load) == [0.006, 0.01]
    for load, u_ref in ((0.006, u06), (0.01, u10)):
        ref, half = by_load[load]
        assert ref["error"]["rel_mean"] == 0.0
        expected = common.displacement_error(u_ref + 0.1, u_ref, applied=load)
        assert half["error"]["rel_mean"] == pytest.approx(expected["rel_mean"])
        assert half["ref_seconds_per_step"] / half["seconds_per_step"] == pytest.approx(1.5)
    with pytest.raises(ValueError):   # a load without its all-TLED run
        common.errors_against_reference(rows[1:2])


def test_speedup_within_an_error_budget_interpolates_between_shares():
    from pipeline.reports.dhd_partition import best_speedup_within
    pts = [(1.0, 0.0), (1.2, 0.04), (1.5, 0.10), (2.0, 0.30)]
    assert best_speedup_within(pts, 0.04) == pytest.approx(1.2)
    assert best_speedup_within(pts, 0.07) == pytest.approx(1.35)
    assert best_speedup_within(pts, 1.0) == pytest.approx(2.0)
    assert best_speedup_within([(1.0, 0.05), (1.3, 0.2)], 0.01) is None


def test_at_share_matches_the_engine_rounding():
    row = {"cheap_elements": 5932, "elements": 11863}
    assert common.at_share(row, 0.5) and not common.at_share(row, 0.4)


# --------------------------------------------------------------------------- timing and costs
def test_cost_model_reproduces_the_uniform_runs_and_mixes_by_share():
    timing = {"runs": [
        {"threads": 1, "steps_per_second": 1000.0, "counts": {"linear": 0, "tled": 100, "corotational": 0}},
        {"threads": 1, "steps_per_second": 2000.0, "counts": {"linear": 100, "tled": 0, "corotational": 0}},
        {"threads": 1, "steps_per_second": 100.0, "counts": {"linear": 0, "tled": 0, "corotational": 100}},
        {"threads": 1, "steps_per_second": 1300.0, "counts": {"linear": 50, "tled": 50, "corotational": 0}},
        {"threads": 2, "steps_per_second": 9999.0, "counts": {"linear": 0, "tled": 100, "corotational": 0}},
    ]}
    uniform, mixed = common.cost_model(timing)
    assert uniform == {"tled": 1e-3, "linear": 5e-4, "corotational": 1e-2}   # one thread only
    (run, measured, modelled), = mixed
    assert measured == pytest.approx(1 / 1300.0) and modelled == pytest.approx(0.75e-3)
    assert common.model_time(uniform, {"tled": 30, "corotational": 10}) == pytest.approx(0.75 * 1e-3 + 0.25 * 1e-2)


def test_timing_schedule_interleaves_every_partition_in_every_round_and_rotates_the_start():
    from pipeline.stages.dhd_timing import schedule
    order = schedule(3, [1], 3)
    assert len(order) == 9
    for rnd in range(3):
        assert sorted(k for r, _, k in order if r == rnd) == [0, 1, 2]
    assert [order[3 * rnd][2] for rnd in range(3)] == [0, 1, 2]


def test_relative_cost_recovers_a_linear_cost_law():
    from pipeline.reports.dhd_table1 import relative_cost
    r = np.linspace(0, 1, 11)
    assert relative_cost(r, 2.0 * ((1 - r) + 0.3 * r)) == pytest.approx(0.3)
    # The paper's Table 1 frame rates imply cheap linear elements (c well below 1).
    rates = {0: 22, 10: 24, 20: 28, 30: 32, 40: 34, 50: 40}
    c = relative_cost([k / 100 for k in rates], [1 / f for f in rates.values()])
    assert 0.0 < c < 0.2


def test_paper_points_sit_at_the_frame_time_ratio_and_the_table_error():
    from pipeline.reports.dhd_pareto import paper_points
    paper = {"table1": {"linear_fraction_percent": [0, 10, 20, 30, 40, 50], "frame_rate_hz": [22, 24, 28, 32, 34, 40]},
             "table2": {"applied_displacement": 0.6, "linear_fraction_percent": [10, 20, 30, 40],
                        "mean_error_percent": [5.7, 9.5, 14.5, 22.7]}}
    pts = paper_points(paper)[0.6]
    assert pts[0] == pytest.approx((22 / 24, 0.057, 10))
    assert pts[-1] == pytest.approx((22 / 34, 0.227, 40))


# --------------------------------------------------------------------------- node sets
def test_node_set_selectors(mesh):
    x = np.asarray(mesh["nodes"])
    b = np.asarray(mesh["boundary"])
    low = node_sets.select({"select": "half_space", "point_in_box": [0.25, 0, 0], "normal": [-1, 0, 0]}, x, b)
    assert np.array_equal(low, np.flatnonzero(x[:, 0] <= 0.01 + 1e-12))
    ball = node_sets.select({"select": "sphere", "point": [0.02, 0.02, 0.03], "radius": 0.0101}, x, b)
    assert len(ball) == 6   # the top-centre node, its 4 neighbours on the top face, 1 below
    # Nearest boundary node to a point above the top face: the top-centre node.
    top = node_sets.select({"select": "nearest", "point_in_box": [0.5, 0.5, 2.0], "boundary_only": True}, x, b)
    assert np.allclose(x[top[0]], [0.02, 0.02, 0.03])
    # boundary_only excludes interior nodes (an empty selection is an error).
    inner = node_sets.select({"select": "sphere", "point": [0.02, 0.02, 0.01], "radius": 0.001}, x, b)
    assert len(inner) == 1
    with pytest.raises(ConfigError, match="/sets/inner: expected a selector that picks at least one node"):
        node_sets.select({"select": "sphere", "point": [0.02, 0.02, 0.01], "radius": 0.001,
                          "boundary_only": True}, x, b, "/sets/inner")


def test_vertex_normals_point_outward(mesh):
    x = np.asarray(mesh["nodes"])
    n = node_sets.vertex_normals(x, np.asarray(mesh["boundary"]))
    top_centre = int(np.flatnonzero(np.all(np.isclose(x, [0.02, 0.02, 0.03]), axis=1))[0])
    assert np.allclose(n[top_centre], [0, 0, 1])
    interior = int(np.flatnonzero(np.all(np.isclose(x, [0.02, 0.02, 0.01]), axis=1))[0])
    assert np.allclose(n[interior], 0)


def test_add_node_sets_records_and_refuses_duplicates(mesh):
    out, rec = node_sets.add_node_sets(mesh, {"push": {"select": "nearest", "point_in_box": [0.5, 0.5, 2.0],
                                                       "boundary_only": True}})
    assert rec["push"]["count"] == 1 and np.allclose(rec["push"]["outward_normal"], [0, 0, 1])
    assert "push" in out["node_sets"] and "push" not in mesh["node_sets"]
    with pytest.raises(ConfigError, match="/sets/push: expected a name the mesh does not already use"):
        node_sets.add_node_sets(out, {"push": {"select": "nearest", "point": [0, 0, 0]}})
    with pytest.raises(ConfigError, match='/sets/bad: expected no key "colour"'):
        node_sets.add_node_sets(mesh, {"bad": {"select": "sphere", "point": [0, 0, 0], "radius": 1,
                                               "colour": 2}})
    # A key of another selector is unknown to this one; a selector needs exactly one point.
    with pytest.raises(ConfigError, match='/sets/bad: expected no key "radius"'):
        node_sets.add_node_sets(mesh, {"bad": {"select": "nearest", "point": [0, 0, 0], "radius": 1}})
    with pytest.raises(ConfigError, match='/sets/bad: expected exactly one of "point" and "point_in_box"'):
        node_sets.add_node_sets(mesh, {"bad": {"select": "nearest", "point": [0, 0, 0], "point_in_box": [0, 0, 0]}})
    with pytest.raises(ConfigError, match="/sets/bad/normal: expected a non-zero vector"):
        node_sets.add_node_sets(mesh, {"bad": {"select": "half_space", "point": [0, 0, 0], "normal": [0, 0, 0]}})
    with pytest.raises(ConfigError, match="/sets/bad/select: expected one of"):
        node_sets.add_node_sets(mesh, {"bad": {"select": "cube", "point": [0, 0, 0]}})


# --------------------------------------------------------------------------- pictures and summary
def test_boundary_owner_finds_the_tet_of_each_face(mesh):
    tets = np.asarray(mesh["tets"])
    owner = common.boundary_owner(tets, np.asarray(mesh["boundary"]))
    for f, e in zip(mesh["boundary"], owner):
        assert set(f) <= set(tets[e])


def test_cut_open_boundary_is_a_closed_surface(mesh):
    from pipeline.reports.dhd_fig9 import half_boundary
    x, t = np.asarray(mesh["nodes"]), np.asarray(mesh["tets"])
    for keep_below in (None, 0.02):
        tri, keep = half_boundary(x, t, axis=1, keep_below=keep_below)
        edges = {}
        for f in tri:
            for a, b in ((f[0], f[1]), (f[1], f[2]), (f[2], f[0])):
                edges[tuple(sorted((int(a), int(b))))] = edges.get(tuple(sorted((int(a), int(b)))), 0) + 1
        assert set(edges.values()) == {2}          # every edge shared by two faces: closed
    # The half block: the 4 × 2 × 3 cells below y = 2 cm, cut face included.
    tri, keep = half_boundary(x, t, axis=1, keep_below=0.02)
    assert len(keep) == 5 * 4 * 2 * 3
    assert len(tri) == 2 * 2 * (4 * 2 + 4 * 3 + 2 * 3)   # two triangles per cell face on the surface


def test_verdict_speaks_only_of_what_was_measured():
    assert common.verdict({}) == ""
    text = common.verdict({"table2": {"settled_10_40": {"1 cm": [0.05, 0.1]}, "paper_10_40": {"1 cm": [5.8, 9.8]},
                                      "transient_10_40": {}, "larger_load_larger": True}})
    assert "5.8–9.8 %" in text and "Table 1" not in text and "speed" not in text
    text = common.verdict({"table1": {"speedup_50_ours": 1.05, "speedup_50_paper": 40 / 22, "c_ours": 0.9,
                                      "c_paper": 0.07, "ns_tled": 5.0, "ns_linear": 4.5, "node_ns": 11.0,
                                      "steps_per_second_tled": 5000.0}})
    assert "our step is 1.05 times as fast as all-TLED, against the paper's 1.82" in text
    assert "4.5 ns against 5 ns for TLED (0.9×" in text and "11 ns per node of an all-TLED mesh)" in text
    text = common.verdict({"table1": {"speedup_50_ours": 1.4, "speedup_50_paper": 40 / 22, "c_ours": 0.44,
                                      "c_paper": 0.07, "ns_tled": 5.75, "ns_linear": 3.04, "node_ns": 14.3,
                                      "node_ns_linear": 4.6, "steps_per_second_tled": 7500.0}})
    assert "3.04 ns against 5.75 ns for TLED (0.53×" in text and "4.6 ns of an all-linear one" in text


def test_summary_is_assembled_in_a_fixed_order(tmp_path):
    ctx = FakeContext(tmp_path)
    common.write_section(ctx, "liver", "### liver part")
    common.write_section(ctx, "table1", "### table 1 part")
    text = (tmp_path / "summary.md").read_text()
    assert text.startswith("## DHD-FEA")
    assert text.index("table 1 part") < text.index("liver part")


# --------------------------------------------------------------------------- experiment files
def _stages(name):
    path = ROOT / "experiments" / f"{name}.json"
    if not path.exists():
        pytest.skip(f"{path.name} not present")
    return json.loads(path.read_text())["stages"]


def test_runs_shared_between_experiments_are_defined_once():
    """dhd_partition, dhd_pareto and dhd_fig9 run stages of dhd_table2 (and each other) so that
    the cache computes them once: each such stage is defined in one experiment and included by
    {"ref": ...} in the others (pipeline/EXPERIMENTS.md), so it cannot drift between them."""
    from pipeline import experiment as experiment_mod
    names = ["dhd_table2", "dhd_partition", "dhd_pareto", "dhd_fig9"]
    stages = {n: _stages(n) for n in names}
    defined = {}
    for n in names:
        for s, spec in stages[n].items():
            if "report" not in spec and "ref" not in spec:
                defined.setdefault(s, []).append(n)
    for n in names:
        exp = experiment_mod.load(n)
        for s in stages[n]:
            if "report" in stages[n][s]:
                continue
            assert len(defined.get(s, [])) <= 1, f"stage {s!r} is defined in {defined[s]}: define it once, ref it"
            origin = experiment_mod.origin(exp, s)
            # The run an experiment makes of a shared stage is the defining experiment's run.
            owner, stage = origin.split(".")
            if owner != n:
                ref = experiment_mod.load(owner)
                assert [exp.runs[r].config for r in exp.stage_runs[s]] == \
                    [ref.runs[r].config for r in ref.stage_runs[stage]]


def test_paper_numbers_are_copied_verbatim():
    path = ROOT / "experiments" / "dhd_table2.json"
    if not path.exists():
        pytest.skip("dhd_table2.json not present")
    paper = json.loads(path.read_text())["paper"]
    assert paper["table2"]["mean_error_percent"] == [5.7, 9.5, 14.5, 22.7]
    assert paper["table3"]["mean_error_percent"] == [5.8, 9.8, 15.1, 23.7]


def test_node_set_stage_writes_a_mesh_the_engine_can_read(tmp_path, mesh):
    from pipeline.artifacts import read_artifact, write_artifact
    src = tmp_path / "mesh.json"
    write_artifact(src, "tet_mesh", 1, "test", {}, mesh)
    ctx = SimpleNamespace(config={"mesh": str(src), "sets": {"push": {"select": "nearest", "point_in_box": [0.5, 0.5, 2],
                                                                       "boundary_only": True}}},
                          out_path=tmp_path / "out.json", root=tmp_path, log=lambda line: None)
    node_sets.run(ctx)
    payload = read_artifact(tmp_path / "out.json", "tet_mesh")["payload"]
    assert set(payload) <= {"units", "nodes", "tets", "boundary", "node_sets", "element_tags", "quality", "source"}
    assert len(payload["node_sets"]["push"]) == 1
    ctx.config["extra"] = 1
    with pytest.raises(ConfigError, match='config: /: expected no key "extra"'):
        node_sets.run(ctx)


# --------------------------------------------------------------------------- end to end
def test_table2_report_end_to_end_on_a_small_cuboid(pipeline_env):
    """A miniature of dhd_table2 through the real dhd_sim: the report finds the all-TLED run of
    each load, its error is zero, the others are positive, and the tables carry the paper's
    column beside ours."""
    from conftest import run_pipeline, tool
    from pathlib import Path
    tool("dhd_sim")
    scene = {"mesh": "@mesh", "material": {"model": "neo_hookean_paper", "E": 5000, "nu": 0.35, "density": 1000},
             "damping": {"alpha": 50},
             "partition": {"kind": "linear_fraction", "linear_fraction": 0.0, "distance": "depth"},
             "boundary": {"fixed": ["bottom"], "prescribed": [{"nearest": [0.02, 0.02, 0.03], "displacement": [0, 0, -0.002],
                                                               "ramp_time": 0.1, "ramp": "smooth"}]},
             "solver": {"kind": "explicit", "steps": 300, "safety_factor": 0.5}}
    doc = {"description": "mini table 2", "results": "dhd",
           "paper": {"table2": {"applied_displacement": 0.2, "linear_fraction_percent": [50], "mean_error_percent": [9.9]}},
           "stages": {"mesh": {"tool": "mesher", "config": {"source": {"kind": "cuboid", "cells": [4, 4, 3], "size": [0.04, 0.04, 0.03]}}},
                      "sim": {"tool": "dhd_sim", "config": scene,
                              "sweep": {"partition.linear_fraction": [0.0, 0.5],
                                        "boundary.prescribed.0.displacement": [[0, 0, -0.002], [0, 0, -0.003]]}},
                      "table": {"report": "pipeline.reports.dhd_table2", "inputs": ["sim"],
                                "params": {"sim": "sim", "display_unit": "cm"}}}}
    (Path(pipeline_env["PIPELINE_EXPERIMENTS"]) / "mini.json").write_text(json.dumps(doc))
    r = run_pipeline(pipeline_env, "run", "mini")
    assert r.returncode == 0, r.stdout + r.stderr
    out = Path(pipeline_env["PIPELINE_RESULTS"]) / "dhd"
    rows = (out / "table2.csv").read_text().splitlines()
    assert len(rows) == 3 and rows[1].startswith("0 %,0,240,0.0,")
    e50 = float(rows[2].split(",")[3])
    assert 0.0 < e50 < 5.0                       # percent: small for a 2 mm push
    assert rows[2].split(",")[4] == "9.9"        # the paper's column, labelled as such
    assert (out / "table3.csv").exists() and (out / "summary.md").read_text().startswith("## DHD-FEA")
    again = run_pipeline(pipeline_env, "run", "mini")
    assert "pipeline: 6 cached" in again.stdout


def test_every_section_names_the_material_law_and_whether_it_was_defaulted(tmp_path):
    paper = {"model": "neo_hookean_paper", "model_defaulted": True, "E": 3000, "nu": 0.45, "density": 1000}
    chosen = dict(paper, model="neo_hookean_decoupled", model_defaulted=False)
    ctx = FakeContext(tmp_path, runs={"sim": [run({"material": paper}), run({"material": paper})],
                                      "other": [run({"material": chosen}), run({"no_material": 1})]})
    line = common.material_line(ctx)
    assert line.count("`neo_hookean_paper`") == 1 and "left out" in line
    assert "`neo_hookean_decoupled`" in line and "chosen in the config" in line
    assert "E = 3000 Pa" in line and "ν = 0.45" in line
    common.write_section(ctx, "table1", "Some text.")
    assert (tmp_path / common.SECTION_DIR / "table1.md").read_text().strip().endswith(line)
    only_chosen = FakeContext(tmp_path / "b", runs={"sim": [run({"material": chosen})]})
    assert "left out" not in common.material_line(only_chosen)
    assert common.material_line(FakeContext(tmp_path / "c", runs={"sim": [run({})]})) == ""
