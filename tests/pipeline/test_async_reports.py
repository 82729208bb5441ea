"""The async_* reports (paper 001) on small synthetic async_sim artifacts: the tables hold the
values computed from the artifacts' numbers and series (units converted, rows ordered, errors
split into halves, second differences and settling times as defined)."""
import numpy as np
import pytest

from report_ctx import FakeContext, read_csv, run
from pipeline.reports import async_adaptive, async_inputs, async_solvers, async_table


def payload(solver="implicit/backward_euler", E=5000.0, t=None, whole=None, asyn=None, primary=None, every=20,
            interpolate=True, input_kind="chirp", inp=None, whole_time=40e-6, async_time=10e-6, vs_whole=(0.02, 0.05),
            exact=None, secondary_solver="implicit/backward_euler", step_limit=None):
    t = np.linspace(0.0, 1.0, 101) if t is None else t
    whole = np.sin(2 * np.pi * t) * 1e-3 if whole is None else whole
    asyn = whole + 1e-5 if asyn is None else asyn
    exact = whole if exact is None else exact
    p = {
        "model": {"youngs_modulus": E, "nodes": 40, "free_nodes": 39, "eq4_step_limit": 2e-3, "omega_max_bound": 1234.5},
        "whole": {"solver": solver, "seconds_per_frame": whole_time, "peak_force": float(np.abs(whole).max()),
                  "max_second_difference": 1e-7, "error_vs_exact": {"rms_relative": 0.003, "peak_relative": 0.006}},
        "exact": {"peak_force": float(np.abs(exact).max()), "loop_spectral_radius": 0.5},
        "haptics": {"frame_step": 1e-3, "probe_stiffness": 10.0},
        "input": dict({"kind": input_kind}, **(inp or {})),
        "series": {"time": t.tolist(), "force_whole": whole.tolist(), "force_async": asyn.tolist(),
                   "force_exact": exact.tolist(), "probe": (0.01 * t).tolist(), "contact_whole": (0.005 * t).tolist(),
                   "primary_nodes": [10] * len(t)},
    }
    if step_limit is not None:
        p["explicit_step_limit_in_use"] = step_limit
    prim = dict({"policy": "fixed", "min_nodes": 10, "max_nodes": 10}, **(primary or {}))
    p["async"] = {"primary": prim, "secondary": [{"every": every, "rate": 1000.0 / every, "solver": secondary_solver}],
                  "interpolate": interpolate, "primary_solver": "implicit/backward_euler",
                  "seconds_per_frame": async_time, "speed_gain": whole_time / async_time,
                  "peak_force": float(np.abs(asyn).max()), "max_second_difference": 2e-7,
                  "error_vs_whole": {"rms_relative": vs_whole[0], "peak_relative": vs_whole[1]},
                  "error_vs_exact": {"rms_relative": 0.025, "peak_relative": 0.04},
                  "primary_nodes": {"mean": float(prim["min_nodes"]), "min": prim["min_nodes"], "max": prim["max_nodes"]}}
    return p


# --------------------------------------------------------------------------- async_inputs
def test_second_difference_sees_a_jump_inside_the_window_only():
    t = np.arange(0, 1.0001, 0.01)
    f = 0.5 * t.copy()               # a ramp: second difference zero
    f[t >= 0.5] += 3e-3              # a jump of 3 mN at t = 0.5
    assert async_inputs.max_second_difference(f, t, [0.3, 0.7]) == pytest.approx(3e-3)
    assert async_inputs.max_second_difference(f, t, [0.7, 1.0]) == pytest.approx(0.0, abs=1e-15)
    assert async_inputs.max_second_difference(f, t, [2.0, 3.0]) is None


def test_settling_time_is_the_last_excursion_beyond_one_percent():
    t = np.arange(0, 2.0001, 0.001)
    f = 1.0 - np.exp(-(t - 0.5).clip(0) / 0.1)   # starts at 0.5 s, time constant 0.1 s
    f[-1] = 1.0
    # |f − 1| > 0.01 until exp(−τ/0.1) ≤ 0.01: τ = 0.1 ln 100 ≈ 460.5 ms after the start.
    assert async_inputs.settling_ms(f, t, 0.5) == pytest.approx(100 * np.log(100), abs=1.0)
    assert async_inputs.settling_ms(np.ones_like(t), t, 0.5) == 0.0


def test_inputs_table_holds_the_artifacts_values(tmp_path):
    t = np.arange(0, 1.0001, 0.01)
    whole = np.where(t >= 0.2, 2e-3, 0.0)
    held = whole.copy()
    held[t >= 0.6] += 1e-4                     # a step of 0.1 mN in the window
    interp = whole.copy()
    inp = {"amplitude": 0.001, "start_time": 0.2}
    runs = [run(payload(t=t, whole=whole, asyn=held, input_kind="step", inp=inp, interpolate=False), run_id="r#0"),
            run(payload(t=t, whole=whole, asyn=interp, input_kind="step", inp=inp, interpolate=True), run_id="r#1")]
    ctx = FakeContext(tmp_path, {"runs": runs}, params={"jump_window": {"step": [0.3, 1.0]}})
    async_inputs.report(ctx)
    rows = read_csv(tmp_path / "inputs.csv")
    assert rows[0] == async_inputs.HEADERS
    assert [r[1] for r in rows[1:]] == ["interpolated", "held"]       # interpolated first
    interp_row, held_row = rows[1], rows[2]
    assert float(interp_row[2]) == pytest.approx(2.0)                   # peak force whole, mN
    assert float(held_row[3]) == pytest.approx(2.1)                     # peak force regions, mN
    assert float(held_row[5]) == pytest.approx(2.0)                     # RMS error vs whole, %
    assert float(held_row[9]) == pytest.approx(100.0)                   # max |Δ²F| regions, µN
    assert float(interp_row[9]) == pytest.approx(0.0, abs=1e-9)
    assert float(interp_row[10]) == pytest.approx(0.0)                  # settled at once after the step
    assert (tmp_path / "summary_inputs.md").read_text().startswith("## Inputs")


# --------------------------------------------------------------------------- async_adaptive
def test_adaptive_table_splits_the_error_into_halves(tmp_path):
    t = np.linspace(0, 1, 200)
    whole = 1e-3 * np.sin(2 * np.pi * t)
    err = np.where(t < 0.5, 1e-6, 4e-6)                # small error first, larger later
    runs = [run(payload(t=t, whole=whole, asyn=whole + err), run_id="r#0"),
            run(payload(t=t, whole=whole, asyn=whole + 2 * err,
                        primary={"policy": "linear", "min_nodes": 10, "max_nodes": 30, "gradient": 4}), run_id="r#1")]
    ctx = FakeContext(tmp_path, {"runs": runs})
    async_adaptive.report(ctx)
    rows = read_csv(tmp_path / "table2.csv")
    assert rows[0] == async_adaptive.HEADERS
    assert [r[0] for r in rows[1:]] == ["fixed 10", "linear, gradient 4 (10-30)"]
    peak = np.abs(whole).max()
    for row, scale in zip(rows[1:], (1, 2)):
        assert float(row[11]) == pytest.approx(100 * scale * 1e-6 / peak)   # first half
        assert float(row[12]) == pytest.approx(100 * scale * 4e-6 / peak)   # second half
        assert float(row[2]) == pytest.approx(10.0) and float(row[3]) == pytest.approx(40.0)   # µs
        assert float(row[4]) == pytest.approx(4.0)
    words = (tmp_path / "summary_adaptive.md").read_text()
    assert f"the RMS error is {100 * 4e-6 / peak:.3g} % with 10 fixed nodes and {100 * 8e-6 / peak:.3g} %" in words


# --------------------------------------------------------------------------- async_solvers
def test_solvers_table_orders_the_solvers_and_converts_units(tmp_path):
    whole = [run(payload(solver=s, whole_time=w, step_limit=lim), run_id=f"w#{i}") for i, (s, w, lim) in
             enumerate([("explicit/central", 5e-6, 1.5e-3), ("static", 2e-6, None), ("implicit/newmark", 9e-6, None)])]
    mixed = [run(payload(secondary_solver=s, every=10), run_id=f"m#{i}") for i, s in enumerate(["static", "explicit/central"])]
    ctx = FakeContext(tmp_path, {"whole": whole, "mixed": mixed})
    async_solvers.report(ctx)
    rows = read_csv(tmp_path / "solvers.csv")
    assert [r[0] for r in rows[1:]] == ["static", "implicit/newmark", "explicit/central"]
    assert rows[1][1] == "" and float(rows[3][1]) == pytest.approx(1.5)    # step limit in ms
    assert [float(r[2]) for r in rows[1:]] == pytest.approx([2.0, 9.0, 5.0])   # µs per frame
    assert float(rows[1][5]) == pytest.approx(0.3)                           # RMS error vs exact, %
    mixed_rows = read_csv(tmp_path / "solvers_mixed.csv")
    assert [r[1] for r in mixed_rows[1:]] == ["explicit/central", "static"]
    assert all(r[2] == "10" for r in mixed_rows[1:])


# --------------------------------------------------------------------------- async_table
def sweep_rows():
    from pipeline.reports import async_common as C
    out = []
    for i, (n, every, rms, t_async) in enumerate([(5, 10, 0.004, 8e-6), (5, 20, 0.03, 6e-6), (10, 20, 0.08, 4e-6)]):
        out.append(C.run_row(run(payload(primary={"min_nodes": n, "max_nodes": n}, every=every, vs_whole=(rms, 2 * rms),
                                         async_time=t_async), run_id=f"s#{i}")))
    return out


def test_table1_lists_the_whole_model_then_each_setting(tmp_path):
    ctx = FakeContext(tmp_path)
    name, _ = async_table.table1(ctx, sweep_rows(), 5000.0)
    assert name == "table1_E5kPa"
    rows = read_csv(tmp_path / f"{name}.csv")
    assert rows[0] == async_table.T1_HEADERS
    assert rows[1][0] == "whole (39)" and float(rows[1][1]) == pytest.approx(1000.0)
    # Sorted by n, then by falling rate (every 10th frame = 100 Hz before every 20th = 50 Hz).
    assert [(r[0], float(r[1])) for r in rows[2:]] == [("5", 100.0), ("5", 50.0), ("10", 50.0)]
    assert [float(r[3]) for r in rows[2:]] == pytest.approx([8.0, 6.0, 4.0])
    assert [float(r[10]) for r in rows[2:]] == pytest.approx([0.4, 3.0, 8.0])
    assert float(rows[2][6]) == pytest.approx(40e-6 / 8e-6)           # against the median whole time


def test_tradeoff_picks_the_fastest_setting_within_each_error_budget(tmp_path):
    ctx = FakeContext(tmp_path)
    rows = sweep_rows()
    best = async_table.tradeoff(ctx, rows, [0.01, 0.05])
    assert best[(0.01, 5000.0)]["run"].id == "s#0"      # the only one under 1 %
    assert best[(0.05, 5000.0)]["run"].id == "s#1"      # the faster of the two under 5 %
    table = read_csv(tmp_path / "tradeoff.csv")
    assert [r[-1] for r in table[1:]] == ["", "≤ 5 %", "≤ 1 %"]      # fastest first
