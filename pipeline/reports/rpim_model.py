"""results/rpim/: the RPIM meshless plate model of paper 002 (rpim_precompute) — the ANSYS check
beside CalculiX, the support readings, the Lee–Radok modulus, conditioning, the stability sweep,
convergence under node refinement, quadrature sensitivity, datasets and timing.

params (stage names of experiments/rpim_datasets.json):
  "datasets": [ref, ...]        the datasets handed to marquardt_fit
  "check": ref                   the §5.2 force with the default model (+ Lee–Radok inputs)
  (a ref is a stage, or "stage/member" for one member of an rpim_dataset_set)
  "readings": stage              the check swept over plate.supports × rpim.d_c
  "polynomial": stage            the check with linear polynomial augmentation
  "quadrature": stage            the check swept over plate.gauss_order
  "fine": stage                  the check on 21 × 21 × 5 nodes
  "stability": [stage, ...]      rpim_stability artifacts
  "convergence": [stage, ...]    rpim_convergence artifacts
  "calculix": stage              calculix_plate runs swept over support × divisions

Every number in a table is measured by this project; the paper's numbers (from the experiment's
"paper" block) appear beside them, labelled "paper".
"""
import numpy as np

from pipeline import plots
from pipeline.tables import fmt, write_table

MM = 1e3


# --------------------------------------------------------------------------- helpers
def _payloads(ctx, ref):
    """Payloads named by "stage" (each of its runs) or "stage/member" (that member of each run's
    rpim_dataset_set: several datasets of one model built once)."""
    stage, _, member = ref.partition("/")
    payloads = [r.payload for r in ctx.runs(stage)]
    if not member:
        return payloads
    for p in payloads:
        if member not in p.get("members", {}):
            raise ValueError(f"stage {stage!r}: no dataset member {member!r} "
                             f"(members: {sorted(p.get('members', {}))})")
    return [p["members"][member] for p in payloads]


def _single(ctx, ref):
    payloads = _payloads(ctx, ref)
    if len(payloads) != 1:
        raise ValueError(f"{ref!r}: expected one run, found {len(payloads)}")
    return payloads[0]


def _loaded_disp(p, case=0):
    """Loaded-node displacement of a dataset case (m)."""
    return np.asarray(p["cases"][case]["top_displacement"][p["loaded_node"] - 1], dtype=float)


def _compliance(p):
    """u_a / F_a at the loaded node for unit forces along x, y, z (m/N)."""
    n = p["loaded_node"] - 1
    return np.array([p["unit_solutions"][a][n][a] for a in range(3)], dtype=float)


def _dc_label(model):
    req = model["d_c_requested"]
    if "length" in req:
        return f"{req['length'] * MM:g} mm"
    return f"{req['spacing_factor']:g} h ({model['d_c'] * MM:.2f} mm)"


def _ccx_runs(ctx, stage):
    out = {}
    for r in ctx.runs(stage):
        p = r.payload
        out[(p["support"], tuple(p["divisions"]))] = p
    return out


def _ccx_label(p):
    d = p["divisions"]
    return f"CalculiX {p['element_type']} {d[0]}×{d[1]}×{d[2]} ({p['element_size'][0] * MM:.2f} mm)" \
        if isinstance(p.get("element_size"), list) else f"CalculiX {p['element_type']} {d[0]}×{d[1]}×{d[2]}"


def _short(message, limit=150):
    if message is None:
        return None
    m = message.split(": RPIM shape functions at ")[-1]
    return m if len(m) <= limit else m[:limit - 1] + "…"


# --------------------------------------------------------------------------- the §5.2 check
def _check_tables(ctx, paper, check, poly, fine, ccx):
    force = np.asarray(check["cases"][0]["force"], dtype=float)
    sup = check["plate"]["supports"]
    rows = []

    def row(label, u, ref=None):
        u = np.asarray(u, dtype=float)
        rel = [None] * 3 if ref is None else list(u / ref)
        rows.append([label] + list(u * MM) + [float(force @ u) * 1e3] + rel)

    ref_key = (sup, (10, 10, 2))
    ref = np.asarray(ccx[ref_key]["top_centre"]["displacement"]) if ref_key in ccx else None
    row(f"RPIM (this project): paper's α_c, d_c, q; {sup}; 11×11×3 nodes", _loaded_disp(check), ref)
    row("RPIM + linear polynomial (this project)", _loaded_disp(poly), ref)
    nodes = fine["plate"]["nodes"]
    row(f"RPIM on {nodes[0]}×{nodes[1]}×{nodes[2]} nodes (this project)", _loaded_disp(fine), ref)
    for key in sorted(k for k in ccx if k[0] == sup):
        row(_ccx_label(ccx[key]) + f"; {sup}", ccx[key]["top_centre"]["displacement"], ref)
    a = paper.get("ansys_check", {})
    if a:
        for label, key in (("paper: ANSYS (002 §5.2)", "ansys_mm"), ("paper: RPIM (002 §5.2)", "paper_rpim_mm")):
            u = np.asarray(a[key], dtype=float) / MM
            row(label, u, ref)
    write_table(ctx, "rpim_ansys_check",
                ["model", "u_x (mm)", "u_y (mm)", "u_z (mm)", "f·u (mJ)",
                 "u_x / CalculiX 10×10×2", "u_y / CalculiX 10×10×2", "u_z / CalculiX 10×10×2"], rows,
                f"Displacement of node 61 under the force ({', '.join(f'{v:g}' for v in force)}) N "
                "(002 §5.2). f·u < 0 in the paper's rows: its in-plane signs follow another "
                "convention (see cpp/apps/rpim_precompute.md); compare magnitudes. The loaded node "
                "of a point force has no converged value (u ∝ 1/h), so each row belongs to its "
                "own resolution.")
    return rows


def _readings_table(ctx, paper, readings, ccx):
    eq49 = paper.get("eq49_mm_per_N", {})
    ansys = np.asarray(paper.get("ansys_check", {}).get("ansys_mm", [np.nan] * 3), dtype=float)
    rows = []
    for r in readings:
        p = r.payload
        sup = p["plate"]["supports"]
        u = _loaded_disp(p) * MM
        c = _compliance(p) * MM
        c10 = ccx.get((sup, (10, 10, 2)))
        c20 = ccx.get((sup, (20, 20, 4)))
        u10 = np.asarray(c10["top_centre"]["displacement"]) * MM if c10 else [None] * 3
        u20 = np.asarray(c20["top_centre"]["displacement"]) * MM if c20 else [None] * 3
        rows.append([sup, _dc_label(p["model"]), u[0], u[1], u[2], c[0], c[2],
                     u10[0], u10[2], u20[0], u20[2],
                     None if c10 is None else float(np.linalg.norm(np.asarray(u10) / 1.0) / np.linalg.norm(ansys))])
    rows.append(["paper: ANSYS / paper eq. 49", "–", ansys[0], ansys[1], ansys[2],
                 abs(eq49.get("x", np.nan)), abs(eq49.get("z", np.nan)), None, None, None, None, 1.0])
    write_table(ctx, "rpim_support_readings",
                ["supports", "d_c", "RPIM u_x (mm)", "RPIM u_y (mm)", "RPIM u_z (mm)",
                 "RPIM |u_x/F_x| (mm/N)", "RPIM |u_z/F_z| (mm/N)",
                 "CalculiX 10×10×2 u_x", "CalculiX 10×10×2 u_z", "CalculiX 20×20×4 u_x", "CalculiX 20×20×4 u_z",
                 "|u| CalculiX 10×10×2 / |u| paper ANSYS"], rows,
                "The three readings of \"four edges are fixed\" (002 §4.1) and the two readings of "
                "d_c = 2.0, under the §5.2 force at node 61. The last row holds the paper's ANSYS "
                "displacement and the slopes of its eq. 49 (its RPIM model's compliance).")


def _far_field_table(ctx, runs, ccx):
    """RPIM top displacements against CalculiX's 11 × 11 grid, matched by position (a finer RPIM
    node set holds the grid among its top nodes)."""
    rows = []
    for p in runs:
        sup = p["plate"]["supports"]
        pos = np.asarray(p["top_nodes"], dtype=float)
        u_all = np.asarray(p["cases"][0]["top_displacement"], dtype=float)
        centre = pos[p["loaded_node"] - 1, :2]
        nodes = p["plate"]["nodes"]
        for div in ((10, 10, 2), (20, 20, 4)):
            c = ccx.get((sup, div))
            if c is None:
                continue
            gp = np.asarray(c["top_grid"]["positions"], dtype=float)
            idx = [int(np.argmin(np.linalg.norm(pos - q, axis=1))) for q in gp]
            if np.max(np.linalg.norm(pos[idx] - gp, axis=1)) > 1e-9:
                continue  # the grid is not among this run's nodes
            u = u_all[idx]
            uc = np.array([x if x is not None else [np.nan] * 3 for x in c["top_grid"]["displacement"]], dtype=float)
            far = (np.linalg.norm(gp[:, :2] - centre, axis=1) >= 9.5e-3) & np.all(np.isfinite(uc), axis=1)
            diff = np.linalg.norm(u[far] - uc[far], axis=1)
            scale = np.linalg.norm(uc[far], axis=1).max()
            ratio = np.linalg.norm(u[far], axis=1).sum() / np.linalg.norm(uc[far], axis=1).sum()
            rows.append([sup, f"{nodes[0]}×{nodes[1]}×{nodes[2]}", _dc_label(p["model"]), f"{div[0]}×{div[1]}×{div[2]}",
                         int(far.sum()), float(np.sqrt(np.mean(diff ** 2)) / scale), float(diff.max() / scale),
                         float(ratio)])
    write_table(ctx, "rpim_far_field",
                ["supports", "RPIM nodes", "d_c", "CalculiX C3D20R", "grid nodes",
                 "RMS |u_RPIM − u_CalculiX| / max |u_CalculiX|", "max |u_RPIM − u_CalculiX| / max |u_CalculiX|",
                 "Σ|u_RPIM| / Σ|u_CalculiX|"], rows,
                "Top-grid nodes at least 9.6 mm (two grid steps) from node 61, where the point-load "
                "singularity has faded: the RPIM field against CalculiX on the same plate and supports, "
                "under the §5.2 force. Both discretisations are too stiff when coarse; the ratio in the "
                "last column rises as the RPIM nodes are refined.")


def _centre_line_plot(ctx, check, poly, ccx):
    sup = check["plate"]["supports"]
    pos = np.asarray(check["top_nodes"], dtype=float)
    j = 5  # y = 24 mm: nodes 56..66
    idx = [i + 11 * j for i in range(11)]
    x = pos[idx, 0] * MM
    fig, axes = plots.plt.subplots(1, 2, figsize=(10, 4), dpi=110)
    for comp, ax in zip((0, 2), axes):
        for label, p, style in (("RPIM (paper's parameters)", check, "o-"), ("RPIM + linear polynomial", poly, "s--")):
            u = np.asarray(p["cases"][0]["top_displacement"], dtype=float)[idx, comp] * MM
            ax.plot(x, u, style, label=label, ms=4)
        for key in sorted(k for k in ccx if k[0] == sup):
            g = ccx[key]["top_grid"]["displacement"]
            u = np.array([g[k][comp] if g[k] is not None else np.nan for k in idx]) * MM
            ax.plot(x, u, "^:", label=_ccx_label(ccx[key]), ms=4)
        ax.set_xlabel("x (mm) along y = 24 mm (nodes 56–66)")
        ax.set_ylabel(f"u_{'xyz'[comp]} (mm)")
        ax.grid(True, alpha=0.3)
    axes[0].legend(fontsize=7)
    fig.suptitle(f"Top centre line under the §5.2 force, supports {sup}", fontsize=9)
    plots.save(fig, ctx.out("rpim_centre_line.png"))


# --------------------------------------------------------------------------- material
def _lee_radok_table(ctx, paper, check):
    ind = check.get("indentation")
    if not ind:
        return
    e_paper = paper.get("material", {}).get("youngs_modulus_MPa")
    # The depth at which eq. 47-48 would give the scene's modulus for the same force and probe:
    # E ∝ δ^(-3/2)  =>  δ = δ₀ (E₀ / E)^(2/3).
    depth_for_scene = ind["depth"] * (ind["youngs_modulus"] / ind["scene_youngs_modulus"]) ** (2.0 / 3.0)
    force_for_scene = ind["force"] * ind["scene_youngs_modulus"] / ind["youngs_modulus"]
    rows = [["F (N)", ind["force"]], ["δ (mm)", ind["depth"] * MM], ["R (mm)", ind["probe_radius"] * MM],
            ["ν", ind["poisson_ratio"]],
            ["G = 3F / (16 δ √(Rδ)) (kPa), eq. 47", ind["shear_modulus"] / 1e3],
            ["E = 2G(1 + ν) (MPa), eq. 48", ind["youngs_modulus"] / 1e6],
            ["paper: E (MPa), 002 §4.1", e_paper],
            ["E (eq. 48) / E used by the model", ind["ratio_to_scene"]],
            ["δ that would give the model's E at this F (mm)", depth_for_scene * MM],
            ["F that would give the model's E at this δ (N)", force_for_scene]]
    write_table(ctx, "rpim_lee_radok", ["quantity", "value"], rows,
                "002 eqs. 47–48 evaluated with the paper's own inputs (6 mm, 0.4 N, R = 2 mm, ν = 0.49).")


# --------------------------------------------------------------------------- conditioning
def _cond_row(label, c):
    mm, sc = c["moment_matrix"], c["shape_consistency"]
    kp, kf = c.get("stiffness_penalized"), c.get("stiffness_free_dofs")
    return [label, mm["condition_min"], mm["condition_median"], mm["condition_max"],
            c["support_nodes"]["min"], c["support_nodes"]["mean"], c["support_nodes"]["max"],
            sc["partition_of_unity_error"], sc["linear_reproduction_error"], sc["gradient_reproduction_error"],
            c["rigid_mode_energy"]["max_ratio"],
            None if kf is None else kf["condition"], None if kp is None else kp["condition"],
            c["factorisation_pivot_ratio"]]


COND_HEADERS = ["model", "moment cond min", "moment cond median", "moment cond max",
                "support min", "support mean", "support max", "max |Σφ−1|", "max |Σφ(x_I−x)|/h",
                "max |Σ∇φ x_Iᵀ − I|", "rigid-mode energy ratio", "cond K (free dofs)",
                "cond K (with penalty)", "min pivot / max diag K"]


def _conditioning_table(ctx, check, poly):
    rows = [_cond_row("RPIM, paper's parameters (no polynomial)", check["conditioning"]),
            _cond_row("RPIM + linear polynomial", poly["conditioning"])]
    write_table(ctx, "rpim_conditioning", COND_HEADERS, rows,
                "Moment matrices at the 4096 Gauss points (1-norm condition estimates), shape-function "
                "consistency, the rigid-body energy of K before supports (uᵀKu / (|u|² mean diag K)), "
                "and the 2-norm condition of K (Lanczos) without and with the penalty λ = 1e7.")


# --------------------------------------------------------------------------- stability sweep
def _stability(ctx, stages):
    all_rows = []
    fig, axes = plots.plt.subplots(2, 4, figsize=(14, 6.5), dpi=110, sharex="col")
    params = ["q", "alpha_c", "support_spacing_factor", "nearest_count"]
    for stage in stages:
        for run in ctx.runs(stage):
            p = run.payload
            variant = p["base"]["polynomial"]
            rows = []
            for pt in p["points"]:
                ok = pt["status"] == "ok"
                c = pt.get("conditioning") or {}
                rows.append([variant, pt["parameter"], pt["value"], pt["status"],
                             c.get("moment_matrix", {}).get("condition_max") if ok else None,
                             (c.get("stiffness_free_dofs") or {}).get("condition") if ok else None,
                             c.get("shape_consistency", {}).get("partition_of_unity_error") if ok else None,
                             c.get("rigid_mode_energy", {}).get("max_ratio") if ok else None,
                             pt["compliance"][0] * MM if ok else None, pt["compliance"][2] * MM if ok else None,
                             None if ok else _short(pt["message"])])
            all_rows += rows
            for col, name in enumerate(params):
                pts = [pt for pt in p["points"] if pt["parameter"] == name]
                if not pts:
                    continue
                good = [pt for pt in pts if pt["status"] == "ok"]
                bad = [pt for pt in pts if pt["status"] != "ok"]
                marker = "o-" if variant == "none" else "s--"
                axes[0, col].plot([pt["value"] for pt in good], [pt["compliance"][2] * MM for pt in good], marker,
                                  ms=4, label=f"polynomial: {variant}")
                axes[1, col].semilogy([pt["value"] for pt in good],
                                      [pt["conditioning"]["moment_matrix"]["condition_max"] for pt in good], marker,
                                      ms=4, label=f"polynomial: {variant}")
                for pt in bad:
                    for row in (0, 1):
                        axes[row, col].axvline(pt["value"], color="red" if variant == "none" else "orange",
                                               alpha=0.5, lw=1)
                axes[1, col].set_xlabel(name + (" (× mean spacing)" if name == "support_spacing_factor" else ""))
                if name in ("alpha_c", "nearest_count"):
                    axes[0, col].set_xscale("log")
                    axes[1, col].set_xscale("log")
    axes[0, 0].set_ylabel("|u_z/F_z| at node 61 (mm/N)")
    axes[1, 0].set_ylabel("max moment-matrix condition")
    for ax in axes.flat:
        ax.grid(True, alpha=0.3)
    axes[0, 0].legend(fontsize=7)
    fig.suptitle("Stability sweep (one parameter varied at a time around the paper's setting); "
                 "vertical lines: NumericalError (red: no polynomial, orange: linear)", fontsize=9)
    plots.save(fig, ctx.out("rpim_stability.png"))
    write_table(ctx, "rpim_stability",
                ["polynomial", "parameter", "value", "status", "moment cond max", "cond K (free dofs)",
                 "max |Σφ−1|", "rigid-mode energy", "|u_x/F_x| (mm/N)", "|u_z/F_z| (mm/N)", "failure"],
                all_rows,
                "Each row changes one parameter of the default (α_c = 1, d_c = 2 mm, q = 1.03, support radius "
                "3 h); \"numerical_error\" rows are runs that stop with exit code 3 instead of returning a "
                "model (singular moment matrix, or shape functions that cannot reproduce a constant).")
    return all_rows


# --------------------------------------------------------------------------- convergence
def _convergence(ctx, stages):
    rows, rates = [], []
    fig, ax = plots.figure()
    for stage in stages:
        for run in ctx.runs(stage):
            p = run.payload
            m = p["model"]
            label = (f"{p['block']['field']}: α_c = {m['alpha_c']:g}, d_c = {m['d_c_requested'].get('spacing_factor', '?')} h, "
                     f"polynomial {m['polynomial']}")
            h = [r["spacing"] for r in p["rows"]]
            e = [r["relative_rms_error"] for r in p["rows"]]
            ax.loglog(h, e, "o-", ms=4, label=label)
            for r in p["rows"]:
                rows.append([label, r["nodes_per_edge"], r["spacing"], r["relative_rms_error"], r["relative_max_error"]])
            rates.append([label, p["observed_rate"]["rms"], p["observed_rate"]["max"]])
    ax.set_xlabel("nodal spacing h (m), unit cube")
    ax.set_ylabel("RMS nodal error / max |u_exact|")
    ax.legend(fontsize=6)
    ax.set_title("Manufactured solutions on a block, all boundary nodes held by penalty", fontsize=9)
    plots.save(fig, ctx.out("rpim_convergence.png"))
    write_table(ctx, "rpim_convergence", ["variant", "nodes per edge", "h (m)", "relative RMS error", "relative max error"],
                rows, "Node refinement of a unit cube (E = 1000 Pa, ν = 0.3, 3³ Gauss points per cell, one cell "
                      "per nodal interval, support radius 3 h). plane_wave: u = c sin(a·x) with its exact body "
                      "force; linear_patch: the Galerkin patch test.")
    write_table(ctx, "rpim_convergence_rates", ["variant", "observed rate (RMS)", "observed rate (max)"], rates,
                "Least-squares slopes of log error against log h.")
    return rates


# --------------------------------------------------------------------------- quadrature, datasets, timing
def _quadrature_table(ctx, runs):
    rows = []
    for r in sorted(runs, key=lambda r: r.payload["plate"]["gauss_order"]):
        p = r.payload
        u = _loaded_disp(p) * MM
        c = _compliance(p) * MM
        rows.append([p["plate"]["gauss_order"], p["conditioning"]["gauss_points"], u[0], u[1], u[2], c[0], c[2],
                     p["timing"]["total_s"]])
    write_table(ctx, "rpim_quadrature", ["Gauss order per direction", "Gauss points", "u_x (mm)", "u_y (mm)", "u_z (mm)",
                                          "|u_x/F_x| (mm/N)", "|u_z/F_z| (mm/N)", "precompute (s)"], rows,
                "Node 61 under the §5.2 force against the Gauss rule of the 64 background cells "
                "(002 does not state it; 4 is the default).")


def _set_timings(ctx, refs):
    """The whole-run timing of every dataset-set stage among refs ("stage/member"), once each."""
    out = {}
    for ref in refs:
        stage, _, member = ref.partition("/")
        if member and stage not in out:
            out[stage] = [r.payload["timing"] for r in ctx.runs(stage)]
    return out


def _datasets_table(ctx, refs, paper):
    rows, timing_rows = [], []
    sets = _set_timings(ctx, refs)
    # A set's members share one build: its total counts once.
    total = sum(t["total_s"] for ts in sets.values() for t in ts)
    for ref in refs:
        for p in _payloads(ctx, ref):
            stage = ref
            d = p["dataset"]
            u = np.asarray([c["top_displacement"] for c in p["cases"]], dtype=float)
            u61 = u[:, p["loaded_node"] - 1, :] * MM
            f = np.asarray([c["force"] for c in p["cases"]], dtype=float)
            rows.append([stage, d["kind"], d["count"], d["seed"], float(np.linalg.norm(f, axis=1).min()),
                         float(np.linalg.norm(f, axis=1).max()), float(np.abs(u61).max()),
                         float(np.linalg.norm(u, axis=2).max() * MM)])
            t = p["timing"]
            if "/" not in ref:
                total += t["total_s"]
            timing_rows.append([stage, t["cases_solved"], t["shape_functions_s"], t["assembly_s"], t["penalty_s"],
                                t["factorisation_s"], t["solves_s"], t["total_s"], t["threads"]])
    for stage, ts in sets.items():
        for t in ts:
            timing_rows.append([f"{stage}: all {t['datasets']} datasets, one build", t["cases_solved"], None, None,
                                None, None, t["solves_s"], t["total_s"], None])
    write_table(ctx, "rpim_datasets", ["stage", "kind", "cases", "seed", "min |F| (N)", "max |F| (N)",
                                        "max |u_61 component| (mm)", "max |u| top (mm)"], rows,
                "The rpim_dataset artifacts read by marquardt_fit (forces at node 61; all 121 top nodes stored).")
    rt = paper.get("run_time_s", {})
    timing_rows.append(["paper: one full RPIM solve (002 §5.1.2)", 1, None, None, None, None, None,
                        rt.get("rpim_full_solve"), None])
    write_table(ctx, "rpim_timing", ["run", "load cases", "shape functions (s)", "assembly (s)", "penalty (s)",
                                      "factorisation (s)", "solves (s)", "total (s)", "threads"], timing_rows,
                "Wall-clock breakdown recorded in each artifact; the members of a dataset set share one build "
                "and factorisation (the build columns repeat it, each total is that build plus the member's own "
                "solves, and the set's row is the whole run). The machine is shared, so compare orders of "
                "magnitude. cpp/bench/bench_rpim.cpp times the whole precompute of all datasets in one process.")
    return total


# --------------------------------------------------------------------------- summary
def _summary(ctx, check, poly, ccx, total_time, rates, paper):
    sup = check["plate"]["supports"]
    u = _loaded_disp(check) * MM
    c10 = ccx.get((sup, (10, 10, 2)))
    u10 = np.asarray(c10["top_centre"]["displacement"]) * MM if c10 else None
    ansys = paper.get("ansys_check", {}).get("ansys_mm")
    ind = check.get("indentation")
    cond = check["conditioning"]
    lines = ["## RPIM meshless plate model (002 §2, §4.1, §5.2)\n",
             f"- Node 61 under (0.9, −0.7, −0.22) N, supports `{sup}`, the paper's α_c = 1, d_c = 2 mm, "
             f"q = 1.03 on 11×11×3 nodes: ({fmt(u[0])}, {fmt(u[1])}, {fmt(u[2])}) mm. "
             + (f"CalculiX C3D20R with 4.8 mm elements on the same plate and supports: "
                f"({fmt(u10[0])}, {fmt(u10[1])}, {fmt(u10[2])}) mm. " if u10 is not None else "")
             + (f"Paper: ANSYS ({', '.join(fmt(v) for v in ansys)}) mm. " if ansys else "")
             + "See [rpim_ansys_check.md](rpim/rpim_ansys_check.md) and "
               "[rpim_support_readings.md](rpim/rpim_support_readings.md).",
             "- Far from the load the RPIM field is compared with CalculiX in [rpim_far_field.md](rpim/rpim_far_field.md) "
             "and along the centre line in ![](rpim/rpim_centre_line.png)."]
    if ind:
        lines.append(f"- Lee–Radok with the paper's inputs (0.4 N, 6 mm, R = 2 mm, ν = 0.49) gives "
                     f"E = {fmt(ind['youngs_modulus'] / 1e6)} MPa, {fmt(ind['ratio_to_scene'])} × the 0.32 MPa "
                     "the paper uses ([rpim_lee_radok.md](rpim/rpim_lee_radok.md)).")
    lines.append(f"- Conditioning: moment matrices up to {fmt(cond['moment_matrix']['condition_max'])}, "
                 f"K on free dofs {fmt((cond.get('stiffness_free_dofs') or {}).get('condition'))}; without the "
                 f"polynomial a rigid translation costs a strain-energy ratio of {fmt(cond['rigid_mode_energy']['max_ratio'])} "
                 f"(with it: {fmt(poly['conditioning']['rigid_mode_energy']['max_ratio'])}). Stability sweep: "
                 "[rpim_stability.md](rpim/rpim_stability.md), ![](rpim/rpim_stability.png).")
    if rates:
        lines.append("- Convergence under node refinement (manufactured solutions): "
                     + "; ".join(f"{r[0]}: rate {fmt(r[1], 3)}" for r in rates)
                     + " ([rpim_convergence.md](rpim/rpim_convergence.md)).")
    lines.append(f"- The fit datasets took {fmt(total_time, 3)} s of precompute in total "
                 f"(paper: {fmt(paper.get('run_time_s', {}).get('rpim_full_solve'))} s per RPIM solve); "
                 "[rpim_timing.md](rpim/rpim_timing.md).")
    ctx.out("rpim_model_summary.md").write_text("\n".join(lines) + "\n")


def report(ctx):
    prm = ctx.params
    paper = ctx.experiment.get("paper", {})
    check = _single(ctx, prm["check"])
    poly = _single(ctx, prm["polynomial"])
    fine = _single(ctx, prm["fine"])
    ccx = _ccx_runs(ctx, prm["calculix"])
    readings = ctx.runs(prm["readings"])
    _check_tables(ctx, paper, check, poly, fine, ccx)
    _readings_table(ctx, paper, readings, ccx)
    _far_field_table(ctx, [r.payload for r in readings] + [fine], ccx)
    _centre_line_plot(ctx, check, poly, ccx)
    _lee_radok_table(ctx, paper, check)
    _conditioning_table(ctx, check, poly)
    _stability(ctx, prm["stability"])
    rates = _convergence(ctx, prm["convergence"])
    _quadrature_table(ctx, ctx.runs(prm["quadrature"]))
    total = _datasets_table(ctx, prm["datasets"], paper)
    _summary(ctx, check, poly, ccx, total, rates, paper)
