"""The regions summary's verdicts follow the measured errors: which exchange (held or
interpolated interface values) wins is judged per scene, never written once for all."""
from pipeline.reports.haptic_regions import held_against_interpolated


def rows(scene, held, interpolated):
    return ([{"scene": scene, "coupling": "exchange_held", "rms": e} for e in held]
            + [{"scene": scene, "coupling": "exchange_interpolated", "rms": e} for e in interpolated])


def test_the_exchange_that_wins_is_named_per_scene_from_the_errors():
    text = held_against_interpolated(rows("cuboid", [1.0, 2.0], [3.0, 4.0]) + rows("refined liver", [20.0], [5.0]))
    assert "held interface values give the smaller median RMS error on the cuboid (1.5 % against 3.5 %)" in text
    assert "interpolated ones on the refined liver (20 % against 5 %" in text
    text = held_against_interpolated(rows("cuboid", [3.0], [1.0]))
    assert "held interface values give the smaller" not in text and "interpolated ones on the cuboid" in text
    assert held_against_interpolated(rows("cuboid", [1.0], [])) == ""


def test_the_hybrid_liver_is_described_by_its_partition():
    from types import SimpleNamespace
    from pipeline.reports.haptic_regions import hybrid_words
    cfg = {"model": {"partition": {"kind": "sphere", "center": [-0.04, -0.05, 1.52], "radius": 0.03}}}
    rows = [{"scene": "liver, hybrid", "run": SimpleNamespace(config=cfg)}] * 2 + [{"scene": "liver"}]
    assert hybrid_words(rows) == "000's partition: TLED within 3 cm of (-4, -5, 152) cm, linear elsewhere"
    assert hybrid_words([{"scene": "liver"}]) == "no hybrid run"


def test_either_names_every_value_the_runs_took_once():
    from pipeline.tables import either
    assert either([10, 10.0, None], unit="N/m") == "10 N/m"
    assert either([20, 10], unit="N/m") == "10 or 20 N/m"
    assert either([None]) == "unknown"
    assert either(["grasp", "attached"], str) == "attached or grasp"


def test_the_share_of_the_exchange_in_the_bar_error_is_judged_per_rate():
    from pipeline.reports.async_table import exchange_words
    in_turn = [{"E": 5000, "n": 5, "vs_whole": {"rms_relative": 0.16}}]
    sweep = [{"E": 5000, "n": 5, "every": 2, "vs_whole": {"rms_relative": 0.25}},
             {"E": 5000, "n": 5, "every": 60, "vs_whole": {"rms_relative": 0.45}}]
    text = exchange_words(in_turn, sweep)
    assert "makes 0.36-0.64 of the sweep's RMS error" in text
    assert "most of it with the secondary region every 2 frames; less than half every 60 frames" in text
    assert "most of the error at every secondary rate" in exchange_words(in_turn, sweep[:1])
    assert "less than half at every secondary rate" in exchange_words(in_turn, sweep[1:])
