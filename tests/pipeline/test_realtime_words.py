"""The served real-time runs are described by their own duration, rate and press, and carry the
machine's load beside their figures."""
import numpy as np

from report_ctx import FakeContext, run
from pipeline.reports import haptic_regions, haptic_regions_liver


def served(seconds, rate, machine=None):
    frames = int(seconds * rate)
    rt = np.full(frames, 0.2 / rate)
    rt[:3] = 2.0 / rate     # three late answers
    payload = {"frames": frames, "rate": rate, "seconds": seconds, "round_trip_seconds": rt.tolist(),
               "timing": {"frame_seconds_p50": 0.1 / rate, "frame_seconds_p99": 0.5 / rate, "deadline_misses": 0},
               "regions": None, "solver": "whole_model", "model": {"tets": 100}, "substeps": 1, "events": 0,
               "peak_force": 1.0, "machine": machine}
    return run(payload, {"press": {"depth": 0.01, "ramp_time": 0.5}})


BUSY = {"cores": 2, "load_before": 3.2, "load_after": 3.0, "steal_percent": 0.0, "calibration_before_s": 0.01,
        "calibration_after_s": 0.01, "calibration_change": 0.0, "disturbed": ["load"], "retaken": True,
        "flagged": True}


def test_the_realtime_summary_gives_the_runs_duration_rate_and_load(tmp_path):
    ctx = FakeContext(tmp_path, runs={"realtime_cube_whole": [served(10, 1000, BUSY)]})
    rows = haptic_regions.realtime_rows(ctx)
    text = haptic_regions.realtime_summary(rows)
    assert "10 s at 1 kHz" in text and "60 s" not in text
    assert "3 of 10000 answers later than 1 ms" in text
    assert "(timed on a busy machine: load 3.2 on 2 cores; so was the retake)" in text
    assert haptic_regions.press_words(rows) == "a press of 1 cm over 0.5 s, held"

    ctx = FakeContext(tmp_path / "b", runs={"realtime_cube_whole": [served(2, 500)]})
    text = haptic_regions.realtime_summary(haptic_regions.realtime_rows(ctx))
    assert "2 s at 0.5 kHz" in text and "3 of 1000 answers later than 2 ms" in text
    assert "machine load not recorded" in text


def test_a_served_line_of_the_liver_reports_reads_its_run():
    line = haptic_regions_liver.realtime_line(served(10, 2000))
    assert "paced at 2 kHz for 10 s, a press of 1 cm over 0.5 s, held" in line
    assert "3 of 20000 answers later than 0.5 ms" in line


def whole_run(stiffness, frame_step):
    frames = 20
    payload = {"force": [[0.0, 0.0, -0.1 * k] for k in range(frames)], "time": [k * frame_step for k in range(frames)],
               "timing": {"frame_seconds_p50": 0.2 * frame_step, "frame_seconds_p99": 0.5 * frame_step,
                          "frame_seconds_max": frame_step, "deadline_misses": 0},
               "model": {"nodes": 10, "tets": 12}, "substeps": 2, "dt": frame_step / 2, "frames": frames,
               "events": [], "frame_step": frame_step}
    return run(payload, {"input": {"kind": "press"}, "probe": {"stiffness": stiffness}})


def test_the_whole_model_summary_gives_the_runs_spring_and_period(tmp_path):
    from pipeline.reports import haptic_whole
    ctx = FakeContext(tmp_path, runs={"cube_run": [whole_run(40, 0.002)], "liver_run": [whole_run(40, 0.002)]})
    haptic_whole.report(ctx)
    text = (tmp_path / "summary.md").read_text()
    assert "through a 40 N/m spring once per 2 ms frame" in text and "100 N/m" not in text and "1 ms" not in text
    assert "fits the 2 ms haptic period" in text


def robust_run(law, depth, ramp, events):
    frames, step = 40, 0.05
    time = [k * step for k in range(frames)]
    force = [[0.0, 0.0, -0.0 if (events and k % 2 and t > ramp) else -1.0 * min(t / ramp, 1.0)]
             for k, t in enumerate(time)]
    payload = {"force": force, "time": time, "events": [{"frame": 25, "message": "inverted"}] * events,
               "timing": {"frame_seconds_p50": 1e-4, "frame_seconds_p99": 2e-4, "frame_seconds_max": 3e-4,
                          "deadline_misses": 0},
               "frames": frames, "substeps": 1, "model": {"tets": 12}, "frame_step": step}
    return run(payload, {"model": {"material": {"model": law}}, "probe": {"stiffness": 70},
                         "input": {"kind": "press", "depth": depth, "ramp_time": ramp}})


def test_the_deep_press_summary_gives_the_runs_depth_ramp_hold_and_spring(tmp_path):
    from pipeline.reports import haptic_robust
    ctx = FakeContext(tmp_path, runs={"press_run": [robust_run("neo_hookean_paper", 0.02, 0.5, 3),
                                                    robust_run("stable_neo_hookean", 0.02, 0.5, 0)]})
    haptic_robust.report(ctx)
    table = (tmp_path / "robust.md").read_text()
    assert "through a 70 N/m spring" in table and "The hold is the 1.45 s after the ramp" in table
    text = (tmp_path / "robust_summary.md").read_text()
    assert "pressed 2 cm into the liver" in text and "three times" not in text


def test_the_modal_caption_gives_each_scenes_radius_law_and_probe_from_its_runs(tmp_path):
    from pipeline.reports import haptic_regions_modal as rep
    from test_haptic_regions_modal_report import runs_for
    t = np.linspace(0, 1, 200)
    w = np.stack([0 * t, 0 * t, np.sin(6 * t)], axis=1)
    runs = runs_for(w, 1.03, 1.005)
    for stage in ("cube_massless", "cube_guyan", "cube_modal"):
        for r in runs[stage]:
            r.payload["regions"]["radius"] = 0.03
            r.config.update(probe={"stiffness": 55, "contact": "attached"},
                            model={"material": {"model": "stable_neo_hookean"}})
    rep.report(FakeContext(tmp_path, runs=runs))
    caption = (tmp_path / "regions_modal.md").read_text()
    assert "cuboid: radius 3 cm, stable neo-Hookean, probe 55 N/m, attached" in caption
    assert "2.5 cm" not in caption and "100 N/m" not in caption


def test_the_liver_causes_name_the_regions_their_runs_used():
    rows = [{"radius": 0.03, "every": 5}, {"radius": 0.035, "every": 5}]
    assert haptic_regions_liver.regions_words(rows) == "regions of radius 3 or 3.5 cm, secondary every 5 frames"


def test_the_dynamic_far_field_summary_gives_its_runs_spring_and_rate(tmp_path, monkeypatch):
    from pipeline.reports import haptic_regions_dynamic as rep
    rows = {"cube_run": [], "liver_run": [], "cube_exchange": [], "liver_exchange": []}
    for secondary, rms in (("static", 30.0), ("implicit", 35.0)):
        rows["liver_exchange"].append(run({}, {"regions": {"secondary": secondary}, "probe": {"stiffness": 45},
                                               "input": {"kind": "press"}}))
    def fake_row(scene, r, whole):
        return {"scene": scene, "input": "press", "rms": 30.0 if r.config["regions"]["secondary"] == "static" else 35.0,
                "peak": 1.0, "mean": 1e-3, "whole_mean": 1e-3, "region_events": 0, "whole_events": 0, "every": 7}
    monkeypatch.setattr(rep, "row_of", fake_row)
    monkeypatch.setattr(rep, "whole_rows", lambda ctx, stage: {})
    rep.report(FakeContext(tmp_path, runs=rows))
    text = (tmp_path / "regions_dynamic_summary.md").read_text()
    assert "through a 45 N/m probe spring" in text and "100 N/m" not in text
    assert "secondary every 7 frames" in (tmp_path / "regions_dynamic.md").read_text()
