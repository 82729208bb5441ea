"""Linked asynchronous regions in 3-D against the whole model -> results/haptic/:
regions_table.md/csv (001 Tables 1-2: force error and speed gain against primary radius and
secondary rate, per coupling), regions_inputs.md/csv (every input at the reference setting),
regions_adaptive.md/csv (001 Fig. 5 and skipped secondary updates), regions_forces_<scene>.png
(force against time: whole model, eq. 7 held and interpolated, condensed), regions_tradeoff.png
(time per frame against force error, every setting), regions_summary.md."""
import numpy as np

from pipeline import plots
from pipeline.bench import cpu_description
from pipeline.stages.machine_load import busy_note
from pipeline.tables import either, write_table

# scene label, whole-model stage, regions stages
SCENES = (("cuboid", "cube_run", "cube"), ("liver", "liver_run", "liver"),
          ("liver, hybrid", "hybrid_run", "hybrid"), ("refined liver", "fine_run", "fine"))
COUPLINGS = ("condensed", "exchange_interpolated", "exchange_held")
LABEL = {"condensed": "condensed", "exchange_interpolated": "eq. 7, interpolated", "exchange_held": "eq. 7, held"}
COLOUR = {"condensed": "tab:green", "exchange_interpolated": "tab:orange", "exchange_held": "tab:red"}


def coupling_of(p):
    r = p["regions"]
    if r["coupling"] == "condensed":
        return "condensed"
    return "exchange_interpolated" if r["interpolate"] else "exchange_held"


def errors(force, whole):
    """RMS and peak of |F - F_whole| over the frames, relative to the whole model's peak |F| (%)."""
    peak = np.linalg.norm(whole, axis=1).max()
    e = np.linalg.norm(force - whole, axis=1)
    if not (np.all(np.isfinite(e)) and peak > 0):
        return float("nan"), float("nan")
    return 100 * float(np.sqrt(np.mean(e ** 2)) / peak), 100 * float(e.max() / peak)


def runs_of(ctx, stage):
    """The runs of a stage, none when the experiment leaves it out."""
    try:
        return ctx.runs(stage)
    except KeyError:
        return []


def whole_rows(ctx, stage):
    out = {}
    for run in runs_of(ctx, stage):
        p = run.payload
        out[run.config["input"]["kind"]] = {"force": np.array(p["force"]), "timing": p["timing"], "payload": p}
    return out


def row_of(scene, run, whole):
    p = run.payload
    w = whole[run.config["input"]["kind"]]
    rms, peak = errors(np.array(p["force"]), w["force"])
    t, tw, r = p["timing"], w["timing"], p["regions"]
    primary = r["primary"] or {}
    return {
        "scene": scene, "input": run.config["input"]["kind"], "coupling": coupling_of(p),
        "radius": r["radius"], "every": r["secondary_every"], "adaptive": r["adaptive"]["kind"],
        "skip_below": r["skip_below"], "tets": p["model"]["tets"],
        "primary_tets": primary.get("primary_tets"), "interface": primary.get("interface_nodes"),
        "mean": t["frame_seconds_mean"], "p50": t["frame_seconds_p50"], "p99": t["frame_seconds_p99"],
        "max": t["frame_seconds_max"], "misses": t["deadline_misses"],
        "whole_mean": tw["frame_seconds_mean"], "whole_p50": tw["frame_seconds_p50"],
        "whole_misses": tw["deadline_misses"],
        "gain": tw["frame_seconds_mean"] / t["frame_seconds_mean"], "gain_p50": tw["frame_seconds_p50"] / t["frame_seconds_p50"],
        "rms": rms, "peak": peak, "region_events": len(p["events"]), "whole_events": len(w["payload"]["events"]),
        "updates": r["secondary_updates"], "skipped": r["secondary_skipped"], "builds": r["builds"],
        "build_max": r["build_seconds_max"], "secondary_max": r["secondary_seconds_max"],
        "frames_per_level": r["adaptive"]["frames_per_level"], "run": run, "period": p.get("frame_step"),
    }


HEAD = ["scene", "input", "coupling", "radius (m)", "primary tets", "interface nodes", "every (frames)",
        "secondary rate (Hz)", "RMS error (%)", "peak error (%)", "frame mean (ms)", "frame p50 (ms)",
        "frame p99 (ms)", "frame max (ms)", "deadline misses", "whole mean (ms)", "speed gain (mean)",
        "speed gain (p50)", "events", "secondary updates", "skipped", "regions built", "build max (s)"]


def cells(r):
    return [r["scene"], r["input"], LABEL[r["coupling"]], r["radius"], r["primary_tets"], r["interface"], r["every"],
            1000.0 / r["every"], r["rms"], r["peak"], 1e3 * r["mean"], 1e3 * r["p50"], 1e3 * r["p99"], 1e3 * r["max"],
            r["misses"], 1e3 * r["whole_mean"], r["gain"], r["gain_p50"], r["region_events"], r["updates"],
            r["skipped"], r["builds"], r["build_max"]]


def plot_forces(scene, whole, rows, path):
    inputs = [k for k in ("press", "slide", "growing_sine", "chirp") if k in whole]
    fig, axes = plots.plt.subplots(len(inputs), 1, figsize=(7.5, 2.0 * len(inputs)), dpi=110, sharex=True)
    for ax, kind in zip(np.atleast_1d(axes), inputs):
        w = whole[kind]
        t = np.array(w["payload"]["time"])
        ax.plot(t, np.linalg.norm(w["force"], axis=1), color="black", lw=1.6, label="whole model")
        for r in rows:
            if r["input"] == kind:
                f = np.array(r["run"].payload["force"])
                ax.plot(t, np.linalg.norm(f, axis=1), color=COLOUR[r["coupling"]], lw=0.9,
                        label=f"{LABEL[r['coupling']]} ({r['rms']:.2g} % RMS)")
        ax.set_title(kind, fontsize=8)
        ax.set_ylabel("|F| on tool (N)", fontsize=7)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=6, loc="upper right")
    np.atleast_1d(axes)[-1].set_xlabel("time (s)")
    fig.suptitle(f"{scene}: force on the tool, whole model against the linked regions", fontsize=9)
    plots.save(fig, path)


def plot_tradeoff(rows, path):
    fig, ax = plots.figure(7, 4.6)
    markers = {"cuboid": "o", "liver": "s", "liver, hybrid": "D", "refined liver": "^"}
    for c in COUPLINGS:
        for scene, m in markers.items():
            pts = [(r["rms"], 1e3 * r["mean"]) for r in rows if r["coupling"] == c and r["scene"] == scene and np.isfinite(r["rms"])]
            if pts:
                x, y = zip(*pts)
                ax.scatter(x, y, marker=m, color=COLOUR[c], s=16, alpha=0.8, label=f"{LABEL[c]}, {scene}")
    for scene, m in markers.items():
        whole = [1e3 * r["whole_mean"] for r in rows if r["scene"] == scene]
        if whole:
            ax.axhline(np.median(whole), color="grey", lw=0.8, ls=":")
            ax.text(ax.get_xlim()[0] if False else 1e-3, np.median(whole), f" whole model, {scene}", fontsize=6,
                    va="bottom", color="grey")
    periods = sorted({r["period"] for r in rows if r.get("period")}) or [1e-3]
    for period in periods:
        ax.axhline(1e3 * period, color="black", lw=0.8, ls="--")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("RMS force error against the whole model (% of its peak)")
    ax.set_ylabel("mean time per frame (ms)")
    ax.set_title("Run time against force error, every setting (dashed: the "
                 + " or ".join(f"{1e3 * v:g} ms" for v in periods) + " haptic period)", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=6, ncol=2)
    plots.save(fig, path)


def best(rows, key, budget):
    # A comparison with a whole model that itself failed (events) says nothing: left out.
    ok = [r for r in rows if np.isfinite(r["rms"]) and r["rms"] <= budget and r["region_events"] == 0
          and r["whole_events"] == 0]
    return min(ok, key=lambda r: r["mean"]) if ok else None


def report(ctx):
    cpu = cpu_description()
    table, inputs, adaptive = [], [], []
    for scene, whole_stage, prefix in SCENES:
        whole = whole_rows(ctx, whole_stage)
        if not whole:
            continue
        for c in COUPLINGS:
            table += [row_of(scene, run, whole) for run in runs_of(ctx, f"{prefix}_{c}")]
        inputs_here = [row_of(scene, run, whole) for c in COUPLINGS for run in runs_of(ctx, f"{prefix}_inputs_{c}")]
        inputs += inputs_here
        adaptive += [row_of(scene, run, whole) for run in runs_of(ctx, f"{prefix}_adaptive")]
        plot_forces(scene, whole, inputs_here, ctx.out(f"regions_forces_{prefix}.png"))
    note = (f"One thread, each run alone in the pipeline, on {cpu}. Errors: |F − F_whole| per frame, RMS and peak "
            "over the 2000 frames, relative to the whole model's peak |F| (the whole model is haptic_whole's run of "
            "the same input). Speed gain: the whole model's mean (or median) time per frame over the regions'; the "
            "two come from separate runs on the same machine, so load from other processes enters both.")
    write_table(ctx, "regions_table", HEAD, [cells(r) for r in table],
                "001 Tables 1–2 in 3-D: primary radius and secondary rate swept for each coupling. " + note)
    write_table(ctx, "regions_inputs", HEAD, [cells(r) for r in inputs],
                "Every input at the reference setting of each scene. " + note)
    write_table(ctx, "regions_adaptive", HEAD + ["adaptive", "skip below (m)", "frames per size level"],
                [cells(r) + [r["adaptive"], r["skip_below"], r["frames_per_level"]] for r in adaptive],
                "The adaptive primary radius (001 Fig. 5: linear in the contact displacement; threshold: the farthest "
                "node that moved more than the threshold) and skipped secondary updates. " + note)
    everything = table + inputs + adaptive
    plot_tradeoff(everything, ctx.out("regions_tradeoff.png"))
    realtime = realtime_rows(ctx)
    text = summary(table, inputs, adaptive, cpu)
    if realtime:
        write_table(ctx, "regions_realtime", ["scene", "solver", "tets", "substeps", "frames", "round trip p50 (ms)",
                                              "round trip p99 (ms)", "round trip max (ms)", "late answers (> one period)",
                                              "compute p50 (ms)", "compute p99 (ms)", "deadline misses (compute)",
                                              "events", "peak |F| (N)"],
                    [[r["scene"], r["solver"], r["tets"], r["substeps"], r["frames"], 1e3 * r["rt50"], 1e3 * r["rt99"],
                      1e3 * r["rtmax"], r["late"], 1e3 * r["p50"], 1e3 * r["p99"], r["misses"], r["events"], r["peak"]]
                     for r in realtime],
                    f"haptic_sim serve driven for {realtime_run_words(realtime)} by a paced client over a pipe "
                    f"({press_words(realtime)}), one thread, on {cpu}. Round trip: position sent "
                    "to force received, as a device bridge sees it; compute: the frame's own time inside haptic_sim"
                    + machine_words(realtime) + ".")
        plot_realtime(realtime, ctx.out("regions_realtime.png"))
        text += "\n\n" + realtime_summary(realtime)
    ctx.out("regions_summary.md").write_text(text + "\n")


REALTIME = (("realtime_cube_whole", "cuboid"), ("realtime_liver_whole", "liver"),
            ("realtime_liver_condensed", "liver"), ("realtime_fine_exchange", "refined liver"),
            ("realtime_fine_condensed", "refined liver"))


def realtime_rows(ctx):
    rows = []
    for stage, scene in REALTIME:
        for run in runs_of(ctx, stage):
            p = run.payload
            rt = np.array(p["round_trip_seconds"])
            solver = "whole model" if p["solver"] == "whole_model" else \
                f"regions, {LABEL[coupling_of(p)]}, radius {p['regions']['radius']:g} m"
            rows.append({"scene": scene, "solver": solver, "tets": p["model"]["tets"], "substeps": p["substeps"],
                         "frames": p["frames"], "rt": rt, "rt50": float(np.median(rt)),
                         "rt99": float(np.percentile(rt, 99)), "rtmax": float(rt.max()),
                         "late": int((rt > 1.0 / p["rate"]).sum()), "p50": p["timing"]["frame_seconds_p50"],
                         "p99": p["timing"]["frame_seconds_p99"], "misses": p["timing"]["deadline_misses"],
                         "events": p["events"], "peak": p["peak_force"], "seconds": p["seconds"], "rate": p["rate"],
                         "press": (run.config or {}).get("press", {}), "machine": p.get("machine")})
    return rows


def _either(values, unit="", scale=1.0):
    return either([v * scale for v in values if v is not None], unit=unit)


def realtime_run_words(rows) -> str:
    """"10 s at 1 kHz": the duration and rate of the served runs, from their artifacts."""
    return f"{_either([r['seconds'] for r in rows], 's')} at {_either([r['rate'] for r in rows], 'kHz', 1e-3)}"


def press_words(rows) -> str:
    """The press of the served runs, from their configs: "a press of 1 cm over 0.5 s, held"."""
    return (f"a press of {_either([r['press'].get('depth') for r in rows], 'cm', 100)} over "
            f"{_either([r['press'].get('ramp_time') for r in rows], 's')}, held")


def machine_words(rows) -> str:
    """The served runs' busy-machine notes (pipeline.stages.machine_load), each once."""
    notes = []
    for r in rows:
        note = busy_note(r["machine"])
        if note and note not in notes:
            notes.append(note)
    return (" " + " ".join(notes)) if notes else ""


def plot_realtime(rows, path):
    fig, ax = plots.figure(7, 4.2)
    bins = np.logspace(-5, 0, 80)
    for r in rows:
        ax.hist(r["rt"], bins=bins, histtype="step", lw=1.1, label=f"{r['scene']}: {r['solver']}")
    for rate in sorted({r["rate"] for r in rows}):
        ax.axvline(1.0 / rate, color="black", ls="--", lw=0.8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("round trip per frame (s)")
    ax.set_ylabel("frames")
    ax.set_title(f"Real-time loop, {realtime_run_words(rows)} per scene (dashed: one period)", fontsize=9)
    ax.legend(fontsize=6)
    ax.grid(True, which="both", alpha=0.3)
    plots.save(fig, path)


def realtime_summary(rows):
    lines = [f"Real-time loop, {realtime_run_words(rows)} per scene over a pipe ([table](regions_realtime.md), "
             f"[histograms](regions_realtime.png)){machine_words(rows)}:"]
    for r in rows:
        lines.append(f"- {r['scene']}, {r['solver']} ({r['tets']} tets): round trip median {1e3 * r['rt50']:.3g} ms, "
                     f"p99 {1e3 * r['rt99']:.3g} ms; {r['late']} of {r['frames']} answers later than "
                     f"{1e3 / r['rate']:.3g} ms; "
                     f"{r['events']} events.")
    return "\n".join(lines)


def summary(table, inputs, adaptive, cpu):
    lines = ["## Linked asynchronous regions in 3-D (001 §5)", "",
             "The primary region around the contact is the dhd_sim engine on its own elements every substep; the "
             "secondary region is linear and quasi-static, factorised once, and coupled either by 001 eq. 7's "
             "exchange every k frames (interface values held or interpolated, 001 Fig. 4) or by condensing its "
             "stiffness onto the interface (a force at every substep). Tables: [radius × rate](regions_table.md), "
             "[inputs](regions_inputs.md), [adaptive radius and skipping](regions_adaptive.md); plots: "
             "[run time against error](regions_tradeoff.png), forces on the "
             "[cuboid](regions_forces_cube.png), [liver](regions_forces_liver.png), "
             f"[hybrid liver](regions_forces_hybrid.png) ({hybrid_words(table + inputs)}), "
             "[refined liver](regions_forces_fine.png).", ""]
    for scene in [s[0] for s in SCENES]:
        rows = [r for r in table + inputs if r["scene"] == scene]
        if not rows:
            continue
        by = {c: [r for r in rows if r["coupling"] == c and np.isfinite(r["rms"])] for c in COUPLINGS}
        parts = []
        for c in COUPLINGS:
            if by[c]:
                rms = [r["rms"] for r in by[c]]
                ev = sum(r["region_events"] for r in by[c])
                parts.append(f"{LABEL[c]}: RMS error {min(rms):.3g}–{max(rms):.3g} %" +
                             (f" ({ev} numerical events)" if ev else ""))
        lines.append(f"- **{scene}** ({rows[0]['tets']} tets; whole model {1e3 * np.median([r['whole_mean'] for r in rows]):.3g} "
                     f"ms mean per frame, {max(r['whole_misses'] for r in rows)} deadline misses at most per run): "
                     + "; ".join(parts) + ".")
        for budget in (1.0, 5.0):
            b = best(rows, "rms", budget)
            if b:
                lines.append(f"  - fastest within {budget:g} % RMS: {LABEL[b['coupling']]}, radius {b['radius']:g} m "
                             f"({b['primary_tets']} primary tets), every {b['every']} frames: {1e3 * b['mean']:.3g} ms "
                             f"mean per frame, speed gain {b['gain']:.3g} (p50: {b['gain_p50']:.3g}), error "
                             f"{b['rms']:.3g} % RMS / {b['peak']:.3g} % peak, {b['misses']} deadline misses.")
            else:
                lines.append(f"  - no setting within {budget:g} % RMS.")
    # The paper's statement: primary size matters more than secondary rate (for eq. 7).
    for c in ("exchange_interpolated", "condensed"):
        rows = [r for r in table if r["coupling"] == c and np.isfinite(r["rms"]) and r["input"] == "chirp"]
        if rows:
            by_radius = {}
            by_every = {}
            for r in rows:
                by_radius.setdefault((r["scene"], r["every"]), []).append(r["rms"])
                by_every.setdefault((r["scene"], r["radius"]), []).append(r["rms"])
            radius_factors = [max(v) / max(min(v), 1e-12) for v in by_radius.values() if len(v) > 1]
            every_factors = [max(v) / max(min(v), 1e-12) for v in by_every.values() if len(v) > 1]
            if not (radius_factors and every_factors):
                continue
            f_radius, f_every = np.median(radius_factors), np.median(every_factors)
            lines.append(f"- {LABEL[c]}, chirp: across the radii the RMS error changes by a factor {f_radius:.3g} "
                         f"(median over scenes and rates), across the secondary rates by {f_every:.3g} (paper 001: "
                         "\"the primary region size has more effect on the force error than the secondary frequency\").")
    if adaptive:
        for r in adaptive:
            lines.append(f"- {r['scene']}, {r['input']}, {LABEL[r['coupling']]}" +
                         (f", adaptive ({r['adaptive']})" if r["adaptive"] != "fixed" else "") +
                         (f", skipping below {r['skip_below']:g} m" if r["skip_below"] > 0 else "") +
                         f": {r['rms']:.3g} % RMS, {r['builds']} regions built, frames per size level "
                         f"{r['frames_per_level']}, secondary updates {r['updates']} done / {r['skipped']} skipped, "
                         f"{1e3 * r['mean']:.3g} ms mean per frame.")
    lines += ["", plain_words(inputs, cpu)]
    return "\n".join(lines)


def hybrid_words(rows) -> str:
    """The hybrid liver's partition from its runs: "000's partition: TLED within 5 cm of
    (-4, -5, 152) cm, linear elsewhere"."""
    parts = []
    for r in rows:
        if r["scene"] != "liver, hybrid":
            continue
        p = (r["run"].config.get("model") or {}).get("partition") or {}
        if p.get("kind") == "sphere":
            centre = ", ".join(f"{100 * c:g}" for c in p["center"])
            text = (f"000's partition: {p.get('nonlinear_element', 'TLED').upper()} within {100 * p['radius']:g} cm "
                    f"of ({centre}) cm, {p.get('linear_element', 'linear')} elsewhere")
        else:
            text = f"partition {p.get('kind', 'as its config sets')}"
        if text not in parts:
            parts.append(text)
    return "; ".join(parts) or "no hybrid run"


def held_against_interpolated(rows) -> str:
    """001 eq. 7's exchange with held against interpolated interface values, per scene, from the
    median RMS error of the runs without numerical events of either."""
    held_wins, interp_wins = [], []
    for scene in dict.fromkeys(r["scene"] for r in rows):
        med = {}
        for c in ("exchange_held", "exchange_interpolated"):
            e = [r["rms"] for r in rows if r["scene"] == scene and r["coupling"] == c and np.isfinite(r["rms"])]
            if e:
                med[c] = float(np.median(e))
        if len(med) == 2:
            (held_wins if med["exchange_held"] < med["exchange_interpolated"] else interp_wins).append(
                f"{scene} ({med['exchange_held']:.2g} % against {med['exchange_interpolated']:.2g} %)")
    if not (held_wins or interp_wins):
        return ""
    parts = []
    if held_wins:
        parts.append("held interface values give the smaller median RMS error on the " + ", ".join(held_wins))
    if interp_wins:
        parts.append("interpolated ones on the " + ", ".join(interp_wins) + " (held first)")
    return ("001 eq. 7's exchange adds the lag of its interface values to this: " + "; ".join(parts)
            + "; both can turn unstable (the events above).")


def plain_words(inputs, cpu):
    """The findings in words, with the reference setting's measured errors."""
    def err(scene, kind, coupling="condensed"):
        for r in inputs:
            if r["scene"] == scene and r["input"] == kind and r["coupling"] == coupling:
                return r
        return None
    press, chirp, liver = err("cuboid", "press"), err("cuboid", "chirp"), err("liver", "slide")
    failed = sorted({(r["scene"], r["input"]) for r in inputs if r["whole_events"]})
    text = ["In plain words: the regions are only as good as their far field."]
    if press and chirp:
        top = chirp["run"].config["input"].get("end_frequency")
        text.append(f"On the cuboid pressed slowly, the condensed coupling (the far field's exact quasi-static "
                    f"stiffness at every substep) follows the whole model to {press['rms']:.2g} % RMS at "
                    f"{press['gain']:.2g}× its speed; the chirp"
                    + (f", which reaches {top:g} Hz," if top is not None else "")
                    + f" leaves {chirp['rms']:.2g} %.")
    if liver:
        # What causes the liver's error is separated by haptic_regions_liver, one cause at a time;
        # this report's runs alone cannot tell them apart, so it names none.
        text.append(f"On the liver, held at one end, even a slide leaves {liver['rms']:.2g} %; which cause makes "
                    "this error (the probe's spring, the sliding grasp, the far field's missing inertia, eq. 7's "
                    "lag) is measured one at a time in regions_liver_summary.md, not by these runs.")
    text.append(held_against_interpolated(inputs))
    if failed:
        text.append("Where the whole model itself failed (" + ", ".join(f"{s} {k}" for s, k in failed) +
                    ": the tool pulls an element inside out), the errors compare against a model that restarted "
                    "and say nothing; the fastest settings above leave these runs out.")
    text.append(f"Timings come from {cpu}, and the gains are ratios from separate runs.")
    return " ".join(text)
