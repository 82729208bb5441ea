"""The sentences of the Tables 2–3 report (000 §3.2) that state a fact, each computed from the
run's numbers rather than written for one set of results: whether the runs reached the static
solution, whether the error grows with the share r (ours and the paper's), how the two applied
displacements compare, and what the literal, transient reading shows. A changed config (less
damping, a shorter ramp, fewer steps) changes the words."""
from typing import Optional

from pipeline.tables import fmt

# A run counts as settled when its displacement field is within this fraction (e, experiments/dhd.md)
# of Newton's static solution of the same scene; params "settled_within" overrides it.
SETTLED_WITHIN = 0.01


def grows(values) -> bool:
    """Whether a sequence never decreases (the error against r)."""
    values = list(values)
    return all(b >= a for a, b in zip(values, values[1:]))


def first_fall(shares, values) -> Optional[tuple]:
    """The first pair of consecutive shares (percent) where the error falls, or None."""
    pairs = list(zip(shares, values))
    for (ra, a), (rb, b) in zip(pairs, pairs[1:]):
        if b < a:
            return ra, rb
    return None


def settle_state(settle, tolerance: float = SETTLED_WITHIN) -> Optional[dict]:
    """From [(load, r, e against the static solution)]: whether every compared run is within
    `tolerance`, and the worst one. None when no run was compared."""
    if not settle:
        return None
    worst = max(settle, key=lambda s: s[2])
    return {"settled": worst[2] <= tolerance, "worst": worst, "tolerance": tolerance, "compared": len(settle)}


def state_word(state: Optional[dict], steps: int) -> str:
    """"settled" only when the static check says so; otherwise what the runs are: a state after n steps."""
    return "settled" if state and state["settled"] else f"after {steps} steps"


def _where(worst, unit_scale, unit) -> str:
    return f"r = {fmt(100 * worst[1])} %, {fmt(worst[0] * unit_scale)} {unit}"


def settle_caption(state: Optional[dict], steps: int, unit_scale: float, unit: str) -> str:
    """The part of a table caption that says what state the runs compare."""
    if state is None:
        return f"{steps} steps (not compared with a static solution)"
    e = fmt(100 * state["worst"][2], 2)
    if state["settled"]:
        return (f"{steps} steps, settled: within {fmt(100 * state['tolerance'])} % of Newton's static solution "
                f"(largest difference {e} %)")
    return (f"{steps} steps, **not settled**: up to {e} % away from Newton's static solution "
            f"({_where(state['worst'], unit_scale, unit)}), so the table compares states still in motion")


def settle_sentence(state: Optional[dict], unit_scale: float, unit: str) -> str:
    if state is None:
        return ""
    e = fmt(100 * state["worst"][2], 2)
    where = _where(state["worst"], unit_scale, unit)
    if state["settled"]:
        return (f"The runs of the tables have settled: against Newton's static solution the largest difference "
                f"is {e} % ({where}), within the {fmt(100 * state['tolerance'])} % taken as settled.")
    return (f"The runs of the tables have not settled: against Newton's static solution they differ by up to {e} % "
            f"({where}), more than the {fmt(100 * state['tolerance'])} % taken as settled, so their errors mix the "
            "cheap elements' own error with a difference in motion.")


def trend_clause(ours_grow: bool, ours_fall, paper_grow: Optional[bool]) -> str:
    """"the error grows with r ..." compared with the paper's trend, both computed."""
    ours = "the error grows with r at every share" if ours_grow else \
        f"the error does not grow monotonically with r (it falls from r = {ours_fall[0]} % to {ours_fall[1]} %)"
    if paper_grow is None:
        return ours
    if ours_grow == paper_grow:
        return ours + (", as the paper's does" if paper_grow else "; neither does the paper's")
    return ours + (", while the paper's grows at every share it reports" if paper_grow
                   else ", while the paper's does not")


def load_clause(larger: int, shares: int, paper_larger: Optional[int], paper_shares: int) -> str:
    """How often the larger applied displacement gives the larger error, ours and the paper's."""
    ours = f"The larger displacement gives the larger error at {larger} of {shares} shares"
    if paper_larger is None or not paper_shares:
        return ours
    paper = f"at all {paper_shares}" if paper_larger == paper_shares else f"at {paper_larger} of {paper_shares}"
    return ours + f" (the paper: {paper})"


def ratio_clause(ratios) -> str:
    """"5.2–9.7 times below the paper's", or above, or on both sides, from paper / ours."""
    lo, hi = min(ratios), max(ratios)
    if lo >= 1:
        return f"{fmt(lo, 2)}–{fmt(hi, 2)} times below the paper's" if lo != hi else f"{fmt(lo, 2)} times below the paper's"
    if hi <= 1:
        return (f"{fmt(1 / hi, 2)}–{fmt(1 / lo, 2)} times above the paper's" if lo != hi
                else f"{fmt(1 / lo, 2)} times above the paper's")
    return f"between {fmt(1 / lo, 2)} times above and {fmt(hi, 2)} times below the paper's"


def transient_why(moving: Optional[float], tolerance: float, settled_share: Optional[float]) -> str:
    """Why the literal reading's error differs from the settled one, said only as far as the run
    shows it: `moving` is the all-TLED transient run's difference to the static solution,
    `settled_share` the largest ratio of the settled error to the transient one at the same r."""
    if moving is None:
        return ""
    if moving <= tolerance:
        return (f" The block has come to rest by then too ({fmt(100 * moving, 2)} % from the static solution at "
                "r = 0), so this error is not a difference in motion.")
    text = f" The block is still moving then ({fmt(100 * moving, 2)} % from the static solution at r = 0)"
    if settled_share is not None and settled_share < 0.5:
        return text + (f", and the settled error is at most {fmt(100 * settled_share, 2)} % of this one: most of it is "
                       "the difference in motion of two vibrating bodies of slightly different stiffness, so it "
                       "depends on the damping and on the step at which it is sampled, which the paper does not give.")
    return text + "; the settled error is of the same size, so the motion is not what makes this error."
