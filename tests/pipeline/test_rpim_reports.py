"""The RPIM reports (paper 002) on small synthetic artifacts: rpim_fit's relation and error
tables convert the fit's SI coefficients to millimetres and newtons and set the paper's numbers
beside ours; rpim_model reads the loaded node's displacement and compliance, labels the
variants and tabulates convergence and quadrature studies with the artifacts' values."""
import numpy as np
import pytest

from report_ctx import FakeContext, read_csv, run
from pipeline.reports import rpim_fit, rpim_model


# --------------------------------------------------------------------------- rpim_fit
def test_polynomial_terms_and_surface_labels():
    assert [rpim_fit._term(p) for p in ((0, 0), (1, 0), (0, 1), (2, 3))] == ["1", "x", "y", "x^2 y^3"]
    assert rpim_fit._surface_label({"model": "separable", "orders": [2, 3]}) == "separable (2, 3)"
    assert rpim_fit._surface_label({"model": "bivariate", "degree": 4}) == "bivariate n = 4"
    assert rpim_fit._surface_label({"model": "zero"}) == "zero"
    assert rpim_fit._mm([0.002, None]) == [2.0, None]
    flat = rpim_fit._flatten_numbers({"a": {"b": 1, "c": True, "d": "s"}, "e": 2.5})
    assert flat == [("a.b", 1.0), ("e", 2.5)]          # booleans and strings are not numbers


def test_eq49_table_sets_our_coefficients_beside_the_papers(tmp_path):
    fit = {"selection": {"x": {"force_order": 1, "force_choice": {"cv": {"rmse": 2e-6}}},
                         "z": {"force_order": 2, "force_choice": {}}},
           "paper_units": {"x": {"force_to_loaded_mm_per_N_power": [0.01, 1.5]},
                           "z": {"force_to_loaded_mm_per_N_power": [0.02, 2.5, -0.3]}}}
    paper = {"eq49": {"x": [0.0, 1.4], "z": [0.0, 2.6]}}
    ctx = FakeContext(tmp_path)
    rpim_fit._eq49(ctx, fit, paper)
    rows = read_csv(tmp_path / "fit_eq49.csv")
    assert rows[1] == ["force along x", "1", "0.01", "1.5", "", "0.002", "0.0", "1.4"]   # CV RMSE in mm
    assert rows[2] == ["force along z", "2", "0.02", "2.5", "-0.3", "", "0.0", "2.6"]
    assert len(rows) == 3                                                   # no y selection, no row


def test_table3_gives_rmse_in_mm_and_the_papers_values(tmp_path):
    check = {"x": {"errors": {"rmse": [1e-6, 2e-6, 3e-6]}, "rmse_per_newton": [4e-6, 5e-6, 6e-6]}}
    paper = {"table3_mm_per_N": {"x": [0.1, 0.2, 0.3]}}
    ctx = FakeContext(tmp_path)
    rpim_fit._table3(ctx, [("ours", {"check": check}), ("no check", {})], paper)
    rows = read_csv(tmp_path / "fit_table3_rmse.csv")
    assert len(rows) == 2
    assert rows[1][:2] == ["ours", "force along x"]
    assert [float(v) for v in rows[1][2:11]] == pytest.approx([0.001, 0.002, 0.003, 0.004, 0.005, 0.006, 0.1, 0.2, 0.3])
    # Without relation 1 (ours) or eq. 49 (the paper's) there is no range to divide by: no relative RMSE.
    assert all(v == "" for v in rows[1][11:])


# --------------------------------------------------------------------------- rpim_model
def dataset(loaded_node=2, u=(1e-4, -2e-4, -3e-3), unit=(1e-3, 2e-3, 5e-3), gauss_order=4, total_s=1.5):
    """A dataset payload: node `loaded_node` (1-based) carries `u` and the unit-load compliances."""
    top = [[0.0, 0.0, 0.0] for _ in range(3)]
    top[loaded_node - 1] = list(u)
    sols = []
    for a in range(3):
        per_node = [[0.0, 0.0, 0.0] for _ in range(3)]
        per_node[loaded_node - 1][a] = unit[a]
        sols.append(per_node)
    return {"loaded_node": loaded_node, "cases": [{"top_displacement": top}], "unit_solutions": sols,
            "plate": {"gauss_order": gauss_order}, "conditioning": {"gauss_points": 64 * gauss_order ** 3},
            "timing": {"total_s": total_s}}


def test_loaded_node_displacement_and_compliance_are_read_at_the_one_based_node():
    p = dataset()
    assert rpim_model._loaded_disp(p) == pytest.approx([1e-4, -2e-4, -3e-3])
    assert rpim_model._compliance(p) == pytest.approx([1e-3, 2e-3, 5e-3])
    assert rpim_model._dc_label({"d_c_requested": {"length": 0.002}}) == "2 mm"
    assert rpim_model._dc_label({"d_c_requested": {"spacing_factor": 1.5}, "d_c": 0.0045}) == "1.5 h (4.50 mm)"
    msg = "rpim_precompute: RPIM shape functions at node 3: moment matrix singular"
    assert rpim_model._short(msg) == "node 3: moment matrix singular"
    assert rpim_model._short("x" * 200, limit=10) == "x" * 9 + "…"


def test_quadrature_table_orders_by_gauss_rule_and_converts_to_mm(tmp_path):
    runs = [run(dataset(gauss_order=5, u=(0, 0, -2e-3), total_s=3.0), run_id="q#1"),
            run(dataset(gauss_order=2, u=(0, 0, -1e-3), unit=(1e-3, 0, 4e-3), total_s=0.5), run_id="q#0")]
    ctx = FakeContext(tmp_path)
    rpim_model._quadrature_table(ctx, runs)
    rows = read_csv(tmp_path / "rpim_quadrature.csv")
    assert [r[0] for r in rows[1:]] == ["2", "5"]
    assert [float(v) for v in rows[1][1:]] == pytest.approx([512, 0, 0, -1.0, 1.0, 4.0, 0.5])
    assert float(rows[2][4]) == pytest.approx(-2.0)


def test_convergence_tables_hold_every_refinement_and_the_observed_rates(tmp_path):
    h = [0.5, 0.25, 0.125]
    err = [0.1 * x ** 2 for x in h]
    payload = {"block": {"field": "plane_wave"},
               "model": {"alpha_c": 4.0, "d_c_requested": {"spacing_factor": 1.0}, "polynomial": "linear"},
               "rows": [{"spacing": s, "nodes_per_edge": int(1 / s) + 1, "relative_rms_error": e,
                         "relative_max_error": 2 * e} for s, e in zip(h, err)],
               "observed_rate": {"rms": 2.0, "max": 1.9}}
    ctx = FakeContext(tmp_path, {"conv": [run(payload)]})
    rates = rpim_model._convergence(ctx, ["conv"])
    label = "plane_wave: α_c = 4, d_c = 1.0 h, polynomial linear"
    assert rates == [[label, 2.0, 1.9]]
    rows = read_csv(tmp_path / "rpim_convergence.csv")
    assert [r[1] for r in rows[1:]] == ["3", "5", "9"]
    assert [float(r[3]) for r in rows[1:]] == pytest.approx(err)
    assert [float(r[4]) for r in rows[1:]] == pytest.approx([2 * e for e in err])
    assert read_csv(tmp_path / "rpim_convergence_rates.csv")[1] == [label, "2.0", "1.9"]


def test_dataset_set_members_are_read_by_stage_and_member_and_their_build_counts_once(tmp_path):
    def member(kind, total_s, solves_s):
        p = dataset(total_s=total_s)
        p["dataset"] = {"kind": kind, "count": 1, "seed": None}
        p["cases"][0]["force"] = [0.0, 0.0, -1.0]
        p["timing"].update({"cases_solved": 4, "shape_functions_s": 0.1, "assembly_s": 0.1, "penalty_s": 0.0,
                            "factorisation_s": 0.2, "solves_s": solves_s, "threads": 2})
        return p
    members = {"x": member("axis_x", 0.45, 0.05), "check": member("check", 0.42, 0.02)}
    whole = {"members": members, "timing": {"build_s": 0.4, "solves_s": 0.07, "total_s": 0.47, "datasets": 2,
                                             "cases_solved": 8}}
    ctx = FakeContext(tmp_path, runs={"datasets": [run(whole)]})
    assert rpim_model._single(ctx, "datasets/check") is members["check"]
    assert rpim_model._payloads(ctx, "datasets/x") == [members["x"]]
    with pytest.raises(ValueError, match="no dataset member 'y'"):
        rpim_model._payloads(ctx, "datasets/y")
    total = rpim_model._datasets_table(ctx, ["datasets/x", "datasets/check"], {})
    assert total == pytest.approx(0.47)          # the shared build once, not 0.45 + 0.42
    rows = read_csv(tmp_path / "rpim_timing.csv")
    assert [r[0] for r in rows[1:]] == ["datasets/x", "datasets/check", "datasets: all 2 datasets, one build",
                                        "paper: one full RPIM solve (002 §5.1.2)"]
