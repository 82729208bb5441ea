"""The regions-with-tools report's own computations: force errors against the whole model with the
same tool, the cut cost table (local updates against rebuilds), and sentences that follow the
runs (a ratio only where both kinds of cut happened; chatter named only where the whole model
chatters)."""
import numpy as np

from pipeline.reports import haptic_regions_tools as report_mod
from report_ctx import FakeContext, read_csv, run


def timing(mean, peak=None, misses=0):
    return {"frame_seconds_mean": mean, "frame_seconds_p50": mean, "frame_seconds_p99": mean,
            "frame_seconds_max": peak or mean, "deadline_misses": misses}


def topology(local=0, rebuilds=0):
    return {"changes": local + rebuilds, "local_updates": local, "local_seconds_total": 2e-6 * local,
            "local_seconds_max": 3e-6 if local else 0.0, "rebuilds": rebuilds,
            "rebuild_seconds_total": 0.1 * rebuilds, "rebuild_seconds_max": 0.1 if rebuilds else 0.0,
            "secondary_seconds_total": 0.08 * rebuilds, "secondary_seconds_max": 0.08,
            "linear_model_seconds_total": 0.02 * rebuilds, "cached_regions_invalidated": 0}


def payload(force, mean, regions=None, cuts=(), peak=None, misses=0):
    p = {"force": force.tolist(), "time": list(range(len(force))), "timing": timing(mean, peak, misses), "events": [],
         "model": {"tets": 4000}, "cuts": [{"update_seconds": s} for s in cuts]}
    if regions is not None:
        p["regions"] = regions
    return p


def regions(radius, local=0, rebuilds=0, moves=1):
    return {"radius": radius, "primary": {"primary_tets": 300}, "tool_covers": moves, "late_contacts": 0,
            "builds": 1 + moves, "topology": topology(local, rebuilds)}


def test_the_tables_and_the_summary_follow_the_runs(tmp_path):
    t = np.linspace(0, 1, 40)
    whole = np.stack([0 * t, 0 * t, t], axis=1)
    press = {"input": {"kind": "press"}}
    runs = {"cube_tool_whole": [run(payload(whole, 2e-4), press)],
            "cube_tool_regions": [run(payload(whole * 1.01, 1e-4, regions(0.02)), press)],
            "cube_cut_whole": [run(payload(whole, 2e-4, cuts=[2e-5, 4e-5]), press)],
            "cube_cut_regions": [run(payload(whole, 3e-4, regions(0.025, local=3, rebuilds=2), peak=0.1, misses=2),
                                     press)]}
    ctx = FakeContext(tmp_path, runs=runs)
    report_mod.report(ctx)
    text = (tmp_path / "regions_tools_summary.md").read_text()
    assert "peak error 1 %, 1 % at the last frame" in text, text
    assert "speed gain 2" in text and "moved or grew 1 time for the tool" in text
    assert "3 local updates of 2 µs on average; 2 rebuilds of 100 ms" in text, text
    assert "A rebuild costs 5e+04 local updates" in text
    assert "whole model's local update took 30 µs per cut" in text
    assert "chatter" not in text and "liver" not in text  # no chatter, no liver runs
    cuts = read_csv(tmp_path / "regions_tools_cuts.csv")
    assert cuts[1][0] == "cuboid" and cuts[1][3] == "3" and cuts[1][6] == "2"
    assert (tmp_path / "regions_tools.md").exists() and (tmp_path / "regions_tools_forces.png").exists()


def test_chatter_in_the_whole_model_is_named():
    f = np.array([[0, 0, 0.1], [0, 0, 0.5], [0, 0, 0.1]])
    assert np.isclose(report_mod.largest_jump(f), 0.4)
    assert np.isclose(report_mod.final_error(f * 1.1, f), 10.0)
    row = {"scene": "cuboid", "input": "slide", "radius": 0.02, "primary_tets": 1, "tets": 2, "rms": 1, "peak": 1,
           "final": 1, "jump": 0.1, "whole_jump": 0.4, "mean": 1, "whole_mean": 1, "gain": 1, "moves": 0, "late": 0,
           "events": 0, "whole_force": f}
    assert any("chatter" in line and "cuboid slide" in line for line in report_mod.summary_lines([row], []))
