"""A fit whose forces take one value means nothing (played back, every force would give the same
displacement): marquardt_fit refuses it with exit 3 whether the orders are fixed or chosen by
cross-validation, and writes no artifact."""
import json

import pytest

from conftest import run_tool, write_json
from test_bad_input import Inputs


@pytest.mark.parametrize("value", [0.0, 0.5])
@pytest.mark.parametrize("orders", ["cv", "fixed"])
def test_forces_of_one_value_are_refused(tmp_path, value, orders):
    dataset = json.loads(Inputs(tmp_path).dataset("z").read_text())
    for case in dataset["payload"]["cases"]:
        case["force"] = [0.0, 0.0, value]
    flat = write_json(tmp_path / "flat.json", dataset)
    config = {"datasets": {"z": str(flat)}, "timing": {"evaluations": 0}}
    if orders == "cv":
        config["cv"] = {"folds": 3, "max_orders": {"force": 2, "surface": [2, 2], "bivariate": 2, "parameters": 1}}
    else:
        config["orders"] = {"z": {"force": 1, "components": {
            c: {"surface": {"model": "separable", "orders": [2, 2]}, "parameters": 1} for c in "xyz"}}}
    out = tmp_path / "fit.json"
    r = run_tool("marquardt_fit", "fit", "--config", write_json(tmp_path / "c.json", config), "--out", out)
    assert r.returncode == 3, r.stderr
    assert "relation 1" in r.stderr and "ill_conditioned" in r.stderr, r.stderr
    assert not out.exists()
