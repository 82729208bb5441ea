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


def test_cut_mesh_appends_node_copies_and_repoints_moved_elements():
    # Two tets sharing the face (1, 2, 3), separated along it: the second takes copies 4, 5, 6 of
    # nodes 1, 2, 3; the boundary of what is left is then the 8 faces of two loose tets.
    mesh = {"nodes": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1]], "tets": [[0, 1, 2, 3], [4, 1, 2, 3]]}
    payload = {"node_copies": [[1, 5], [2, 6], [3, 7]], "moved_elements": [[1, 4, 5, 6, 7]]}
    nodes, tets = cutting.cut_mesh(mesh, payload)
    assert nodes.shape == (8, 3)
    assert np.array_equal(nodes[5:], nodes[1:4])
    assert tets.tolist() == [[0, 1, 2, 3], [4, 5, 6, 7]]
    assert len(cutting.remaining_boundary(tets, [])) == 8
    same_nodes, same_tets = cutting.cut_mesh(mesh, {})
    assert same_nodes.shape == (5, 3) and same_tets.tolist() == mesh["tets"]
