"""Why the linked regions miss the whole model on the liver, one candidate cause at a time ->
results/haptic/regions_liver.md/csv (every run: contact, law, input, coupling, force error against
the whole model of the same contact, law and input), regions_liver_fine.md/csv (the refined
liver's frame time, where it goes, and the single-precision interface product),
regions_liver_forces.png and regions_liver_summary.md."""
import numpy as np

from pipeline import plots
from pipeline.bench import cpu_description
from pipeline.reports.haptic_regions import errors, runs_of
from pipeline.stages.machine_load import busy_note
from pipeline.tables import either, write_table

REGION_STAGES = ("condensed", "guyan", "exchange")
LABEL = {"condensed": "condensed", "guyan": "condensed + Guyan mass", "exchange": "eq. 7, held"}
COLOUR = {"condensed": "tab:green", "guyan": "tab:blue", "exchange": "tab:red"}
LAW = {"neo_hookean_paper": "neo-Hookean", "stable_neo_hookean": "stable neo-Hookean", "linear": "linear"}
DYNAMIC = ("press", "growing sine", "chirp")
FAR = {"static": "massless", "guyan": "Guyan mass", "implicit": "implicit"}


def input_label(inp):
    """The input's name in the tables; a press ramped over more than a second is the slow one."""
    if inp["kind"] == "press":
        return "slow press" if inp["ramp_time"] > 1.0 else "press"
    return inp["kind"].replace("_", " ")


def key_of(run):
    c = run.config
    return c["probe"]["contact"], c["model"]["material"]["model"], input_label(c["input"]), c["probe"]["stiffness"]


def end_error(force, whole):
    """|F - F_whole| at the last frame relative to the whole model's peak |F| (%): the equilibrium
    reached after the slow press is held."""
    peak = np.linalg.norm(whole, axis=1).max()
    e = np.linalg.norm(force[-1] - whole[-1])
    return 100 * float(e / peak) if np.isfinite(e) and peak > 0 else float("nan")


def chatter(force):
    """The largest change of |F| from one frame to the next, relative to the peak |F| (%): a smooth
    input gives a small one; a spring coupling past its limit makes the force flip between frames."""
    n = np.linalg.norm(force, axis=1)
    return 100 * float(np.abs(np.diff(n)).max() / n.max()) if len(n) > 1 and n.max() > 0 else float("nan")


def rows_of(ctx):
    whole = {key_of(r): r.payload for r in runs_of(ctx, "whole")}
    rows = []
    for stage in REGION_STAGES:
        for run in runs_of(ctx, stage):
            k = key_of(run)
            if k not in whole:
                continue
            p, w = run.payload, whole[k]
            f, fw = np.array(p["force"]), np.array(w["force"])
            rms, peak = errors(f, fw)
            rows.append({"stage": stage, "contact": k[0], "law": k[1], "input": k[2], "k": k[3], "rms": rms, "peak": peak,
                         "end": end_error(f, fw), "mean": p["timing"]["frame_seconds_mean"],
                         "whole_mean": w["timing"]["frame_seconds_mean"], "events": len(p["events"]),
                         "whole_events": len(w["events"]), "whole_chatter": chatter(fw), "force": f, "whole": fw, "time": np.array(p["time"]),
                         "radius": (p.get("regions") or {}).get("radius"),
                         "every": (p.get("regions") or {}).get("secondary_every"),
                         "ramp": run.config.get("input", {}).get("ramp_time")})
    return rows


def regions_words(rows) -> str:
    """"regions of radius 3.5 cm, secondary every 10 frames", from the region runs."""
    return (f"regions of radius {either([r['radius'] for r in rows], lambda v: f'{100 * v:g}')} cm, secondary every "
            f"{either([r['every'] for r in rows], str)} frames")


# The spring at which the whole model is stable on the liver (see the summary's first point).
STABLE_K = 20


def pick(rows, stage, contact, law, inp, k=STABLE_K):
    for r in rows:
        if (r["stage"], r["contact"], r["law"], r["input"], r["k"]) == (stage, contact, law, inp, k):
            return r
    return None


def clean(r):
    """A comparison means something only where neither model restarted."""
    return r is not None and r["events"] == 0 and r["whole_events"] == 0 and np.isfinite(r["rms"])


def fmt_run(r):
    if r is None:
        return "not run"
    ev = ""
    if r["whole_events"] or r["events"]:
        ev = f" ({r['whole_events']} whole-model and {r['events']} regions events: no reference)"
    return f"{r['rms']:.3g} % RMS{ev}"


def median_over(rows, stage, contact, law, inputs):
    vals = [r["rms"] for r in (pick(rows, stage, contact, law, i) for i in inputs) if clean(r)]
    return (float(np.median(vals)), len(vals)) if vals else (float("nan"), 0)


def forces_plot(ctx, rows, law):
    inputs = [i for i in ("slow press",) + DYNAMIC if pick(rows, "condensed", "attach", law, i)]
    if not inputs:
        return
    fig, axes = plots.plt.subplots(len(inputs), 1, figsize=(7.5, 2.0 * len(inputs)), dpi=110, sharex=True)
    for ax, inp in zip(np.atleast_1d(axes), inputs):
        first = pick(rows, "condensed", "attach", law, inp)
        ax.plot(first["time"], np.linalg.norm(first["whole"], axis=1), color="black", lw=1.6, label="whole model")
        for stage in REGION_STAGES:
            r = pick(rows, stage, "attach", law, inp)
            if r is not None:
                ax.plot(r["time"], np.linalg.norm(r["force"], axis=1), color=COLOUR[stage], lw=0.9,
                        label=f"{LABEL[stage]} ({r['rms']:.2g} % RMS)")
        ax.set_title(inp, fontsize=8)
        ax.set_ylabel("|F| on tool (N)", fontsize=7)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=6, loc="upper right")
    np.atleast_1d(axes)[-1].set_xlabel("time (s)")
    fig.suptitle(f"liver, attached probe, {LAW[law]}: whole model against the linked regions", fontsize=9)
    plots.save(fig, ctx.out("regions_liver_forces.png"))


def fine_runs(ctx, stages):
    """The refined liver's region runs of `stages`, each with the whole model's payload (stage
    fine_whole) and its RMS and peak force error against it: (run, whole, rms, peak); none without
    the whole model's run."""
    whole = runs_of(ctx, "fine_whole")
    if not whole:
        return []
    w = whole[0].payload
    fw = np.array(w["force"])
    return [(run, w, *errors(np.array(run.payload["force"]), fw)) for s in stages for run in runs_of(ctx, s)]


def fine_rows(ctx):
    out = []
    for run, w, rms, peak in fine_runs(ctx, ("fine_condensed", "fine_guyan")):
        p = run.payload
        reg = p["regions"]
        frames = reg["frames"] or 1
        out.append({"radius": reg["radius"], "precision": reg.get("precision", "double"),
                    "secondary": reg.get("secondary", "static"), "every": reg["secondary_every"],
                    "recover_ms": 1e3 * reg["secondary_seconds_total"] / frames,
                    "interface": (reg["primary"] or {}).get("interface_nodes"),
                    "primary_tets": (reg["primary"] or {}).get("primary_tets"),
                    "mean": p["timing"]["frame_seconds_mean"], "p50": p["timing"]["frame_seconds_p50"],
                    "p99": p["timing"]["frame_seconds_p99"], "misses": p["timing"]["deadline_misses"],
                    "interface_ms": 1e3 * reg["interface_seconds_total"] / frames,
                    "whole_mean": w["timing"]["frame_seconds_mean"], "rms": rms, "peak": peak,
                    "events": len(p["events"]), "whole_events": len(w["events"]), "substeps": p["substeps"],
                    "frames": len(p["force"]), "period": p.get("frame_step")})
    return sorted(out, key=lambda r: (r["secondary"] != "static", -r["radius"], r["precision"], r["every"]))


def report(ctx):
    rows = rows_of(ctx)
    write_table(ctx, "regions_liver",
                ["coupling", "probe (N/m)", "contact", "law", "input", "RMS error (%)", "peak error (%)", "end error (%)",
                 "frame mean (ms)", "whole mean (ms)", "events", "whole-model events",
                 "whole-model frame-to-frame jump (%)"],
                [[LABEL[r["stage"]], r["k"], r["contact"], LAW[r["law"]], r["input"], r["rms"], r["peak"], r["end"],
                  1e3 * r["mean"], 1e3 * r["whole_mean"], r["events"], r["whole_events"], r["whole_chatter"]]
                 for r in rows],
                f"The liver held at one end, {regions_words(rows)}, against the whole "
                "model with the same contact, law and input. Errors relative to the whole model's peak |F|; the end "
                f"error is at the last frame. One thread on {cpu_description()} while other work ran.")
    for law in ("stable_neo_hookean", "linear"):
        if pick(rows, "condensed", "attach", law, "chirp"):
            forces_plot(ctx, rows, law)
            break
    fine = fine_rows(ctx)
    if fine:
        write_table(ctx, "regions_liver_fine",
                    ["radius (m)", "far field", "precision", "recovered every (frames)", "primary tets",
                     "interface nodes", "substeps", "frame mean (ms)", "frame p50 (ms)", "frame p99 (ms)",
                     "deadline misses", "interface product (ms per frame)", "recovery (ms per frame)",
                     "whole mean (ms)", "RMS error (%)", "peak error (%)", "events", "whole-model events"],
                    [[r["radius"], FAR[r["secondary"]], r["precision"], r["every"], r["primary_tets"], r["interface"],
                      r["substeps"], 1e3 * r["mean"], 1e3 * r["p50"], 1e3 * r["p99"], r["misses"], r["interface_ms"],
                      r["recover_ms"], 1e3 * r["whole_mean"],
                      r["rms"], r["peak"], r["events"], r["whole_events"]] for r in fine],
                    "Refined liver, attached probe, stable neo-Hookean law, 001's chirp; the condensed regions' frame "
                    "time and the part of it spent in the interface product (-S u_I, every substep). One thread on "
                    f"{cpu_description()} while other work ran: upper bounds.")
    realtime = runs_of(ctx, "fine_realtime")
    ctx.out("regions_liver_summary.md").write_text("\n".join(summary_lines(rows, fine, realtime)) + "\n")


def summary_lines(rows, fine, realtime=()):
    L = ["## Why the regions miss the liver: the causes one at a time", "",
         "The liver held at one end, the condensed regions (radius "
         f"{either([r['radius'] for r in rows if r['stage'] == 'condensed'], lambda v: f'{100 * v:g}')} cm) "
         "against the whole model with the same "
         "contact, law and input; RMS force error relative to the whole model's peak force "
         "([table](regions_liver.md), [forces](regions_liver_forces.png)).", ""]
    inputs = ("slow press",) + DYNAMIC
    # The probe spring held over a frame: the whole model's own events at the stiff and the soft spring.
    for k in sorted({r["k"] for r in rows}, reverse=True):
        runs = [r for r in rows if r["stage"] == "condensed" and r["k"] == k]
        failed = sum(1 for r in runs if r["whole_events"])
        L.append(f"- **the probe's spring, {k:g} N/m:** the whole model itself has events (a restart after an inverted "
                 f"element or a blow-up) in {failed} of {len(runs)} runs"
                 + (f" ({', '.join(sorted({LAW[r['law']] for r in runs if r['whole_events']}))})" if failed else "")
                 + "; where it did not restart, its force changed from one frame to the next by up to "
                + (f"{np.median([r['whole_chatter'] for r in runs if not r['whole_events']]):.2g} % of its peak (median "
                   "over those runs)" if any(not r["whole_events"] for r in runs) else "nothing")
                + "; median RMS error of the condensed regions over the runs where neither model restarted: "
                 + (f"{np.median([r['rms'] for r in runs if clean(r)]):.3g} %" if any(clean(r) for r in runs) else "none")
                 + ".")
    L.append(f"  The rest is at {STABLE_K} N/m.")
    # (a) the sliding grasp: neo-Hookean, grasp against attach.
    L.append("- **(a) the sliding contact.** Condensed, the paper's neo-Hookean law, grasp → attached: " + "; ".join(
        f"{i}: {fmt_run(pick(rows, 'condensed', 'grasp', 'neo_hookean_paper', i))} → "
        f"{fmt_run(pick(rows, 'condensed', 'attach', 'neo_hookean_paper', i))}" for i in inputs) + ".")
    # (b) the inversions: attached, neo-Hookean against stable.
    ev = [(i, pick(rows, "condensed", "attach", "neo_hookean_paper", i),
           pick(rows, "condensed", "attach", "stable_neo_hookean", i)) for i in inputs]
    L.append("- **(b) the whole model's inversions.** Attached, neo-Hookean → stable neo-Hookean: " + "; ".join(
        f"{i}: {fmt_run(a)} → {fmt_run(b)}" for i, a, b in ev) + ".")
    # The quasi-static check.
    lin = pick(rows, "condensed", "attach", "linear", "slow press")
    stab = pick(rows, "condensed", "attach", "stable_neo_hookean", "slow press")
    if lin is not None:
        exact = lin["end"] < 0.01
        hold = lin["time"][-1] - lin["ramp"] if lin["ramp"] is not None and len(lin["time"]) else None
        line = (f"- **quasi-static.** Slow press ("
                + (f"{lin['ramp']:g} s ramp, held {hold:.2g} s" if hold is not None else "ramp and hold")
                + "), attached: with linear elements everywhere the "
                f"condensed far field ends {lin['end']:.2g} % from the whole model "
                + ("(what the damped settling leaves: the condensation is exact at equilibrium on the liver's curved "
                   "mesh as on the cuboid)"
                   if exact else "(not exact: the condensation has a bug on this mesh)")
                + f", {lin['rms']:.3g} % RMS over the press")
        if stab is not None:
            line += (f"; with the stable neo-Hookean law it ends {stab['end']:.2g} % away ({stab['rms']:.3g} % RMS), "
                     "the small-strain far field's own error at this deformation")
        L.append(line + ".")
    # (c) the far field's inertia: attached, linear, dynamic inputs, massless against Guyan.
    for law in ("linear", "stable_neo_hookean"):
        pairs = [(i, pick(rows, "condensed", "attach", law, i), pick(rows, "guyan", "attach", law, i)) for i in DYNAMIC]
        if any(g is not None for _, _, g in pairs):
            L.append(f"- **(c) the far field's inertia** ({LAW[law]}, attached). Condensed massless → with the far "
                     "field's Guyan mass on the interface: " + "; ".join(
                         f"{i}: {fmt_run(c)} → {fmt_run(g)}" for i, c, g in pairs) + ".")
    # (d) eq. 7's lag: attached, exchange against condensed.
    for law in ("linear", "stable_neo_hookean"):
        pairs = [(i, pick(rows, "exchange", "attach", law, i), pick(rows, "condensed", "attach", law, i)) for i in inputs]
        if any(e is not None for _, e, _ in pairs):
            L.append(f"- **(d) eq. 7's lag** ({LAW[law]}, attached). eq. 7 held, every 10 frames → condensed: " + "; ".join(
                f"{i}: {fmt_run(e)} → {fmt_run(c)}" for i, e, c in pairs) + ".")
    L += ["", "In plain words: " + plain_words(rows)]
    if fine:
        L += ["", "### The refined liver's frame time ([table](regions_liver_fine.md))", ""]
        for r in fine:
            share = 100 * r["interface_ms"] / (1e3 * r["mean"]) if r["mean"] > 0 else float("nan")
            rec = 100 * r["recover_ms"] / (1e3 * r["mean"]) if r["mean"] > 0 else float("nan")
            L.append(f"- radius {r['radius']:g} m ({r['interface']} interface nodes, {r['substeps']} substeps per frame), "
                     f"{FAR[r['secondary']]}, {r['precision']} precision, far field recovered every {r['every']} frames: "
                     f"{1e3 * r['mean']:.3g} ms mean per frame (p50 {1e3 * r['p50']:.3g}, "
                     f"p99 {1e3 * r['p99']:.3g}), of which the interface product {r['interface_ms']:.3g} ms "
                     f"({share:.0f} %) and the far field's recovery {r['recover_ms']:.3g} ms ({rec:.0f} %); "
                     f"{r['misses']} of {r['frames']} frames over {period_words(r)}; "
                     f"{fmt_run(r)} against the whole model ({1e3 * r['whole_mean']:.3g} ms per frame).")
        L += ["", "In plain words: " + fine_words(fine)]
    for run in realtime:
        L += ["", realtime_line(run)]
    return L


def realtime_line(run):
    """One served run: `haptic_sim serve` paced at its rate, its round trips and compute per frame;
    the rate, duration and press from the run, the machine's load beside the figures."""
    p = run.payload
    rt = np.array(p["round_trip_seconds"])
    reg = p["regions"] or {}
    rate = p.get("rate", 1000)
    period_ms = 1e3 / rate
    press = (run.config or {}).get("press", {})
    held = (f"a press of {100 * press['depth']:g} cm over {press['ramp_time']:g} s, held"
            if "depth" in press and "ramp_time" in press else "a press held")
    far = FAR.get(reg.get("secondary"), "") + (f" and {reg['modes']} modes" if reg.get("modes") else "")
    busy = busy_note(p.get("machine"))
    return (f"Real-time loop (`haptic_sim serve` over a pipe, paced at {rate / 1000:g} kHz for {len(rt) / rate:g} s, "
            f"{held}; radius {reg.get('radius', float('nan')):g} m, {far}, "
            f"{reg.get('precision', '')} precision, no pictures): round trip median {1e3 * np.median(rt):.3g} ms, "
            f"p99 {1e3 * np.percentile(rt, 99):.3g} ms, max {1e3 * rt.max():.3g} ms; {int((rt > 1.0 / rate).sum())} of "
            f"{len(rt)} answers later than {period_ms:.3g} ms; compute per frame p50 "
            f"{1e3 * p['timing']['frame_seconds_p50']:.3g} ms, "
            f"p99 {1e3 * p['timing']['frame_seconds_p99']:.3g} ms; {p['events']} events"
            + set_up_words(rt, reg) + (f" {busy}" if busy else "") + ".")


def set_up_words(rt, reg):
    """Whether the region's set-up fell inside the first round trip (built at the first contact) or
    before the device's clock started (haptic_sim serve with realtime.announce)."""
    build = reg.get("build_seconds_max")
    if not build:
        return ""
    if rt[0] >= 0.5 * build:
        return f"; the first answer waited for the region's set-up ({build:.3g} s, built at the first contact)"
    return (f"; the region's set-up ({build:.3g} s) was done before the device's clock started (serve announces "
            f"it), so the first answer took {1e3 * rt[0]:.3g} ms")


def plain_words(rows):
    words = []
    stiff = [r for r in rows if r["stage"] == "condensed" and r["k"] > STABLE_K]
    if stiff:
        failed = sum(1 for r in stiff if r["whole_events"])
        grasped = [r for r in stiff if r["contact"] == "grasp" and not r["whole_events"]]
        words.append(f"the stiffer spring is past what the soft liver carries: the spring's force, held over a frame, "
                     f"couples it to the model explicitly, and the whole model itself restarted in {failed} of "
                     f"{len(stiff)} runs at it"
                     + (f", while where the sliding grasp kept it alive its force flips by up to "
                        f"{np.median([r['whole_chatter'] for r in grasped]):.2g} % of its peak between frames (median), "
                        "which the regions, with their own small differences, do not follow" if grasped else "")
                     + f". At {STABLE_K} N/m no run restarted and the force is smooth; that spring, not the regions, "
                     "made most of the earlier liver error.")
    g_n, g_a = (median_over(rows, "condensed", c, "neo_hookean_paper", ("slow press",) + DYNAMIC)[0]
                for c in ("grasp", "attach"))
    lin = pick(rows, "condensed", "attach", "linear", "slow press")
    if np.isfinite(g_n) and np.isfinite(g_a):
        words.append(f"Holding the material point instead of sliding changes the median error of the runs without "
                     f"restarts from {g_n:.3g} % to {g_a:.3g} %.")
    if lin is not None:
        words.append(f"At equilibrium the condensed far field equals the whole linear model on the liver "
                     f"({lin['end']:.2g} % at the end of the slow press)." if lin["end"] < 0.01 else
                     f"At equilibrium the condensed far field misses the whole linear model by {lin['end']:.2g} %.")
    c_l, _ = median_over(rows, "condensed", "attach", "linear", DYNAMIC)
    g_l, _ = median_over(rows, "guyan", "attach", "linear", DYNAMIC)
    if np.isfinite(c_l) and np.isfinite(g_l):
        words.append(f"On the linear liver under the dynamic inputs, the far field's inertia is what is left: median "
                     f"{c_l:.3g} % massless, {g_l:.3g} % with its Guyan mass on the interface"
                     + (" (the static-shape mass carries most of it)." if g_l < 0.5 * c_l else
                        " (the static-shape mass is not enough: the far field's own modes matter)."
                        if g_l < c_l else " (the lumped static-shape mass does not help here)."))
    c_s, _ = median_over(rows, "condensed", "attach", "stable_neo_hookean", DYNAMIC)
    g_s, _ = median_over(rows, "guyan", "attach", "stable_neo_hookean", DYNAMIC)
    if np.isfinite(c_s):
        words.append(f"With the stable neo-Hookean law (no restarts) the dynamic inputs leave median {c_s:.3g} % "
                     f"massless" + (f" and {g_s:.3g} % with the Guyan mass" if np.isfinite(g_s) else "") + ".")
    every = ("slow press",) + DYNAMIC
    e_l, _ = median_over(rows, "exchange", "attach", "linear", every)
    cc_l, _ = median_over(rows, "condensed", "attach", "linear", every)
    gg_l, _ = median_over(rows, "guyan", "attach", "linear", DYNAMIC)
    if np.isfinite(e_l) and np.isfinite(cc_l):
        words.append(f"eq. 7's exchange (held, every 10 frames), whose primary region keeps its interface nodes' own "
                     f"mass, leaves median {e_l:.3g} % over all four inputs against {cc_l:.3g} % for the massless "
                     "condensed far field" + (f" and {gg_l:.3g} % over the dynamic inputs with the Guyan mass" if
                                              np.isfinite(gg_l) else "") + " (linear, attached).")
    text = " ".join(words) if words else "no runs."
    return text[:1].upper() + text[1:]


def period_words(r) -> str:
    """The run's frame period ("1 ms"), from its artifact; 1 ms where an older artifact lacks it."""
    return f"{1e3 * (r.get('period') or 1e-3):g} ms"


def fine_words(fine):
    by = {(r["radius"], r["precision"]): r for r in fine if r["secondary"] == "static"}
    out = []
    for radius in sorted({r["radius"] for r in by.values()}, reverse=True):
        d, s = by.get((radius, "double")), by.get((radius, "single"))
        if d and s:
            out.append(f"at {radius:g} m the interface product takes {d['interface_ms']:.3g} ms per frame in double "
                       f"precision and {s['interface_ms']:.3g} ms in single, with the same RMS error ({d['rms']:.3g} % "
                       f"and {s['rms']:.3g} %)")
    text = "; ".join(out) + ". " if out else ""
    static = [r for r in fine if r["secondary"] == "static"]
    guyan = [r for r in fine if r["secondary"] == "guyan"]
    if static and guyan:
        text += (f"The far field's Guyan mass takes the refined liver's error from {min(r['rms'] for r in static):.3g}–"
                 f"{max(r['rms'] for r in static):.3g} % massless to {min(r['rms'] for r in guyan):.3g}–"
                 f"{max(r['rms'] for r in guyan):.3g} %. ")
    worst = max(fine, key=lambda r: r["recover_ms"])
    if worst["recover_ms"] > worst["interface_ms"]:
        text += (f"Recovering the far field's nodes (a sparse solve of the whole far field, for pictures only) is the "
                 f"largest part of the mean where it runs every {worst['every']} frames ({worst['recover_ms']:.3g} ms per "
                 "frame on average, all of it in one frame of each period: the p99). ")
    best = min(fine, key=lambda r: r["p50"])
    text += (f"The fastest setting (radius {best['radius']:g} m, {FAR[best['secondary']]}, {best['precision']} precision, "
             f"recovered every {best['every']} frames) takes {1e3 * best['p50']:.3g} ms per frame at the median and "
             f"{1e3 * best['mean']:.3g} ms on average, with {best['misses']} of {best['frames']} frames over "
             f"{period_words(best)}, at "
             f"{best['rms']:.3g} % RMS error; ")
    period = best["period"] or 1e-3
    text += (f"its median fits the {period_words(best)} period on this machine, its mean does not."
             if best["p50"] <= period < best["mean"] else
             f"it fits the {period_words(best)} period." if best["mean"] <= period else
             f"the {1e-3 / period:g} kHz target is not met on this machine.")
    return text
