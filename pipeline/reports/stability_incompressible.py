"""Near incompressibility -> results/stability/incompressible.md/csv, incompressible.png and
summary_incompressible.md."""
from pipeline import plots
from pipeline.reports.stability_common import gather_summary, stale_note
from pipeline.tables import write_table

LABELS = {"linear": "dhd_sim linear tet", "anp": "dhd_sim ANP tet", "ccx_C3D4": "CalculiX C3D4 (same tets)"}


def report(ctx):
    p = ctx.runs("sweep")[0].payload
    ref_key = "ccx_" + p["hex_element_type"]
    columns = p["elements"] + ["ccx_C3D4"]
    rows = []
    for r in p["rows"]:
        ref = r[ref_key]
        row = [r["nu"], ref]
        for c in columns:
            row += [r.get(c), None if r.get(c) is None else r[c] / ref]
        row += [r["dt_critical"], r["dt_exact_linear"], r["dt_critical"] / p["rows"][0]["dt_critical"],
                "ran" if r.get("explicit_auto", {}).get("exit") == 0 else r.get("explicit_auto", {}).get("message", "–")]
        rows.append(row)
    headers = ["ν", f"CalculiX {p['hex_element_type']} tip deflection (m)"]
    for c in columns:
        headers += [f"{LABELS.get(c, c)} (m)", f"{LABELS.get(c, c)} / reference"]
    headers += ["Δt_cr = h_min/c (s)", "exact 2/ω_max (s)", "Δt_cr / Δt_cr(ν₀)", "explicit run, automatic step"]
    write_table(ctx, "incompressible", headers, rows,
                f"Cantilever {p['box'][0]*100:g} × {p['box'][1]*100:g} × {p['box'][2]*100:g} cm, clamped at x = 0, "
                f"{p['pressure']:g} Pa on the top, E = {p['E']:g} Pa: mean vertical deflection of the free end. "
                f"Reference: CalculiX {p['hex_element_type']} ({p['hex_elements']} quadratic hexahedra, reduced "
                f"integration, free of volumetric locking). A ratio below 1 is a too-stiff (locking) element. "
                f"Right: the critical step of the {p['tets']}-tet mesh.")
    fig, (ax1, ax2) = plots.plt.subplots(1, 2, figsize=(10, 3.8), dpi=110)
    nus = [r["nu"] for r in p["rows"]]
    x = [1 - 2 * nu for nu in nus]
    for c in columns:
        ax1.plot(x, [r[c] / r[ref_key] if r.get(c) is not None else float("nan") for r in p["rows"]], "o-",
                 label=LABELS.get(c, c))
    ax1.axhline(1.0, color="k", lw=0.8, label=f"CalculiX {p['hex_element_type']}")
    ax1.set_xscale("log")
    ax1.invert_xaxis()
    ax1.set_xlabel("1 − 2ν (→ incompressible)")
    ax1.set_ylabel("tip deflection / reference")
    ax1.set_ylim(0, 1.2)
    ax1.grid(True, alpha=0.3)
    ax1.legend(fontsize=7, loc="upper right")
    for xi, nu in zip(x, nus):
        ax1.annotate(f"ν={nu:g}", (xi, 0.05), fontsize=7, ha="center")
    ax2.loglog(x, [r["dt_critical"] for r in p["rows"]], "o-", label="Δt_cr = h_min/c (000 eqs. 34–35)")
    ax2.loglog(x, [r["dt_exact_linear"] for r in p["rows"]], "s--", label="exact 2/ω_max")
    ax2.invert_xaxis()
    ax2.set_xlabel("1 − 2ν")
    ax2.set_ylabel("critical step (s)")
    ax2.grid(True, alpha=0.3, which="both")
    ax2.legend(fontsize=7)
    plots.save(fig, ctx.out("incompressible.png"))

    first, last = p["rows"][0], p["rows"][-1]
    lin = [r.get("linear") for r in p["rows"]]
    text = ["## Near incompressibility", "",
            f"Cantilever under pressure, ν from {first['nu']:g} to {last['nu']:g} ([table](incompressible.md), "
            "[plot](incompressible.png)).", ""]
    if None not in lin:
        text.append(f"- Linear (constant-strain) tets: {first['linear'] / first[ref_key]:.2f} of the reference "
                    f"deflection at ν = {first['nu']:g}, {last['linear'] / last[ref_key]:.2f} at ν = {last['nu']:g}: "
                    "the element locks as ν → 0.5 (CalculiX's C3D4 on the same tets gives the same numbers, so this "
                    "is the element, not the code).")
    else:
        text.append("- dhd_sim's static solve failed for some ν (see the table); CalculiX C3D4 on the same tets: "
                    f"{first['ccx_C3D4'] / first[ref_key]:.2f} → {last['ccx_C3D4'] / last[ref_key]:.2f} of the reference.")
    if "anp" in p["elements"] and None not in [r.get("anp") for r in p["rows"]]:
        text.append(f"- Average-nodal-pressure tets: {first['anp'] / first[ref_key]:.2f} → {last['anp'] / last[ref_key]:.2f} "
                    "of the reference: the locking is removed.")
    text.append(f"- The critical step falls as c grows: Δt_cr(ν = {last['nu']:g}) = "
                f"{last['dt_critical'] / first['dt_critical']:.3f} × Δt_cr(ν = {first['nu']:g}), so the explicit "
                f"solver needs {first['dt_critical'] / last['dt_critical']:.0f}× more steps per simulated second; "
                "dhd_sim's automatic step follows it and stays stable (the explicit runs completed)" +
                (". " if all(r.get("explicit_auto", {}).get("exit") == 0 for r in p["rows"]) else " except where the table says otherwise. ") +
                "ν ≥ 0.5 is refused as bad input (exit 2).")
    text.append(stale_note([p]))
    ctx.out("summary_incompressible.md").write_text("\n".join(text) + "\n")
    gather_summary(ctx)
