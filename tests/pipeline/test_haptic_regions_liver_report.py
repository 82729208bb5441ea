"""The liver causes report: each regions run is compared with the whole model of the same
contact, law and input; a run where either model restarted is said to have no reference; the
quasi-static verdict follows the end error; the refined liver's frame time is split as measured."""
import numpy as np

from pipeline.reports import haptic_regions_liver as rep
from report_ctx import FakeContext, run

SLOW = {"kind": "press", "ramp_time": 1.5}
FAST = {"kind": "press", "ramp_time": 0.5}
CHIRP = {"kind": "chirp"}


def timing(mean):
    return {"frame_seconds_mean": mean, "frame_seconds_p50": mean, "frame_seconds_p99": mean,
            "frame_seconds_max": mean, "deadline_misses": 0}


def liver_run(force, contact, law, inp, events=0, regions=None, mean=1e-3, k=20):
    payload = {"force": force.tolist(), "time": list(np.arange(len(force)) * 1e-3), "timing": timing(mean),
               "events": [{"frame": 1, "message": "inverted"}] * events, "substeps": 4}
    if regions:
        payload["regions"] = regions
    return run(payload, {"probe": {"contact": contact, "stiffness": k}, "model": {"material": {"model": law}}, "input": inp})


def test_inputs_are_named_by_kind_and_ramp():
    assert rep.input_label(SLOW) == "slow press"
    assert rep.input_label(FAST) == "press"
    assert rep.input_label({"kind": "growing_sine"}) == "growing sine"


def test_each_run_meets_its_own_reference_and_restarts_have_none(tmp_path):
    t = np.linspace(0, 1, 100)
    w = np.stack([0 * t, 0 * t, np.minimum(t / 0.6, 1.0)], axis=1)
    runs = {"whole": [liver_run(w, "attach", "linear", SLOW), liver_run(w, "attach", "linear", CHIRP),
                      liver_run(2 * w, "attach", "neo_hookean_paper", SLOW, events=3),
                      liver_run(w, "attach", "linear", SLOW, events=5, k=100)],
            # linear slow press: exact at the end (the last 40 frames equal), 10 % off during the ramp
            "condensed": [liver_run(np.where(t[:, None] < 0.6, 1.1 * w, w), "attach", "linear", SLOW),
                          liver_run(1.2 * w, "attach", "linear", CHIRP),
                          liver_run(2 * w, "attach", "neo_hookean_paper", SLOW),
                          liver_run(w, "attach", "linear", SLOW, k=100)],
            "guyan": [liver_run(1.05 * w, "attach", "linear", CHIRP)]}
    ctx = FakeContext(tmp_path, runs=runs)
    rep.report(ctx)
    rows = rep.rows_of(ctx)
    slow = rep.pick(rows, "condensed", "attach", "linear", "slow press")
    assert slow["end"] == 0.0 and 0 < slow["rms"] < 10
    assert np.isclose(rep.pick(rows, "condensed", "attach", "linear", "chirp")["rms"],
                      100 * 0.2 * np.sqrt(np.mean(w[:, 2] ** 2)))
    text = (tmp_path / "regions_liver_summary.md").read_text()
    assert "exact at equilibrium" in text and "has a bug" not in text
    assert "no reference" in text  # the neo-Hookean whole model restarted
    assert "the probe's spring, 100 N/m:** the whole model itself has events" in text
    assert "restarted in 1 of 1 runs" in text
    assert "linear, attached). Condensed massless" in text
    assert (tmp_path / "regions_liver.md").exists() and (tmp_path / "regions_liver_forces.png").exists()
    # A condensation that misses the linear equilibrium is called out.
    runs["condensed"][0] = liver_run(1.1 * w, "attach", "linear", SLOW)
    rep.report(FakeContext(tmp_path, runs=runs))
    assert "has a bug" in (tmp_path / "regions_liver_summary.md").read_text()


def test_the_refined_liver_frame_time_is_split_as_measured(tmp_path):
    w = np.ones((10, 3))
    regions = lambda precision, seconds: {"radius": 0.035, "precision": precision, "frames": 10,
                                          "interface_seconds_total": seconds, "secondary_every": 10,
                                          "secondary_seconds_total": 0.05,
                                          "primary": {"interface_nodes": 447, "primary_tets": 5000}}
    runs = {"fine_whole": [liver_run(w, "attach", "stable_neo_hookean", CHIRP, mean=0.1)],
            "fine_condensed": [liver_run(w, "attach", "stable_neo_hookean", CHIRP, regions=regions("double", 0.08),
                                         mean=0.02),
                               liver_run(w, "attach", "stable_neo_hookean", CHIRP, regions=regions("single", 0.04),
                                         mean=0.016)]}
    served = {"round_trip_seconds": [2e-4] * 998 + [3e-3, 4e-3], "timing": timing(1e-4), "events": 0,
              "regions": {"radius": 0.015, "secondary": "guyan", "precision": "single"}}
    runs["fine_realtime"] = [run(served)]
    rep.report(FakeContext(tmp_path, runs=runs))
    text = (tmp_path / "regions_liver_summary.md").read_text()
    assert "2 of 1000 answers later than 1 ms" in text and "Guyan mass, single precision" in text
    assert "of which the interface product 8 ms (40 %) and the far field's recovery 5 ms (25 %)" in text
    assert "of which the interface product 4 ms (25 %)" in text
    assert "the 1 kHz target is not met on this machine" in text


def test_chatter_is_the_largest_frame_to_frame_change_of_the_force():
    smooth = np.stack([np.zeros(5), np.zeros(5), np.linspace(0, 1, 5)], axis=1)
    assert np.isclose(rep.chatter(smooth), 25.0)
    flipping = smooth.copy()
    flipping[3, 2] = 0.0
    assert np.isclose(rep.chatter(flipping), 100.0)


def test_set_up_words_tell_whether_the_first_answer_waited_for_the_region():
    import numpy as np
    from pipeline.reports import haptic_regions_liver as report
    waited = report.set_up_words(np.array([10.3, 2e-4]), {"build_seconds_max": 10.0})
    assert "waited" in waited and "10 s" in waited
    before = report.set_up_words(np.array([1.2e-3, 2e-4]), {"build_seconds_max": 10.0})
    assert "before the device's clock started" in before and "1.2 ms" in before
    assert report.set_up_words(np.array([2e-4]), {}) == ""
