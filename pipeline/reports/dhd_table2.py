"""000 Tables 2 and 3: mean error of DHD-FEA against all-TLED versus the share of linear
elements, the paper's layer split, two applied displacements → results/dhd/table2.*, table3.*,
table2_3_transient.*, table2_3_metrics.csv, table2_3_error.png and the "table2" part of
summary.md.

Inputs (params name them):
  sim        dhd_sim swept over the share r × the applied displacement (main tables), meant to
             settle: the report checks it against `static` before it calls the runs settled
  static     the static solutions of some (r, load) pairs: how far the last step is from equilibrium
  transient  the paper's literal reading — displacement applied fast, little damping — swept
             over the damping α as well: the error after the last step, moving or not
  settled_within  the largest e against the static solution that still counts as settled
             (default dhd_table2_words.SETTLED_WITHIN)

Every sentence that states a fact (settled, the trend with r, the paper's trend, the literal
reading) is computed in dhd_table2_words from the runs and the paper block."""

from pipeline import plots
from pipeline.reports import dhd_common as common
from pipeline.reports import dhd_table2_words as words_mod
from pipeline.tables import fmt, write_table

METRIC_KEYS = ("rel_mean", "rel_applied", "rel_rms", "rel_max", "rel_per_node", "mean_diff", "max_diff", "mean_ref")


def paper_tables(ctx):
    """{applied (paper's number): {r percent: error percent}} of 000 Tables 2 and 3."""
    paper = ctx.experiment.get("paper", {})
    out = {}
    for name in ("table2", "table3"):
        t = paper.get(name)
        if t:
            out[t["applied_displacement"]] = dict(zip(t["linear_fraction_percent"], t["mean_error_percent"]))
    return out


def _paper_for(paper, load, unit_scale):
    return next((v for k, v in paper.items() if abs(k - load * unit_scale) < 1e-9), {})


def report(ctx):
    unit, unit_scale = common.display_unit(ctx)
    paper = paper_tables(ctx)
    # The shares the paper reports (experiments/dhd_table2.json), for the comparisons in words.
    paper_shares = common.paper_error_shares(ctx.experiment.get("paper", {}))
    by_load = common.errors_against_reference(common.sim_rows(ctx, ctx.params.get("sim", "sim")))
    loads = sorted(by_load)
    steps = by_load[loads[0]][0]["run"].payload["solver"]["steps"]

    # ---- how far the runs are from the static solutions: what the captions and words may claim
    static = _static_rows(ctx)
    tolerance = float(ctx.params.get("settled_within", words_mod.SETTLED_WITHIN))
    state = words_mod.settle_state(_against_static(by_load, static), tolerance)
    state_word = words_mod.state_word(state, steps)

    # ---- the main tables
    all_rows = [g for load in loads for g in by_load[load]]
    split, cheap = common.split_words(all_rows), common.cheap_kinds(all_rows)
    headers = [f"share of {cheap} elements r", f"{cheap} elements", "TLED elements", "mean error e (ours, %)",
               "mean error (paper, %)", "mean |Δu| (µm)", "max |Δu| (µm)", "mean |Δu| / applied (%)",
               f"largest {cheap} ‖∇u‖ (%)"]
    md_tables = []
    for n, load in enumerate(loads):
        name = f"table{n + 2}"
        ref_paper = _paper_for(paper, load, unit_scale)
        body = []
        for g in by_load[load]:
            rp = int(round(100 * g["r"]))
            body.append([f"{rp} %", g["cheap_elements"], g["tled_elements"], common.pct(g["error"]["rel_mean"], 3),
                         ref_paper.get(rp), g["error"]["mean_diff"] * 1e6, g["error"]["max_diff"] * 1e6,
                         common.pct(g["error"]["rel_applied"], 3), _small_strain_pct(g)])
        caption = (f"**Table {n + 2}: DHD-FEA vs. all-TLED, top centre pushed down {fmt(load * unit_scale)} {unit}**, "
                   f"{common.split_words(by_load[load])}, "
                   f"{words_mod.settle_caption(state, steps, unit_scale, unit)}. "
                   "e = Σ_nodes |u − u_TLED| / Σ_nodes |u_TLED| (experiments/dhd.md). The last column is the "
                   f"largest deformation any {cheap} element reached in the run (small_strain_check: 000 §2.2.2 "
                   f"takes them as valid below {limit_words(by_load[load])}). The paper's column is "
                   f"copied from 000 Table {n + 2} ('Mean Error', displacement {fmt(load * unit_scale)} in an "
                   "unstated unit).")
        md_tables.append(write_table(ctx, name, headers, body, caption))

    # ---- the literal, transient reading
    transient_md, transient = "", {}
    tstage = ctx.params.get("transient")
    if tstage:
        rows = common.sim_rows(ctx, tstage)
        for g in rows:
            g["alpha"] = float(g["run"].config["damping"]["alpha"])
        for alpha in sorted({g["alpha"] for g in rows}):
            for load, group in common.errors_against_reference([g for g in rows if g["alpha"] == alpha]).items():
                transient[(alpha, load)] = {int(round(100 * g["r"])): g for g in group}
        alphas = sorted({a for a, _ in transient})
        shares = sorted({r for v in transient.values() for r in v if r > 0})
        body = []
        for load in loads:
            ref_paper = _paper_for(paper, load, unit_scale)
            for r in shares:
                body.append([f"{fmt(load * unit_scale)} {unit}", f"{r} %"]
                            + [common.pct(transient[(a, load)][r]["error"]["rel_mean"], 2)
                               if r in transient.get((a, load), {}) else None for a in alphas]
                            + [common.pct(transient[(a, load)][r]["error"]["rel_per_node"], 2)
                               if r in transient.get((a, load), {}) else None for a in alphas]
                            + [ref_paper.get(r)])
        ramp = rows[0]["run"].config["boundary"]["prescribed"][0]
        transient_steps = rows[0]["run"].payload["solver"]["steps"]
        # Is the block still moving at the sampled step? The all-TLED run of each damping against
        # the static solution of the same load.
        moving = {a: max((v for v in (_static_distance(transient.get((a, load), {}).get(0), static, load)
                                      for load in loads) if v is not None), default=None) for a in alphas}
        motion = "; ".join(f"α = {fmt(a)}: {fmt(100 * m, 2)} %" for a, m in moving.items() if m is not None)
        transient_md = write_table(
            ctx, "table2_3_transient",
            ["applied", "r"] + [f"e, α = {fmt(a)} 1/s (%)" for a in alphas]
            + [f"per-node mean, α = {fmt(a)} (%)" for a in alphas] + ["paper (%)"], body,
            f"**Tables 2–3 read literally**: the displacement applied over a {fmt(ramp['ramp_time'] * 1e3)} ms "
            f"{ramp['ramp']} ramp, damping α as in the columns, error after {transient_steps} steps"
            + (f" (distance of the all-TLED run from the static solution then, largest over the loads: {motion})"
               if motion else "") + ". The per-node mean is the mean over moving nodes of |Δu|/|u_TLED|. "
            "The paper's column: 000 Tables 2–3.")

    # ---- every normalisation
    metric_rows = [[load * unit_scale, g["r"], g["cheap_elements"]] + [g["error"][k] for k in METRIC_KEYS]
                   for load in loads for g in by_load[load]]
    write_table(ctx, "table2_3_metrics",
                [f"applied ({unit})", "r", f"{cheap} elements", "Σ|Δu|/Σ|u_TLED|", "mean|Δu|/applied", "RMS ratio",
                 "max ratio", "mean per-node ratio", "mean |Δu| (m)", "max |Δu| (m)", "mean |u_TLED| (m)"],
                metric_rows, "Every error normalisation of Tables 2–3, settled runs (fractions, not percent).")

    # ---- plot
    fig, ax = plots.figure(6.6, 4.4)
    for n, load in enumerate(loads):
        g = [x for x in by_load[load] if x["r"] > 0]   # r = 0 is the reference (zero on a log axis)
        ax.plot([100 * x["r"] for x in g], [100 * x["error"]["rel_mean"] for x in g], "o-", color=f"C{n}",
                label=f"ours, {state_word}, {fmt(load * unit_scale)} {unit}")
        if transient:
            a0 = min(a for a, _ in transient)
            t = {r: v for r, v in transient.get((a0, load), {}).items() if r > 0}
            ax.plot(sorted(t), [100 * t[r]["error"]["rel_mean"] for r in sorted(t)], "^:", color=f"C{n}",
                    label=f"ours, transient α = {fmt(a0)}, {fmt(load * unit_scale)} {unit}")
        p = _paper_for(paper, load, unit_scale)
        if p:
            ax.plot(list(p), list(p.values()), "s--", color=f"C{n}", mfc="none",
                    label=f"paper Table {n + 2} ({fmt(load * unit_scale)}, unit not given)")
    ax.set_yscale("log")
    ax.set_xlabel(f"share of {cheap} elements r (%)")
    ax.set_ylabel("mean error e (%)")
    ax.set_title(f"DHD-FEA against all-TLED, {split}", fontsize=10)
    ax.legend(fontsize=7)
    common.save(fig, ctx, "table2_3_error.png")

    # ---- plain words, every claim computed from the runs and the paper block
    words = []
    for load in loads:
        g = {int(round(100 * x["r"])): x for x in by_load[load]}
        p = _paper_for(paper, load, unit_scale)
        if p:
            ours = ", ".join(f"{fmt(100 * g[k]['error']['rel_mean'], 2)} %" for k in sorted(p) if k in g)
            words.append(f"At {fmt(load * unit_scale)} {unit} and r = {common.share_range(sorted(p))} % our error "
                         f"({state_word}) is {ours}; the paper reports {', '.join(f'{v} %' for v in p.values())}.")
        full = g.get(100)
        if full:
            words.append(f"All-{cheap} (r = 100 %) differs from all-TLED by {fmt(100 * full['error']['rel_mean'], 3)} % "
                         "there.")
    trend = _trend(by_load, paper, loads, unit_scale)
    if len(loads) >= 2:
        words.append(words_mod.load_clause(trend["larger"], trend["shares"], trend["paper_larger"],
                                           trend["paper_shares"]) + "; "
                     + words_mod.trend_clause(trend["ours_grow"], trend["ours_fall"], trend["paper_grow"]) + ".")
    else:
        words.append(words_mod.trend_clause(trend["ours_grow"], trend["ours_fall"], trend["paper_grow"])
                     .capitalize() + ".")
    words.append(words_mod.settle_sentence(state, unit_scale, unit))
    words.append(_small_strain_sentence(by_load, loads, unit_scale, unit))
    transient_facts = {}
    if transient:
        a0 = min(a for a, _ in transient)
        t = transient.get((a0, loads[0]), {})
        p = _paper_for(paper, loads[0], unit_scale)
        shared = [r for r in sorted(p) if r in t and t[r]["error"]["rel_mean"] > 0]
        if shared:
            tvals = [t[r]["error"]["rel_mean"] for r in shared]
            ratios = [p[r] / (100 * v) for r, v in zip(shared, tvals)]
            g = {int(round(100 * x["r"])): x for x in by_load[loads[0]]}
            settled_share = max(g[r]["error"]["rel_mean"] / t[r]["error"]["rel_mean"] for r in shared if r in g) \
                if state and state["settled"] and all(r in g for r in shared) else None
            t_grow = words_mod.grows(tvals)
            p_grow = words_mod.grows([p[r] for r in shared])
            words.append(f"Read literally ({fmt(ramp['ramp_time'] * 1e3)} ms ramp, α = {fmt(a0)}), the error after "
                         f"{transient_steps} steps at {fmt(loads[0] * unit_scale)} {unit} is "
                         + ", ".join(f"{fmt(100 * v, 2)} %" for v in tvals)
                         + f" for r = {shared[0]}–{shared[-1]} %, {words_mod.ratio_clause(ratios)}, "
                         + ("growing with r as the paper's does." if t_grow and p_grow else
                            "growing with r while the paper's does not." if t_grow else
                            "not growing at every share, unlike the paper's." if p_grow else
                            "not growing at every share, nor does the paper's.")
                         + words_mod.transient_why(moving.get(a0), tolerance, settled_share))
            transient_facts = {"alpha": a0, "grows": t_grow, "moving": moving.get(a0) is not None
                               and moving[a0] > tolerance}
    lines = [f"### Tables 2–3: error against the share of {cheap} elements\n"] + md_tables
    if transient_md:
        lines.append(transient_md)
    lines.append("Plot: [dhd/table2_3_error.png](dhd/table2_3_error.png); every normalisation: "
                 "[dhd/table2_3_metrics.csv](dhd/table2_3_metrics.csv).\n")
    lines.append(" ".join(w for w in words if w) + "\n")
    facts = {"settled_10_40": {}, "paper_10_40": {}, "transient_10_40": {}, "larger_load_larger": None,
             "settled": bool(state and state["settled"]), "state": state_word, "ours_grow": trend["ours_grow"],
             "paper_grow": trend["paper_grow"], "paper_larger_load_larger": None, "transient": transient_facts}
    for load in loads:
        label = f"{fmt(load * unit_scale)} {unit}"
        g = {int(round(100 * x["r"])): x for x in by_load[load]}
        p = _paper_for(paper, load, unit_scale)
        facts["settled_10_40"][label] = [100 * g[r]["error"]["rel_mean"] for r in paper_shares if r in g]
        if p:
            facts["paper_10_40"][label] = [p[r] for r in paper_shares if r in p]
        if transient:
            t = transient.get((min(a for a, _ in transient), load), {})
            facts["transient_10_40"][label] = [100 * t[r]["error"]["rel_mean"] for r in paper_shares if r in t]
    if len(loads) >= 2:
        facts["larger_load_larger"] = trend["larger"] == trend["shares"]
        if trend["paper_larger"] is not None:
            facts["paper_larger_load_larger"] = trend["paper_larger"] == trend["paper_shares"]
    common.write_section(ctx, "table2", "\n".join(lines), facts)


def limit_words(rows) -> str:
    """The small-strain limit the runs checked against (their small_strain_check blocks)."""
    limits = sorted({g["run"].payload["small_strain_check"]["limit"] for g in rows
                     if g["run"].payload.get("small_strain_check")})
    return " or ".join(f"{fmt(100 * v)} %" for v in limits) if limits else "a limit the runs did not record"


def _small_strain_pct(g):
    """The run's largest small-strain deformation in percent (None: an all-TLED run, or a run
    from before the check existed)."""
    check = g["run"].payload.get("small_strain_check")
    return 100 * check["largest"] if check and check["elements"] > 0 else None


def _small_strain_sentence(by_load, loads, unit_scale, unit) -> str:
    """000 §2.2.2's condition (linear elements below 10 % deformation), as the runs met it."""
    broken, held = [], []
    for load in loads:
        for g in by_load[load]:
            check = g["run"].payload.get("small_strain_check")
            if not check or check["elements"] == 0:
                continue
            (broken if check["broken"] else held).append((load, g["r"], check))
    if not broken and not held:
        return ""
    limit = (broken or held)[0][2]["limit"]
    if not broken:
        top = max(c["largest"] for _, _, c in held)
        return (f"000 §2.2.2's condition held in every hybrid run: no small-strain element deformed beyond "
                f"{fmt(100 * top, 2)} % (limit {fmt(100 * limit)} %).")
    where = ", ".join(f"r = {int(round(100 * r))} % at {fmt(load * unit_scale)} {unit} ({fmt(100 * c['largest'], 2)} %)"
                      for load, r, c in broken)
    return (f"000 §2.2.2's condition (small-strain elements below {fmt(100 * limit)} % deformation) was broken in "
            f"{len(broken)} of {len(broken) + len(held)} hybrid runs: {where}.")


def _static_rows(ctx) -> dict:
    """{(load, cheap elements): row} of the static stage (params "static"), {} without one."""
    stage = ctx.params.get("static")
    if not stage:
        return {}
    return {(round(g["applied"], 12), g["cheap_elements"]): g for g in common.sim_rows(ctx, stage)}


def _static_distance(row, static: dict, load) -> float:
    """e of a run against the static solution of the same load and split; None without one."""
    if row is None:
        return None
    s = static.get((round(load, 12), row["cheap_elements"]))
    if s is None:
        return None
    return common.displacement_error(common.displacement(row["run"]), common.displacement(s["run"]))["rel_mean"]


def _against_static(by_load, static) -> list:
    """[(load, r, e against the static solution)] of every main run that has a static counterpart."""
    out = []
    for load, group in by_load.items():
        for g in group:
            e = _static_distance(g, static, load)
            if e is not None:
                out.append((load, g["r"], e))
    return out


def _trend(by_load, paper, loads, unit_scale) -> dict:
    """Whether the error grows with r (ours over every share, the paper's over its shares) and how
    often the larger load gives the larger error (ours over the shared shares r > 0, the paper's)."""
    ours_grow, ours_fall = True, None
    for load in loads:
        rs = [int(round(100 * x["r"])) for x in by_load[load]]
        es = [x["error"]["rel_mean"] for x in by_load[load]]
        if not words_mod.grows(es):
            ours_grow, ours_fall = False, ours_fall or words_mod.first_fall(rs, es)
    tables = [_paper_for(paper, load, unit_scale) for load in loads]
    tables = [t for t in tables if t]
    paper_grow = all(words_mod.grows([t[r] for r in sorted(t)]) for t in tables) if tables else None
    out = {"ours_grow": ours_grow, "ours_fall": ours_fall, "paper_grow": paper_grow, "larger": 0, "shares": 0,
           "paper_larger": None, "paper_shares": 0}
    if len(loads) >= 2:
        ea = {round(x["r"], 6): x["error"]["rel_mean"] for x in by_load[loads[0]]}
        eb = {round(x["r"], 6): x["error"]["rel_mean"] for x in by_load[loads[1]]}
        rs = [r for r in ea if r in eb and r > 0]
        out["larger"], out["shares"] = sum(eb[r] > ea[r] for r in rs), len(rs)
        pa, pb = _paper_for(paper, loads[0], unit_scale), _paper_for(paper, loads[1], unit_scale)
        if pa and pb:
            shared = [r for r in pa if r in pb]
            out["paper_larger"], out["paper_shares"] = sum(pb[r] > pa[r] for r in shared), len(shared)
    return out
