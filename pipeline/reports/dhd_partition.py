"""Partition strategies at equal share r (000 §2.2.1 makes the top layers nonlinear; we also try
a sphere around the tool and a strain-driven split, each with linear or corotational cheap
elements) → results/dhd/partition_<load>.md/csv, partition_budget.md/csv, partition_error.png and
the "partition" part of summary.md.

Inputs: the dhd_sim stages named in params "stages" (every run's strategy, share and cheap kind
are read from its config and checked against its artifact); one of them must hold the all-TLED
run (r = 0) of each load.

"Least error per unit of time" is answered two ways: at equal r (the same element counts, hence
the same time per step for the same cheap kind) the error columns compare directly; and for an
error budget (params "budgets", fractions) the table gives the largest speed-up over all-TLED
each family reaches without exceeding it, interpolating linearly between shares. Times per step
come from the cost model of dhd_common.cost_model (params "timing" names the dhd_timing stage)."""

import json

from pipeline import plots
from pipeline.reports import dhd_common as common
from pipeline.stages.machine_load import busy_note
from pipeline.tables import fmt, write_table


FAMILY_ORDER = [("layer", "linear"), ("distance", "linear"), ("strain", "linear"),
                ("layer", "corotational"), ("distance", "corotational"), ("strain", "corotational")]


# A family is "fastest" only where its speed-up over all-TLED exceeds 1 by more than this.
BEATS = 0.005


def family_label(strategy: str, cheap_kind: str) -> str:
    return f"{strategy}, {cheap_kind}"


def family_rows(ctx, stages):
    """{family label: {load: [row sorted by r]}}, a family being (strategy, cheap kind): every
    run's error against the all-TLED run of its load (found in any of the stages) and its time
    per step. The shared end points complete every family: r = 0 (all TLED) and r = 1 of the
    family's cheap kind (all linear or all corotational; the strategy does not matter there)."""
    rows = []
    for stage in stages:
        rows += common.sim_rows(ctx, stage)
    common.errors_against_reference(rows)
    ends = {}
    for g in rows:
        load = round(g["applied"], 12)
        if g["cheap_elements"] == 0:
            ends.setdefault((load, None), g)
        elif g["tled_elements"] == 0:
            ends.setdefault((load, g["cheap_kind"]), g)
    groups = {}
    for g in rows:
        if 0 < g["cheap_elements"] < g["elements"]:
            groups.setdefault(_family_key(g), {}).setdefault(round(g["applied"], 12), []).append(g)
    rank = {k: i for i, k in enumerate(FAMILY_ORDER)}
    keys = sorted(groups, key=lambda k: (rank.get(k[:2], len(rank)), k))
    labels = _family_labels(keys)
    out = {}
    for key in keys:
        strategy, kind, _ = key
        by_load = groups[key]
        for load, group in by_load.items():
            for end in (ends.get((load, None)), ends.get((load, kind))):
                if end is not None:
                    group.append(end)
            by_load[load] = sorted(group, key=lambda x: x["r"])
        out[labels[key]] = by_load
    return out


def _family_key(g):
    """(strategy, cheap kind, the rest of the partition config but the share): runs of one family
    differ in r only."""
    rest = {k: v for k, v in (g["run"].config.get("partition") or {}).items() if k != "linear_fraction"}
    return (g["strategy"], g["cheap_kind"], json.dumps(rest, sort_keys=True))


def _family_labels(keys) -> dict:
    """A label per family naming what its config asks for: "distance, linear", with the settings
    that tell it apart from a family of the same strategy and kind ("distance, linear (distance
    geodesic)") so that no two families share a label."""
    labels = {}
    for key in keys:
        strategy, kind, rest = key
        twins = [k for k in keys if k[:2] == (strategy, kind)]
        label = family_label(strategy, kind)
        if len(twins) > 1:
            mine = json.loads(rest)
            others = [json.loads(k[2]) for k in twins if k != key]
            differ = sorted(n for n in set(mine) | {n for o in others for n in o}
                            if any(o.get(n) != mine.get(n) for o in others))
            label += " (" + ", ".join(f"{n.replace('_', ' ')} {mine.get(n, 'default')}" for n in differ) + ")"
        labels[key] = label
    return labels


def shares_at(data, load):
    """The shares r (to 6 digits) of every family's runs at a load, ascending."""
    return sorted({round(x["r"], 6) for fam in data.values() for x in fam.get(load, [])})


def run_at(data, label, load, r):
    """A family's run at a load and share r (to 6 digits), or None."""
    return next((x for x in data[label].get(load, []) if round(x["r"], 6) == r), None)


def share_winners(data, load):
    """For each share of a load with mixed runs (0 < r < 1), ascending, the family of least mean
    error there; a tie goes to the label first in sort order."""
    winners = []
    for r in shares_at(data, load):
        cands = [(x["error"]["rel_mean"], label) for label in data for x in data[label].get(load, [])
                 if round(x["r"], 6) == r and 0 < x["cheap_elements"] < x["elements"]]
        if cands:
            winners.append(min(cands)[1])
    return winners


def best_speedup_within(points, budget):
    """Largest speed-up (t_ref / t) over points (speed-up, error) sorted by r, with the error
    interpolated linearly between neighbouring shares, that keeps the error ≤ budget."""
    best = None
    for (s0, e0), (s1, e1) in zip(points[:-1], points[1:]):
        for s, e in ((s0, e0), (s1, e1)):
            if e <= budget:
                best = s if best is None else max(best, s)
        if (e0 - budget) * (e1 - budget) < 0:
            s = s0 + (budget - e0) / (e1 - e0) * (s1 - s0)
            best = s if best is None else max(best, s)
    if len(points) == 1 and points[0][1] <= budget:
        best = points[0][0]
    return best


def budget_sentence(budget, cells, where, note="") -> str:
    """Which family is fastest within an error budget at each load: cells are (load label,
    family, speed-up or None); a family is named only where it beats all-TLED."""
    parts = []
    for w in where:
        cands = [(speedup, family) for load, family, speedup in cells if load == w and speedup is not None]
        best = max(cands) if cands else None
        if best and best[0] > 1.0 + BEATS:
            parts.append(f"the fastest at {w} is {best[1]} ({fmt(best[0], 3)}× all-TLED)")
        else:
            parts.append(f"nothing beats all-TLED at {w}")
    return f"Within e ≤ {fmt(100 * budget)} %, " + "; ".join(parts) + note + "."


def layer_jump(data, loads):
    """How much the layer split's error grows from its largest mixed share to all-cheap, the step
    at which the top layer under the tool turns cheap too: the smallest such factor over the loads
    (None without a layer family)."""
    jumps = []
    for label, fam in data.items():
        if not label.startswith("layer,"):
            continue
        for load in loads:
            g = fam.get(load, [])
            mixed = [x for x in g if 0 < x["cheap_elements"] < x["elements"]]
            full = [x for x in g if x["tled_elements"] == 0]
            if mixed and full and mixed[-1]["error"]["rel_mean"] > 0:
                jumps.append(full[0]["error"]["rel_mean"] / mixed[-1]["error"]["rel_mean"])
    return min(jumps) if jumps else None


def report(ctx):
    unit, unit_scale = common.display_unit(ctx)
    budgets = ctx.params.get("budgets", [0.02, 0.05, 0.10])
    data = family_rows(ctx, ctx.params["stages"])
    labels = list(data)
    timing = ctx.runs(ctx.params.get("timing", "timing"))[0].payload
    uniform, _ = common.cost_model(timing)
    busy = busy_note(timing.get("machine"))
    note = f" {busy}" if busy else ""
    for fam in data.values():
        for group in fam.values():
            for x in group:
                x["model_seconds_per_step"] = common.model_time(uniform, x["counts"])
    loads = sorted({load for fam in data.values() for load in fam})
    # What state the errors compare: the runs' own step count (this report has no static
    # solution to call them settled by; dhd_table2 checks the same scene).
    steps = sorted({x["run"].payload["solver"]["steps"] for fam in data.values() for group in fam.values()
                    for x in group})
    mds = []
    for load in loads:
        body = []
        for r in shares_at(data, load):
            row = [f"{int(round(100 * r))} %"]
            for label in labels:
                g = run_at(data, label, load, r)
                row.append(common.pct(g["error"]["rel_mean"], 2) if g else None)
            for kind in ("linear", "corotational"):
                if kind in uniform:
                    m = 1000  # any element count: the model depends on the shares only
                    row.append(common.model_time(uniform, {"tled": m - round(r * m), kind: round(r * m)}) / uniform["tled"])
            body.append(row)
        name = f"partition_{fmt(load * unit_scale)}{unit}".replace(".", "p")
        md = write_table(ctx, name, ["r"] + [f"e {lab} (%)" for lab in labels]
                         + [f"time per step / all-TLED, {k} cheap" for k in ("linear", "corotational") if k in uniform],
                         body,
                         f"**Partition strategies at equal share r, top centre pushed down "
                         f"{fmt(load * unit_scale)} {unit}.** Error e = Σ|u − u_TLED| / Σ|u_TLED| against "
                         f"the all-TLED run, both after {' or '.join(str(n) for n in steps)} steps; time per step "
                         "relative to all-TLED from the cost model ("
                         + ", ".join(f"all-{k} {fmt(1e6 * t, 3)} µs" for k, t in uniform.items())
                         + f" per step, one thread){note}.")
        mds.append(md)

    # Error budgets: the speed-up each family reaches.
    budget_rows = []
    for load in loads:
        for label in labels:
            pts = [(uniform["tled"] / x["model_seconds_per_step"], x["error"]["rel_mean"])
                   for x in data[label].get(load, [])]
            budget_rows.append([f"{fmt(load * unit_scale)} {unit}", label]
                               + [best_speedup_within(pts, b) for b in budgets])
    budget_md = write_table(ctx, "partition_budget", ["applied", "family"]
                            + [f"speed-up within e ≤ {fmt(100 * b)} %" for b in budgets], budget_rows,
                            "**Largest speed-up over all-TLED (time per step ratio, cost model) each family "
                            "reaches while its error stays within the budget** (linear interpolation between the "
                            "measured shares; 1: only all-TLED stays within it)" + (f"{note}." if busy else "."))

    # Plot: error vs r per family, one panel per load.
    fig, axes = plots.plt.subplots(1, len(loads), figsize=(5.2 * len(loads), 4.2), dpi=110, squeeze=False)
    styles = {}
    for i, label in enumerate(labels):
        styles[label] = dict(color=f"C{i % 3}", ls="-" if "corot" not in label else "--",
                             marker="os^"[i % 3])
    for ax, load in zip(axes[0], loads):
        for label in labels:
            g = data[label].get(load, [])
            ax.plot([100 * x["r"] for x in g], [100 * x["error"]["rel_mean"] for x in g], label=label,
                    ms=4, **styles[label])
        ax.set_title(f"top centre displaced by {fmt(load * unit_scale)} {unit}", fontsize=9)
        ax.set_xlabel("share of cheap elements r (%)")
        ax.set_ylabel("mean error e (%)")
        ax.grid(True, alpha=0.3)
        ax.set_yscale("symlog", linthresh=0.1)
    axes[0][0].legend(fontsize=7)
    common.save(fig, ctx, "partition_error.png")

    # Plain words: which family wins at equal r, and per budget.
    words = []
    total_wins, total_shares = {}, 0
    for load in loads:
        wins = {}
        for label in share_winners(data, load):
            wins[label] = wins.get(label, 0) + 1
            total_wins[label] = total_wins.get(label, 0) + 1
            total_shares += 1
        ranking = ", ".join(f"{k} at {v}" for k, v in sorted(wins.items(), key=lambda kv: -kv[1]))
        words.append(f"At {fmt(load * unit_scale)} {unit} the smallest error at equal r comes from: {ranking} "
                     "of the shares.")
    for b_i, b in enumerate(budgets):
        where = [f"{fmt(load * unit_scale)} {unit}" for load in loads]
        words.append(budget_sentence(b, [(row[0], row[1], row[2 + b_i]) for row in budget_rows], where, note))
    lines = ["### Partition strategy at equal share\n"] + mds + [budget_md]
    lines.append("Plot: [dhd/partition_error.png](dhd/partition_error.png).\n")
    lines.append(" ".join(words) + "\n")
    best = max(total_wins, key=total_wins.get) if total_wins else None
    facts = {"best_family": best, "best_wins": total_wins.get(best), "shares": total_shares,
             "best_strategy": best.split(",")[0] if best else None, "layer_jump": layer_jump(data, loads)}
    common.write_section(ctx, "partition", "\n".join(lines), facts)
