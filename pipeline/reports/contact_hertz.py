"""A rigid sphere pressed into a block by frictionless kinematic contact (dhd_sim boundary.tools)
-> results/contact/: hertz.md/csv (per mesh: forces at three depths against Hertz, the fitted
exponent, the held force), hertz.png (force against depth, log-log, with Hertz's line) and
summary.md. Every sentence is computed from the runs."""
import math

import numpy as np

from pipeline import plots
from pipeline.bench import cpu_description
from pipeline.tables import fmt, write_table

DEPTHS = (0.0005, 0.001, 0.002)  # m: where the table compares
THICKNESS = 0.04                  # m: the block's height (experiments/contact_hertz.json)


def ramp_at(t, duration, shape):
    s = np.clip(np.asarray(t) / duration, 0.0, 1.0) if duration > 0 else np.ones_like(np.asarray(t))
    return s if shape == "linear" else s * s * (3.0 - 2.0 * s)


def hertz_force(depth, radius, youngs, poisson):
    """Hertz: a rigid sphere on an elastic half-space, F = (4/3) E* sqrt(R) d^(3/2)."""
    e_star = youngs / (1.0 - poisson ** 2)
    return 4.0 / 3.0 * e_star * math.sqrt(radius) * np.asarray(depth) ** 1.5


def bonded_layer_factor(depth, radius, thickness, poisson):
    """Dimitriadis et al. (2002, Biophys. J. 82, 2798, eqs. for a sample bonded to a rigid
    substrate): Hertz's force on a layer of finite thickness h is F_H times a series in
    χ = sqrt(R d) / h with α₀, β₀ fitted functions of ν. Our block's bottom is fixed (bonded)."""
    chi = np.sqrt(radius * np.asarray(depth)) / thickness
    nu = poisson
    a0 = -(1.2876 - 1.4678 * nu + 1.3442 * nu ** 2) / (1 - nu)
    b0 = (0.6387 - 1.0277 * nu + 1.5164 * nu ** 2) / (1 - nu)
    pi = math.pi
    return (1 - 2 * a0 / pi * chi + 4 * a0 ** 2 / pi ** 2 * chi ** 2
            - 8 / pi ** 3 * (a0 ** 3 + 4 * pi ** 2 * b0 / 15) * chi ** 3
            + 16 * a0 / pi ** 4 * (a0 ** 3 + 3 * pi ** 2 * b0 / 5) * chi ** 4)


def curve_of(run):
    """Depth (m) and force on the sphere (N, upwards positive) at the energy samples."""
    cfg = run.config
    tool_cfg = cfg["boundary"]["tools"][0]
    tool = run.payload["tools"][0]
    t = np.array(tool["time"])
    depth = -tool_cfg["travel"][2] * ramp_at(t, tool_cfg["ramp_time"], tool_cfg.get("ramp", "linear"))
    force = np.array(tool["force"])[:, 2]
    return t, depth, force, tool


def row_of(run):
    cfg = run.config
    mat = cfg["material"]
    tool_cfg = cfg["boundary"]["tools"][0]
    radius, youngs, poisson = tool_cfg["radius"], mat["E"], mat["nu"]
    t, depth, force, tool = curve_of(run)
    loading = t <= tool_cfg["ramp_time"]  # the depth grows monotonically while the ramp runs
    f_at = {d: float(np.interp(d, depth[loading], force[loading])) for d in DEPTHS}
    window = loading & (depth >= DEPTHS[0]) & (depth <= DEPTHS[-1])
    exponent = float(np.polyfit(np.log(depth[window]), np.log(force[window]), 1)[0])
    tets = run.payload["mesh"]["tets"]
    size = 0.08 * 0.08 * 0.04
    h = (size / (tets / 5)) ** (1 / 3)  # the cuboid's cell edge (five tets per cell)
    held = float(force[-1])
    layer = float(bonded_layer_factor(DEPTHS[-1], radius, THICKNESS, poisson))
    return {"layer": layer, "tets": tets, "nodes": run.payload["mesh"]["nodes"], "h": h, "radius": radius, "E": youngs, "nu": poisson,
            "f": f_at, "hertz": {d: float(hertz_force(d, radius, youngs, poisson)) for d in DEPTHS},
            "exponent": exponent, "held": held, "held_depth": float(depth[-1]),
            "held_hertz": float(hertz_force(depth[-1], radius, youngs, poisson)),
            "contacts": tool["contacts"][-1], "dt": run.payload["solver"]["dt"],
            "dt_critical": run.payload["solver"]["dt_critical"], "curve": (depth, force)}


HAPTIC = (("haptic_tool", "cuboid"), ("haptic_tool_liver", "liver"))


def haptic_rows(ctx):
    """The haptic runs with a rigid tool as the instrument (haptic_sim, probe.contact "tool")."""
    rows = []
    for stage, scene in HAPTIC:
        try:
            runs = ctx.runs(stage)
        except KeyError:
            continue
        for r in runs:
            p = r.payload
            force = np.array(p["force"])
            t = p["timing"]
            rows.append({"scene": scene, "tets": p["model"]["tets"], "frames": p["frames"], "substeps": p["substeps"],
                         "peak": float(np.linalg.norm(force, axis=1).max()), "final": force[-1].tolist(),
                         "contact_frames": int(np.sum(p["contact"])), "p50": t["frame_seconds_p50"],
                         "p99": t["frame_seconds_p99"], "misses": t["deadline_misses"], "events": len(p["events"]),
                         "frame_step": p["frame_step"]})
    return rows


def haptic_lines(ctx):
    rows = haptic_rows(ctx)
    if not rows:
        return []
    write_table(ctx, "haptic", ["scene", "tets", "frames", "substeps / frame", "frames in contact", "peak |F| (N)",
                                "final F_z (N)", "frame p50 (ms)", "frame p99 (ms)", "deadline misses", "events"],
                [[r["scene"], r["tets"], r["frames"], r["substeps"], r["contact_frames"], r["peak"], r["final"][2],
                  1e3 * r["p50"], 1e3 * r["p99"], r["misses"], r["events"]] for r in rows],
                "haptic_sim at 1 kHz with a rigid sphere as the instrument (probe.contact \"tool\"): pressed 1 cm "
                f"and held; whole model, one thread, on {cpu_description()}. A deadline miss is a frame whose "
                "computation took longer than the frame period.")
    return [f"- **Haptic scene, {r['scene']}** ({r['tets']} tets): the sphere as the instrument at 1 kHz, in contact in "
            f"{r['contact_frames']} of {r['frames']} frames, {fmt(r['final'][2], 3)} N on the device at full depth "
            f"(peak {fmt(r['peak'], 3)} N); frames {fmt(1e3 * r['p50'])} ms median, {fmt(1e3 * r['p99'])} ms p99, "
            f"{r['misses']} over the {fmt(1e3 * r['frame_step'])} ms deadline, {r['events']} numerical events "
            "([haptic](haptic.md))." for r in rows]


def report(ctx):
    rows = sorted((row_of(r) for r in ctx.runs("press")), key=lambda r: r["tets"])
    headers = ["tets", "cell h (mm)", "a/h at 2 mm"] + \
              [f"F at {fmt(1e3 * d)} mm (mN)" for d in DEPTHS] + \
              [f"Hertz at {fmt(1e3 * d)} mm (mN)" for d in DEPTHS] + \
              ["ratio at 2 mm", "layer-corrected Hertz at 2 mm (mN)", "ratio to it", "exponent (Hertz 1.5)",
               "held F / Hertz", "nodes in contact"]
    body = []
    for r in rows:
        a = math.sqrt(r["radius"] * DEPTHS[-1])
        body.append([r["tets"], 1e3 * r["h"], a / r["h"]] + [1e3 * r["f"][d] for d in DEPTHS]
                    + [1e3 * r["hertz"][d] for d in DEPTHS]
                    + [r["f"][DEPTHS[-1]] / r["hertz"][DEPTHS[-1]], 1e3 * r["layer"] * r["hertz"][DEPTHS[-1]],
                       r["f"][DEPTHS[-1]] / (r["layer"] * r["hertz"][DEPTHS[-1]]), r["exponent"],
                       r["held"] / r["held_hertz"], r["contacts"]])
    r0 = rows[0]
    write_table(ctx, "hertz", headers, body,
                f"A rigid sphere (R = {fmt(1e3 * r0['radius'])} mm) pressed into a linear elastic block (E = "
                f"{fmt(r0['E'])} Pa, ν = {fmt(r0['nu'])}) by frictionless kinematic contact (dhd_sim boundary.tools). "
                "F: the force on the sphere while it is pushed down (smooth ramp); Hertz: (4/3) E* √R d^(3/2), "
                "E* = E/(1 − ν²), for a half-space; a = √(R d), the contact radius; the exponent is the slope of "
                f"log F against log d for d in {fmt(1e3 * DEPTHS[0])}–{fmt(1e3 * DEPTHS[-1])} mm; held: the force at "
                "the end, the sphere held at full depth. Layer-corrected: Hertz times Dimitriadis et al.'s (2002) "
                f"series for a layer of thickness {fmt(1e3 * THICKNESS)} mm bonded to a rigid base (our fixed bottom).")

    fig, ax = plots.figure(6.0, 4.2)
    d = np.linspace(1e-4, DEPTHS[-1], 200)
    ax.loglog(1e3 * d, 1e3 * hertz_force(d, r0["radius"], r0["E"], r0["nu"]), "k--", label="Hertz (half-space)")
    for k, r in enumerate(rows):
        depth, force = r["curve"]
        keep = (depth > 1e-4) & (force > 0)
        ax.loglog(1e3 * depth[keep], 1e3 * force[keep], "-", color=f"C{k}",
                  label=f"ours, {r['tets']} tets (h = {fmt(1e3 * r['h'], 2)} mm)")
    ax.set_xlabel("depth d (mm)")
    ax.set_ylabel("force on the sphere (mN)")
    ax.set_title("Rigid sphere on an elastic block: kinematic contact against Hertz", fontsize=10)
    ax.legend(fontsize=7)
    plots.save(fig, ctx.out("hertz.png"))

    fine = rows[-1]
    ratios = [r["f"][DEPTHS[-1]] / r["hertz"][DEPTHS[-1]] for r in rows]
    layered = [r["f"][DEPTHS[-1]] / (r["layer"] * r["hertz"][DEPTHS[-1]]) for r in rows]
    resolved = [r for r in rows if r["contacts"] >= 5]  # a patch of a few nodes at least
    exps = ", ".join(f"{fmt(r['exponent'], 3)}" for r in rows)
    lines = [
        "## Contact: a rigid sphere against Hertz", "",
        "Frictionless kinematic contact of a rigid tool in the explicit engine (issue 23; dhd_sim `boundary.tools`, "
        "cpp/apps/dhd_sim.md): after each step a node inside the tool is moved to its surface, and the force the "
        "move takes is the contact force. [Table](hertz.md), [plot](hertz.png).", "",
        f"- At {fmt(1e3 * DEPTHS[-1])} mm the force on the sphere is "
        + ", ".join(f"{fmt(ratio, 3)}×" for ratio in ratios)
        + f" Hertz's half-space force on the {len(rows)} meshes ({', '.join(str(r['tets']) for r in rows)} tets), "
        f"and {', '.join(f'{fmt(x, 3)}×' for x in layered)} the force of Hertz's solution corrected for a "
        f"{fmt(1e3 * THICKNESS)} mm layer bonded to a rigid base (Dimitriadis et al. 2002; the correction is "
        f"{fmt(fine['layer'], 3)}× at this depth).",
        f"- The force grows as d^p with p = {exps} (Hertz: 1.5; a flat punch would give 1)"
        + (f"; the coarsest mesh's sphere touches {rows[0]['contacts']} node(s) at full depth, too few to resolve "
           "the contact patch." if rows[0]["contacts"] < 5 else "."),
        (f"- On the meshes that resolve the patch (≥ 5 nodes in contact), the force at full depth is within "
         f"{fmt(100 * max(abs(x - 1) for x, r in zip(layered, rows) if r in resolved), 2)} % of the "
         "layer-corrected solution." if resolved else "- No mesh resolves the contact patch (≥ 5 nodes)."),
        f"- Held at full depth, the finest mesh's force is {fmt(fine['held'] / fine['held_hertz'], 3)}× Hertz's with "
        f"{fine['contacts']} nodes in contact; the step was {fmt(fine['dt'])} s against a critical step of "
        f"{fmt(fine['dt_critical'])} s (the projection adds no stiffness: the critical step is the body's own).",
        *haptic_lines(ctx),
        "- Friction exists (`friction`); this frictionless comparison does not use it. CalculiX's contact on the same "
        "meshes: [calculix](calculix.md).", ""]
    ctx.out("summary.md").write_text("\n".join(lines) + "\n")
