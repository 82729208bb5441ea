"""The element kinds of a "dhd_result" artifact, read from its "element_kind_legend": the
engine's one table of kinds (fem::kElementKinds, cpp/softsim/fem/element_kind.hpp) in code
order, entry k describing element_kind value k as {"name", "small_strain", "description"}.
Nothing in the pipeline lists the kinds itself."""
import numpy as np


def element_kinds(payload: dict) -> np.ndarray:
    """Each element's kind code."""
    return np.asarray(payload["element_kind"], dtype=int)


def kind_legend(payload: dict) -> list:
    """The element kinds of a dhd_result payload in code order (its "element_kind_legend", the
    engine's table fem::kElementKinds): [{"name", "small_strain", "description"}], entry k for
    element_kind value k."""
    legend = payload.get("element_kind_legend")
    if not isinstance(legend, list) or not legend or not all(isinstance(e, dict) and "name" in e for e in legend):
        raise ValueError("the dhd_result payload has no element_kind_legend of {\"name\", \"small_strain\"} "
                         "entries (an artifact of an older dhd_sim: run it again)")
    return legend


def kind_names(payload: dict) -> list:
    """Every element kind's name, in code order."""
    return [e["name"] for e in kind_legend(payload)]


def small_strain_kinds(payload: dict) -> list:
    """The names of the small-strain (cheap) kinds: linear stiffness, put away from the tool."""
    return [e["name"] for e in kind_legend(payload) if e.get("small_strain")]


def element_kind_names(payload: dict) -> np.ndarray:
    """Each element's kind name."""
    names = kind_names(payload)
    kinds = element_kinds(payload)
    bad = kinds[(kinds < 0) | (kinds >= len(names))]
    if len(bad):
        raise ValueError(f"element_kind {int(bad[0])} is not in the artifact's legend {names}")
    return np.asarray(names)[kinds] if len(kinds) else np.asarray([], dtype=str)


def kind_counts(payload: dict) -> dict:
    """{kind name: number of elements} for every kind of the legend (zero for absent ones)."""
    names = kind_names(payload)
    counts = {name: 0 for name in names}
    for name, n in zip(*np.unique(element_kind_names(payload), return_counts=True)):
        counts[str(name)] = int(n)
    return counts
