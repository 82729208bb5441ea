"""The far field's dynamics beyond its static shape -> results/haptic/regions_modal.md/csv (every
run: scene, input, far field, force error against the whole model with the same input),
regions_modal_forces.png and regions_modal_summary.md (per scene and input, which far field
meets the 1 % RMS target and by how much the others miss it)."""
import numpy as np

from pipeline import plots
from pipeline.bench import cpu_description
from pipeline.reports.haptic_regions import errors, runs_of
from pipeline.reports.haptic_regions_liver import LAW, fine_runs, input_label, period_words, realtime_line
from pipeline.tables import either, write_table

SCENES = ("cube", "liver")
SCENE_NAME = {"cube": "paper's cuboid", "liver": "liver"}
INPUTS = ("slow press", "press", "slide", "growing sine", "chirp")
TARGET = 1.0  # % RMS of the whole model's peak force (the target)


def far_field(run):
    """The far field's model of a regions run: massless, Guyan, or Guyan plus N modes."""
    reg = run.config["regions"]
    if reg.get("secondary", "static") != "guyan":
        return "massless"
    m = reg.get("modes", 0)
    return f"{m} modes" if m else "Guyan"


def far_order(name):
    return (0, 0) if name == "massless" else (1, 0) if name == "Guyan" else (2, int(name.split()[0]))


def rows_of(ctx):
    rows = []
    for scene in SCENES:
        whole = {input_label(r.config["input"]): r.payload for r in runs_of(ctx, f"{scene}_whole")}
        for stage in ("massless", "guyan", "modal"):
            for run in runs_of(ctx, f"{scene}_{stage}"):
                inp = input_label(run.config["input"])
                if inp not in whole:
                    continue
                p, w = run.payload, whole[inp]
                f, fw = np.array(p["force"]), np.array(w["force"])
                rms, peak = errors(f, fw)
                reg = p["regions"]
                frames = reg["frames"] or 1
                rows.append({"scene": scene, "input": inp, "far": far_field(run), "rms": rms, "peak": peak,
                             "events": len(p["events"]), "whole_events": len(w["events"]),
                             "mean": p["timing"]["frame_seconds_mean"], "whole_mean": w["timing"]["frame_seconds_mean"],
                             "interface_ms": 1e3 * reg["interface_seconds_total"] / frames,
                             "build_s": reg["build_seconds_total"], "builds": reg["builds"],
                             "force": f, "whole": fw, "time": np.array(p["time"]), **scene_of(run)})
    return sorted(rows, key=lambda r: (SCENES.index(r["scene"]), INPUTS.index(r["input"]), far_order(r["far"])))


def scene_of(run) -> dict:
    """The scene values a caption states, from one region run: radius, law, probe spring and contact."""
    probe = run.config.get("probe") or {}
    law = law_of(run)
    return {"radius": (run.payload.get("regions") or {}).get("radius"), "law": LAW.get(law, law),
            "probe": probe.get("stiffness"), "contact": probe.get("contact")}


def law_of(run):
    return ((run.config.get("model") or {}).get("material") or {}).get("model")


def scene_caption(rows) -> str:
    """"cuboid: radius 2.5 cm, neo-Hookean, probe 100 N/m, grasp; liver: ...", every value from the
    runs of each scene ("2.5 or 3.5 cm" where they differ)."""
    parts = []
    for scene in dict.fromkeys(r["scene"] for r in rows):
        sel = [r for r in rows if r["scene"] == scene]
        parts.append(f"{SCENE_NAME[scene]}: radius {either([r['radius'] for r in sel], lambda v: f'{100 * v:g}', 'cm')}, "
                     f"{either([r['law'] for r in sel], str)}, probe {either([r['probe'] for r in sel], unit='N/m')}, "
                     f"{either([r['contact'] for r in sel], str)}")
    return "; ".join(parts)


def fars(rows, scene):
    return sorted({r["far"] for r in rows if r["scene"] == scene}, key=far_order)


def pick(rows, scene, inp, far):
    return next((r for r in rows if (r["scene"], r["input"], r["far"]) == (scene, inp, far)), None)


def forces_plot(ctx, rows):
    panels = [(s, i) for s in SCENES for i in ("growing sine", "chirp") if pick(rows, s, i, "Guyan")]
    if not panels:
        return
    fig, axes = plots.plt.subplots(len(panels), 1, figsize=(7.5, 2.1 * len(panels)), dpi=110, sharex=True)
    colours = {"massless": "tab:green", "Guyan": "tab:blue"}
    for ax, (scene, inp) in zip(np.atleast_1d(axes), panels):
        first = pick(rows, scene, inp, "Guyan")
        ax.plot(first["time"], np.linalg.norm(first["whole"], axis=1), color="black", lw=1.6, label="whole model")
        modal = ("tab:orange", "tab:red", "tab:purple", "tab:brown")
        for far in fars(rows, scene):
            r = pick(rows, scene, inp, far)
            if r is not None:
                colour = colours.get(far) or modal[len([f for f in fars(rows, scene) if f.endswith("modes") and
                                                        far_order(f) < far_order(far)]) % len(modal)]
                ax.plot(r["time"], np.linalg.norm(r["force"], axis=1), lw=0.8, color=colour,
                        label=f"{far} ({r['rms']:.2g} % RMS)")
        ax.set_title(f"{SCENE_NAME[scene]}, {inp}", fontsize=8)
        ax.set_ylabel("|F| on tool (N)", fontsize=7)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=6, loc="upper right")
    np.atleast_1d(axes)[-1].set_xlabel("time (s)")
    fig.suptitle("whole model against the condensed regions: far field massless, Guyan, Guyan + modes", fontsize=9)
    plots.save(fig, ctx.out("regions_modal_forces.png"))


def fine_caption(ctx) -> str:
    """The refined liver's scene from its region runs: tets, probe, law, input and its duration,
    the interface product's precision."""
    runs = [run for run, *_ in fine_runs(ctx, ("fine_guyan", "fine_modal"))]

    def words(vals):
        return either([str(v) for v in vals if v is not None], str)
    probes = [run.config.get("probe") or {} for run in runs]
    springs = [f"{p['stiffness']:g}" for p in probes if p.get("stiffness") is not None]
    durations = [f"{run.payload['time'][-1]:.3g}" for run in runs if run.payload.get("time")]
    laws = [LAW.get(law_of(run), law_of(run)) for run in runs]
    precisions = [(run.payload["regions"] or {}).get("precision") for run in runs]
    return (f"Refined liver ({words((run.payload.get('model') or {}).get('tets') for run in runs)} tets), "
            f"{words(p.get('contact') for p in probes)} probe {words(springs)} N/m, {words(laws)}, "
            f"{words(input_label(run.config['input']) for run in runs if 'input' in run.config)} for "
            f"{words(durations)} s, condensed "
            f"regions with a {words(precisions)}-precision interface product")


def fine_rows(ctx):
    """The refined liver: Guyan against Guyan + modes, each at the far-field recovery it ran with,
    against the whole model's chirp; error and frame time."""
    out = []
    for run, w, rms, peak in fine_runs(ctx, ("fine_guyan", "fine_modal")):
        p, reg = run.payload, run.payload["regions"]
        t = p["timing"]
        out.append({"radius": reg["radius"], "far": far_field(run), "every": reg["secondary_every"],
                    "interface": (reg["primary"] or {}).get("interface_nodes"), "rms": rms, "peak": peak,
                    "mean": t["frame_seconds_mean"], "p50": t["frame_seconds_p50"], "p99": t["frame_seconds_p99"],
                    "misses": t["deadline_misses"], "frames": len(p["force"]), "build_s": reg["build_seconds_total"],
                    "period": p.get("frame_step"),
                    "whole_mean": w["timing"]["frame_seconds_mean"], "events": len(p["events"])})
    return sorted(out, key=lambda r: (-r["radius"], far_order(r["far"]), r["every"]))


def report(ctx):
    rows = rows_of(ctx)
    write_table(ctx, "regions_modal",
                ["scene", "input", "far field", "RMS error (%)", "peak error (%)", "frame mean (ms)",
                 "whole mean (ms)", "interface force (ms per frame)", "region builds", "build time (s)", "events",
                 "whole-model events"],
                [[SCENE_NAME[r["scene"]], r["input"], r["far"], r["rms"], r["peak"], 1e3 * r["mean"],
                  1e3 * r["whole_mean"], r["interface_ms"], r["builds"], r["build_s"], r["events"], r["whole_events"]]
                 for r in rows],
                f"Condensed regions ({scene_caption(rows)}) against the whole model with the same input. Errors "
                "relative to the whole model's peak |F|. The interface force includes the modes' coupling; the build "
                "time includes the modes' eigensolution. The first region is built before the first frame; a region "
                "built as the contact slides is in that frame's time. One thread on "
                f"{cpu_description()} while other work ran: times are upper bounds.")
    forces_plot(ctx, rows)
    fine = fine_rows(ctx)
    if fine:
        write_table(ctx, "regions_modal_fine",
                    ["radius (m)", "far field", "recovered every (frames)", "interface nodes", "RMS error (%)",
                     "peak error (%)", "frame mean (ms)", "frame p50 (ms)", "frame p99 (ms)", "frames over the frame period",
                     "region build (s)", "whole mean (ms)", "events"],
                    [[r["radius"], r["far"], r["every"], r["interface"], r["rms"], r["peak"], 1e3 * r["mean"],
                      1e3 * r["p50"], 1e3 * r["p99"], r["misses"], r["build_s"], 1e3 * r["whole_mean"], r["events"]]
                     for r in fine],
                    f"{fine_caption(ctx)}. The region is built before the "
                    "first frame (its build time, the modes' eigensolution included, is not in the frame time). One "
                    "thread on "
                    f"{cpu_description()} while other work ran: times are upper bounds.")
    served = [realtime_line(run) for run in runs_of(ctx, "fine_realtime")]
    ctx.out("regions_modal_summary.md").write_text("\n".join(summary_lines(rows) + fine_lines(fine) +
                                                             [x for line in served for x in ("", line)]) + "\n")


def summary_lines(rows):
    L = ["## The far field's dynamics: massless, Guyan mass, fixed-interface modes", "",
         "RMS force error of the condensed regions against the whole model, relative to its peak force "
         f"(target {TARGET:g} %; [table](regions_modal.md), [forces](regions_modal_forces.png)).", ""]
    for scene in SCENES:
        names = fars(rows, scene)
        inputs = [i for i in INPUTS if any(r["scene"] == scene and r["input"] == i for r in rows)]
        if not inputs:
            continue
        L += [f"### The {SCENE_NAME[scene]}", "", "| input | " + " | ".join(names) + " |",
              "| --- |" + " --- |" * len(names)]
        for inp in inputs:
            cells = []
            for far in names:
                r = pick(rows, scene, inp, far)
                cells.append("" if r is None else f"{r['rms']:.3g} %" + (f" ({r['events']} events)" if r["events"] else ""))
            L.append(f"| {inp} | " + " | ".join(cells) + " |")
        L += ["", plain_line(rows, scene, names, inputs), ""]
    return L


def worst(rows, scene, far, inputs):
    rs = [pick(rows, scene, i, far) for i in inputs]
    rs = [r for r in rs if r is not None]
    if len(rs) < len(inputs) or not all(np.isfinite(r["rms"]) and r["events"] == 0 for r in rs):
        return None
    return max(rs, key=lambda r: r["rms"])


def plain_line(rows, scene, names, inputs):
    """One plain sentence per scene: which far field meets the target with every input, else the
    best one's worst input."""
    best = None
    for far in names:
        w = worst(rows, scene, far, inputs)
        if w is not None and (best is None or w["rms"] < best[1]["rms"]):
            best = (far, w)
    if best is None:
        return f"In plain words: on the {SCENE_NAME[scene]} no far field ran every input without events."
    far, w = best
    guyan = worst(rows, scene, "Guyan", inputs)
    base = f" (Guyan alone: worst {guyan['rms']:.3g} %, {guyan['input']})" if guyan is not None and far != "Guyan" else ""
    if w["rms"] <= TARGET:
        first = next(f for f in names if (x := worst(rows, scene, f, inputs)) is not None and x["rms"] <= TARGET)
        fewest = "" if first == far else (
            f"; the fewest that meet it: {first}, worst {worst(rows, scene, first, inputs)['rms']:.3g} % "
            f"({worst(rows, scene, first, inputs)['input']})")
        return (f"In plain words: on the {SCENE_NAME[scene]} the far field with {far} meets the {TARGET:g} % target with "
                f"every input, worst {w['rms']:.3g} % RMS ({w['input']}){fewest}{base}.")
    return (f"In plain words: on the {SCENE_NAME[scene]} no far field meets the {TARGET:g} % target with every input; the "
            f"best, {far}, misses it by {w['rms'] - TARGET:.3g} points on the {w['input']} ({w['rms']:.3g} % RMS){base}.")


def fine_lines(fine):
    if not fine:
        return []
    L = ["### The refined liver ([table](regions_modal_fine.md))", ""]
    for r in fine:
        L.append(f"- radius {r['radius']:g} m ({r['interface']} interface nodes), {r['far']}, recovered every "
                 f"{r['every']} frames: {r['rms']:.3g} % RMS; {1e3 * r['mean']:.3g} ms mean per frame (p50 "
                 f"{1e3 * r['p50']:.3g}, p99 {1e3 * r['p99']:.3g}), {r['misses']} of {r['frames']} frames over "
                 f"{period_words(r)}; "
                 f"whole model {1e3 * r['whole_mean']:.3g} ms.")
    met = [r for r in fine if r["far"] != "Guyan" and r["events"] == 0 and r["rms"] <= TARGET]
    best = min(fine, key=lambda r: r["rms"])
    if met:
        fast = min(met, key=lambda r: r["mean"])
        L += ["", f"In plain words: on the refined liver the modes take the chirp under the {TARGET:g} % target: "
                  f"{fast['rms']:.3g} % RMS at radius {fast['radius']:g} m, {1e3 * fast['mean']:.3g} ms mean per frame "
                  f"with {fast['misses']} of {fast['frames']} frames over {period_words(fast)}."]
    else:
        L += ["", f"In plain words: on the refined liver no setting meets the {TARGET:g} % target on the chirp; the "
                  f"best is {best['rms']:.3g} % RMS ({best['far']}, radius {best['radius']:g} m)."]
    return L
