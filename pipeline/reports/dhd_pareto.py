"""Run time against error for every configuration (layer / distance / strain split, linear or
corotational cheap elements, every share r) with its Pareto front, one panel per applied
displacement → results/dhd/pareto.png, pareto_front.md/csv and the "pareto" part of summary.md.

The time axis is the time per step relative to all-TLED on the same mesh, from the cost model of
dhd_common.cost_model (uniform runs of the "timing" stage; its mixed runs check it). The paper's points are placed on the same relative
axis: 000 Table 1 gives frame rates f(r) on the 14450-tet mesh only, so a paper point at share r
sits at time 22 Hz / f(r) (its r = 0 frame time over its frame time at r, assuming that ratio does
not depend on the mesh size) and at the error of Table 2 or 3. Table 1 has no row for r > 50 %, so
paper points exist for r = 10–40 % only."""

from pipeline import plots
from pipeline.reports import dhd_common as common
from pipeline.reports.dhd_partition import family_rows
from pipeline.stages.machine_load import busy_note
from pipeline.tables import fmt, write_table


def paper_points(paper: dict):
    """{applied: [(relative time, error fraction, r percent)]} from Tables 1–3 of the paper."""
    t1 = paper.get("table1")
    out = {}
    if not t1:
        return out
    rate = dict(zip(t1["linear_fraction_percent"], t1["frame_rate_hz"]))
    f0 = rate.get(0)
    for name in ("table2", "table3"):
        t = paper.get(name)
        if not t or not f0:
            continue
        pts = [(f0 / rate[r], e / 100.0, r) for r, e in zip(t["linear_fraction_percent"], t["mean_error_percent"])
               if r in rate]
        out[t["applied_displacement"]] = pts
    return out


def paper_table_names(paper: dict) -> dict:
    """{applied: "Table n"}: which table of the paper gives the error at each applied
    displacement, from the block's own keys (table2, table3)."""
    return {t["applied_displacement"]: f"Table {name[len('table'):]}" for name, t in paper.items()
            if name in ("table2", "table3") and isinstance(t, dict) and "applied_displacement" in t}


def front_sentence(where: str, front, pts, names: dict, fam_on_front: dict) -> str:
    """The front in words, its ends named from the points themselves (fastest, most accurate)."""
    n = len(front)
    if n == 0:
        return f"At {where} there is no configuration."
    fastest = min(front, key=lambda i: pts[i][0])
    accurate = min(front, key=lambda i: pts[i][1])
    text = f"At {where}, the front has {n} point{'s' if n != 1 else ''}"
    text += (f" ({names[fastest]})" if n == 1 else
             f" ({names[fastest]} the fastest, {names[accurate]} the most accurate)")
    mixed = ", ".join(f"{v} from {k}" for k, v in sorted(fam_on_front.items(), key=lambda kv: -kv[1]))
    return text + (f"; mixed configurations: {mixed}." if mixed else "; no mixed configuration is on it.")


def report(ctx):
    unit, unit_scale = common.display_unit(ctx)
    data = family_rows(ctx, ctx.params["stages"])
    labels = list(data)
    loads = sorted({load for fam in data.values() for load in fam})
    paper = paper_points(ctx.experiment.get("paper", {}))
    table_names = paper_table_names(ctx.experiment.get("paper", {}))
    timing = ctx.runs(ctx.params.get("timing", "timing"))[0].payload
    uniform, mixed = common.cost_model(timing)
    busy = busy_note(timing.get("machine"))
    note = f" {busy}" if busy else ""
    t_tled = uniform["tled"]

    fig, axes = plots.plt.subplots(1, len(loads), figsize=(5.4 * len(loads), 5.4), dpi=110, squeeze=False)
    front_rows = []
    words = []
    for ax, load in zip(axes[0], loads):
        pts = []
        for i, label in enumerate(labels):
            g = data[label].get(load, [])
            for x in g:
                x["model_seconds_per_step"] = common.model_time(uniform, x["counts"])
            rel_t = [x["model_seconds_per_step"] / t_tled for x in g]
            err = [x["error"]["rel_mean"] for x in g]
            ax.plot(rel_t, [100 * e for e in err], marker="os^"[i % 3], ls="none", ms=4,
                    color=f"C{i}", label=label, alpha=0.85)
            pts += [(t, e, label, x) for t, e, x in zip(rel_t, err, g)]
        front = common.pareto_front([p[0] for p in pts], [p[1] for p in pts])
        ax.plot([pts[i][0] for i in front], [100 * pts[i][1] for i in front], "k-", lw=0.8, alpha=0.6,
                label="Pareto front (ours)")
        names = {}
        for i in front:
            t, e, label, x = pts[i]
            name = ("all TLED" if x["cheap_elements"] == 0 else f"all {x['cheap_kind']}" if x["tled_elements"] == 0
                    else label)
            names[i] = name
            front_rows.append([f"{fmt(load * unit_scale)} {unit}", name, f"{int(round(100 * x['r']))} %",
                               t, x["model_seconds_per_step"] * 1e6, common.pct(e, 2)])
        pp, table = None, None
        for applied, ppts in paper.items():
            if abs(applied - load * unit_scale) < 1e-9:
                pp, table = ppts, table_names[applied]
        if pp:
            ax.plot([p[0] for p in pp], [100 * p[1] for p in pp], "kD", mfc="none", ms=6,
                    label=f"paper (Table 1 + {table})")
            for t, e, r in pp:
                ax.annotate(f"{r}%", (t, 100 * e), textcoords="offset points", xytext=(4, 3), fontsize=6)
        ax.set_yscale("symlog", linthresh=0.01)
        ax.set_xscale("log")
        ax.set_xlabel("time per step / all-TLED time per step (log)")
        ax.set_ylabel("mean error e (%)")
        ax.set_title(f"top centre displaced by {fmt(load * unit_scale)} {unit}", fontsize=9)
        ax.grid(True, alpha=0.3)
        # Each panel its own legend (the paper's points come from a different table per load),
        # below the axes so that it hides no point.
        ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=3)
        fam_on_front = {}
        for i in front:
            x = pts[i][3]
            if 0 < x["cheap_elements"] < x["elements"]:
                fam_on_front[pts[i][2]] = fam_on_front.get(pts[i][2], 0) + 1
        words.append(front_sentence(f"{fmt(load * unit_scale)} {unit}", front, pts, names, fam_on_front) + note)
    common.save(fig, ctx, "pareto.png")
    md = write_table(ctx, "pareto_front", ["applied", "family", "r", "time per step / all-TLED",
                                           "time per step (µs, model)", "e (%)"], front_rows,
                     "**The configurations on the Pareto front** (no other configuration is both faster "
                     "and more accurate), per applied displacement. Time per step from the cost model"
                     + (f"{note}." if busy else "."))
    cost_rows = [[f"all {k}", 1e6 * t, t / t_tled, None, None] for k, t in uniform.items()]
    for run, measured, modelled in mixed:
        d = common.describe_partition(run["partition"])
        cost_rows.append([f"{d['strategy']} r = {fmt(d['requested_r'])}, {d['cheap_kind']} (check)",
                          1e6 * measured, measured / t_tled, 1e6 * modelled, 100 * (modelled / measured - 1)])
    cost_md = write_table(ctx, "pareto_cost_model", ["run", "time per step (µs)", "/ all-TLED",
                                                     "model (µs)", "model − measured (%)"], cost_rows,
                          "**Cost model of the time axis**: uniform runs (best of the repeats, one thread, "
                          "same mesh and scene) and the mixed runs that check it" + (f"{note}." if busy else "."))
    lines = ["### Run time against error\n",
             "![pareto](dhd/pareto.png)\n",
             "Every configuration of the partition comparison as (time per step relative to all-TLED, "
             "error); the paper's points combine its Table 1 frame-time ratios with its Tables 2–3 "
             "errors (see experiments/dhd.md for the placement).\n", md, cost_md, " ".join(words) + "\n"]
    common.write_section(ctx, "pareto", "\n".join(lines))
