"""The regions report's own computations: force errors relative to the whole model's peak, and
sentences that follow the runs (the fastest setting within an error budget is the one named;
a budget no setting meets is said to be unmet)."""
import numpy as np

from pipeline.reports import haptic_regions
from report_ctx import FakeContext, run


def test_errors_are_relative_to_the_whole_models_peak():
    whole = np.array([[0.0, 0.0, 1.0], [0.0, 0.0, 2.0]])
    rms, peak = haptic_regions.errors(whole + [[0.0, 0.0, 0.1], [0.0, 0.0, 0.1]], whole)
    assert np.isclose(rms, 5.0) and np.isclose(peak, 5.0)
    assert np.isnan(haptic_regions.errors(whole * np.nan, whole)[0])


def whole_run(kind, force, mean):
    timing = {"frame_seconds_mean": mean, "frame_seconds_p50": mean, "frame_seconds_p99": mean,
              "frame_seconds_max": mean, "deadline_misses": 0}
    return run({"force": force.tolist(), "time": list(range(len(force))), "timing": timing, "events": [],
                "model": {"tets": 4000}}, {"input": {"kind": kind}})


def regions_run(kind, force, mean, coupling, interpolate, radius):
    timing = {"frame_seconds_mean": mean, "frame_seconds_p50": mean, "frame_seconds_p99": mean,
              "frame_seconds_max": mean, "deadline_misses": 0}
    regions = {"coupling": coupling, "interpolate": interpolate, "radius": radius, "secondary_every": 10,
               "adaptive": {"kind": "fixed", "frames_per_level": [len(force)]}, "skip_below": 0.0,
               "primary": {"primary_tets": 300, "interface_nodes": 50}, "secondary_updates": 10,
               "secondary_skipped": 0, "builds": 1, "build_seconds_max": 0.1, "secondary_seconds_max": 1e-3}
    return run({"force": force.tolist(), "time": list(range(len(force))), "timing": timing, "events": [],
                "model": {"tets": 4000}, "regions": regions}, {"input": {"kind": kind}})


def test_the_summary_names_the_fastest_setting_within_each_budget(tmp_path):
    t = np.linspace(0, 1, 50)
    whole = np.stack([0 * t, 0 * t, np.sin(3 * t)], axis=1)
    runs = {"cube_run": [whole_run("press", whole, 1e-3), whole_run("chirp", whole, 1e-3)],
            "cube_condensed": [regions_run(k, whole * 1.002, 4e-4, "condensed", True, 0.02) for k in ("press", "chirp")],
            "cube_exchange_interpolated": [regions_run(k, whole * 1.03, 2e-4, "exchange", True, 0.02)
                                           for k in ("press", "chirp")],
            "cube_exchange_held": [regions_run(k, whole * 1.2, 1e-4, "exchange", False, 0.02)
                                   for k in ("press", "chirp")]}
    ctx = FakeContext(tmp_path, runs=runs)
    haptic_regions.report(ctx)
    text = (tmp_path / "regions_summary.md").read_text()
    within_1 = next(l for l in text.splitlines() if "fastest within 1 % RMS" in l)
    within_5 = next(l for l in text.splitlines() if "fastest within 5 % RMS" in l)
    assert "condensed" in within_1 and "speed gain 2.5" in within_1
    assert "eq. 7, interpolated" in within_5 and "speed gain 5" in within_5
    assert "**refined liver**" not in text  # no runs, no line
    assert "nan" not in text  # one radius and one rate: no factor across them
    assert (tmp_path / "regions_table.md").exists() and (tmp_path / "regions_tradeoff.png").exists()
