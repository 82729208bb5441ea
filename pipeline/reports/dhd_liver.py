"""The Tables 2–3 sweep on a real organ: a liver fixed on one side, one upper-surface node pushed
down → results/dhd/liver_<load>.md/csv, liver_error.png, liver.png and the "liver" part of
summary.md.

Inputs (params name them): "sets" (the mesh with the node sets "fixed" and "push"), the dhd_sim
stages of params "stages" (one strategy each, swept over r and the load), and optionally
"static" (the static all-TLED solution at one load: how settled the last step is)."""
import numpy as np

from pipeline import plots
from pipeline.reports import dhd_common as common
from pipeline.reports.dhd_partition import family_rows, run_at, share_winners, shares_at
from pipeline.tables import fmt, write_table


def report(ctx):
    unit, unit_scale = common.display_unit(ctx)
    mesh_run = ctx.runs(ctx.params.get("sets", "sets"))[0]
    mesh = mesh_run.payload
    nodes = np.asarray(mesh["nodes"], dtype=float)
    tets = np.asarray(mesh["tets"], dtype=int)
    sets = mesh["source"]["node_sets"]
    push = sets["push"]
    data = family_rows(ctx, ctx.params["stages"])
    labels = list(data)
    loads = sorted({load for fam in data.values() for load in fam})

    # Scene facts: the push must point into the organ.
    rows0 = common.sim_rows(ctx, ctx.params["stages"][0])
    direction = common.applied_vector(rows0[0]["run"].config)
    direction = direction / np.linalg.norm(direction)
    normal = np.asarray(push.get("outward_normal") or [0, 0, 0], dtype=float)
    angle = float(np.degrees(np.arccos(np.clip(-direction @ normal, -1, 1)))) if normal.any() else None
    size = nodes.max(axis=0) - nodes.min(axis=0)

    mds = []
    for load in loads:
        body = []
        for r in shares_at(data, load):
            row = [f"{int(round(100 * r))} %"]
            runs = [run_at(data, label, load, r) for label in labels]
            row += [common.pct(g["error"]["rel_mean"], 3) if g else None for g in runs]
            row += [g["error"]["max_diff"] * 1e3 if g else None for g in runs]
            body.append(row)
        name = f"liver_{fmt(load * unit_scale)}{unit}".replace(".", "p")
        mds.append(write_table(
            ctx, name, ["r"] + [f"e {lab} (%)" for lab in labels] + [f"max |Δu| {lab} (mm)" for lab in labels], body,
            f"**Liver, upper-surface node pushed {fmt(load * unit_scale)} {unit} into the organ**, settled; error "
            "e = Σ|u − u_TLED| / Σ|u_TLED| against the all-TLED run. 'layer': the elements deepest below the pushed "
            "node linear; 'distance': farthest from it; 'strain': smallest displacement gradient under the "
            "all-linear solution."))

    settle = None
    if ctx.params.get("static"):
        srows = common.sim_rows(ctx, ctx.params["static"])
        for s in srows:
            load = round(s["applied"], 12)
            ref = next((x for fam in data.values() for x in fam.get(load, []) if x["cheap_elements"] == 0), None)
            if ref is not None:
                settle = (load, common.displacement_error(common.displacement(ref["run"]),
                                                          common.displacement(s["run"]))["rel_mean"])

    # Error against r.
    fig, axes = plots.plt.subplots(1, len(loads), figsize=(5.2 * len(loads), 4.0), dpi=110, squeeze=False)
    for ax, load in zip(axes[0], loads):
        for i, label in enumerate(labels):
            g = [x for x in data[label].get(load, []) if x["r"] > 0]
            ax.plot([100 * x["r"] for x in g], [100 * x["error"]["rel_mean"] for x in g], marker="os^"[i % 3],
                    ms=4, label=label)
        ax.set_yscale("log")
        ax.set_xlabel("share of linear elements r (%)")
        ax.set_ylabel("mean error e (%)")
        ax.set_title(f"liver, push {fmt(load * unit_scale)} {unit}", fontsize=9)
        ax.grid(True, alpha=0.3)
    axes[0][0].legend(fontsize=7)
    common.save(fig, ctx, "liver_error.png")

    # Pictures: all-TLED and the mixed run of the best family at r = 0.5, largest load.
    load = loads[-1]
    ref = next(x for x in data[labels[0]][load] if x["cheap_elements"] == 0)
    best = min(labels, key=lambda lab: next((x["error"]["rel_mean"] for x in data[lab][load]
                                             if common.at_share(x, 0.5)), np.inf))
    mixed = next(x for x in data[best][load] if common.at_share(x, 0.5))
    layer_mixed = next((x for x in data.get(labels[0], {}).get(load, []) if common.at_share(x, 0.5)), None)
    cases = [("all TLED", ref), (f"{best}, r = 50 %", mixed)]
    if layer_mixed is not None and best != labels[0]:
        cases.append((f"{labels[0]}, r = 50 %", layer_mixed))
    tri = np.asarray(mesh["boundary"], dtype=int)
    u_ref = common.displacement(ref["run"])
    vmax = np.linalg.norm(u_ref, axis=1).max() * 1e3
    fig = plots.plt.figure(figsize=(4.2 * len(cases), 7.6), dpi=110)
    grid = fig.add_gridspec(2, len(cases), left=0.02, right=0.88, top=0.9, bottom=0.03, wspace=0.05, hspace=0.1)
    fixed = nodes[mesh["node_sets"]["fixed"]] * 1e3
    for i, (title, x) in enumerate(cases):
        u = common.displacement(x["run"])
        kinds = common.element_kind_names(x["run"].payload)
        ax = fig.add_subplot(grid[0, i], projection="3d")
        m1 = common.draw_deformed(ax, nodes, tets, tri, u, kinds, vmax=vmax, view=(28, -70))
        ax.scatter(fixed[:, 0], fixed[:, 1], fixed[:, 2], s=1, c="tab:red", alpha=0.5)
        ax.set_title(f"{title}: |u|", fontsize=8)
        ax = fig.add_subplot(grid[1, i], projection="3d")
        diff = np.linalg.norm(u - u_ref, axis=1) * 1e3
        dmax = max(np.linalg.norm(common.displacement(c[1]["run"]) - u_ref, axis=1).max() for c in cases) * 1e3 or 1.0
        m2 = common.draw_difference(ax, nodes, tets, tri, u, kinds, diff, dmax, view=(28, -70))
        ax.set_title(f"{title}: |u − u_TLED|", fontsize=8)
    fig.colorbar(m1, cax=fig.add_axes([0.91, 0.55, 0.014, 0.33])).set_label("|u| (mm)", fontsize=8)
    fig.colorbar(m2, cax=fig.add_axes([0.91, 0.08, 0.014, 0.33])).set_label("|u − u_TLED| (mm)", fontsize=8)
    fig.suptitle(f"Liver, push {fmt(load * unit_scale)} {unit} (mm axes; red dots: fixed nodes; edges: white TLED, "
                 "dark linear)", fontsize=9)
    plots.save(fig, ctx.out("liver.png"), tight=False)

    # Plain words.
    words = [f"The organ: {len(nodes)} nodes, {len(tets)} tets, {fmt(size[0] * 100, 3)} × {fmt(size[1] * 100, 3)} × "
             f"{fmt(size[2] * 100, 3)} cm; {sets['fixed']['count']} boundary nodes fixed at the thick end; the pushed "
             "node's outward normal is "
             + (f"{fmt(angle, 2)}° from the push reversed (the push points into the organ)." if angle is not None
                else "unknown.")]
    for load in loads:
        at = {lab: {int(round(100 * x["r"])): x["error"]["rel_mean"] for x in data[lab].get(load, [])} for lab in labels}
        order = sorted(labels, key=lambda lab: at[lab].get(50, np.inf))
        words.append(f"At {fmt(load * unit_scale)} {unit} and r = 50 % the errors are "
                     + ", ".join(f"{fmt(100 * at[lab].get(50, np.nan), 3)} % ({lab})" for lab in order)
                     + f"; all-linear is off by {fmt(100 * at[labels[0]].get(100, np.nan), 3)} %.")
    if settle:
        words.append(f"Settling check: the all-TLED state after the last step is {fmt(100 * settle[1], 2)} % from "
                     f"the static solution at {fmt(settle[0] * unit_scale)} {unit}; the hybrid runs share that slow "
                     "residual motion, so their differences from all-TLED move far less (experiments/dhd.md).")
    lines = ["### A real organ: the liver\n", "![liver](dhd/liver.png)\n"] + mds + [
        "Plot: [dhd/liver_error.png](dhd/liver_error.png).\n", " ".join(words) + "\n"]
    wins = {}
    for load in loads:
        for label in share_winners(data, load):
            wins[label] = wins.get(label, 0) + 1
    facts = {"best_family": max(wins, key=wins.get) if wins else None, "wins": wins}
    common.write_section(ctx, "liver", "\n".join(lines), facts)
