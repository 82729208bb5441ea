"""results/validation/: dhd_sim's static solve against CalculiX (and the analytic uniaxial
solution where one exists) on a cuboid, and CalculiX on paper 002's plate check.

params:
  "mesh": stage of the tet_mesh the comparisons ran on (for the analytic field),
  "comparisons": [{"case": name, "ccx": stage, "dhd": stage or null, "analytic": "uniaxial"|null,
                   "description": text}]
      ccx and dhd stages sweep the same material models in the same order; runs are paired by
      the material model each artifact reports,
  "plate": [stage, ...]  calculix_plate runs to tabulate,
  "plate_refinement": stage  (a sweep over divisions, optionally supports) for the plot,
  "plate_field": {"stage", "support", "divisions"}  the run whose top-surface field is drawn.
"""
import numpy as np

from pipeline.reports import dhd_common as common
from pipeline import plots
from pipeline.reports.dhd_common import displacement_error
from pipeline.stages.calculix_analytic import uniaxial_linear, uniaxial_neo_hookean_decoupled
from pipeline.tables import write_table

MM = 1e3
# Paper 002 numbers the 11 × 11 top grid N = x/4.8 + 11 y/4.8 + 1; node 61 is the centre.
LOADED_NODE = 61
NEAR_NODES = (50, 39)  # 4.8 mm and 9.6 mm from the loaded node along −y


# --------------------------------------------------------------------------- tet comparisons
def _model_of(payload):
    m = payload.get("material", {})
    return m.get("model") if isinstance(m, dict) else m


def _dhd_displacement(payload):
    u = payload.get("displacement")
    if u is None and isinstance(payload.get("static"), dict):
        u = payload["static"].get("displacement")
    return None if u is None else np.asarray(u, dtype=float)


def _top_reaction_vector(payload):
    """The total reaction (N) of the constraint named "prescribed top" (calculix_result and
    dhd_result name constraint entries alike), or None."""
    found = [c["force"] for c in payload.get("reactions", [])
             if c.get("name") == "prescribed top"]
    return np.asarray(found[0], dtype=float) if len(found) == 1 else None


def _along(vector, direction):
    return None if vector is None else float(np.dot(vector, direction))


def _prescribed_top(config):
    """The prescribed top motion (m) of a shared boundary block; unlisted components are 0."""
    for entry in config["boundary"].get("prescribed", []):
        if entry.get("set") == "top":
            comps = entry.get("components", "xyz")
            return np.array([entry["displacement"][k] if "xyz"[k] in comps else 0.0
                             for k in range(3)])
    raise ValueError("comparison case without a prescribed top displacement")


def _analytic_uniaxial(nodes, material, top_uz):
    """Homogeneous uniaxial field about the bottom-front-left corner and the axial force on the
    top face (N) for the bottom sliding on z = min, lateral faces free."""
    lo = nodes.min(axis=0)
    size = nodes.max(axis=0) - lo
    x = nodes - lo
    stretch = 1.0 + top_uz / size[2]
    area = size[0] * size[1]
    if material["model"] == "linear":
        lateral, _ = uniaxial_linear(material["nu"], stretch - 1.0)
        factors = np.array([lateral, lateral, stretch - 1.0])
        force = material["E"] * (stretch - 1.0) * area
    else:
        lt, _, nominal = uniaxial_neo_hookean_decoupled(material["mu"],
                                                        material["bulk_modulus"], stretch)
        factors = np.array([lt - 1.0, lt - 1.0, stretch - 1.0])
        force = nominal * area
    return x * factors, force


def _rel(a, b):
    return float(np.linalg.norm(a - b) / np.linalg.norm(b))


def _comparison_rows(ctx, nodes):
    rows, worst = [], {}
    for case in ctx.params["comparisons"]:
        ccx_runs = ctx.runs(case["ccx"])
        dhd_runs = {}
        if case.get("dhd"):
            for run in ctx.runs(case["dhd"]):
                dhd_runs[_model_of(run.payload)] = run
        for run in ccx_runs:
            pl = run.payload
            mat = pl["material"]
            u_ccx = np.asarray(pl["displacement"])
            exact, force_exact = (None, None)
            motion = _prescribed_top(run.config)
            direction = motion / np.linalg.norm(motion)
            if case.get("analytic") == "uniaxial":
                exact, force_exact = _analytic_uniaxial(nodes, mat, motion[2])
                force_exact *= direction[2]
            dhd = dhd_runs.get(mat["model"])
            u_dhd = _dhd_displacement(dhd.payload) if dhd else None
            err = _rel(u_dhd, u_ccx) if u_dhd is not None else None
            max_err = displacement_error(u_dhd, u_ccx)["rel_max"] if u_dhd is not None else None
            if err is not None:
                worst[(case["case"], mat["model"])] = err
            a = pl["analysis"]
            f_ccx = _top_reaction_vector(pl)
            f_dhd = _top_reaction_vector(dhd.payload) if dhd else None
            f_err = _rel(f_dhd, f_ccx) if f_dhd is not None and f_ccx is not None else None
            rows.append([
                case["case"], mat["model"], "yes" if a["nlgeom"] else "no",
                err, max_err,
                _rel(u_ccx, exact) if exact is not None else None,
                _rel(u_dhd, exact) if exact is not None and u_dhd is not None else None,
                _along(f_dhd, direction), _along(f_ccx, direction), force_exact, f_err,
                f"{a['increments_taken']}/{a['iterations']}",
            ])
    return rows, worst


# --------------------------------------------------------------------------- plate
def _grid_u(payload, number):
    g = payload["top_grid"]
    u = g["displacement"][g["paper_node_numbers"].index(number)]
    return None if u is None else np.asarray(u)


def _plate_rows(ctx, paper):
    rows, seen = [], set()
    for stage in ctx.params.get("plate", []):
        for run in ctx.runs(stage):
            pl = run.payload
            key = (pl["element_type"], tuple(pl["divisions"]), pl["support"],
                   pl["analysis"]["nlgeom"], tuple(pl["force"]))
            if key in seen:  # the same run listed by two stages
                continue
            seen.add(key)
            u = np.asarray(pl["top_centre"]["displacement"]) * MM
            near = [_grid_u(pl, n) for n in NEAR_NODES]
            d = pl["divisions"]
            rows.append([
                "ours (CalculiX)", pl["element_type"], f"{d[0]}×{d[1]}×{d[2]}",
                pl["element_size"][0] * MM, pl["support"],
                "NLGEOM" if pl["analysis"]["nlgeom"] else "linear",
                u[0], u[1], u[2], float(np.linalg.norm(u)),
                *[float(np.linalg.norm(v) * MM) if v is not None else None for v in near],
                pl["node_count"]])
    ref = paper.get("plate_002", {})
    for label, key, method, nodes, spacing in (
            ("paper: ANSYS", "ansys_displacement_mm", "?", "?", None),
            ("paper: RPIM-MM", "rpim_displacement_mm", "RPIM", ref.get("rpim_nodes", "?"),
             ref.get("rpim_node_spacing_mm"))):
        if key in ref:
            v = ref[key]
            rows.append([label + f" ({ref.get('source', '002')})", method, nodes, spacing,
                         "\"four edges fixed\"", "?", v[0], v[1], v[2],
                         float(np.linalg.norm(v)), None, None, None])
    return rows


def _refinement_plot(ctx, paper):
    stage = ctx.params.get("plate_refinement")
    if not stage:
        return None
    by_support = {}
    for r in ctx.runs(stage):
        by_support.setdefault(r.payload["support"], []).append(r)
    fig, ax = plots.figure(9.5, 4.8)
    styles = ["-", "--", ":"]
    for s_index, (support, runs) in enumerate(sorted(by_support.items(), reverse=True)):
        runs = sorted(runs, key=lambda r: -r.payload["element_size"][0])
        h = np.array([r.payload["element_size"][0] * MM for r in runs])
        ls = styles[s_index % len(styles)]
        series = [(f"node {LOADED_NODE} (loaded)", "o",
                   [r.payload["top_centre"]["displacement"] for r in runs])]
        for n in NEAR_NODES:
            series.append((f"node {n} ({4.8 * (LOADED_NODE - n) / 11:.1f} mm away)", "s",
                           [_grid_u(r.payload, n) for r in runs]))
        for k, (label, marker, values) in enumerate(series):
            ax.loglog(h, [np.linalg.norm(v) * MM for v in values], marker=marker, ls=ls,
                      color=f"C{k}", label=f"{label}, {support}")
    ref = paper.get("plate_002", {}).get("ansys_displacement_mm")
    if ref:
        ax.axhline(np.linalg.norm(ref), color="k", lw=0.8, ls="-.",
                   label="paper: ANSYS, node 61 (002 §5.2)")
    p0 = ctx.runs(stage)[0].payload
    sizes = sorted({r.payload["element_size"][0] * MM for r in ctx.runs(stage)})
    ax.set_xticks(sizes)
    ax.set_xticklabels([f"{v:g}" for v in sizes])
    ax.minorticks_off()
    lo, hi = ax.get_ylim()
    ticks = [t for t in (0.2, 0.3, 0.5, 1, 2, 3, 5, 10, 20, 30) if lo <= t <= hi]
    ax.set_yticks(ticks)
    ax.set_yticklabels([f"{t:g}" for t in ticks])
    ax.set_xlabel("in-plane element size h (mm)")
    ax.set_ylabel("‖u‖ (mm)")
    ax.set_title(f"CalculiX {p0['element_type']}: point force {tuple(p0['force'])} N at node 61",
                 fontsize=9)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    name = "calculix_plate_refinement.png"
    plots.save(fig, ctx.out(name))
    return name


def _field_plot(ctx):
    spec = ctx.params.get("plate_field")
    if not spec:
        return None
    matches = [r for r in ctx.runs(spec["stage"]) if r.payload["support"] == spec["support"]
               and r.payload["divisions"] == spec["divisions"]]
    if not matches:
        raise ValueError(f"plate_field: no run of {spec['stage']} with {spec}")
    pl = matches[0].payload
    x = np.asarray(pl["top_surface"]["positions"]) * MM
    u = np.asarray(pl["top_surface"]["displacement"]) * MM
    fig, ax = plots.figure(5.6, 4.6)
    ax.grid(False)
    t = ax.tricontourf(x[:, 0], x[:, 1], u[:, 2], levels=20, cmap="viridis")
    fig.colorbar(t, ax=ax, label="u_z (mm)")
    g = np.asarray(pl["top_grid"]["positions"]) * MM
    ax.plot(g[:, 0], g[:, 1], "k.", ms=2)
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    d = pl["divisions"]
    ax.set_title(f"top surface u_z, {pl['element_type']} {d[0]}×{d[1]}×{d[2]}, {pl['support']}",
                 fontsize=9)
    name = "calculix_plate_top_uz.png"
    plots.save(fig, ctx.out(name))
    return name


def _plate_findings(ctx, paper):
    """Measured statements about the refinement study (numbers computed, not quoted)."""
    stage = ctx.params.get("plate_refinement")
    if not stage:
        return ""
    by_support = {}
    for r in ctx.runs(stage):
        by_support.setdefault(r.payload["support"], []).append(r.payload)
    parts = []
    far = NEAR_NODES[-1]
    for support, pls in sorted(by_support.items(), reverse=True):
        pls = sorted(pls, key=lambda p: -p["element_size"][0])
        if len(pls) < 3:
            continue
        c0 = np.linalg.norm(pls[0]["top_centre"]["displacement"])
        c1 = np.linalg.norm(pls[-1]["top_centre"]["displacement"])
        f = [np.linalg.norm(_grid_u(p, far)) for p in pls]
        parts.append(
            f"with {support} fixed, refining h from {pls[0]['element_size'][0] * MM:g} to "
            f"{pls[-1]['element_size'][0] * MM:g} mm multiplies ‖u‖ at node {LOADED_NODE} by "
            f"{c1 / c0:.2f}, while at node {far} (9.6 mm away) the last two refinements change "
            f"‖u‖ by {100 * (f[-2] / f[-3] - 1):+.1f} % and {100 * (f[-1] / f[-2] - 1):+.1f} %")
    # A line support in 3-D acts like a point force in 2-D: its compliance is log-singular.
    text = ("Refinement study (C3D20R): " + "; ".join(parts) + ". A point force on a 3-D solid "
            "has no finite displacement under it (Kelvin: u ∝ F/(μr)), and a support along a "
            "line in 3-D has a logarithmically singular compliance, so with edge supports even "
            "distant nodes keep creeping up as h shrinks, while clamped faces give a converging "
            "field away from the load. Node 61's displacement is therefore only comparable between "
            "models of equal node spacing.")
    ref = paper.get("plate_002", {}).get("ansys_displacement_mm")
    coarse = [p for p in by_support.get("vertical_corner_edges", [])
              if abs(p["element_size"][0] * MM - 4.8) < 1e-9]
    if ref and coarse:
        u = np.asarray(coarse[0]["top_centre"]["displacement"]) * MM
        text += (f" At the paper's 4.8 mm spacing with the vertical corner edges fixed, CalculiX "
                 f"gives ‖u‖ = {np.linalg.norm(u):.3f} mm at node 61, u = ({u[0]:.3f}, "
                 f"{u[1]:.3f}, {u[2]:.3f}) mm; the paper's ANSYS value has ‖u‖ = "
                 f"{np.linalg.norm(ref):.3f} mm.")
    return text + "\n"


# --------------------------------------------------------------------------- report
def report(ctx):
    paper = ctx.experiment.get("paper", {})
    nodes = np.asarray(ctx.runs(ctx.params["mesh"])[0].payload["nodes"])
    mesh_q = ctx.runs(ctx.params["mesh"])[0].payload.get("quality", {})
    rows, worst = _comparison_rows(ctx, nodes)
    md_tet = write_table(
        ctx, "calculix_vs_dhd",
        ["case", "material", "NLGEOM", "‖u_dhd − u_ccx‖/‖u_ccx‖",
         "max_i ‖u_dhd − u_ccx‖_i / max_i ‖u_ccx‖_i",
         "‖u_ccx − u_exact‖/‖u_exact‖", "‖u_dhd − u_exact‖/‖u_exact‖",
         "top reaction dhd (N)", "top reaction CalculiX (N)", "top reaction analytic (N)",
         "‖F_dhd − F_ccx‖/‖F_ccx‖", "ccx increments/iterations"],
        rows,
        f"dhd_sim's static solve vs. CalculiX (C3D4, the same tetrahedra) on a cuboid of "
        f"{mesh_q.get('nodes', len(nodes))} nodes / {mesh_q.get('tets', '?')} tets. "
        "'uniaxial': bottom sliding on z = 0, lateral faces free (homogeneous analytic solution); "
        "'clamped_*': bottom fixed, top moved rigidly. u_exact is the analytic field; reactions "
        "are the top face's total force along the prescribed motion; '–' where no analytic "
        "solution exists or the run is absent.")
    plate_rows = _plate_rows(ctx, paper)
    md_plate = write_table(
        ctx, "calculix_plate",
        ["source", "element", "divisions", "h (mm)", "support", "analysis",
         "u_x node 61 (mm)", "u_y (mm)", "u_z (mm)", "‖u‖ node 61 (mm)",
         f"‖u‖ node {NEAR_NODES[0]} (mm)", f"‖u‖ node {NEAR_NODES[1]} (mm)", "nodes"],
        plate_rows,
        "Paper 002's plate check: 48 × 48 × 6 mm, E = 0.32 MPa, ν = 0.49, point force "
        "(0.9, −0.7, −0.22) N at the top-centre node 61. Rows marked 'paper' are the paper's "
        "numbers, copied from the experiment file; '?' where the paper does not say. h is the "
        "in-plane element edge (the node spacing of 20-node elements is h/2).")
    refinement = _refinement_plot(ctx, paper)
    field = _field_plot(ctx)

    lines = ["## Validation against CalculiX\n",
             "### dhd_sim static solve vs. CalculiX\n", md_tet]
    if worst:
        case, err = max(worst.items(), key=lambda kv: kv[1])
        lines.append(f"Largest relative L2 difference: {err:.2e} ({case[0]}, {case[1]}).\n")
    else:
        lines.append("No dhd_sim runs were available for this comparison.\n")
    lines += ["### Paper 002 plate: CalculiX reference\n", md_plate, _plate_findings(ctx, paper)]
    ref = paper.get("plate_002", {})
    if "ansys_displacement_mm" in ref:
        lines.append(
            "The paper's force (0.9, −0.7, −0.22) N and its ANSYS displacement "
            f"{tuple(ref['ansys_displacement_mm'])} mm have a negative product f·u, impossible for "
            "a single point force on an elastic body: the x and y signs of one of them follow "
            "another convention. By the plate's mirror symmetry, reversing the in-plane force "
            "reverses u_x and u_y exactly; compare magnitudes.\n")
    for name in (refinement, field):
        if name:
            lines.append(f"![{name}](validation/{name})\n")
    ctx.out("summary.md").write_text("\n".join(lines))
    common.append_material_line(ctx, ctx.out("summary.md"))
