"""The fits' playback through Python: marquardt_fit play's payload, and the same numbers as the
fit artifact's own assessment of its training data."""
import json
from pathlib import Path

import numpy as np
import pytest

from conftest import import_softsim, payload, run_tool

softsim = import_softsim()

# The model fitted on forces along z (conftest RECIPES): x and y components play nothing.
FORCES = [[0.0, 0.0, 0.5], [0.0, 0.0, -0.8], [0.3, -0.2, 0.25]]


@pytest.fixture(scope="module")
def fit(corpus_inputs):
    return Path(corpus_inputs.substitute("@FIT@")), Path(corpus_inputs.substitute("@DATASET_Z@"))


def test_play_fit_equals_marquardt_fit_play(fit, tmp_path):
    fit_path, reference = fit
    config = {"fit": str(fit_path), "forces": FORCES, "reference": str(reference)}
    (tmp_path / "c.json").write_text(json.dumps(config))
    assert run_tool("marquardt_fit", "play", "--config", tmp_path / "c.json", "--out", tmp_path / "p.json").returncode == 0
    cli = payload(tmp_path / "p.json")
    assert softsim.play_fit(config) == cli

    model = softsim.FitModel.load(fit_path)
    assert model.directions == ["z"] and model.loaded_node_index + 1 == cli["loaded_node"]
    assert np.array_equal(model.nodes, np.array(cli["top_nodes"]))
    played = model.play(FORCES)
    assert played.shape == (3, model.node_count, 3)
    assert np.array_equal(played, np.array([c["top_displacement"] for c in cli["cases"]]))
    assert np.array_equal(model.loaded_displacement(FORCES), np.array([c["relation1_displacement"] for c in cli["cases"]]))
    assert np.array_equal(model.play(FORCES[2]), played[2])  # one force: n x 3


def test_playback_reproduces_the_fits_assessment_of_its_training_data(fit):
    """The artifact's per-case training errors (fit against the RPIM displacements) come out of
    the same playback: the loaded node's fitted displacement and the largest error per component
    must be the artifact's to the last bit."""
    fit_path, dataset = fit
    model = softsim.FitModel.load(fit_path)
    rows = json.loads(fit_path.read_text())["payload"]["training"]["z"]["per_case"]
    cases = payload(dataset)["cases"]
    assert len(rows) == len(cases) == 6
    for row, case in zip(rows, cases):
        assert row["force"] == case["force"]
        u = model.play(case["force"])
        assert u[model.loaded_node_index].tolist() == row["loaded_node_fit"]
        assert np.abs(u - np.array(case["top_displacement"])).max(axis=0).tolist() == row["fit_max_abs"]


def test_model_dict_round_trip_plays_the_same(fit):
    fit_path, _ = fit
    model = softsim.load_fit_model(fit_path)
    model_dict = json.loads(fit_path.read_text())["payload"]["model"]
    assert model.to_dict() == model_dict
    again = softsim.load_fit_model(model_dict)
    assert np.array_equal(again.play(FORCES), model.play(FORCES))


def test_forces_of_the_wrong_shape_or_not_finite_are_input_errors(fit):
    model = softsim.FitModel.load(fit[0])
    with pytest.raises(softsim.InputError, match=r"shape \(2\)"):
        model.play([1.0, 2.0])
    with pytest.raises(softsim.InputError, match="finite"):
        model.play([[0.0, 0.0, float("nan")]])
    with pytest.raises(softsim.InputError, match=r"^<dict>: /basis: missing required field"):
        softsim.FitModel.from_dict({})
