"""000 Fig. 9 equivalent: the deformed cuboid for all-linear, all-TLED and mixed partitions
→ results/dhd/fig9.png (the whole block and its half cut open at the centre plane, coloured by
|u|; a second row coloured by the difference to all-TLED), fig9_<case>.vtu for ParaView, and the
"fig9" part of summary.md.

Element kind is shown as in 000 Fig. 10: light triangle edges for TLED (nonlinear) elements, dark
edges for linear ones (blue for corotational). 000 Fig. 9(c)'s caption puts the linear elements in
the upper part, unlike §2.2.1 and Fig. 10 (upper part nonlinear); both mixed cases are drawn.

Inputs: "mesh" (the cuboid), "sim" (a dhd_sim stage swept over the share r and the load: the
all-TLED, all-linear and mixed-share runs at params "applied" are taken from it), and optionally
"extra" stages (more cases at the same load, e.g. the top layers linear)."""
import numpy as np

from pipeline import plots
from pipeline.reports import dhd_common as common
from pipeline.tables import fmt, write_table


def half_boundary(nodes, tets, axis=1, keep_below=None):
    """Boundary triangles of the tets whose centroid lies below `keep_below` along `axis` (the
    block cut open); with keep_below None, the whole block."""
    tets = np.asarray(tets)
    if keep_below is None:
        keep = np.arange(len(tets))
    else:
        keep = np.flatnonzero(nodes[tets].mean(axis=1)[:, axis] < keep_below)
    faces = {}
    for t in tets[keep]:
        for f in ((t[1], t[2], t[3]), (t[0], t[2], t[3]), (t[0], t[1], t[3]), (t[0], t[1], t[2])):
            key = tuple(sorted(int(v) for v in f))
            faces[key] = None if key in faces else f
    return np.array([f for f in faces.values() if f is not None], dtype=int), keep


def _case_label(x):
    if x["cheap_elements"] == 0:
        return "all TLED (000 Fig. 9b)"
    if x["tled_elements"] == 0:
        return f"all {x['cheap_kind']} (000 Fig. 9a)"
    return x["label"]


def report(ctx):
    applied = float(ctx.params.get("applied", 0.01))
    mixed_r = float(ctx.params.get("mixed_r", 0.5))
    mesh = ctx.runs("mesh")[0].payload
    nodes = np.asarray(mesh["nodes"], dtype=float)
    tets = np.asarray(mesh["tets"], dtype=int)
    rows = [x for x in common.sim_rows(ctx, ctx.params.get("sim", "sim_layer"))
            if abs(x["applied"] - applied) < 1e-12]
    ref = dict(next(x for x in rows if x["cheap_elements"] == 0), slug="all_tled")
    all_cheap = next(x for x in rows if x["tled_elements"] == 0)
    cases = [dict(all_cheap, slug=f"all_{all_cheap['cheap_kind']}"), ref]
    mixed = next(x for x in rows if common.at_share(x, mixed_r))
    cases.append(dict(mixed, slug="mixed_top_tled",
                      label=f"lower {fmt(100 * mixed['r'])} % linear, upper part TLED (000 Fig. 10)"))
    for stage in ctx.params.get("extra", ["sim_top_linear"]):
        for x in common.sim_rows(ctx, stage):
            if abs(x["applied"] - applied) < 1e-12:
                cases.append(dict(x, slug=stage.replace("sim_", "mixed_"), label=f"upper {fmt(100 * x['r'])} % linear, lower part "
                                                             "TLED (000 Fig. 9c caption)"))
    u_ref = common.displacement(ref["run"])
    cut = 0.5 * (nodes[:, 1].min() + nodes[:, 1].max())
    tri_full, _ = half_boundary(nodes, tets)
    tri_half, _ = half_boundary(nodes, tets, axis=1, keep_below=cut)
    vmax = max(np.linalg.norm(common.displacement(x["run"]), axis=1).max() for x in cases) * 1e3
    dmax = max(np.linalg.norm(common.displacement(x["run"]) - u_ref, axis=1).max() for x in cases) * 1e3 or 1.0

    n = len(cases)
    # mplot3d draws the z label of the top row's view, and the x label, outside the panel: the
    # spacing leaves room for them, and transparent panels never paint over a neighbour's labels.
    fig = plots.plt.figure(figsize=(3.6 * n + 1.0, 10.4), dpi=110)
    grid = fig.add_gridspec(3, n, left=0.03, right=0.88, top=0.92, bottom=0.03, wspace=0.18, hspace=0.2)
    table = []
    for i, x in enumerate(cases):
        u = common.displacement(x["run"])
        kinds = common.element_kind_names(x["run"].payload)
        diff = np.linalg.norm(u - u_ref, axis=1)
        ax = fig.add_subplot(grid[0, i], projection="3d", facecolor="none")
        m1 = common.draw_deformed(ax, nodes, tets, tri_full, u, kinds, vmax=vmax, view=(24, -62))
        ax.set_title(_case_label(x), fontsize=7)
        ax = fig.add_subplot(grid[1, i], projection="3d", facecolor="none")
        common.draw_deformed(ax, nodes, tets, tri_half, u, kinds, vmax=vmax, view=(12, 72))
        ax.set_title("cut open at the centre plane", fontsize=7)
        ax = fig.add_subplot(grid[2, i], projection="3d", facecolor="none")
        m2 = common.draw_difference(ax, nodes, tets, tri_half, u, kinds, diff * 1e3, dmax)
        ax.set_title("|u − u_TLED|, cut open", fontsize=7)
        e = common.displacement_error(u, u_ref, applied=applied)
        slug = x["slug"]
        common.write_vtu(ctx.out(f"fig9_{slug}.vtu"), nodes, tets, u, common.element_kinds(x["run"].payload),
                         {"difference_to_tled": u - u_ref})
        table.append([_case_label(x), x["counts"]["linear"], x["counts"]["tled"], x["counts"]["corotational"],
                      np.linalg.norm(u, axis=1).max() * 1e3, common.pct(e["rel_mean"], 3), diff.max() * 1e3,
                      f"[fig9_{slug}.vtu](dhd/fig9_{slug}.vtu)"])
    cb1 = fig.colorbar(m1, cax=fig.add_axes([0.91, 0.42, 0.014, 0.45]))
    cb1.set_label("|u| (mm), rows 1–2", fontsize=8)
    cb2 = fig.colorbar(m2, cax=fig.add_axes([0.91, 0.06, 0.014, 0.25]))
    cb2.set_label("|u − u_TLED| (mm), row 3", fontsize=8)
    fig.suptitle(f"Top centre pushed down {fmt(applied * 100)} cm (mm axes). Edges: white TLED, dark linear",
                 fontsize=9)
    plots.save(fig, ctx.out("fig9.png"), tight=False)
    md = write_table(ctx, "fig9", ["case", "linear", "TLED", "corotational", "max |u| (mm)", "e vs all-TLED (%)",
                                   "max |u − u_TLED| (mm)", "VTU"], table,
                     f"**000 Fig. 9 equivalent**, top centre pushed down {fmt(applied * 100)} cm, settled. The VTU "
                     "files hold the reference mesh with point data displacement and difference_to_tled and cell data "
                     "element_kind (0 linear, 1 TLED, 2 corotational); ParaView's Warp By Vector shows the deformation.")
    words = (f"All four cases deform into the same dimple; at this scale the pictures differ only in the colour of "
             f"the difference row: the all-linear block departs from all-TLED by up to {fmt(table[0][6], 3)} mm under "
             f"the tool, the mixed block with the TLED elements on top by {fmt(table[2][6], 3)} mm")
    if len(table) > 3:
        words += f", the mixed block with the linear elements on top (Fig. 9c's caption) by {fmt(table[3][6], 3)} mm"
    words += ": the nonlinearity sits under the tool, so the side that holds the TLED elements decides the error."
    common.write_section(ctx, "fig9", "### Fig. 9: the deformed cuboid\n\n![fig9](dhd/fig9.png)\n\n" + md + "\n"
                         + words + "\n")
