"""The 3-D haptic scene, whole model -> results/haptic/: whole.md/csv (per mesh and input: size,
substeps, peak force, frame times, deadline misses, events), forces_cube.png and
forces_liver.png (force on the tool against time, with the probe's depth), summary.md."""
import numpy as np

from pipeline import plots
from pipeline.bench import cpu_description
from pipeline.tables import either, write_table

SCENES = (("cube_run", "cuboid", "forces_cube.png"), ("liver_run", "liver", "forces_liver.png"))


def row_of(scene, run):
    p = run.payload
    force = np.array(p["force"])
    t = p["timing"]
    magnitude = np.linalg.norm(force, axis=1)
    return {
        "scene": scene, "input": run.config["input"]["kind"], "nodes": p["model"]["nodes"], "tets": p["model"]["tets"],
        "substeps": p["substeps"], "dt": p["dt"], "frames": p["frames"], "peak": float(magnitude.max()),
        "p50": t["frame_seconds_p50"], "p99": t["frame_seconds_p99"], "max": t["frame_seconds_max"],
        "misses": t["deadline_misses"], "events": len(p["events"]), "frame_step": p["frame_step"],
        "first_event": p["events"][0] if p["events"] else None,
        "probe": (run.config.get("probe") or {}).get("stiffness"),
    }


def period_words(rows) -> str:
    return either([r["frame_step"] for r in rows], lambda v: f"{1e3 * v:g} ms")


def plot_forces(runs, title, path):
    fig, axes = plots.plt.subplots(len(runs), 1, figsize=(7, 1.9 * len(runs)), dpi=110, sharex=True)
    for ax, run in zip(np.atleast_1d(axes), runs):
        p = run.payload
        t = np.array(p["time"])
        force = np.array(p["force"])
        ax.grid(True, alpha=0.3)
        for k, (name, colour) in enumerate((("x", "tab:blue"), ("y", "tab:green"), ("z", "tab:red"))):
            ax.plot(t, force[:, k], lw=0.9, color=colour, label=f"F{name}")
        ax.set_ylabel("force on tool (N)", fontsize=7)
        ax.set_title(run.config["input"]["kind"], fontsize=8)
        ax.legend(fontsize=6, loc="upper right", ncol=3)
    np.atleast_1d(axes)[-1].set_xlabel("time (s)")
    fig.suptitle(title, fontsize=9)
    plots.save(fig, path)


def plain_median(rows):
    """Whether the median frame fits the frame period, in every run or not in some."""
    over = [r for r in rows if r["p50"] > r["frame_step"]]
    if not over:
        return (f"In plain words: on meshes of this size the whole model's median frame fits the {period_words(rows)} "
                "haptic period on one core")
    names = ", ".join(f"{r['scene']} {r['input']}" for r in over)
    return (f"In plain words: the whole model's median frame fits the {period_words(rows)} haptic period on one core "
            f"except in {names} "
            "(where the median also carries the recoveries from the events above, or other work on the machine)")


def report(ctx):
    rows = []
    for stage, scene, png in SCENES:
        runs = ctx.runs(stage)
        rows += [row_of(scene, r) for r in runs]
        rate = either([1.0 / r.payload["frame_step"] for r in runs], lambda v: f"{v / 1000:g} kHz")
        plot_forces(runs, f"{scene}: force on the tool, whole model at {rate}", ctx.out(png))
    write_table(ctx, "whole", ["scene", "input", "nodes", "tets", "substeps / frame", "Δt (s)", "frames",
                               "peak |F| (N)", "frame p50 (ms)", "frame p99 (ms)", "frame max (ms)",
                               "deadline misses", "events"],
                [[r["scene"], r["input"], r["nodes"], r["tets"], r["substeps"], r["dt"], r["frames"], r["peak"],
                  1e3 * r["p50"], 1e3 * r["p99"], 1e3 * r["max"], r["misses"], r["events"]] for r in rows],
                f"Whole model, one thread, offline runs of the generated inputs (haptic_sim run), each run alone in the "
                f"pipeline on "
                f"{cpu_description()}. A deadline miss is a frame whose computation took longer than the "
                f"{period_words(rows)} frame period.")
    worst = max(rows, key=lambda r: r["p99"])
    misses = sum(r["misses"] for r in rows)
    frames = sum(r["frames"] for r in rows)
    events = sum(r["events"] for r in rows)
    text = [
        "## The 3-D haptic scene (whole model)", "",
        f"A tool tip pulls the organ's surface through a {either([r['probe'] for r in rows], lambda v: f'{v:g} N/m')} "
        f"spring once per {period_words(rows)} frame; the spring's force is the model's input and the force on the device (001 §3, here on tetrahedral TLED models of 000). "
        "[Table](whole.md), [cuboid forces](forces_cube.png), [liver forces](forces_liver.png).", "",
        f"- Every frame of every input was answered: {frames} frames, {events} numerical events.",
        *[f"- **{r['scene']}, {r['input']}: {r['events']} events** (the model recovered to rest and the frames went "
          f"on); the first, in frame {r['first_event']['frame']}: {r['first_event']['message']}. With the tip held "
          "at full depth the spring pulls the model straight back into the same failure after each recovery; the "
          "stable neo-Hookean law runs the same deep press without events ([robust](robust_summary.md))."
          for r in rows if r["events"]],
        f"- Frame time, whole model on one core ({cpu_description()}): the slowest scene's p99 is "
        f"{1e3 * worst['p99']:.3f} ms ({worst['scene']}, {worst['input']}, {worst['tets']} tets, "
        f"{worst['substeps']} substeps per frame); {misses} of {frames} frames missed their deadline "
        f"({period_words(rows)}).",
        f"- Median frame time: at most {1e3 * max(r['p50'] for r in rows):.3f} ms over all runs.",
        "", plain_median(rows) + "; its tail does not, on this machine: the p99 and the deadline misses include every "
        "interruption by other processes (the pipeline runs these alone, but nothing else on the machine is "
        "stopped), so they are an upper bound until measured on a quiet core. These runs are the reference the "
        "linked asynchronous regions of 001 are measured against ([regions](regions_summary.md)).",
    ]
    ctx.out("summary.md").write_text("\n".join(text) + "\n")
