"""A live scene while it changes -> results/haptic/: live.md/csv (per region-building scheme:
the client's latency, the longest gap between answers, the force error against the whole model
replaying the same frames offline, the regions' builds and swaps, the load), live_error.png
(force error over time with the cut instants), live_latency.png (round trips over time),
live_summary.md."""
import os

import numpy as np

from pipeline import plots
from pipeline.tables import write_table

NAMES = {"background": "built beside the frames (background)", "inline": "built inside the frame (inline, previous)"}


def window_error(err, ref_rms, centre, rate, half=0.05):
    k0, k1 = max(0, int((centre - half) * rate)), min(len(err), int((centre + half) * rate))
    return float(np.sqrt(np.mean(err[k0:k1] ** 2)) / ref_rms) if k1 > k0 else float("nan")


def row_of(name, run, whole, rate, cut_times):
    rt = np.array(run["round_trip_seconds"])
    at = np.array(run["answered_at_seconds"])
    f = np.array(run["force"])
    ref = np.array(whole["force"])
    err = np.linalg.norm(f - ref, axis=1)
    ref_rms = float(np.sqrt(np.mean(np.sum(ref ** 2, axis=1))))
    r, bg = run["regions"], run["regions"]["background"]
    return {
        "name": name, "frames": len(rt), "missing": int(np.isnan(f).any(axis=1).sum()),
        "p50": float(np.percentile(rt, 50)), "p99": float(np.percentile(rt, 99)),
        "p999": float(np.percentile(rt, 99.9)), "max": float(rt.max()), "late": int((rt > 1e-3).sum()),
        "over2": int((rt > 2e-3).sum()), "gap": float(np.diff(at).max()),
        "rms": float(np.sqrt(np.mean(err ** 2)) / ref_rms),
        "cut_windows": [window_error(err, ref_rms, t, rate) for t in cut_times],
        "builds": r["builds"], "build_max": r["build_seconds_max"],
        "build_mean": r["build_seconds_total"] / max(r["builds"], 1), "swaps": bg["swaps"],
        "swap_max": bg["swap_seconds_max"], "held": bg["frames_contact_held"],
        "while_building": bg["frames_while_building"], "rebuilds": r["topology"]["rebuilds"],
        "recoveries": r.get("far_field_recoveries", 0), "events": len(run["events"]),
        "ready": run["setup_seconds_to_ready"], "load": run["load_before"][0], "load_after": run["load_after"][0],
        "err": err / ref_rms, "rt": rt,
    }


def target_verdict(r, busy) -> str:
    """The latency targets (no answer later than 2 ms, at most 0.1 % later than 1 ms) for one
    scheme: met, or by how much not; on a busy machine, said to be no verdict on the targets."""
    share = r["late"] / max(r["frames"], 1)
    name = NAMES.get(r["name"], r["name"])
    name = name[:1].upper() + name[1:]
    if r["over2"] == 0 and share <= 1e-3:
        verdict = f"{name}: the latency targets are met ({100 * share:.2f} % later than 1 ms, none later than 2 ms)."
    else:
        verdict = (f"{name}: the latency targets are not met: {100 * share:.2f} % of the answers later than 1 ms "
                   f"(target at most 0.1 %), {r['over2']} later than 2 ms (target none), the longest "
                   f"{1e3 * r['max']:.1f} ms.")
    return verdict + (" (Busy machine: not a verdict on the idle targets.)" if busy else "")


def report(ctx):
    [run] = ctx.runs("session")
    p = run.payload
    rate = p["rate"]
    cut_times = [c["time"] for c in p["cuts"]]
    rows = [row_of(name, s, p["whole"], rate, cut_times) for name, s in p["served"].items()]
    t = np.arange(p["frames"]) / rate
    fig, ax = plots.plt.subplots(figsize=(7, 3), dpi=110)
    ax.grid(True, alpha=0.3)
    for r, colour in zip(rows, ("tab:blue", "tab:red")):
        ax.plot(t, 100 * r["err"], lw=0.7, color=colour, label=NAMES.get(r["name"], r["name"]))
    for c in cut_times:
        ax.axvline(c, color="k", ls="--", lw=0.8)
    ax.set_xlabel("time (s); dashed: cuts")
    ax.set_ylabel("|F - F_whole| / RMS |F_whole| (%)")
    ax.legend(fontsize=7)
    plots.save(fig, ctx.out("live_error.png"))
    fig, ax = plots.plt.subplots(figsize=(7, 3), dpi=110)
    ax.grid(True, alpha=0.3)
    for r, colour in zip(rows, ("tab:blue", "tab:red")):
        ax.semilogy(t, 1e3 * r["rt"], lw=0.5, color=colour, label=NAMES.get(r["name"], r["name"]))
    ax.axhline(1.0, color="k", lw=0.8)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("round trip (ms)")
    ax.legend(fontsize=7)
    plots.save(fig, ctx.out("live_latency.png"))
    cpu = p["cpu"]
    cores = p.get("cores") or os.cpu_count() or 1
    busy = max(max(r["load"], r["load_after"]) for r in rows) > cores - 1
    machine = (f"busy (load above {cores - 1} on {cores} cores: these are not idle figures)" if busy else
               f"quiet (load at most {cores - 1} on {cores} cores while the runs were served)")
    write_table(ctx, "live", ["regions built", "load (1 min) before / after", "frames", "missing", "p50 (ms)",
                              "p99 (ms)", "p99.9 (ms)", "max (ms)", "later than 1 ms", "later than 2 ms",
                              "longest gap (ms)", "RMS force error", "error, 100 ms around each cut",
                              "regions built", "build mean / max (s)", "swaps", "swap max (ms)",
                              "frames contact held", "far-field rebuilds", "far-field recoveries", "events",
                              "set-up to ready (s)"],
                [[NAMES.get(r["name"], r["name"]), f"{r['load']:.1f} / {r['load_after']:.1f}", r["frames"],
                  r["missing"], 1e3 * r["p50"], 1e3 * r["p99"], 1e3 * r["p999"], 1e3 * r["max"], r["late"],
                  r["over2"], 1e3 * r["gap"], f"{100 * r['rms']:.2f} %",
                  ", ".join(f"{100 * w:.1f} %" for w in r["cut_windows"]), r["builds"],
                  f"{r['build_mean']:.3f} / {r['build_max']:.3f}", r["swaps"], 1e3 * r["swap_max"], r["held"],
                  r["rebuilds"], r["recoveries"], r["events"], r["ready"]] for r in rows],
                f"The liver served by `haptic_sim serve` over a pipe to a client in another process pacing 1 kHz "
                f"in wall-clock time for {p['seconds']:g} s ({p['frames']} frames), on {cpu} ({cores} cores; the load "
                f"average is beside each row: {machine}). Latency: from the "
                "client sending a position to reading its answer. Force error against the whole model replaying "
                "the same frames offline, relative to its RMS force.")
    text = ["## A live scene while it changes (liver, served)", "",
            "[Table](live.md), [force error](live_error.png), [latency](live_latency.png).", ""]
    for r in rows:
        text.append(f"- **{NAMES.get(r['name'], r['name'])}** (load {r['load']:.1f} before, {r['load_after']:.1f} "
                    f"after, on {cores} cores): p50 {1e3 * r['p50']:.2f} ms, p99 {1e3 * r['p99']:.2f} ms, p99.9 "
                    f"{1e3 * r['p999']:.2f} ms, max {1e3 * r['max']:.1f} ms; {r['late']} of {r['frames']} answers "
                    f"later than 1 ms, {r['over2']} later than 2 ms, {r['missing']} missing; longest gap between "
                    f"answers {1e3 * r['gap']:.1f} ms. Force error {100 * r['rms']:.2f} % RMS of the whole "
                    f"model's; around the cuts " + ", ".join(f"{100 * w:.1f} %" for w in r["cut_windows"]) +
                    f". {r['builds']} regions built ({r['build_mean']:.3f} s on average, {r['build_max']:.3f} s at "
                    f"most), {r['swaps']} swapped in from the worker (the swap at most {1e3 * r['swap_max']:.2f} ms), "
                    f"{r['held']} frames with the contact held while its region was built.")
    text += ["", f"The machine: {machine}. " + " ".join(target_verdict(r, busy) for r in rows) +
             " The two schemes are from one run, one after the other."]
    ctx.out("live_summary.md").write_text("\n".join(text) + "\n")
