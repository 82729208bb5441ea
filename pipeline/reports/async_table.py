"""Asynchronous regions on the 1-D bar, chirp input (001 §6, Table 1, Figs. 6-7) -> results/async/:
table1_E<kPa>.md/csv (one per stiffness), held_vs_interpolated.md/csv, dense_timing.md/csv,
tradeoff.md/csv + tradeoff.png (force error vs time per frame over all settings, the settings
under each error threshold highlighted), error_vs_frequency.png, force_envelope.png,
forces_<n>_<every>.png and the "table" part of summary.md (summary_table.md)."""
import numpy as np

from pipeline import plots
from pipeline.reports import async_common as C
from pipeline.reports import async_scene as S
from pipeline.stages.machine_load import busy_note, worst
from pipeline.tables import fmt, write_table

T1_HEADERS = ["n (primary nodes)", "f (Hz)", "every (frames)", "time/frame regions (µs)", "time/frame whole (µs)",
              "speed gain", "speed gain vs median whole", "peak force regions (mN)", "peak force whole (mN)", "peak force exact (mN)",
              "RMS error vs whole (%)", "peak error vs whole (%)", "RMS error vs exact (%)", "peak error vs exact (%)"]


def exchange_words(in_turn, sweep) -> str:
    """How much of the sweep's error the exchange of 001 eq. 7 alone (both regions every frame)
    makes: the in-turn error over the sweep's error at the same stiffness and primary size, for
    every secondary rate; whether that is most of it is judged per rate from the numbers."""
    share = {}
    for r in in_turn:
        for s in sweep:
            if s["E"] == r["E"] and s["n"] == r["n"] and s["vs_whole"]["rms_relative"] > 0:
                share.setdefault(s["every"], []).append(r["vs_whole"]["rms_relative"] / s["vs_whole"]["rms_relative"])
    if not share:
        return ""
    lo, hi = min(min(v) for v in share.values()), max(max(v) for v in share.values())
    most = sorted(e for e, v in share.items() if min(v) >= 0.5)
    less = sorted(e for e, v in share.items() if max(v) < 0.5)
    text = (f"The exchange of 001 eq. 7 alone makes {lo:.2g}-{hi:.2g} of the sweep's RMS error at the same primary "
            "size (a region sees its neighbours only through their displacements at the connection nodes, once per "
            "update)")
    if most and not less and len(most) == len(share):
        return text + ": most of the error at every secondary rate; the lower rate adds the rest."
    if less and len(less) == len(share):
        return text + ": less than half at every secondary rate; most of the error comes from the lower rate."
    parts = []
    if most:
        parts.append(f"most of it with the secondary region every {', '.join(map(str, most))} frames")
    if less:
        parts.append(f"less than half every {', '.join(map(str, less))} frames, where the lower rate makes most")
    return text + ": " + "; ".join(parts) + "."


def timing_note(rows) -> str:
    """The busy-machine note of the runs' timings (pipeline.stages.machine_load): async_sim times
    itself, so a run without a "machine" record says that its load was not recorded."""
    return busy_note(worst(r["run"].payload.get("machine") for r in rows))


def interpolation(rows) -> str:
    """How the secondary values are passed on, from the runs: interpolated (001 Fig. 4) or held."""
    kinds = sorted({bool(r.get("interpolate")) for r in rows if "interpolate" in r})
    return " or ".join("interpolated secondary values" if k else "secondary values held between updates"
                       for k in kinds) or "secondary values passed as the runs set"


def table1(ctx, rows, E):
    sel = sorted((r for r in rows if r["E"] == E), key=lambda r: (r["n"], -r["rate"]))
    first = sel[0]
    whole_times = [r["whole_time"] for r in sel]
    median_whole = float(np.median(whole_times))
    out = [[f"whole ({first['free_nodes']})", 1.0 / first["frame_step"], 1, None, C.us(median_whole), 1.0, 1.0,
            None, C.mn(first["whole_peak"]), C.mn(first["exact_peak"]), 0.0, 0.0,
            C.pct(first["whole_vs_exact"]["rms_relative"]), C.pct(first["whole_vs_exact"]["peak_relative"])]]
    for r in sel:
        out.append([r["n"], r["rate"], r["every"], C.us(r["async_time"]), C.us(r["whole_time"]), r["speed_gain"],
                    median_whole / r["async_time"], C.mn(r["async_peak"]), C.mn(r["whole_peak"]), C.mn(r["exact_peak"]),
                    C.pct(r["vs_whole"]["rms_relative"]), C.pct(r["vs_whole"]["peak_relative"]),
                    C.pct(r["vs_exact"]["rms_relative"]), C.pct(r["vs_exact"]["peak_relative"])])
    name = f"table1_E{E / 1000:g}kPa"
    cap = (f"Like 001 Table 1, E = {E / 1000:g} kPa, {S.describe(sel)}, {interpolation(sel)}. Errors are relative to the peak force of the reference (whole model or exact). "
           "The speed gain is the whole model's time per frame over the regions' time, both measured in the same "
           "run (fastest of 20 alternating repeats); the machine is shared, so the gain against the median whole-model "
           f"time of the sweep is given too (whole-model times across runs: median {C.us(float(np.median(whole_times))):.3g} µs, range "
           f"{C.us(min(whole_times)):.3g}-{C.us(max(whole_times)):.3g} µs). Exact closed-loop spectral radius "
           f"{first['loop_radius']:.4f} (< 1: the sampled probe coupling is stable on the exact model)."
           + (f" Times {timing_note(sel)[1:-1]}." if timing_note(sel) else ""))
    return name, write_table(ctx, name, T1_HEADERS, out, cap)


def held_table(ctx, interp, held):
    key = lambda r: (r["n"], r["every"])
    by = {key(r): r for r in interp if r["E"] == held[0]["E"]}
    out = []
    for h in sorted(held, key=lambda r: (r["n"], -r["rate"])):
        i = by.get(key(h))
        if i is None:
            continue
        out.append([h["n"], h["rate"], C.pct(i["vs_whole"]["rms_relative"]), C.pct(h["vs_whole"]["rms_relative"]),
                    C.pct(i["vs_whole"]["peak_relative"]), C.pct(h["vs_whole"]["peak_relative"]),
                    C.mn(h["whole_jump"]) * 1e3, C.mn(i["async_jump"]) * 1e3, C.mn(h["async_jump"]) * 1e3])
    headers = ["n", "f (Hz)", "RMS error interpolated (%)", "RMS error held (%)", "peak error interpolated (%)",
               "peak error held (%)", "max |Δ²F| whole (µN)", "max |Δ²F| interpolated (µN)", "max |Δ²F| held (µN)"]
    cap = ("Secondary values interpolated (001 Fig. 4, one update late) or held between updates, E = "
           f"{held[0]['E'] / 1000:g} kPa, {S.chirp(held)}. max |Δ²F| is the largest second difference of the force over "
           "consecutive frames: a jump J in the force shows as about J, a smooth force as O(frame step²).")
    paired = [by[key(h)] for h in held if key(h) in by]
    cap += S.same_scene_clause(held, paired, "the held runs", "the interpolated ones")
    write_table(ctx, "held_vs_interpolated", headers, out, cap)


def in_turn_table(ctx, in_turn, sweep):
    """Both regions every frame, solved in turn: the exchange of eq. 7 alone, beside the rates of the sweep."""
    E = in_turn[0]["E"]
    out = []
    for r in sorted(in_turn, key=lambda r: r["n"]):
        same = {s["every"]: s for s in sweep if s["E"] == E and s["n"] == r["n"]}
        out.append([r["n"], C.pct(r["vs_whole"]["rms_relative"])] +
                   [C.pct(same[e]["vs_whole"]["rms_relative"]) if e in same else None for e in sorted(same)])
    every = sorted({s["every"] for s in sweep})
    headers = ["n", "both every frame, in turn: RMS error (%)"] + [f"secondary every {e}: RMS error (%)" for e in every]
    cap = (f"E = {E / 1000:g} kPa, {S.chirp(in_turn)}. First column: primary and secondary region both solved every frame but one "
           "after the other (001 eq. 7 with the other region's values on the right-hand side, one block Gauss-Seidel "
           "sweep per frame). Its error is that of the exchange between regions alone; the other columns add the lower "
           "secondary rate." + S.same_scene_clause(in_turn, [s for s in sweep if s["E"] == E],
                                                   "the in-turn runs", "the sweep"))
    write_table(ctx, "exchange_error", headers, out, cap)


def dense_table(ctx, dense):
    out = [[r["n"], r["rate"], C.us(r["async_time"]), C.us(r["whole_time"]), r["speed_gain"],
            C.pct(r["vs_whole"]["rms_relative"])] for r in sorted(dense, key=lambda r: (r["n"], -r["rate"]))]
    headers = ["n", "f (Hz)", "time/frame regions (µs)", "time/frame whole (µs)", "speed gain", "RMS error vs whole (%)"]
    cap = ("Dense Cholesky solves (the direct elimination of 001 §4, cost growing with the square of the region "
           f"size) instead of the sparse factorisation, E = {' or '.join(f'{r:g}' for r in sorted({r['E'] / 1000 for r in dense}))} kPa, "
           f"{S.chirp(dense)}." + (f" Times {timing_note(dense)[1:-1]}." if timing_note(dense) else ""))
    write_table(ctx, "dense_timing", headers, out, cap)


def tradeoff(ctx, rows, thresholds):
    """Force error against time per frame over every (E, n, f); settings under each threshold marked."""
    fig, ax = plots.figure(7.0, 4.6)
    markers = {2000: "o", 5000: "s", 10000: "^"}
    colours = ["tab:green", "tab:orange"]
    th = sorted(thresholds)
    for E in sorted({r["E"] for r in rows}):
        sel = [r for r in rows if r["E"] == E]
        x = np.array([C.us(r["async_time"]) for r in sel])
        y = np.array([C.pct(r["vs_whole"]["rms_relative"]) for r in sel])
        c = ["tab:green" if v <= 100 * th[0] else ("tab:orange" if len(th) > 1 and v <= 100 * th[1] else "0.55") for v in y]
        ax.scatter(x, y, c=c, marker=markers.get(E, "o"), s=28, edgecolors="k", linewidths=0.4,
                   label=f"E = {E / 1000:g} kPa")
        ax.axvline(C.us(float(np.median([r["whole_time"] for r in sel]))), color="k", lw=0.6, ls=":")
    for t, col in zip(th, colours):
        ax.axhline(100 * t, color=col, lw=0.8, ls="--")
    ax.set_xscale("log")
    ax.set_yscale("log")
    plots.plain_log_ticks(ax.xaxis)
    plots.plain_log_ticks(ax.yaxis)
    ax.set_xlabel("time per frame, asynchronous regions (µs); dotted: whole model")
    ax.set_ylabel("RMS force error vs whole model (%)")
    ax.set_title("Run time against force error, every (n, f); green ≤ "
                 f"{100 * th[0]:g} %, orange ≤ {100 * th[-1]:g} %", fontsize=9)
    ax.legend(fontsize=8)
    plots.save(fig, ctx.out("tradeoff.png"))
    out = []
    for r in sorted(rows, key=lambda r: (r["E"], r["async_time"])):
        e = r["vs_whole"]["rms_relative"]
        tier = next((f"≤ {100 * t:g} %" for t in th if e <= t), "")
        out.append([r["E"] / 1000, r["n"], r["rate"], C.us(r["async_time"]), r["speed_gain"], C.pct(e),
                    C.pct(r["vs_whole"]["peak_relative"]), tier])
    headers = ["E (kPa)", "n", "f (Hz)", "time/frame (µs)", "speed gain", "RMS error vs whole (%)",
               "peak error vs whole (%)", "error budget met"]
    write_table(ctx, "tradeoff", headers, out, "Every setting of the sweep, fastest first per stiffness."
                + (f" Times {timing_note(rows)[1:-1]}." if timing_note(rows) else ""))
    best = {}
    for t in th:
        for E in sorted({r["E"] for r in rows}):
            ok = [r for r in rows if r["E"] == E and r["vs_whole"]["rms_relative"] <= t]
            best[(t, E)] = max(ok, key=lambda r: r["speed_gain"]) if ok else None
    return best


def error_vs_frequency(ctx, rows, E):
    sel = [r for r in rows if r["E"] == E]
    fig, axes = plots.plt.subplots(1, 2, figsize=(10.0, 4.0), dpi=110, sharey=True)
    every_ref = 20 if any(r["every"] == 20 for r in sel) else sel[0]["every"]
    n_ref = 10 if any(r["n"] == 10 for r in sel) else sel[0]["n"]
    for ax, group, title in ((axes[0], sorted((r for r in sel if r["every"] == every_ref), key=lambda r: r["n"]),
                              f"secondary every {every_ref} frames, primary size varies"),
                             (axes[1], sorted((r for r in sel if r["n"] == n_ref), key=lambda r: -r["rate"]),
                              f"primary {n_ref} nodes, secondary rate varies")):
        for r in group:
            b = r["run"].payload["by_frequency"]["async_vs_whole"]
            rel = 100 * np.asarray(b["rms_error"]) / np.maximum(np.asarray(b["rms_reference"]), 1e-300)
            ax.plot(b["frequency"], rel, marker=".", label=C.label(r))
        ax.set_title(title, fontsize=9)
        ax.set_xlabel("input frequency (Hz)")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    axes[0].set_ylabel("RMS force error vs whole, per 0.25 Hz bin (% of bin RMS)")
    fig.suptitle(f"Force error against the chirp's frequency, E = {E / 1000:g} kPa (like 001 Fig. 6)", fontsize=10)
    plots.save(fig, ctx.out("error_vs_frequency.png"))


def force_envelope(ctx, forces):
    """Peak |F| per frequency bin of the chirp: whole, exact and each regions setting (001 Fig. 6)."""
    fig, ax = plots.figure(7.0, 4.2)
    drawn = False
    for r in sorted(forces, key=lambda r: (r["n"], -r["rate"])):
        s = C.series(r["run"])
        edges = np.arange(0.0, s["frequency"].max() + 0.25, 0.25)
        idx = np.digitize(s["frequency"], edges) - 1
        def env(f):
            return [np.abs(f[idx == k]).max() if np.any(idx == k) else np.nan for k in range(len(edges) - 1)]
        centre = 0.5 * (edges[:-1] + edges[1:])
        if not drawn:
            ax.plot(centre, 1e3 * np.asarray(env(s["force_exact"])), color="0.6", lw=2.2, label="exact")
            ax.plot(centre, 1e3 * np.asarray(env(s["force_whole"])), color="k", lw=1.0, ls="--", label="whole model")
            drawn = True
        ax.plot(centre, 1e3 * np.asarray(env(s["force_async"])), marker=".", lw=1.0, label=C.label(r))
    ax.set_xlabel("input frequency (Hz)")
    ax.set_ylabel("peak force in the bin (mN)")
    moduli = " or ".join(f"{e:g}" for e in sorted({r["E"] / 1000 for r in forces}))
    ax.set_title(f"Output force against input frequency, E = {moduli} kPa, {S.chirp(forces)} (like 001 Fig. 6)",
                 fontsize=9)
    ax.legend(fontsize=7)
    plots.save(fig, ctx.out("force_envelope.png"))


def report(ctx):
    params = ctx.params
    thresholds = params.get("thresholds", [0.01, 0.05])
    sweep = C.rows(ctx, "sweep")
    held = C.rows(ctx, "held")
    dense = C.rows(ctx, "dense")
    in_turn = C.rows(ctx, "in_turn")
    forces = C.rows(ctx, "forces")
    tables = {E: table1(ctx, sweep, E) for E in sorted({r["E"] for r in sweep})}
    held_table(ctx, sweep, held)
    dense_table(ctx, dense)
    in_turn_table(ctx, in_turn, sweep)
    best = tradeoff(ctx, sweep, thresholds)
    E_plot = params.get("frequency_plot_modulus", 5000)
    error_vs_frequency(ctx, sweep, E_plot)
    force_envelope(ctx, forces)
    force_pngs = []
    for r in forces:
        png = f"forces_n{r['n']}_every{r['every']}.png"
        C.force_plot(ctx.out(png), r["run"], f"E = {r['E'] / 1000:g} kPa, {S.chirp([r])}, {C.label(r)} (like 001 Fig. 7)",
                     window=(8.0, 9.0))
        force_pngs.append(png)

    # What the sweep says about the paper's findings, measured.
    five = [r for r in sweep if r["E"] == E_plot]
    def spread(group):
        e = [r["vs_whole"]["rms_relative"] for r in group]
        return max(e) / min(e) if group and min(e) > 0 else float("nan")
    by_n = [spread([r for r in five if r["n"] == n]) for n in sorted({r["n"] for r in five})]
    by_f = [spread([r for r in five if r["every"] == e]) for e in sorted({r["every"] for r in five})]
    lines = ["## Asynchronous regions: primary size, secondary rate and stiffness (001 Table 1, Figs. 6-7)\n",
             f"{S.describe(sweep)}, {interpolation(sweep)}. The paper's numeric columns did not survive the text extraction "
             "(experiments/async_table.json copies what is legible), so its findings are compared, not its numbers.\n",
             tables[E_plot][1] if E_plot in tables else "",
             "All stiffnesses: " + ", ".join(f"[{n}](async/{n}.md)" for n, _ in tables.values()) + ".\n",
             "Paper: \"the primary region size has more effect on the force error than the secondary frequency\". "
             f"Measured at {E_plot / 1000:g} kPa: for a fixed primary size the RMS error changes by a factor "
             f"{min(by_n):.2g}-{max(by_n):.2g} across the secondary rates; for a fixed rate it changes by a factor "
             f"{min(by_f):.2g}-{max(by_f):.2g} across the primary sizes.\n",
             "Where the error comes from: with both regions solved every frame, one after the other, the RMS error is "
             + ", ".join(f"{C.pct(r['vs_whole']['rms_relative']):.2g} % (n = {r['n']})" for r in sorted(in_turn, key=lambda r: r["n"]))
             + " ([exchange_error](async/exchange_error.md))."
             + S.same_scene_clause(in_turn, [r for r in sweep if r["E"] in {t["E"] for t in in_turn}],
                                   "the in-turn runs", "the sweep")
             + " " + exchange_words(in_turn, sweep) + "\n",
             "Fastest settings within an error budget (RMS force error vs the whole model)"
             + (f" {timing_note(sweep)}" if timing_note(sweep) else "") + ":\n"]
    for (t, E), r in sorted(best.items()):
        lines.append(f"- ≤ {100 * t:g} % at E = {E / 1000:g} kPa: " +
                     (f"n = {r['n']}, f = {r['rate']:.3g} Hz, speed gain {fmt(r['speed_gain'])}, error "
                      f"{100 * r['vs_whole']['rms_relative']:.2g} %" if r else "no setting of the sweep"))
    lines += ["", "![tradeoff](async/tradeoff.png)", "",
              "Plots: [error vs frequency](async/error_vs_frequency.png), [force envelope](async/force_envelope.png), "
              + ", ".join(f"[{p}](async/{p})" for p in force_pngs) + ". Interpolated vs held values: "
              "[held_vs_interpolated](async/held_vs_interpolated.md); dense solves: [dense_timing](async/dense_timing.md).\n"]
    ctx.out("summary_table.md").write_text("\n".join(lines) + "\n")
    C.gather_summary(ctx)


