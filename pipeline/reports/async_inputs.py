"""Step, ramp-and-hold and chirp inputs, secondary values interpolated or held (001 §5 Fig. 4)
-> results/async/inputs.md/csv, inputs_<input>.png and summary_inputs.md."""
import numpy as np

from pipeline import plots
from pipeline.reports import async_common as C
from pipeline.reports import async_scene as S
from pipeline.tables import write_table
from pipeline.artifacts import write_text_atomic

HEADERS = ["input", "secondary values", "peak force whole (mN)", "peak force regions (mN)", "peak force exact (mN)",
           "RMS error vs whole (%)", "peak error vs whole (%)", "RMS error vs exact (%)",
           "max |Δ²F| whole (µN)", "max |Δ²F| regions (µN)", "settling whole (ms)", "settling regions (ms)"]


def max_second_difference(force, time, window):
    """Largest |F[n] - 2F[n-1] + F[n-2]| with t[n] inside the window (away from the input's own kinks)."""
    d2 = np.abs(force[2:] - 2 * force[1:-1] + force[:-2])
    sel = (time[2:] >= window[0]) & (time[2:] <= window[1])
    return float(d2[sel].max()) if np.any(sel) else None


def settling_ms(force, time, start):
    """Time after `start` (the end of the input's motion) until |F - F_end| stays within 1 % of |F_end|."""
    final = force[-1]
    outside = np.nonzero(np.abs(force - final) > 0.01 * abs(final))[0]
    last = time[outside[-1]] if len(outside) else time[0]
    return 1e3 * max(0.0, last - start)


def zoom_plot(path, pair, window, title):
    fig, ax = plots.figure(7.0, 3.8)
    first = True
    for r in pair:
        s = C.series(r["run"])
        t = s["time"]
        sel = (t >= window[0]) & (t <= window[1])
        if first:
            ax.plot(t[sel], 1e3 * s["force_exact"][sel], color="0.6", lw=2.4, label="exact")
            ax.plot(t[sel], 1e3 * s["force_whole"][sel], color="tab:blue", lw=1.0, label="whole model")
            first = False
        style = dict(color="tab:red", lw=1.0) if r["interpolate"] else dict(color="tab:orange", lw=1.0, drawstyle="steps-post")
        ax.plot(t[sel], 1e3 * s["force_async"][sel], label="regions, " + ("interpolated" if r["interpolate"] else "held"),
                **style)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("force (mN)")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=8)
    plots.save(fig, path)


def report(ctx):
    rows = C.rows(ctx, "runs")
    zoom = ctx.params.get("zoom", {})
    windows = ctx.params.get("jump_window", {})
    out = []
    order = {"step": 0, "ramp_hold": 1, "chirp": 2}
    for r in sorted(rows, key=lambda r: (order.get(r["input"], 9), not r["interpolate"])):
        s = C.series(r["run"])
        t = s["time"]
        window = windows.get(r["input"], [t[0], t[-1]])
        r["whole_jump_w"] = max_second_difference(s["force_whole"], t, window)
        r["async_jump_w"] = max_second_difference(s["force_async"], t, window)
        inp = r["run"].payload["input"]
        end = inp.get("start_time", 0.0) + inp.get("ramp_time", 0.0)
        settle = r["input"] in ("step", "ramp_hold")
        out.append([r["input"], "interpolated" if r["interpolate"] else "held", C.mn(r["whole_peak"]), C.mn(r["async_peak"]),
                    C.mn(r["exact_peak"]), C.pct(r["vs_whole"]["rms_relative"]), C.pct(r["vs_whole"]["peak_relative"]),
                    C.pct(r["vs_exact"]["rms_relative"]), 1e6 * r["whole_jump_w"], 1e6 * r["async_jump_w"],
                    settling_ms(s["force_whole"], t, end) if settle else None,
                    settling_ms(s["force_async"], t, end) if settle else None])
    md = write_table(ctx, "inputs", HEADERS, out,
                     f"{S.regions(rows)}, probe spring {S.one(rows, 'probe', 1, 'N/m')}. max |Δ²F|: largest "
                     "second difference of the force over consecutive frames inside a window that excludes the input's "
                     "own kinks (" + ", ".join(f"{k} {v[0]:g}-{v[1]:g} s" for k, v in windows.items()) + "): a jump J "
                     "in the force shows as about J. Settling: time after the input stops moving until the force stays "
                     "within 1 % of its final value.")
    pngs = []
    for kind in sorted({r["input"] for r in rows}, key=lambda k: order.get(k, 9)):
        pair = sorted((r for r in rows if r["input"] == kind), key=lambda r: not r["interpolate"])
        t = C.series(pair[0]["run"])["time"]
        window = zoom.get(kind, [t[0], t[-1]])
        png = f"inputs_{kind}.png"
        zoom_plot(ctx.out(png), pair, window,
                  f"{kind.replace('_', ' ')}: secondary values held (steps) or interpolated (like 001 Fig. 4)")
        pngs.append(png)
    ramp = {r["interpolate"]: r for r in rows if r["input"] == "ramp_hold"}
    text = ["## Inputs and interpolation (001 §5 Fig. 4)\n",
            f"Step, ramp-and-hold and chirp through the probe, {S.regions(rows)}.\n", md]
    if True in ramp and False in ramp:
        text.append(f"During the ramp the held secondary values move in steps: the force's largest second difference is "
                    f"{1e6 * ramp[False]['async_jump_w']:.3g} µN held against {1e6 * ramp[True]['async_jump_w']:.3g} µN "
                    f"interpolated and {1e6 * ramp[True]['whole_jump_w']:.3g} µN for the whole model.\n")
    text.append("Plots: " + ", ".join(f"[{p}](async/{p})" for p in pngs) + ".\n")
    write_text_atomic(ctx.out("summary_inputs.md"), "\n".join(text))
    C.gather_summary(ctx)
