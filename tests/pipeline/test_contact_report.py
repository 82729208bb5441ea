"""The contact report's own computations: Hertz's force and the bonded-layer correction, and
sentences that follow the runs (a run that matches the corrected solution is said to, one that
does not is not)."""
import math

import numpy as np

from pipeline.reports import contact_hertz
from report_ctx import FakeContext, run

R, E, NU = 0.02, 5000.0, 0.35


def test_hertz_force_and_the_layer_correction_limits():
    d = 0.001
    assert math.isclose(contact_hertz.hertz_force(d, R, E, NU),
                        4 / 3 * E / (1 - NU ** 2) * math.sqrt(R) * d ** 1.5, rel_tol=1e-14)
    # A layer much thicker than the contact radius is a half-space; a thinner one is stiffer.
    assert abs(contact_hertz.bonded_layer_factor(d, R, 100.0, NU) - 1.0) < 1e-3
    assert contact_hertz.bonded_layer_factor(d, R, 0.02, NU) > contact_hertz.bonded_layer_factor(d, R, 0.04, NU) > 1.0


def press_run(tets, scale, contacts):
    """A synthetic press whose force is `scale` × the layer-corrected Hertz force."""
    ramp = 1.0
    t = np.linspace(0.0, 1.2, 601)
    s = np.clip(t / ramp, 0, 1)
    depth = 0.002 * s * s * (3 - 2 * s)
    force = scale * contact_hertz.hertz_force(depth, R, E, NU) * contact_hertz.bonded_layer_factor(
        np.maximum(depth, 1e-12), R, contact_hertz.THICKNESS, NU)
    payload = {"tools": [{"time": t.tolist(), "force": [[0.0, 0.0, f] for f in force],
                          "contacts": [contacts] * len(t)}],
               "mesh": {"tets": tets, "nodes": tets // 4}, "solver": {"dt": 1e-4, "dt_critical": 2e-4}}
    config = {"material": {"E": E, "nu": NU},
              "boundary": {"tools": [{"radius": R, "travel": [0, 0, -0.002], "ramp_time": ramp, "ramp": "smooth"}]}}
    return run(payload, config)


def test_sentences_follow_the_runs(tmp_path):
    close = FakeContext(tmp_path / "a", runs={"press": [press_run(2500, 0.7, 1), press_run(20000, 1.01, 9)]})
    contact_hertz.report(close)
    text = (tmp_path / "a" / "summary.md").read_text()
    assert "within 1 % of the layer-corrected solution" in text
    assert "touches 1 node(s) at full depth" in text
    assert "0.7×" in text and "1.01×" in text
    far = FakeContext(tmp_path / "b", runs={"press": [press_run(20000, 1.3, 9)]})
    contact_hertz.report(far)
    text = (tmp_path / "b" / "summary.md").read_text()
    assert "within 30 % of the layer-corrected solution" in text
    assert "too few to resolve" not in text


def test_haptic_lines_follow_the_runs(tmp_path):
    force = [[0.0, 0.0, 0.1 * k] for k in range(5)]
    payload = {"force": force, "contact": [0, 1, 1, 1, 1], "frames": 5, "substeps": 2, "frame_step": 1e-3,
               "model": {"tets": 4000}, "events": [],
               "timing": {"frame_seconds_p50": 2e-4, "frame_seconds_p99": 1.5e-3, "deadline_misses": 1}}
    ctx = FakeContext(tmp_path, runs={"haptic_tool": [run(payload)]})
    lines = contact_hertz.haptic_lines(ctx)
    assert len(lines) == 1
    assert "in contact in 4 of 5 frames" in lines[0]
    assert "0.4 N on the device at full depth" in lines[0]
    assert "1 over the 1 ms deadline" in lines[0]
    assert contact_hertz.haptic_lines(FakeContext(tmp_path / "none", runs={})) == []
