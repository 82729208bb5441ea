"""results/rpim_liver/: the RPIM meshless model on a liver (002 §5.3, Figs. 18–21).

Inputs (experiments/rpim_liver.json): the liver mesh with its node sets (the dhd_liver mesh,
fixed nodes and pushed node), the rpim_precompute dataset set on it (axis series, held-out random
forces, the pressed and stretched cases), the marquardt_fit fit of its surface (params `fit`; and
optionally `fit_xy`, a fit of another surface kind shown beside it, e.g. x and y alone), and
dhd_sim's linear static solve of the same mesh, fixed nodes, material and point force.

Written: rpim_liver_model (scene, conditioning), rpim_liver_timing (build, per-case solve, fit,
playback; the paper's run times beside them, labelled), rpim_liver_fit (each fit against RPIM on the
held-out forces), rpim_liver_vs_fem (RPIM against dhd_sim at the loaded node and over the
surface), rpim_liver.png (Figs. 20–21: the deformed surface coloured by displacement) and
summary.md, whose sentences are written from the numbers.
"""
import numpy as np

from pipeline import plots
from pipeline.stages.machine_load import busy_note
from pipeline.tables import fmt, write_table

MM = 1e3
GOOD_FIT = 0.05   # "follows the RPIM field": fit error below 5 % of the displacement range
CLOSE_FEM = 0.25  # "agrees with the FEM": surface RMS difference below 25 % of the FEM's largest displacement


# --------------------------------------------------------------------------- measures
def fit_errors(validation):
    """Per validation dataset: max and RMS of |u_fit − u_rpim| over surface nodes and cases (m),
    the displacement range (largest |u_rpim|) and the loaded node's largest error (m), from the
    full fields the fit artifact carries (its `examples`)."""
    out = {}
    for v in validation:
        ex = v.get("examples", [])
        if len(ex) < v["cases"]:
            raise ValueError(f"validation {v['dataset']}: {len(ex)} full fields for {v['cases']} cases "
                             "(set the fit's \"examples\" to at least the case count)")
        diff = np.concatenate([np.linalg.norm(np.asarray(e["fit"]) - np.asarray(e["data"]), axis=1) for e in ex])
        mag = np.concatenate([np.linalg.norm(np.asarray(e["data"]), axis=1) for e in ex])
        loaded = max(np.linalg.norm(np.asarray(c["loaded_node_fit"]) - np.asarray(c["loaded_node_data"]))
                     for c in v["per_case"])
        name = member_name(v["dataset"])
        out[name] = {"cases": v["cases"], "max": float(diff.max()), "rms": float(np.sqrt(np.mean(diff ** 2))),
                     "range": float(mag.max()), "loaded": float(loaded)}
    return out


SURFACE_KINDS = {"trivariate": "x, y, z (trivariate)", "bivariate": "x, y (bivariate)",
                 "separable": "x, y (separable, 002 eq. 44)", "best": "best of the kinds by CV"}


def surface_kind(fit):
    """What relation 2 of a fit is a polynomial of, with the degrees cross-validation chose
    (from the fit's settings and selection), e.g. 'x, y, z (trivariate), n = 5–7'."""
    model = (fit.get("settings") or {}).get("surface_model", "")
    label = SURFACE_KINDS.get(model, model or "surface")
    degrees = sorted({c["surface"]["degree"] for d in (fit.get("selection") or {}).values()
                      for c in d.get("components", {}).values() if "degree" in c.get("surface", {})})
    if degrees:
        label += f", n = {degrees[0]}" + (f"–{degrees[-1]}" if degrees[-1] != degrees[0] else "")
    return label


def member_name(dataset_label):
    """'path [member]' -> member (how the fit names a member of a dataset set); a path as it is."""
    if dataset_label.endswith("]") and " [" in dataset_label:
        return dataset_label.rsplit(" [", 1)[1][:-1]
    return dataset_label


def fem_comparison(member, fem_payload):
    """RPIM (one check case) against dhd_sim's displacement on the same surface nodes."""
    idx = np.asarray(member["organ"]["surface_node_indices"], dtype=int)
    u_rpim = np.asarray(member["cases"][0]["top_displacement"], dtype=float)
    u_fem = np.asarray(fem_payload["displacement"], dtype=float)[idx]
    loaded = member["loaded_node"] - 1
    d = np.linalg.norm(u_rpim - u_fem, axis=1)
    fem_mag = np.linalg.norm(u_fem, axis=1)
    return {"force": member["cases"][0]["force"],
            "loaded_rpim": u_rpim[loaded], "loaded_fem": u_fem[loaded],
            "loaded_ratio": float(np.linalg.norm(u_rpim[loaded]) / np.linalg.norm(u_fem[loaded])),
            "surface_rms": float(np.sqrt(np.mean(d ** 2))), "surface_max": float(d.max()),
            "fem_max": float(fem_mag.max()),
            "far_ratio": far_field_ratio(u_rpim, u_fem, loaded, member["top_nodes"]),
            "strain": fem_payload.get("small_strain_check")}


def validity_words(check) -> str:
    """Whether the FEM reference stays a small-strain solution, from dhd_sim's small_strain_check
    (the largest ‖∇u‖₂ of its linear elements, 000 §2.2.2's limit): the comparison of a
    small-strain RPIM with it means something only inside that limit."""
    if not check or not check.get("elements"):
        return (" dhd_sim recorded no small-strain check for this run, so whether the comparison stays inside "
                "small-strain validity is not known.")
    largest, limit = check["largest"], check["limit"]
    if largest <= limit:
        return (f" Both stay small-strain: the FEM's most deformed element reaches ‖∇u‖₂ = "
                f"{fmt(100 * largest, 3)} %, within the {fmt(100 * limit)} % limit.")
    return (f" Both models are outside their validity here: the FEM's most deformed element reaches ‖∇u‖₂ = "
            f"{fmt(100 * largest, 3)} %, {fmt(largest / limit, 3)} × the {fmt(100 * limit)} % up to which "
            "small-strain models hold (000 §2.2.2), so this compares two linear models with each other, not "
            "either with the tissue.")


def far_field_ratio(u_rpim, u_fem, loaded, positions):
    """Σ|u_rpim| / Σ|u_fem| over the surface nodes farther than 3 cm from the loaded node: the
    body's compliance away from the point load, where both discretisations converge."""
    x = np.asarray(positions, dtype=float)
    far = np.linalg.norm(x - x[loaded], axis=1) > 0.03
    return float(np.linalg.norm(u_rpim[far], axis=1).sum() / np.linalg.norm(u_fem[far], axis=1).sum())


# --------------------------------------------------------------------------- tables
def _model_rows(member, rpim_set):
    o, m, c = member["organ"], member["model"], member["conditioning"]
    sup = m["support"]
    return [["mesh", f"{o['nodes']} nodes, {o['tets']} tets, {o['boundary_triangles']} boundary triangles"],
            ["surface nodes (reported, fitted)", o["surface_nodes"]],
            ["fixed nodes (sets " + ", ".join(o["fixed_sets"]) + ")", len(o["fixed_nodes"])],
            ["loaded node" + (f" (set {o['loaded_set']})" if o.get("loaded_set") else " (nearest the loaded point)"),
             f"surface node {member['loaded_node']}"],
            ["material", f"E = {fmt(o['youngs_modulus'])} Pa, ν = {fmt(o['poisson_ratio'])}"],
            ["background integration", f"{o['tet_rule']['points']}-point tetrahedral rule (degree "
                                       f"{o['tet_rule']['degree']}), {o['gauss_points']} Gauss points"],
            ["mean nodal spacing h (mm)", fmt(o["mean_spacing"] * MM)],
            ["RPIM", f"MQ q = {fmt(m['q'])}, α_c = {fmt(m['alpha_c'])}, d_c = {fmt(m['d_c'] * MM)} mm, "
                     f"polynomial {m['polynomial']}, support radius {fmt(sup.get('radius', 0) * MM)} mm"],
            ["support nodes per Gauss point (min / mean / max)",
             f"{c['support_nodes']['min']} / {fmt(c['support_nodes']['mean'])} / {c['support_nodes']['max']}"],
            ["moment-matrix condition (max)", fmt(c["moment_matrix"]["condition_max"])],
            ["linear consistency max |Σφ_I(x_I − x)|/h", fmt(c["shape_consistency"]["linear_reproduction_error"])],
            ["rigid-mode strain energy (max ratio)", fmt(c["rigid_mode_energy"]["max_ratio"])],
            ["smallest pivot / largest diagonal", fmt(c["factorisation_pivot_ratio"])],
            ["penalty", f"{m['penalty']['kind']}, λ = {fmt(m['penalty']['lambda'])}"],
            ["solver", m["solver"]]]


def timing_rows(rpim_set, fit, fem_runs, paper):
    t = rpim_set["timing"]
    per_case = t["solves_s"] / t["cases_solved"]
    ft = fit.get("timing") or {}
    rows = [["RPIM build: shape functions, assembly, penalty, factorisation (s)", fmt(t["build_s"]), ""],
            ["RPIM solve per load case (ms)", fmt(per_case * 1e3), ""],
            ["Marquardt fit: cross-validation and fits of all relations (s)", fmt(fit["fit_seconds"]), ""],
            ["playback per surface evaluation, every surface node (µs)",
             fmt(ft.get("playback_s_per_evaluation", float("nan")) * 1e6), ""],
            ["superposition of the unit solutions per evaluation (µs)",
             fmt(ft.get("superposition_s_per_evaluation", float("nan")) * 1e6), ""]]
    fem_solve = [r.payload["timing"].get("solve_seconds") for r in fem_runs]
    if fem_solve and all(s is not None for s in fem_solve):
        rows.append(["dhd_sim linear static solve, same mesh (s)", fmt(float(np.mean(fem_solve))), ""])
    rows.append(["paper: RPIM-MM solve, plate (s)", "", fmt(paper.get("rpim_solve_s"))])
    rows.append(["paper: Marquardt playback, plate (s)", "", fmt(paper.get("playback_s"))])
    return rows


# --------------------------------------------------------------------------- picture
def plot_cases(path, mesh, members, names):
    """Figs. 20–21: the surface under each case, deformed by the RPIM displacement (true scale)
    and coloured by its magnitude (mm); the loaded node marked."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    import matplotlib.pyplot as plt
    nodes = np.asarray(mesh["nodes"], dtype=float)
    tris = np.asarray(mesh["boundary"], dtype=int)
    fig = plt.figure(figsize=(5.2 * len(names), 4.6), dpi=110)
    for k, name in enumerate(names):
        m = members[name]
        idx = np.asarray(m["organ"]["surface_node_indices"], dtype=int)
        u = np.zeros_like(nodes)
        u[idx] = np.asarray(m["cases"][0]["top_displacement"], dtype=float)
        x = nodes + u
        mag = np.linalg.norm(u, axis=1) * MM
        ax = fig.add_subplot(1, len(names), k + 1, projection="3d")
        face_mag = mag[tris].mean(axis=1)
        norm = plt.Normalize(0, max(face_mag.max(), 1e-12))
        coll = Poly3DCollection(x[tris], facecolors=plt.cm.viridis(norm(face_mag)), edgecolor="none")
        ax.add_collection3d(coll)
        lo, hi = x.min(axis=0), x.max(axis=0)
        c, r = (lo + hi) / 2, (hi - lo).max() / 2
        ax.set_xlim(c[0] - r, c[0] + r), ax.set_ylim(c[1] - r, c[1] + r), ax.set_zlim(c[2] - r, c[2] + r)
        loaded = idx[m["loaded_node"] - 1]
        ax.scatter(*x[loaded], color="red", s=25)
        f = m["cases"][0]["force"]
        ax.set_title(f"{name}: F = ({', '.join(fmt(v, 2) for v in f)}) N", fontsize=9)
        ax.view_init(elev=35, azim=-60)
        ax.set_axis_off()
        sm = plt.cm.ScalarMappable(norm=norm, cmap="viridis")
        fig.colorbar(sm, ax=ax, shrink=0.6, label="|u| (mm)")
    plots.save(fig, path)


# --------------------------------------------------------------------------- words
def finding(surface_nodes, paper_nodes, errors, fem, timing, kinds=None, other=None):
    """kinds: (label of the fit, label of the other fit); other: the other fit's errors."""
    out = []
    out.append(f"The liver has {surface_nodes} surface nodes (the paper's liver: {paper_nodes}); every one of them "
               "is an RPIM field node, reported in each load case and covered by the fit.")
    held = errors.get("random")
    if held:
        rel = held["max"] / held["range"]
        verdict = (f"follows the RPIM field within {GOOD_FIT:.0%} of the displacement range"
                   if rel < GOOD_FIT else
                   f"does not follow the RPIM field within {GOOD_FIT:.0%} of the displacement range")
        which = f" ({kinds[0]})" if kinds else ""
        out.append(f"On {held['cases']} held-out random forces (0–1 N) the fitted surface{which} {verdict}: max error "
                   f"{fmt(held['max'] * MM)} mm, RMS {fmt(held['rms'] * MM)} mm, against displacements up to "
                   f"{fmt(held['range'] * MM)} mm ({fmt(rel * 100, 3)} % max, {fmt(held['rms'] / held['range'] * 100, 3)} % RMS).")
        prev = (other or {}).get("random")
        if prev and kinds:
            def than(a, b):
                return (f"{fmt(b / a, 3)} × smaller" if a < b else
                        f"{fmt(a / b, 3)} × larger" if a > b else "the same")
            out.append(f"The surfaces of {kinds[1]} on the same forces: max error {fmt(prev['max'] * MM)} mm, RMS "
                       f"{fmt(prev['rms'] * MM)} mm ({fmt(prev['max'] / prev['range'] * 100, 3)} % max, "
                       f"{fmt(prev['rms'] / prev['range'] * 100, 3)} % RMS); against them the fitted surface above has a "
                       f"max error {than(held['max'], prev['max'])} and an RMS {than(held['rms'], prev['rms'])}.")
    for name, c in fem.items():
        close = c["surface_rms"] / c["fem_max"] < CLOSE_FEM
        word = "agrees with" if close else "differs from"
        out.append(f"{name.capitalize()}: RPIM {word} dhd_sim's linear tetrahedra over the surface (RMS difference "
                   f"{fmt(c['surface_rms'] / c['fem_max'] * 100, 3)} % of the FEM's largest displacement); at the "
                   f"loaded node |u| is {fmt(c['loaded_ratio'], 3)} × the FEM's, away from the load "
                   f"{fmt(c['far_ratio'], 3)} ×." + validity_words(c.get("strain")))
    if timing.get("playback_s") and timing.get("per_case_s"):
        speed = timing["per_case_s"] / timing["playback_s"]
        out.append(f"A playback costs {fmt(timing['playback_s'] * 1e6, 3)} µs for every surface node, "
                   f"{fmt(speed, 3)} × less than one RPIM substitution ({fmt(timing['per_case_s'] * 1e3, 3)} ms), "
                   + ("and fits in a 1 ms haptic frame" if timing["playback_s"] < 1e-3
                      else "but does not fit in a 1 ms haptic frame")
                   + (f" {timing['note']}." if timing.get("note") else "."))
    return out


def closed_surface_note(fit, fit_xy):
    """How the fit(s) cover a closed surface, from the surface kinds they used."""
    def uses_z(f):
        return (f.get("settings") or {}).get("surface_model") == "trivariate"
    xy = "polynomials of x and y (002 eq. 44) give nodes of the upper and lower faces with the same (x, y) " \
         "the same value"
    xyz = "polynomials of x, y and z (the trivariate surface) give every surface node its own value"
    if uses_z(fit):
        note = f"How the fit covers a closed surface: its {xyz}."
        if fit_xy is not None and not uses_z(fit_xy):
            note += f" The second fit's {xy}; the fit table's rows of the two kinds measure what that costs."
    else:
        note = f"How the fit covers a closed surface: its {xy}; the fit error above measures what that costs."
    return note + " At the loaded node, the displacement along the force is relation 1's (002 §5.1.1)."


# --------------------------------------------------------------------------- report
def report(ctx):
    p = ctx.params
    paper = ctx.experiment.get("paper", {})
    mesh = ctx.runs(p["sets"])[0].payload
    rpim_set = ctx.runs(p["rpim"])[0].payload
    members = rpim_set["members"]
    fit = ctx.runs(p["fit"])[0].payload
    fit_xy = ctx.runs(p["fit_xy"])[0].payload if p.get("fit_xy") else None
    fem_runs = ctx.runs(p["fem"])
    first = next(iter(members.values()))

    write_table(ctx, "rpim_liver_model", ["quantity", "value"], _model_rows(first, rpim_set),
                "The RPIM liver (002 §5.3): field nodes = the tetrahedral mesh's nodes, Gauss points in its tetrahedra.")

    errors = fit_errors(fit.get("validation", []))
    fits = [(surface_kind(fit), errors)]
    other = None
    if fit_xy is not None:
        other = fit_errors(fit_xy.get("validation", []))
        fits.append((surface_kind(fit_xy), other))
    rows = [[kind, name, e["cases"], fmt(e["max"] * MM), fmt(e["rms"] * MM), fmt(e["range"] * MM),
             fmt(e["max"] / e["range"] * 100, 3), fmt(e["rms"] / e["range"] * 100, 3), fmt(e["loaded"] * MM)]
            for kind, errs in fits for name, e in errs.items()]
    write_table(ctx, "rpim_liver_fit",
                ["surface (relation 2)", "forces", "cases", "max |u_fit − u_RPIM| (mm)", "RMS (mm)",
                 "largest |u_RPIM| (mm)", "max / range (%)", "RMS / range (%)", "loaded node max error (mm)"], rows,
                "The Marquardt fits (trained on the axis series only) played back against the RPIM solution, every "
                "surface node; 'random' are held-out forces 0–1 N. Relation 2 is a polynomial of the coordinates "
                "named, its degree n chosen by cross-validation per load direction and component.")

    fem = {}
    for name, force in p["cases"].items():
        run = next((r for r in fem_runs
                    if np.allclose(r.config["boundary"]["forces"][0]["force"], force)), None)
        if run is None or name not in members:
            raise ValueError(f"case {name}: no dhd_sim run or RPIM member with force {force}")
        fem[name] = fem_comparison(members[name], run.payload)
    write_table(ctx, "rpim_liver_vs_fem",
                ["case", "force (N)", "loaded node RPIM (mm)", "loaded node dhd_sim (mm)", "|u| ratio RPIM / FEM",
                 "surface RMS |Δu| (mm)", "surface max |Δu| (mm)", "FEM largest |u| (mm)", "far-field ratio",
                 "FEM largest ‖∇u‖₂ (%)"],
                [[n, "(" + ", ".join(fmt(v, 3) for v in c["force"]) + ")",
                  "(" + ", ".join(fmt(v * MM, 3) for v in c["loaded_rpim"]) + ")",
                  "(" + ", ".join(fmt(v * MM, 3) for v in c["loaded_fem"]) + ")",
                  fmt(c["loaded_ratio"], 3), fmt(c["surface_rms"] * MM), fmt(c["surface_max"] * MM),
                  fmt(c["fem_max"] * MM), fmt(c["far_ratio"], 3),
                  fmt(100 * c["strain"]["largest"], 3) if c["strain"] and c["strain"].get("elements") else None]
                 for n, c in fem.items()],
                "RPIM against dhd_sim's linear static solve (linear tetrahedra) on the same mesh, fixed nodes, "
                "material and point force. Far-field ratio: Σ|u| over surface nodes more than 3 cm from the load.")

    t = rpim_set["timing"]
    ft = fit.get("timing") or {}
    timing = {"per_case_s": t["solves_s"] / t["cases_solved"], "playback_s": ft.get("playback_s_per_evaluation"),
              # a speed verdict carries the note of a flagged timing; the caption below says when none was recorded
              "note": busy_note(rpim_set.get("machine")) if rpim_set.get("machine") else ""}
    write_table(ctx, "rpim_liver_timing", ["step", "ours", "paper (labelled)"],
                timing_rows(rpim_set, fit, fem_runs, paper.get("timing", {})),
                "Wall times on this machine (the paper's figures are for its 121-node plate, Fortran and Matlab)"
                + (f"; {busy_note(rpim_set.get('machine'))[1:-1]}." if busy_note(rpim_set.get("machine")) else "."))

    plot_cases(ctx.out("rpim_liver.png"), mesh, members, list(p["cases"]))

    statements = paper.get("statements", [])
    text = ["## The RPIM liver (002 §5.3)", "",
            "Tables: [rpim_liver_model.md](rpim_liver_model.md), [rpim_liver_fit.md](rpim_liver_fit.md), "
            "[rpim_liver_vs_fem.md](rpim_liver_vs_fem.md), [rpim_liver_timing.md](rpim_liver_timing.md). "
            "Picture (Figs. 20–21): ![](rpim_liver.png)", ""]
    kinds = (fits[0][0], fits[1][0]) if len(fits) > 1 else None
    text.append(" ".join(finding(first["organ"]["surface_nodes"], paper.get("surface_nodes"), errors, fem, timing,
                                 kinds, other)))
    text += ["", closed_surface_note(fit, fit_xy)]
    if statements:
        text += ["", "The paper's statements (002 §5.3, quoted):", ""] + [f"- paper: “{s}”" for s in statements]
    ctx.out("summary.md").write_text("\n".join(text) + "\n")
