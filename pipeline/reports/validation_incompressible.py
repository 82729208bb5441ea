"""Nearly incompressible tissue -> results/validation/incompressible_<scene>.md/csv/png,
incompressible_cost.md/csv and incompressible_summary.md.

Per scene (punch, cantilever): the CalculiX C3D20R refinement series (the reference is the finest
mesh's force; the coarse-to-fine change says how far it still moves), dhd_sim's force per element
kind, mesh and ν, its ratio to the reference, and a convergence plot (force against cell size per
kind and ν). Then the cost of each kind per explicit step (steps/s ratio to TLED in the same
stage, kinds interleaved, best of the repeats) and its critical step (power iteration and
altitude rule) on the timed mesh."""
import os
import platform

from pipeline import plots
from pipeline.tables import write_table

TARGET_RATIO = 1.3   # issue target: coarse-mesh force within 1.3× of the converged one
TARGET_GROWTH = 1.5  # and no more than 1.5× growth from ν = 0.49 to 0.499


def reference(ccx_runs):
    """{ν: (finest force, coarse force, finest h, coarse h)} of a swept CalculiX stage."""
    out = {}
    for run in ccx_runs:
        rows = sorted(run.payload["rows"], key=lambda r: r["h"])
        out[rows[0]["nu"]] = (rows[0]["force"], rows[-1]["force"], rows[0]["h"], rows[-1]["h"])
    return out


def cpu_name():
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def scene_report(ctx, scene, ref, p):
    rows, coarse = [], {}
    coarse_h = max(r["h"] for r in p["rows"])
    for r in p["rows"]:
        f = r.get("force")
        ratio = None if f is None else f / ref[r["nu"]][0]
        rows.append([r["nu"], r["element"], "×".join(str(c) for c in r["cells"]), r["tets"], f, ratio,
                     r.get("solve_seconds")])
        if r["h"] == coarse_h:
            coarse[(r["element"], r["nu"])] = ratio
    for nu, (fine, c, hf, hc) in sorted(ref.items()):
        rows.append([nu, "CalculiX C3D20R", f"h = {hc * 1000:g} mm", "", c, c / fine, ""])
        rows.append([nu, "CalculiX C3D20R (reference)", f"h = {hf * 1000:g} mm", "", fine, 1.0, ""])
    what = ("bonded 5 × 5 mm flat punch pushed 1 mm into a 20 × 20 × 10 mm block (bottom clamped)" if scene == "punch"
            else "end face of a 40 × 10 × 10 mm cantilever moved 2 mm down (clamped at x = 0)")
    write_table(ctx, f"incompressible_{scene}", ["ν", "element", "cells (5 tets each) / hex size", "tets", "force (N)",
                                                 "force / reference", "static solve (s, busy machine)"], rows,
                f"Force of the {what}, decoupled neo-Hookean E = {p['E']:g} Pa. Reference: CalculiX C3D20R (NLGEOM) "
                "on the finest hex mesh; its coarser row shows how much the reference still moved.")
    fig, axes = plots.plt.subplots(1, len(p["nus"]), figsize=(4 * len(p["nus"]), 3.6), dpi=110, sharey=True)
    for ax, nu in zip(axes, p["nus"]):
        for element in p["elements"]:
            pts = sorted((r["h"], r["force"]) for r in p["rows"]
                         if r["nu"] == nu and r["element"] == element and r.get("force") is not None)
            ax.plot([h * 1000 for h, _ in pts], [f / ref[nu][0] for _, f in pts], "o-", label=element)
        fine, c, hf, hc = ref[nu]
        ax.plot([hf * 1000, hc * 1000], [1.0, c / fine], "ks--", label="CalculiX C3D20R")
        ax.axhline(TARGET_RATIO, color="r", lw=0.8, ls=":", label=f"{TARGET_RATIO}× target")
        ax.set_xlabel("cell size (mm)")
        ax.set_title(f"{scene}, ν = {nu:g}", fontsize=9)
        ax.grid(True, alpha=0.3)
    axes[0].set_ylabel("force / converged CalculiX force")
    axes[0].legend(fontsize=7)
    plots.save(fig, ctx.out(f"incompressible_{scene}.png"))
    return coarse


def cost_report(ctx, p):
    best = {}
    for r in p["timing"]:
        if r.get("steps_per_second") is None:
            continue
        key = (r["nu"], r["element"])
        b = best.setdefault(key, dict(r))
        b["steps_per_second"] = max(b["steps_per_second"], r["steps_per_second"])
    rows = []
    for (nu, element), b in sorted(best.items()):
        t = best.get((nu, "tled"))
        rows.append([nu, element, b["steps_per_second"], t["steps_per_second"] / b["steps_per_second"] if t else None,
                     b["dt_critical_power_iteration"],
                     b["dt_critical_power_iteration"] / t["dt_critical_power_iteration"] if t else None,
                     b["dt_critical_altitude"]])
    load = open("/proc/loadavg").read().split()[:3] if os.path.exists("/proc/loadavg") else ["?"]
    write_table(ctx, "incompressible_cost",
                ["ν", "element", "explicit steps/s (1 thread)", "cost per step / TLED", "Δt_cr = 2/ω_max (s)",
                 "Δt_cr / TLED's", "Δt_cr altitude rule (s)"], rows,
                f"{p['tets_timed']} tets, one thread, best of the repeats, kinds interleaved in one stage. CPU: "
                f"{cpu_name()}; load average when the report was written: {' '.join(load)} — the machine was shared "
                "and busy, so only the ratios mean something.")
    return {(nu, e): (row[3], row[5]) for row, (nu, e) in zip(rows, sorted(best))}


def report(ctx):
    refs = {"punch": reference(ctx.runs("ccx_punch")), "cantilever": reference(ctx.runs("ccx_cantilever"))}
    lines = ["## Nearly incompressible tissue: element kinds against converged references", ""]
    cost = None
    for scene in ("punch", "cantilever"):
        p = ctx.runs(scene)[0].payload
        coarse = scene_report(ctx, scene, refs[scene], p)
        for nu, (fine, c, hf, hc) in sorted(refs[scene].items()):
            lines.append(f"- {scene}, ν = {nu:g}: CalculiX C3D20R {fine:.4g} N (h = {hf * 1000:g} mm; "
                         f"{c / fine:.3f}× that at h = {hc * 1000:g} mm).")
        lines.append(f"- {scene}, coarse mesh ([table](incompressible_{scene}.md), [plot](incompressible_{scene}.png)), "
                     "force / reference:")
        for element in p["elements"]:
            ratios = [coarse.get((element, nu)) for nu in p["nus"]]
            text = ", ".join(f"{r:.2f} (ν = {nu:g})" if r is not None else f"failed (ν = {nu:g})"
                             for r, nu in zip(ratios, p["nus"]))
            growth = ""
            if 0.49 in p["nus"] and 0.499 in p["nus"] and None not in (coarse.get((element, 0.49)), coarse.get((element, 0.499))):
                g = coarse[(element, 0.499)] / coarse[(element, 0.49)]
                r49, r499 = coarse[(element, 0.49)], coarse[(element, 0.499)]
                ok = r49 <= TARGET_RATIO and r499 <= TARGET_RATIO and g <= TARGET_GROWTH
                growth = (f"; growth 0.49 → 0.499: {g:.2f}× — "
                          f"{'meets' if ok else 'misses'} the target (≤ {TARGET_RATIO}× at both, ≤ {TARGET_GROWTH}× growth)")
            lines.append(f"  - {element}: {text}{growth}")
        if p["timing"]:
            cost = cost_report(ctx, p)
    if cost:
        lines.append("- Cost per explicit step and critical step against TLED ([table](incompressible_cost.md)): " +
                     "; ".join(f"{e} at ν = {nu:g}: {c:.2f}× the cost, Δt_cr {d:.2f}× TLED's"
                               for (nu, e), (c, d) in sorted(cost.items()) if e != "tled" and c is not None) + ".")
    ctx.out("incompressible_summary.md").write_text("\n".join(lines) + "\n")
