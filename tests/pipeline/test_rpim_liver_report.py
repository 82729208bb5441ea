"""The RPIM liver report (results/rpim_liver/): errors read from the fits' full fields, RPIM
against dhd_sim on the surface nodes, and a summary whose verdicts follow the numbers (also when
a second fit of another surface kind stands beside the first)."""
import numpy as np
import pytest

from report_ctx import FakeContext, read_csv, run
from pipeline.reports import rpim_liver

# One tetrahedron: nodes 0-3 all on the surface, node 4 inside (not reported).
NODES = [[0.0, 0.0, 0.0], [0.1, 0.0, 0.0], [0.0, 0.1, 0.0], [0.0, 0.0, 0.1], [0.02, 0.02, 0.02]]
BOUNDARY = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]
SURFACE = [0, 1, 2, 3]
LOADED = 2  # 1-based among the surface nodes: mesh node 1


def member(force, field):
    organ = {"nodes": 5, "tets": 1, "boundary_triangles": 4, "surface_nodes": 4, "surface_node_indices": SURFACE,
             "fixed_sets": ["fixed"], "fixed_nodes": [0], "loaded_set": "push", "youngs_modulus": 5000,
             "poisson_ratio": 0.35, "tet_rule": {"points": 4, "degree": 2}, "gauss_points": 4,
             "mean_spacing": 0.05}
    model = {"q": 1.03, "alpha_c": 1.0, "d_c": 0.05, "polynomial": "linear",
             "support": {"kind": "radius", "radius": 0.125}, "penalty": {"kind": "scale_block", "lambda": 1e7},
             "solver": "sparse_ldlt"}
    cond = {"support_nodes": {"min": 4, "mean": 5.0, "max": 5}, "moment_matrix": {"condition_max": 1e3},
            "shape_consistency": {"linear_reproduction_error": 1e-15}, "rigid_mode_energy": {"max_ratio": 1e-16},
            "factorisation_pivot_ratio": 1e-3}
    return {"organ": organ, "model": model, "conditioning": cond, "loaded_node": LOADED,
            "top_nodes": [NODES[i] for i in SURFACE], "cases": [{"force": force, "top_displacement": field}]}


def field(scale):
    return [[0.0, 0.0, 0.0], [0.0, 0.0, -scale], [0.0, 0.0, -scale / 4], [0.0, 0.0, -scale / 4]]


def validation(fit_error):
    data = field(0.01)
    fitted = [[u[0], u[1], u[2] + fit_error] for u in data]
    return {"dataset": "rpim.json [random]", "cases": 1,
            "per_case": [{"loaded_node_fit": fitted[1], "loaded_node_data": data[1]}],
            "examples": [{"force": [0, 0, -1], "fit": fitted, "data": data}]}


def fit_payload(fit_error, model, degrees):
    selection = {d: {"components": {c: {"surface": {"model": model, "degree": n}} for c, n in zip("xyz", degrees)}}
                 for d in "xyz"}
    return {"validation": [validation(fit_error)], "fit_seconds": 0.5, "settings": {"surface_model": model},
            "selection": selection,
            "timing": {"playback_s_per_evaluation": 2e-6, "superposition_s_per_evaluation": 1e-5}}


def context(tmp_path, fit_error=1e-5, fem_scale=0.01, xy_error=None):
    members = {"pressed": member([0, 0, -1], field(0.01)), "stretched": member([0.6, 0, 0.8], field(-0.01))}
    rpim_set = {"members": members, "timing": {"build_s": 2.0, "solves_s": 0.2, "cases_solved": 10}}
    fit = fit_payload(fit_error, "trivariate", [5, 7, 6])

    def fem(force, s):
        u = [[0.0, 0.0, 0.0]] * 5
        u[:4] = field(s)
        return run({"displacement": u, "timing": {"solve_seconds": 1.5}},
                   config={"boundary": {"forces": [{"force": force}]}})

    runs = {"sets": [run({"nodes": NODES, "boundary": BOUNDARY})], "rpim": [run(rpim_set)], "fit": [run(fit)],
            "fem": [fem([0, 0, -1], fem_scale), fem([0.6, 0, 0.8], -fem_scale)]}
    params = {"sets": "sets", "rpim": "rpim", "fit": "fit", "fem": "fem",
              "cases": {"pressed": [0, 0, -1], "stretched": [0.6, 0, 0.8]}}
    if xy_error is not None:
        runs["fit_xy"] = [run(fit_payload(xy_error, "bivariate", [8, 8, 8]))]
        params["fit_xy"] = "fit_xy"
    paper = {"surface_nodes": 1986, "statements": ["In the liver model, there are 1986 surface nodes"],
             "timing": {"rpim_solve_s": 647.4073, "playback_s": 0.1509}}
    return FakeContext(tmp_path, runs=runs, params=params, experiment={"paper": paper})


def test_tables_follow_the_fields(tmp_path):
    rpim_liver.report(context(tmp_path, fit_error=2e-4, fem_scale=0.02))
    fit = read_csv(tmp_path / "rpim_liver_fit.csv")
    assert fit[1][0] == "x, y, z (trivariate), n = 5–7"  # the kind and the degrees CV chose
    assert fit[1][1] == "random"
    assert float(fit[1][3]) == pytest.approx(0.2)       # max |Δu| (mm)
    assert float(fit[1][5]) == pytest.approx(10.0)      # largest |u_RPIM| (mm)
    assert float(fit[1][6]) == pytest.approx(2.0)       # %
    fem = read_csv(tmp_path / "rpim_liver_vs_fem.csv")
    pressed = [r for r in fem if r[0] == "pressed"][0]
    assert float(pressed[4]) == pytest.approx(0.5)      # loaded node |u| RPIM / FEM = 10 / 20
    assert float(pressed[7]) == pytest.approx(20.0)     # FEM largest |u| (mm)
    timing = read_csv(tmp_path / "rpim_liver_timing.csv")
    assert float([r for r in timing if r[0].startswith("RPIM solve per load case")][0][1]) == pytest.approx(20.0)
    paper_rows = [r for r in timing if r[0].startswith("paper:")]
    assert paper_rows and all(r[1] == "" for r in paper_rows)   # the paper's figures only in its column
    assert (tmp_path / "rpim_liver.png").stat().st_size > 0


def test_the_summary_follows_the_numbers(tmp_path):
    rpim_liver.report(context(tmp_path / "good"))
    text = (tmp_path / "good" / "summary.md").read_text()
    assert "The liver has 4 surface nodes (the paper's liver: 1986)" in text
    assert "the fitted surface follows the RPIM field within 5%" in text
    assert "Pressed: RPIM agrees with dhd_sim's linear tetrahedra" in text
    assert "at the loaded node |u| is 1 × the FEM's" in text
    assert "paper: “In the liver model, there are 1986 surface nodes”" in text
    assert "10000 × less than one RPIM substitution (20 ms), and fits in a 1 ms haptic frame." in text
    # A poor fit and a stiffer FEM turn the verdicts round.
    rpim_liver.report(context(tmp_path / "bad", fit_error=2e-3, fem_scale=0.05))
    text = (tmp_path / "bad" / "summary.md").read_text()
    assert "does not follow the RPIM field within 5%" in text
    assert "Pressed: RPIM differs from dhd_sim's linear tetrahedra" in text
    assert "at the loaded node |u| is 0.2 × the FEM's" in text


def test_too_few_full_fields_is_an_error(tmp_path):
    ctx = context(tmp_path)
    ctx.runs("fit")[0].payload["validation"][0]["cases"] = 5
    with pytest.raises(ValueError, match="examples"):
        rpim_liver.report(ctx)


def test_a_second_fit_stands_beside_the_first_and_the_comparison_follows_the_numbers(tmp_path):
    rpim_liver.report(context(tmp_path / "better", fit_error=1e-4, xy_error=4e-4))
    fit = read_csv(tmp_path / "better" / "rpim_liver_fit.csv")
    assert [r[0] for r in fit[1:]] == ["x, y, z (trivariate), n = 5–7", "x, y (bivariate), n = 8"]
    assert float(fit[2][3]) == pytest.approx(0.4)
    text = (tmp_path / "better" / "summary.md").read_text()
    assert "the fitted surface (x, y, z (trivariate), n = 5–7) follows the RPIM field within 5%" in text
    assert "The surfaces of x, y (bivariate), n = 8 on the same forces: max error 0.4 mm" in text
    assert "max error 4 × smaller and an RMS 4 × smaller" in text
    assert "its polynomials of x, y and z" in text and "The second fit's polynomials of x and y" in text
    rpim_liver.report(context(tmp_path / "worse", fit_error=4e-4, xy_error=1e-4))
    text = (tmp_path / "worse" / "summary.md").read_text()
    assert "max error 4 × larger and an RMS 4 × larger" in text
    # Without a second fit there is no comparison sentence.
    rpim_liver.report(context(tmp_path / "alone"))
    assert "The surfaces of" not in (tmp_path / "alone" / "summary.md").read_text()
