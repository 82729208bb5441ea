"""The modal far-field report: each regions run is compared with the whole model of the same
scene and input; the far field is named from its config; the plain line says which far field
meets the 1 % target with every input, or by how much the best one misses it."""
import numpy as np

from pipeline.reports import haptic_regions_modal as rep
from report_ctx import FakeContext, run

PRESS = {"kind": "press", "ramp_time": 0.5}
CHIRP = {"kind": "chirp"}


def scene_run(force, inp, regions=None, events=0):
    payload = {"force": force.tolist(), "time": list(np.arange(len(force)) * 1e-3),
               "timing": {"frame_seconds_mean": 1e-3}, "events": [{"frame": 1, "message": "x"}] * events}
    config = {"input": inp}
    if regions is not None:
        config["regions"] = regions
        payload["regions"] = {"frames": len(force), "interface_seconds_total": 1e-3, "build_seconds_total": 0.5,
                              "builds": 1}
    return run(payload, config)


GUYAN = {"secondary": "guyan"}
MODAL = {"secondary": "guyan", "modes": 8}


def runs_for(w, guyan_scale, modal_scale, modal_events=0):
    return {"cube_whole": [scene_run(w, PRESS), scene_run(w, CHIRP)],
            "cube_massless": [scene_run(1.3 * w, PRESS, {}), scene_run(1.3 * w, CHIRP, {})],
            "cube_guyan": [scene_run(w, PRESS, GUYAN), scene_run(guyan_scale * w, CHIRP, GUYAN)],
            "cube_modal": [scene_run(w, PRESS, MODAL), scene_run(modal_scale * w, CHIRP, MODAL, modal_events)]}


def test_far_fields_are_named_and_errors_are_against_the_same_input(tmp_path):
    t = np.linspace(0, 1, 200)
    w = np.stack([0 * t, 0 * t, np.sin(6 * t)], axis=1)
    ctx = FakeContext(tmp_path, runs=runs_for(w, 1.03, 1.005))
    rep.report(ctx)
    rows = rep.rows_of(ctx)
    assert [r["far"] for r in rows if r["input"] == "chirp"] == ["massless", "Guyan", "8 modes"]
    peak = np.abs(w[:, 2]).max()
    expected = 100 * 0.03 * np.sqrt(np.mean(w[:, 2] ** 2)) / peak
    assert np.isclose(rep.pick(rows, "cube", "chirp", "Guyan")["rms"], expected)
    assert rep.pick(rows, "cube", "press", "Guyan")["rms"] == 0.0
    text = (tmp_path / "regions_modal_summary.md").read_text()
    assert "the far field with 8 modes meets the 1 % target with every input" in text
    assert "the fewest that meet it" not in text  # the best is also the only one
    assert "Guyan alone: worst" in text
    assert "### The liver" not in text  # a scene without runs is left out
    assert (tmp_path / "regions_modal.md").exists() and (tmp_path / "regions_modal_forces.png").exists()


def test_a_miss_is_stated_with_its_size_and_a_run_with_events_does_not_count(tmp_path):
    t = np.linspace(0, 1, 200)
    w = np.stack([0 * t, 0 * t, np.sin(6 * t)], axis=1)
    rep.report(FakeContext(tmp_path, runs=runs_for(w, 1.03, 1.02)))
    text = (tmp_path / "regions_modal_summary.md").read_text()
    assert "no far field meets the 1 % target with every input; the best, 8 modes, misses it by" in text
    # The modal run restarted: it does not count, and Guyan (3 %) is the best left.
    rep.report(FakeContext(tmp_path, runs=runs_for(w, 1.03, 1.0, modal_events=2)))
    text = (tmp_path / "regions_modal_summary.md").read_text()
    assert "the best, Guyan, misses it" in text and "(2 events)" in text


def test_the_refined_liver_compares_guyan_and_modes_with_their_frame_time(tmp_path):
    w = np.stack([np.zeros(10), np.zeros(10), np.linspace(0.1, 1, 10)], axis=1)

    def fine(scale, regions, mean):
        r = scene_run(scale * w, CHIRP, regions)
        r.payload["regions"].update({"radius": 0.015, "secondary_every": 1000, "primary": {"interface_nodes": 116}})
        r.payload["timing"] = {"frame_seconds_mean": mean, "frame_seconds_p50": mean, "frame_seconds_p99": 2 * mean,
                               "deadline_misses": 1}
        return r

    whole = scene_run(w, CHIRP)
    whole.payload["timing"]["frame_seconds_mean"] = 0.05
    runs = {"fine_whole": [whole], "fine_guyan": [fine(1.04, GUYAN, 2e-4)], "fine_modal": [fine(1.005, MODAL, 3e-4)]}
    rep.report(FakeContext(tmp_path, runs=runs))
    text = (tmp_path / "regions_modal_summary.md").read_text()
    assert "### The refined liver" in text
    assert "the modes take the chirp under the 1 % target" in text and "0.3 ms mean per frame" in text
    assert (tmp_path / "regions_modal_fine.md").exists()
    served = {"round_trip_seconds": [2e-4] * 999 + [3e-3], "events": 0,
              "timing": {"frame_seconds_p50": 1e-4, "frame_seconds_p99": 2e-4},
              "regions": {"radius": 0.015, "secondary": "guyan", "modes": 32, "precision": "single"}}
    runs["fine_realtime"] = [run(served)]
    rep.report(FakeContext(tmp_path, runs=runs))
    text = (tmp_path / "regions_modal_summary.md").read_text()
    assert "Guyan mass and 32 modes" in text and "1 of 1000 answers later than 1 ms" in text
    runs["fine_modal"] = [fine(1.03, MODAL, 3e-4)]
    rep.report(FakeContext(tmp_path, runs=runs))
    assert "no setting meets the 1 % target on the chirp" in (tmp_path / "regions_modal_summary.md").read_text()


def test_the_fewest_modes_that_meet_the_target_are_named_beside_the_best(tmp_path):
    t = np.linspace(0, 1, 200)
    w = np.stack([0 * t, 0 * t, np.sin(6 * t)], axis=1)
    runs = runs_for(w, 1.03, 1.005)
    more = {"secondary": "guyan", "modes": 32}
    runs["cube_modal"] += [scene_run(w, PRESS, more), scene_run(1.001 * w, CHIRP, more)]
    rep.report(FakeContext(tmp_path, runs=runs))
    text = (tmp_path / "regions_modal_summary.md").read_text()
    assert "the far field with 32 modes meets the 1 % target" in text
    assert "the fewest that meet it: 8 modes" in text
