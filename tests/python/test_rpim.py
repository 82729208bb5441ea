"""rpim_precompute through Python: the executable's payload, and the superposition a linear
elastic model obeys."""
import json

import numpy as np

from conftest import import_softsim, make_artifact, payload, without_timing

softsim = import_softsim()

CONFIG = {"plate": {"nodes": [5, 5, 2], "background_cells": [4, 4, 1], "gauss_order": 3},
          "rpim": {"polynomial": "linear"},
          "dataset": {"kind": "random", "count": 4, "seed": 7}, "output": {"all_nodes": True}}


def test_dataset_equals_the_executables(tmp_path):
    cli = payload(make_artifact("rpim_precompute", CONFIG, tmp_path, mode="dataset"))
    assert without_timing(softsim.rpim_precompute(CONFIG)) == without_timing(cli)
    path = tmp_path / "c.json"
    path.write_text(json.dumps(CONFIG))
    assert without_timing(softsim.rpim_precompute(path, mode="dataset")) == without_timing(cli)


def test_every_case_is_the_superposition_of_the_unit_solutions():
    """Linear elasticity: the response to F is sum_d F_d u_d with u_d the unit-force responses
    (same factorised stiffness, so equal to round-off)."""
    p = softsim.rpim_precompute(CONFIG)
    unit = np.array(p["unit_solutions"])  # direction x top node x component
    assert len(p["cases"]) == 4
    for case in p["cases"]:
        force = np.array(case["force"])
        assert np.abs(force).min() > 0  # random forces load all three directions
        expected = np.tensordot(force, unit, axes=1)
        np.testing.assert_allclose(case["top_displacement"], expected, rtol=0, atol=1e-12 * np.abs(expected).max())
