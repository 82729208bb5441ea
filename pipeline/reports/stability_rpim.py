"""RPIM conditioning map -> results/stability/rpim.md/csv, rpim_map.png and summary_rpim.md.

A setting is called trustworthy when (params): rpim_precompute solved it, the largest moment-
matrix condition number is below `max_moment_condition`, the shape functions reproduce a linear
field to `max_linear_error`, and the loaded node's vertical compliance is within
`max_compliance_change` of the paper's setting (q = 1.03, αc = 1): beyond that the answer
depends on a parameter the paper presents as a free choice."""
import math

from pipeline import plots
from pipeline.reports.stability_common import gather_summary
from pipeline.tables import write_table


def points(ctx):
    out = []
    for r in ctx.runs("by_q"):
        q = r.sweep["rpim.q"]
        for pt in r.payload["points"]:
            out.append({"q": q, "alpha_c": r.payload["base"]["alpha_c"], "support": r.payload["base"]["support"].get("requested", {}).get("spacing_factor"),
                        **pt, "swept": pt["parameter"]})
    for r in ctx.runs("q_fine"):
        for pt in r.payload["points"]:
            out.append({"q": None, "alpha_c": r.payload["base"]["alpha_c"], "support": r.payload["base"]["support"].get("requested", {}).get("spacing_factor"),
                        **pt, "swept": pt["parameter"]})
    for pt in out:
        if pt["swept"] == "q":
            pt["q"] = pt["value"]
        elif pt["swept"] == "alpha_c":
            pt["alpha_c"] = pt["value"]
        elif pt["swept"] == "support_spacing_factor":
            pt["support"] = pt["value"]
    return out


def report(ctx):
    prm = ctx.params
    pts = points(ctx)
    base = [p for p in pts if p["status"] == "ok" and abs(p["q"] - prm["base"]["q"]) < 1e-12
            and abs(p["alpha_c"] - prm["base"]["alpha_c"]) < 1e-12]
    c_base = base[0]["compliance"][2] if base else None
    rows = []
    for p in pts:
        c = p.get("conditioning") or {}
        mm = (c.get("moment_matrix") or {}).get("condition_max")
        lin = (c.get("shape_consistency") or {}).get("linear_reproduction_error")
        kfree = (c.get("stiffness_free_dofs") or {}).get("condition")
        comp = p["compliance"][2] if p.get("compliance") else None
        change = None if comp is None or c_base is None else comp / c_base - 1
        trusted = (p["status"] == "ok" and mm is not None and mm <= prm["max_moment_condition"]
                   and lin is not None and lin <= prm["max_linear_error"]
                   and change is not None and abs(change) <= prm["max_compliance_change"])
        p["trusted"] = trusted
        rows.append([p["swept"], p["q"], p["alpha_c"], p["support"], p["status"], mm, kfree, lin,
                     comp, change, "yes" if trusted else "no", (p.get("message") or "")[:160]])
    write_table(ctx, "rpim", ["swept", "q", "αc", "support / spacing", "status", "moment cond (max)", "K cond (free dofs)",
                              "linear reproduction error", "compliance z (m/N)", "vs paper setting", "trustworthy", "message"],
                rows,
                "rpim_precompute's stability sweeps on the 002 plate. Trustworthy: solved, moment condition ≤ "
                f"{prm['max_moment_condition']:g}, linear reproduction error ≤ {prm['max_linear_error']:g}, and the "
                f"loaded node's compliance within {100 * prm['max_compliance_change']:g} % of the paper's setting "
                f"(q = {prm['base']['q']}, αc = {prm['base']['alpha_c']}).")
    fig, axes = plots.plt.subplots(1, 3, figsize=(12, 3.8), dpi=110)
    for ax, swept, xlabel in ((axes[0], "q", "q"), (axes[1], "alpha_c", "αc"), (axes[2], "support_spacing_factor", "support radius / spacing")):
        groups = {}
        for p in pts:
            if p["swept"] != swept:
                continue
            key = "q fine" if swept == "q" else f"q = {p['q']:g}"
            groups.setdefault(key, []).append(p)
        for key, ps in groups.items():
            ps.sort(key=lambda p: p["value"])
            xs = [p["value"] for p in ps]
            ys = [((p.get("conditioning") or {}).get("moment_matrix") or {}).get("condition_max") or math.nan for p in ps]
            line, = ax.semilogy(xs, ys, "-", lw=0.8, label=key)
            ax.scatter([x for x, p in zip(xs, ps) if p["trusted"]], [y for y, p in zip(ys, ps) if p["trusted"]],
                       c=line.get_color(), s=18, marker="o")
            ax.scatter([x for x, p in zip(xs, ps) if not p["trusted"] and p["status"] == "ok"],
                       [y for y, p in zip(ys, ps) if not p["trusted"] and p["status"] == "ok"],
                       c=line.get_color(), s=22, marker="^")
            fails = [x for x, p in zip(xs, ps) if p["status"] != "ok"]
            if fails:
                ax.scatter(fails, [1.0] * len(fails), c="k", marker="x", s=22)
        ax.set_xlabel(xlabel)
        ax.grid(True, alpha=0.3, which="both")
        if swept == "alpha_c":
            ax.set_xscale("log")
        ax.legend(fontsize=6)
    axes[0].set_ylabel("moment-matrix condition (max)")
    fig.suptitle("o trustworthy, ^ solved but not trustworthy, x refused (exit 3 in a dataset run)", fontsize=8)
    plots.save(fig, ctx.out("rpim_map.png"))

    def span(swept):
        ok = sorted(p["value"] for p in pts if p["swept"] == swept and p["trusted"]
                    and (swept == "q" or abs(p["q"] - prm["base"]["q"]) < 1e-12))
        return (ok[0], ok[-1]) if ok else None
    fails = [p for p in pts if p["status"] != "ok"]
    text = ["## RPIM conditioning", "", "Moment-matrix and stiffness condition numbers as q, αc and the support vary "
            "([table](rpim.md), [map](rpim_map.png)).", ""]
    for swept, name in (("q", "q"), ("alpha_c", "αc"), ("support_spacing_factor", "support radius / spacing")):
        s = span(swept)
        if s:
            text.append(f"- {name}: trustworthy from {s[0]:g} to {s[1]:g} around the paper's setting "
                        "(not every value in between: see the map).")
    near_int = [p for p in pts if p["swept"] == "q" and abs(p["value"] - round(p["value"])) < 1e-9 and p["value"] > 0]
    if near_int:
        text.append("- Integer q (" + ", ".join(f"{p['value']:g}: {p['status']}" for p in near_int) + "): the MQ basis "
                    "degenerates into a polynomial there, the moment matrix becomes singular or nearly so.")
    text += ["",
             f"In plain words: of {len(pts)} settings, {sum(p['trusted'] for p in pts)} are trustworthy and "
             f"{len(fails)} were refused. rpim_precompute never returns garbage for a singular setting: the dataset "
             "mode stops with exit 3 naming the Gauss point, the support size and the limit, and the stability mode "
             "records the same message as a row. A setting can be solvable yet untrustworthy: a large αc makes the "
             "moment matrices ill-conditioned long before they are singular, and the compliance drifts with it."]
    ctx.out("summary_rpim.md").write_text("\n".join(text) + "\n")
    gather_summary(ctx)
