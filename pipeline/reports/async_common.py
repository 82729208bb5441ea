"""Shared reading of async_sim artifacts for the async_* reports (paper 001)."""
import numpy as np

from pipeline import plots
from pipeline.report_md import gather_parts
from pipeline.reports import async_scene


def run_row(run):
    """One async_sim run as a flat dict (SI units; times in s, forces in N)."""
    p = run.payload
    m, w = p["model"], p["whole"]
    row = {
        "run": run, "E": m["youngs_modulus"], "nodes": m["nodes"], "free_nodes": m["free_nodes"],
        "input": p["input"]["kind"], "whole_solver": w["solver"],
        "whole_time": w["seconds_per_frame"], "whole_peak": w["peak_force"],
        "whole_jump": w["max_second_difference"],
        "whole_vs_exact": w.get("error_vs_exact"),
        "exact_peak": p.get("exact", {}).get("peak_force"),
        "loop_radius": p.get("exact", {}).get("loop_spectral_radius"),
        "frame_step": p["haptics"]["frame_step"],
        "scene": async_scene.scene(run.config or {}),
    }
    a = p.get("async")
    if a:
        sec = a["secondary"]
        row.update({
            "n": a["primary"]["min_nodes"], "n_max": a["primary"]["max_nodes"], "policy": a["primary"]["policy"],
            "every": sec[0]["every"], "rate": sec[0]["rate"], "interpolate": a["interpolate"],
            "primary_solver": a["primary_solver"], "secondary_solver": sec[0]["solver"],
            "async_time": a["seconds_per_frame"], "speed_gain": a["speed_gain"], "async_peak": a["peak_force"],
            "async_jump": a["max_second_difference"], "vs_whole": a["error_vs_whole"],
            "vs_exact": a.get("error_vs_exact"), "primary_mean": a["primary_nodes"]["mean"],
            "primary_range": (a["primary_nodes"]["min"], a["primary_nodes"]["max"]),
        })
    return row


def rows(ctx, stage):
    return [run_row(r) for r in ctx.runs(stage)]


def pct(x):
    return None if x is None else 100.0 * x


def us(x):
    return None if x is None else 1e6 * x


def mn(x):
    return None if x is None else 1e3 * x


def series(run):
    s = run.payload.get("series")
    if s is None:
        raise KeyError(f"run {run.id} has no time series (set series_every)")
    return {k: np.asarray(v) for k, v in s.items() if isinstance(v, list)}


def label(row):
    return f"n = {row['n']}, f = {row['rate']:.3g} Hz"


def force_plot(path, run, title, window=None):
    """Force sent to the device vs time: whole model, regions, exact; optional zoom window (s)."""
    s = series(run)
    t = s["time"]
    fig, axes = plots.plt.subplots(2 if window else 1, 1, figsize=(7.0, 6.0 if window else 3.6), dpi=110,
                                   squeeze=False)
    spans = [(t[0], t[-1])] + ([window] if window else [])
    for ax, (t0, t1) in zip(axes[:, 0], spans):
        sel = (t >= t0) & (t <= t1)
        ax.plot(t[sel], 1e3 * s["force_whole"][sel], color="tab:blue", lw=2.2, label="whole model")
        if "force_async" in s:
            ax.plot(t[sel], 1e3 * s["force_async"][sel], color="tab:red", lw=1.0, label="asynchronous")
        if "force_exact" in s:
            # Dashed and on top: the exact force lies on the whole model's almost everywhere and
            # would vanish beneath it.
            ax.plot(t[sel], 1e3 * s["force_exact"][sel], color="k", lw=0.9, ls=(0, (4, 3)), zorder=3,
                    label="exact (dashed, on top)")
        ax.set_ylabel("force (mN)")
        ax.grid(True, alpha=0.3)
    axes[-1, 0].set_xlabel("time (s)")
    axes[0, 0].legend(fontsize=8, loc="upper left")
    axes[0, 0].set_title(title, fontsize=9)
    plots.save(fig, path)


SUMMARY_PARTS = ["summary_table.md", "summary_inputs.md", "summary_adaptive.md", "summary_solvers.md"]


def gather_summary(ctx):
    """results/async/summary.md: the parts written by the async_* reports, in a fixed order."""
    gather_parts(ctx, SUMMARY_PARTS)
