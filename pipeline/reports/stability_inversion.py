"""Large deformation and inversion -> results/stability/inversion.md/csv, inversion_static.md/csv
and summary_inversion.md."""
from pipeline.reports.stability_common import gather_summary
from pipeline.tables import write_table


def deepest_words(explicit):
    """Which kind went deepest before its first inversion, per probe (from the measured depths)."""
    words = []
    for probe in dict.fromkeys(r["probe"] for r in explicit):
        depth = {r["kind"]: (1.0 if r["exit"] == 0 else r.get("depth_at_failure")) for r in explicit
                 if r["probe"] == probe}
        depth = {k: d for k, d in depth.items() if d is not None}
        if depth:
            best = max(depth, key=depth.get)
            words.append(f"under the {probe} probe {best} goes deepest ({depth[best]:.2f} × the height)")
    text = "; ".join(words)
    return (text[0].upper() + text[1:] + ". ") if words else ""


def report(ctx):
    p = ctx.runs("push")[0].payload
    rows = []
    for r in p["explicit"]:
        outcome = "reached the full depth" if r["exit"] == 0 else f"exit {r['exit']}"
        rows.append([r["probe"], r["probe_nodes"], r["kind"], outcome, r.get("depth_at_failure"), r.get("step"),
                     r.get("element"), r.get("J"), "yes" if r.get("clear") else "no", r["message"]])
    write_table(ctx, "inversion", ["probe", "nodes pushed", "element", "outcome", "depth at first inversion (× height)",
                                   "step", "element index", "J", "clear message", "dhd_sim's message"], rows,
                "A probe pushed into the top of the block (explicit, automatic step, smooth ramp to the full height). "
                "The depth at which the first element inverted follows from the step named in the message.")
    srows = [[r["probe"], r["kind"], r["depth"], "converged" if r["exit"] == 0 else f"exit {r['exit']}", r["message"]]
             for r in p["static"]]
    write_table(ctx, "inversion_static", ["probe", "element", "depth (× height)", "outcome", "message"], srows,
                "The static solver (Newton, load increments, backtracking against inversion) at growing probe depths; "
                "the sweep stops at the first failure.")
    text = ["## Large deformation and inversion", "",
            "A probe pushed into a block until elements invert ([explicit](inversion.md), [static](inversion_static.md)).", ""]
    for r in p["explicit"]:
        if r["exit"] == 3 and r.get("depth_at_failure") is not None:
            what = (f"first inverted element (element {r.get('element')}, J = {r['J']:.3g})" if r.get("J") is not None
                    else f"failure ({r['message'].split('s): ', 1)[-1]})")
            text.append(f"- {r['probe']} probe, **{r['kind']}**: {what} at a depth of {r['depth_at_failure']:.2f} × the "
                        f"height (step {r.get('step')}); exit 3, no result written.")
        elif r["exit"] == 0:
            text.append(f"- {r['probe']} probe, **{r['kind']}**: reached the full depth without inversion.")
        else:
            text.append(f"- {r['probe']} probe, **{r['kind']}**: exit {r['exit']}: {r['message']}")
    clear = all(r.get("clear") for r in p["explicit"] if r["exit"] == 3)
    unclear = sorted({r["kind"] for r in p["explicit"] if r["exit"] == 3 and not r.get("clear")})
    reach = {}
    for r in p["static"]:
        key = (r["probe"], r["kind"])
        if r["exit"] == 0:
            reach[key] = max(reach.get(key, 0.0), r["depth"])
        else:
            reach.setdefault(key, 0.0)
    stopped = [f"{r['kind']} ({r['probe']})" for r in p["explicit"] if r["exit"] == 3]
    through = [f"{r['kind']} ({r['probe']})" for r in p["explicit"] if r["exit"] == 0]
    if not through:
        opening = "every element kind is stopped by the inversion check, "
    elif stopped:
        opening = (f"{', '.join(through)} reached the full depth (the automatic step, re-estimated on the deformed "
                   f"mesh, shrinks as the elements under the probe flatten); the others are stopped by the inversion "
                   f"check, ")
    else:
        opening = "every element kind reached the full depth without inverting. "
    text += ["",
             "In plain words: " + opening
             + ("" if not stopped else
                "always with a message that names the step, the element and J. " if clear else
                "but the " + ", ".join(unclear) + " element is caught one step late, as a non-finite displacement "
                "(the message names the step and the node, not the inverted element and J). ")
             + deepest_words(p["explicit"])
             + "The corotational element, which has no volumetric resistance to "
               "collapse beyond its linear stiffness, inverts first under a point load; linear elements invert "
               "geometrically without noticing it in their forces and are caught at the next energy sample. "
             + "There is no inversion-safe variant (e.g. Irving et al.'s invertible elements) in dhd_sim: a run that "
               "inverts an element ends with exit 3 and writes nothing. The static solver backtracks against "
               "inversion and reports the increment it cannot complete; deepest converged static push (× height): "
             + ", ".join(f"{k[0]} {k[1]} {v:g}" for k, v in sorted(reach.items())) + "."]
    ctx.out("summary_inversion.md").write_text("\n".join(text) + "\n\n")
    gather_summary(ctx)
