"""How busy the machine was while a timing was taken, so that a report can say when a speed
figure is not to be trusted.

A timing stage wraps its measurement in `measure(take, log)`: before and after it reads the
1-minute load average (/proc/loadavg), the CPU steal counters (/proc/stat) and times a short fixed
calibration kernel. The measurement is disturbed when

  - the load average (before or after) exceeds the number of cores minus one (something else
    wanted a core the measurement needed),
  - the steal time exceeds STEAL_PERCENT of the CPU time over the measurement (a hypervisor took
    the cores), or
  - the calibration kernel's time after differs from its time before by more than
    CALIBRATION_CHANGE (the machine's speed changed during the measurement).

A disturbed measurement is taken once more; if the retake is disturbed too, it is kept and
flagged. The record ("machine" block of the artifact) keeps every figure and the reasons, and
`busy_note` turns a flagged record into the words a report writes beside its verdict.
"""
import os
import statistics
import time

STEAL_PERCENT = 3.0
CALIBRATION_CHANGE = 0.20
CALIBRATION_REPEATS = 5
CALIBRATION_WORK = 200_000


def load_average(path="/proc/loadavg"):
    try:
        with open(path) as f:
            return float(f.read().split()[0])
    except (OSError, ValueError, IndexError):
        return None


def cpu_times(path="/proc/stat"):
    """(steal, total) jiffies of all CPUs, or None where /proc/stat is not there."""
    try:
        with open(path) as f:
            fields = f.readline().split()
    except OSError:
        return None
    if not fields or fields[0] != "cpu":
        return None
    values = [int(v) for v in fields[1:]]
    # user nice system idle iowait irq softirq steal [guest guest_nice]: guest time is already
    # counted in user and nice, so the total stops at steal.
    return (values[7] if len(values) > 7 else 0, sum(values[:8]))


def calibration_seconds():
    """Median time of a fixed single-threaded integer loop (about 10 ms on an idle core)."""
    times = []
    for _ in range(CALIBRATION_REPEATS):
        t0 = time.perf_counter()
        acc = 0
        for i in range(CALIBRATION_WORK):
            acc += i * i % 7
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def _before():
    return {"load": load_average(), "cpu": cpu_times(), "calibration": calibration_seconds()}


def _record(before, cores):
    after = _before()
    steal = None
    if before["cpu"] and after["cpu"]:
        d_total = after["cpu"][1] - before["cpu"][1]
        steal = 100.0 * (after["cpu"][0] - before["cpu"][0]) / d_total if d_total > 0 else 0.0
    change = after["calibration"] / before["calibration"] - 1.0
    loads = [x for x in (before["load"], after["load"]) if x is not None]
    rec = {"cores": cores, "load_before": before["load"], "load_after": after["load"],
           "steal_percent": steal, "calibration_before_s": before["calibration"],
           "calibration_after_s": after["calibration"], "calibration_change": change}
    reasons = []
    if loads and max(loads) > cores - 1:
        reasons.append("load")
    if steal is not None and steal > STEAL_PERCENT:
        reasons.append("steal")
    if abs(change) > CALIBRATION_CHANGE:
        reasons.append("calibration")
    rec["disturbed"] = reasons
    return rec


def measure(take, log=print, cores=None):
    """(result of take(), machine record). A disturbed measurement is retaken once; the record
    says whether it was ("retaken") and whether the kept one is still disturbed ("flagged")."""
    cores = cores or os.cpu_count() or 1
    before = _before()
    result = take()
    rec = _record(before, cores)
    retaken = False
    if rec["disturbed"]:
        log(f"timing disturbed ({', '.join(rec['disturbed'])}: {describe(rec)}): taking it once more")
        before = _before()
        result = take()
        rec = _record(before, cores)
        retaken = True
    rec["retaken"] = retaken
    rec["flagged"] = bool(rec["disturbed"])
    return result, rec


def describe(rec, only=None) -> str:
    """The measured conditions in words: "load 3.2 on 2 cores, CPU steal 0 %, calibration kernel
    +4 % after against before"; `only` keeps the named ones ("load", "steal", "calibration")."""
    loads = [x for x in (rec.get("load_before"), rec.get("load_after")) if x is not None]
    parts = []
    if loads and (only is None or "load" in only):
        parts.append(f"load {max(loads):.1f} on {rec['cores']} core{'s' if rec['cores'] != 1 else ''}")
    if rec.get("steal_percent") is not None and (only is None or "steal" in only):
        parts.append(f"CPU steal {rec['steal_percent']:.0f} %")
    if rec.get("calibration_change") is not None and (only is None or "calibration" in only):
        parts.append(f"calibration kernel {100 * rec['calibration_change']:+.0f} % after against before")
    return ", ".join(parts)


def busy_note(rec) -> str:
    """What a report writes beside a speed verdict taken from this record: "" for an undisturbed
    timing, what disturbed it for a flagged one, and a warning where the timing has no record."""
    if not rec:
        return "(machine load not recorded for this timing)"
    if not rec.get("flagged"):
        return ""
    machine = "a busy machine" if "load" in rec["disturbed"] else "a disturbed machine"
    return (f"(timed on {machine}: {describe(rec, rec['disturbed'])}"
            f"{'; so was the retake' if rec.get('retaken') else ''})")


def worst(records):
    """One record standing for several timings: the first flagged one, or the first one, or None
    where one of them has no record."""
    records = list(records)
    if not records or any(not r for r in records):
        return None
    return next((r for r in records if r.get("flagged")), records[0])
