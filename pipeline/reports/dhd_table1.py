"""000 Table 1: speed against the share of linear elements on the 3564-node / 14450-tet cuboid
→ results/dhd/table1.md/csv, table1_bench.md/csv, table1_speed.png and the "table1" part of
summary.md.

Inputs: "timing" (pipeline.stages.dhd_timing: every share measured in one sitting, interleaved
repeats) and optionally "bench" (`dhd_sim --bench`: all-TLED, all-linear, all-corotational and
one mixed share in one process, a cross-check).

Frame rate. The paper reports frame rates without saying how many explicit steps make a frame;
its remark that small meshes are capped at the display's 75 Hz suggests one simulation step per
rendered frame, so our "equivalent frame rate" is steps/s at one step per frame (rendering not
included). Steps/s is the primary figure; the comparable quantity is the speed-up relative to
r = 0, a ratio measured in one sitting on one machine."""
import numpy as np

from pipeline import plots
from pipeline.hashing import file_hash
from pipeline.paths import BIN
from pipeline.reports import dhd_common as common
from pipeline.stages.machine_load import busy_note
from pipeline.tables import fmt, write_table


def relative_cost(shares, times):
    """c in t(r) = t(0) · ((1 − r) + c · r), least squares through t(0): the cost of the cheap
    model relative to the nonlinear one, everything per element (node work included pro rata)."""
    r = np.asarray(shares, dtype=float)
    t = np.asarray(times, dtype=float)
    t0 = t[np.argmin(r)]
    y = t / t0 - (1.0 - r)
    return float((r @ y) / (r @ r)) if r @ r > 0 else None


def cheaper_or_dearer(ratio: float) -> str:
    """A cost ratio (linear / TLED) in words, from the number itself."""
    if ratio < 0.98:
        return f"linear elements {fmt(1 / ratio, 3)}× cheaper"
    if ratio > 1.02:
        return f"linear elements {fmt(ratio, 3)}× dearer"
    return "no measurable difference"


def report(ctx):
    paper_rate = common.paper_frame_rates(ctx.experiment.get("paper", {}))
    timing = ctx.runs("timing")[0].payload
    runs = [run for run in timing["runs"] if run["threads"] == min(x["threads"] for x in timing["runs"])]
    rows_data = []
    small_strain = common.small_strain_kinds(timing)
    for run in runs:
        c = run["counts"]
        m = sum(c.values())
        rows_data.append({"r": sum(c[k] for k in small_strain) / m, "counts": c, "run": run})
    rows_data.sort(key=lambda x: x["r"])
    base = next(x for x in rows_data if x["r"] == 0.0)["run"]["steps_per_second"]
    f0 = paper_rate.get(0)
    # Every speed figure below carries this note when the sitting was disturbed.
    busy = busy_note(timing.get("machine"))
    # the full conditions once per paragraph, then the short form
    again = busy.split(":")[0] + ")" if ":" in busy else busy
    body = []
    for x in rows_data:
        run = x["run"]
        sps = run["steps_per_second"]
        rp = int(round(100 * x["r"]))
        f = paper_rate.get(rp)
        body.append([f"{rp} %", x["counts"]["linear"], x["counts"]["tled"], sps, run["median"],
                     1e6 / sps, sps / base,
                     sps, sps * run["dt"], f, (f / f0) if (f and f0) else None])
    headers = ["share of linear elements r", "linear", "TLED", "steps/s (best)", "steps/s (median)",
               "time per step (µs)", "speed-up vs r = 0 (ours)", "equivalent frame rate, 1 step/frame (Hz)",
               "real-time factor (simulated s per s)", "frame rate (paper, Hz)", "speed-up vs r = 0 (paper)"]
    first = runs[0]
    n = sum(first["counts"].values())
    mixed = [x["run"] for x in rows_data if 0 < x["r"] < 1]
    split = common.split_phrase([(d["strategy"], run["partition"], d["cheap_kind"]) for run in mixed
                                 for d in [common.describe_partition(run["partition"], small_strain)]])
    caption = (f"**Table 1: speed against the share of linear elements**, {n} tets, one thread, "
               f"{first['steps']} steps per measurement, best of {timing['repeats']} interleaved repeats "
               f"(the least disturbed; median beside it; {timing['cpu']}). Mixed runs: {split}. Equivalent frame rate: one "
               "explicit step per frame, rendering excluded (the paper does not say how many steps make "
               "a frame). Real-time factor: simulated time advanced per wall-clock second (steps/s × Δt, "
               f"Δt = {fmt(first['dt'] * 1e3)} ms). The paper's columns are copied from 000 Table 1."
               + (f" Our columns were {busy[1:-1]}." if busy else ""))
    md = write_table(ctx, "table1", headers, body, caption)

    # Cost of a linear element relative to a TLED element: ours from steps/s, the paper's from
    # its frame times (same model), and the kernels' own ns per element.
    c_ours = relative_cost([x["r"] for x in rows_data], [1.0 / x["run"]["steps_per_second"] for x in rows_data])
    c_paper = relative_cost([r / 100 for r in paper_rate], [1.0 / f for f in paper_rate.values()]) \
        if paper_rate else None
    all_tled = next(x for x in rows_data if x["r"] == 0.0)["run"]
    all_lin = max(rows_data, key=lambda x: x["r"])["run"]
    ns_tled = all_tled["ns_per_element"].get("tled")
    ns_lin = all_lin["ns_per_element"].get("linear")
    node_ns = all_tled.get("node_phase_ns_per_node")
    node_ns_linear = all_lin.get("node_phase_ns_per_node")

    bench_md = ""
    bench_rows = []
    try:
        bench = ctx.runs("bench")[0].payload
        b_runs = bench["runs"]
        b_tled = {r_["threads"]: r_["steps_per_second"] for r_ in b_runs if r_["partition"] == "all_tled"}
        for r_ in b_runs:
            bench_rows.append([r_["partition"], r_["linear_fraction"], r_["threads"], r_["steps"],
                               r_["steps_per_second"], r_["steps_per_second"] / b_tled.get(r_["threads"], np.nan),
                               ", ".join(f"{k} {fmt(v)}" for k, v in r_.get("ns_per_element", {}).items() if v)])
        bench_md = write_table(ctx, "table1_bench", ["partition", "r", "threads", "steps", "steps/s",
                                                    "vs all-TLED", "ns per element"], bench_rows,
                               "`dhd_sim --bench` on the same scene: four partitions measured in one process "
                               "(one sample each; the mixed one uses the engine's default distance split)"
                               + (f" {busy_note(bench.get('machine'))}." if busy_note(bench.get("machine")) else "."))
    except KeyError:
        pass

    # Plot.
    fig, (ax1, ax2) = plots.plt.subplots(1, 2, figsize=(10, 4), dpi=110)
    rr = [100 * x["r"] for x in rows_data]
    ax1.plot(rr, [x["run"]["steps_per_second"] for x in rows_data], "o-", label="ours (best of repeats)")
    ax1.fill_between(rr, [x["run"]["min"] for x in rows_data], [x["run"]["max"] for x in rows_data],
                     alpha=0.2, label="ours (min–max of repeats)")
    ax1.set_xlabel("share of linear elements r (%)")
    ax1.set_ylabel("explicit steps per second")
    ax1.set_title(f"{n} tets, one thread", fontsize=9)
    ax1.grid(True, alpha=0.3)
    ax1.legend(fontsize=7)
    ax2.plot(rr, [x["run"]["steps_per_second"] / base for x in rows_data], "o-", label="ours")
    if paper_rate:
        ax2.plot(list(paper_rate), [f / f0 for f in paper_rate.values()], "s--", mfc="none",
                 label=f"paper (000 Table 1 frame rates / {fmt(f0)} Hz)")
    ax2.axhline(1.0, color="k", lw=0.5)
    ax2.set_xlabel("share of linear elements r (%)")
    ax2.set_ylabel("speed-up relative to r = 0")
    ax2.grid(True, alpha=0.3)
    ax2.legend(fontsize=7)
    common.save(fig, ctx, "table1_speed.png")

    # Plain words.
    at50 = next((x for x in rows_data if abs(x["r"] - 0.5) < 1e-9), None)
    words = []
    if at50:
        s50 = at50["run"]["steps_per_second"] / base
        p50 = paper_rate.get(50)
        words.append(f"At r = 50 % we measure a speed-up of {fmt(s50, 3)} over all-TLED"
                     + (f" {busy}" if busy else "")
                     + (f"; the paper reports {fmt(p50)}/{fmt(f0)} = {fmt(p50 / f0, 3)}." if p50 and f0 else "."))
    words.append(f"All-TLED runs at {fmt(base, 4)} steps/s on one thread, i.e. {fmt(1e6 / base, 3)} µs per step "
                 f"for {n} tets" + (f" {again if at50 else busy}" if busy else "") + (f" (the paper: {fmt(f0)} Hz)." if f0 else "."))
    if c_ours is not None and c_paper is not None:
        words.append(f"Fitting t(r) = t(0)((1 − r) + c r) to the times per step gives c = {fmt(c_ours, 2)} for "
                     f"our engine (a linear element plus its share of the node work costs {fmt(c_ours, 2)} of a "
                     f"TLED one: {cheaper_or_dearer(c_ours)}) and c = {fmt(c_paper, 2)} for the paper's frame times"
                     + (f" {again}." if busy else "."))
    if ns_tled and ns_lin:
        words.append(f"The element phase alone: {fmt(ns_tled, 3)} ns per TLED element and step, {fmt(ns_lin, 3)} ns "
                     f"per linear element (the assembled linear rows; ratio {fmt(ns_lin / ns_tled, 2)}: "
                     f"{cheaper_or_dearer(ns_lin / ns_tled)}); the node "
                     f"phase (gather and central-difference update) takes {fmt(node_ns, 3)} ns per node of an "
                     f"all-TLED mesh and {fmt(node_ns_linear, 3)} ns per node of an all-linear one, whose nodes "
                     "have no corner forces to gather" + (f" {again}." if busy else "."))
    if timing.get("binary_sha256") and (BIN / "dhd_sim").exists() and file_hash(BIN / "dhd_sim") != timing["binary_sha256"]:
        words.append("(Note: these timings were measured with an earlier build of dhd_sim.)")
    lines = ["### Table 1: speed against the share of linear elements\n", md,
             "Plot: [dhd/table1_speed.png](dhd/table1_speed.png).\n", " ".join(words) + "\n"]
    if bench_md:
        lines.append(bench_md)
    facts = {"speedup_50_ours": (at50["run"]["steps_per_second"] / base) if at50 else None,
             "speedup_50_paper": (paper_rate[50] / f0) if (50 in paper_rate and f0) else None,
             "c_ours": c_ours, "c_paper": c_paper, "ns_tled": ns_tled, "ns_linear": ns_lin, "node_ns": node_ns,
             "node_ns_linear": node_ns_linear,
             "steps_per_second_tled": base, "busy_note": busy}
    common.write_section(ctx, "table1", "\n".join(lines), facts)
