"""The Pareto and partition sentences follow the configurations: the front's ends are named from
its points, a family is "fastest" only where it beats all-TLED, and two families of one strategy
and kind that differ in another partition setting get different labels."""
from types import SimpleNamespace

from pipeline.reports.dhd_pareto import front_sentence
from pipeline.reports import dhd_partition


def test_a_front_of_one_point_is_not_said_to_have_two_ends():
    pts = [(1.0, 0.0, "all TLED", {})]
    text = front_sentence("0.6 cm", [0], pts, {0: "all TLED"}, {})
    assert text == "At 0.6 cm, the front has 1 point (all TLED); no mixed configuration is on it."


def test_the_front_names_its_fastest_and_most_accurate_points():
    pts = [(1.0, 0.0, "x", {}), (0.6, 0.01, "layer, linear", {}), (0.5, 0.05, "y", {})]
    names = {0: "all TLED", 1: "layer, linear", 2: "all linear"}
    text = front_sentence("1 cm", [0, 1, 2], pts, names, {"layer, linear": 1})
    assert text.startswith("At 1 cm, the front has 3 points (all linear the fastest, all TLED the most accurate)")
    assert text.endswith("mixed configurations: 1 from layer, linear.")


def run(partition, strategy="distance"):
    return {"strategy": strategy, "cheap_kind": "linear", "run": SimpleNamespace(config={"partition": partition})}


def test_two_families_differing_in_a_partition_setting_get_two_labels():
    a = dhd_partition._family_key(run({"kind": "linear_fraction", "linear_fraction": 0.2, "distance": "euclidean"}))
    b = dhd_partition._family_key(run({"kind": "linear_fraction", "linear_fraction": 0.4, "distance": "geodesic"}))
    c = dhd_partition._family_key(run({"kind": "linear_fraction", "linear_fraction": 0.6, "distance": "euclidean"}))
    assert a == c != b
    labels = dhd_partition._family_labels([a, b])
    assert len(set(labels.values())) == 2
    assert labels[a] == "distance, linear (distance euclidean)" and labels[b] == "distance, linear (distance geodesic)"
    assert dhd_partition._family_labels([a]) == {a: "distance, linear"}


def test_a_family_is_fastest_only_where_it_beats_all_tled():
    cells = [("0.6 cm", "layer, linear", 1.0), ("0.6 cm", "strain, linear", 1.0),
             ("1 cm", "layer, linear", 1.2), ("1 cm", "strain, linear", 1.4)]
    text = dhd_partition.budget_sentence(0.02, cells, ["0.6 cm", "1 cm"])
    assert text == ("Within e ≤ 2 %, nothing beats all-TLED at 0.6 cm; the fastest at 1 cm is strain, linear "
                    "(1.4× all-TLED).")
    assert "fastest" not in dhd_partition.budget_sentence(0.02, [("1 cm", "layer, linear", None)], ["1 cm"])
