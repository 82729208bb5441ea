"""The cutting report's own computations: the boundary of what a cut leaves, and the damped
free fall it checks a loose piece against."""
import numpy as np

from pipeline.reports import cutting
from report_ctx import FakeContext, run


def test_boundary_of_the_elements_left_includes_the_cut_faces():
    # Two tets sharing the face (1, 2, 3): together 6 boundary faces; remove one, 4 are left.
    tets = np.array([[0, 1, 2, 3], [4, 1, 2, 3]])
    assert len(cutting.remaining_boundary(tets, [])) == 6
    left = cutting.remaining_boundary(tets, [1])
    assert len(left) == 4
    assert {tuple(sorted(f)) for f in left} == {(1, 2, 3), (0, 2, 3), (0, 1, 3), (0, 1, 2)}


def test_free_fall_check_is_zero_for_an_exact_damped_fall_and_sees_a_slower_one(tmp_path):
    alpha, g, tc = 20.0, 9.81, 0.25
    t = np.linspace(0.0, 0.5, 501)
    tau = np.clip(t - tc, 0.0, None)
    decay = (1 - np.exp(-alpha * tau)) / alpha
    z = -0.01 - g / alpha * (tau - decay)

    def ctx_for(zz):
        payload = {"trajectories": {"time": t.tolist(), "displacement": [[[0.0, 0.0, v] for v in zz]]},
                   "cuts": [{"time": tc}]}
        config = {"damping": {"alpha": alpha}, "boundary": {"gravity": {"acceleration": [0, 0, -g]}}}
        return FakeContext(tmp_path, runs={"through_cut": [run(payload, config)]})

    exact = cutting.free_fall_check(ctx_for(z))
    assert exact["difference"] < 1e-3 * exact["drop"]
    slow = cutting.free_fall_check(ctx_for(-0.01 + 0.5 * (z + 0.01)))
    assert slow["difference"] > 0.4 * exact["drop"]
