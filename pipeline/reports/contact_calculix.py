"""A rigid sphere pressed into a neo-Hookean block: our kinematic contact (dhd_sim) against
CalculiX's penalty contact on the same mesh (pipeline.stages.calculix_contact) and Hertz's
solution -> results/contact/: calculix.md/csv (force at several depths), calculix.png (force
against depth) and calculix_summary.md. Every sentence is computed from the runs."""
import numpy as np

from pipeline import plots
from pipeline.reports import contact_hertz
from pipeline.reports.contact_hertz import curve_of, hertz_force
from pipeline.tables import fmt, write_table

DEPTHS = (0.0005, 0.001, 0.0015, 0.002)  # m: where the table compares


def mesh_rows(ours, ccx):
    """Per depth: ours, CalculiX's and Hertz's force on one mesh, and the curves."""
    cfg = ours.config
    tool_cfg, mat = cfg["boundary"]["tools"][0], cfg["material"]
    radius, youngs, poisson = tool_cfg["radius"], mat["E"], mat["nu"]
    t, depth, force, tool = curve_of(ours)
    loading = t <= tool_cfg["ramp_time"]
    d_ccx, f_ccx = np.array(ccx["depth"]), np.array(ccx["force"])
    rows = []
    for d in DEPTHS:
        f_ours = float(np.interp(d, depth[loading], force[loading]))
        f_cx = float(np.interp(d, d_ccx, f_ccx))
        f_h = float(hertz_force(d, radius, youngs, poisson))
        rows.append([ccx["element_count"], 1e3 * d, 1e3 * f_ours, 1e3 * f_cx, 1e3 * f_h, f_ours / f_cx,
                     f_ours / f_h, f_cx / f_h])
    return rows, (depth[loading], force[loading]), (d_ccx, f_ccx), tool["contacts"]


def report(ctx):
    ccx_by_mesh = {r.config["mesh"]: r.payload for r in ctx.runs("ccx")}
    meshes = []
    for ours in ctx.runs("ours"):
        ccx = ccx_by_mesh[ours.config["mesh"]]
        meshes.append((ours, ccx, *mesh_rows(ours, ccx)))
    meshes.sort(key=lambda m: m[1]["element_count"])
    ours0, ccx0 = meshes[0][0], meshes[0][1]
    tool_cfg, mat = ours0.config["boundary"]["tools"][0], ours0.config["material"]
    radius, youngs, poisson = tool_cfg["radius"], mat["E"], mat["nu"]
    write_table(ctx, "calculix",
                ["tets", "depth (mm)", "ours (mN)", "CalculiX (mN)", "Hertz (mN)", "ours / CalculiX", "ours / Hertz",
                 "CalculiX / Hertz"], [row for m in meshes for row in m[2]],
                f"A rigid sphere (R = {fmt(1e3 * radius)} mm) pressed into a decoupled neo-Hookean block (E = "
                f"{fmt(youngs)} Pa, ν = {fmt(poisson)}), bottom fixed, frictionless, on each mesh. "
                "Ours: dhd_sim, explicit TLED, kinematic contact on the boundary nodes, the force while the sphere is "
                "pushed down (slow smooth ramp). CalculiX " + ccx0["ccx_version"] + ": the same tets (C3D4), NLGEOM "
                f"static, the sphere a rigid body ({ccx0['sphere_cap_elements']} facets of its lower cap), "
                f"surface-to-surface contact with a linear penalty of {fmt(ccx0['penalty'])} N/m³. Hertz: "
                "(4/3) E* √R d^(3/2) for a half-space.")

    fig, ax = plots.figure(6.0, 4.2)
    d = np.linspace(0, DEPTHS[-1], 200)
    ax.plot(1e3 * d, 1e3 * hertz_force(d, radius, youngs, poisson), "k--", label="Hertz (half-space)")
    for k, (ours, ccx, rows, (dd, ff), (dc, fc), _) in enumerate(meshes):
        n = ccx["element_count"]
        ax.plot(1e3 * dd, 1e3 * ff, "-", color=f"C{k}", label=f"ours (kinematic contact, TLED), {n} tets")
        ax.plot(1e3 * dc, 1e3 * fc, "o--", color=f"C{k}", ms=3, label=f"CalculiX (penalty contact, C3D4), {n} tets")
    ax.set_xlabel("depth d (mm)")
    ax.set_ylabel("force on the sphere (mN)")
    ax.set_title("Rigid sphere on a neo-Hookean block: ours, CalculiX, Hertz", fontsize=10)
    ax.legend(fontsize=7)
    plots.save(fig, ctx.out("calculix.png"))

    lines = ["## Contact: a rigid sphere against CalculiX", "",
             "The same sphere pressed into the same neo-Hookean block by our kinematic contact (dhd_sim) and by "
             "CalculiX's surface-to-surface penalty contact with a rigid-body sphere, on the same meshes "
             "([table](calculix.md), [plot](calculix.png)).", ""]
    for ours, ccx, rows, _, _, contacts in meshes:
        last = rows[-1]
        lines.append(
            f"- {ccx['element_count']} tets: at {fmt(last[1])} mm our force is {fmt(last[2], 3)} mN, CalculiX's "
            f"{fmt(last[3], 3)} mN (ours / CalculiX = {fmt(last[5], 3)}; at " +
            ", ".join(f"{fmt(r[1])} mm {fmt(r[5], 3)}" for r in rows[:-1]) +
            f"), Hertz's half-space force {fmt(last[4], 3)} mN; {contacts[-1]} of our nodes in contact when held; "
            f"CalculiX took {ccx['analysis']['increments_taken']} increments, {ccx['analysis']['iterations']} Newton "
            f"iterations, {fmt(ccx['wall_time_s'], 3)} s.")
    first, last_mesh = meshes[0][2][-1][5], meshes[-1][2][-1][5]
    finest = meshes[-1][2][-1]
    layer = float(contact_hertz.bonded_layer_factor(DEPTHS[-1], radius, contact_hertz.THICKNESS, poisson))
    lines += [
        f"- Against Hertz's solution corrected for the {fmt(1e3 * contact_hertz.THICKNESS)} mm layer bonded to the "
        f"fixed bottom ({fmt(layer, 3)}× the half-space force at {fmt(finest[1])} mm, Dimitriadis et al. 2002), on "
        f"{finest[0]} tets ours is {fmt(finest[2] / (layer * finest[4]), 3)}× and CalculiX's "
        f"{fmt(finest[3] / (layer * finest[4]), 3)}× (a small-strain solution for a finite-strain block: a guide, "
        "not a reference).",
        f"- The two contact formulations differ most where the mesh does not resolve the patch (contact radius "
        f"{fmt(1e3 * np.sqrt(radius * DEPTHS[-1]), 2)} mm at full depth): ours holds the block's nodes on the sphere, "
        "CalculiX's surface-to-surface contact presses the block's faces over their area (on the coarsest mesh our "
        "sphere bears on one node, CalculiX's on the faces around it, a stiffer load). The ratio at full depth "
        f"goes from {fmt(first, 3)} on the coarsest mesh to {fmt(last_mesh, 3)} on the finest compared: the two "
        "approach each other as the mesh resolves the patch.", ""]
    ctx.out("calculix_summary.md").write_text("\n".join(lines) + "\n")
