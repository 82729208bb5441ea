"""The live-scene report's own computations on a synthetic session: the client's latency figures
(quantiles, answers later than 1 and 2 ms, the longest gap between answers), the force error
against the whole model over the session and in the 100 ms around each cut, one row per scheme."""
import numpy as np

from pipeline.reports import haptic_live as report_mod
from report_ctx import FakeContext, read_csv, run


def served(force, round_trip, answered_at, held=0):
    background = {"swaps": 2, "swap_seconds_max": 0.004, "frames_contact_held": held, "frames_while_building": 10}
    return {"round_trip_seconds": round_trip.tolist(), "answered_at_seconds": answered_at.tolist(),
            "force": force.tolist(), "setup_seconds_to_ready": 1.5, "load_before": [3.0, 2, 1],
            "load_after": [3.5, 2, 1], "events": [],
            "regions": {"builds": 3, "build_seconds_max": 1.2, "build_seconds_total": 3.0, "background": background,
                        "topology": {"rebuilds": 1}, "far_field_recoveries": 2}}


def test_latency_and_error_follow_the_session(tmp_path):
    frames, rate = 1000, 1000
    t = np.arange(frames) / rate
    whole = np.stack([0 * t, 0 * t, 1 + 0 * t], axis=1)  # RMS |F| = 1 N
    exact = whole.copy()
    off = whole.copy()
    off[500:550, 2] += 0.1  # 0.1 N off for 50 frames, right after the cut at 0.5 s
    rt = np.full(frames, 2e-4)
    rt[[10, 20]] = 1.5e-3  # two answers later than 1 ms
    rt[30] = 3e-3          # one later than 2 ms
    at = t + rt
    at[700:] += 0.2        # a 200 ms stall before frame 700
    payload = {"frames": frames, "rate": rate, "seconds": 1.0, "cpu": "test cpu", "cores": 2, "cuts": [{"time": 0.5}],
               "served": {"background": served(off, rt, at, held=50), "inline": served(exact, rt, t + rt)},
               "whole": {"force": whole.tolist()}}
    ctx = FakeContext(tmp_path, runs={"session": [run(payload)]})
    report_mod.report(ctx)
    rows = read_csv(tmp_path / "live.csv")
    header, body = rows[0], {r[0]: dict(zip(rows[0], r)) for r in rows[1:]}
    assert len(body) == 2
    bg = body[report_mod.NAMES["background"]]
    inl = body[report_mod.NAMES["inline"]]
    assert bg["later than 1 ms"] == "3" and bg["later than 2 ms"] == "1"
    assert abs(float(bg["longest gap (ms)"]) - 201.0) < 1e-6
    assert abs(float(inl["longest gap (ms)"]) - (1.0 + 2.8)) < 1e-6  # the 3 ms answer after 0.2 ms ones
    # 0.1 N over 50 of 1000 frames: RMS 0.1 sqrt(0.05) = 2.24 % of 1 N; in the 100 ms around the
    # cut (frames 450-549): 0.1 sqrt(0.5) = 7.1 %.
    assert bg["RMS force error"] == "2.24 %"
    assert bg["error, 100 ms around each cut"] == "7.1 %"
    assert inl["RMS force error"] == "0.00 %"
    summary = (tmp_path / "live_summary.md").read_text()
    assert "these are not idle figures" in summary and "load 3.0 before" in summary
    assert "not a verdict on the idle targets" in summary
    assert "0.30 % of the answers later than 1 ms" in summary and "1 later than 2 ms" in summary
    # The same loads on 8 cores are a quiet machine: the verdict stands without the busy caveat.
    payload["cores"] = 8
    quiet = FakeContext(tmp_path / "quiet", runs={"session": [run(payload)]})
    report_mod.report(quiet)
    summary = (tmp_path / "quiet" / "live_summary.md").read_text()
    assert "quiet (load at most 7 on 8 cores" in summary and "not a verdict" not in summary
    assert "latency targets are not met" in summary
