"""The summary table at the top of results/REPORT.md: the headline result of each paper, our
measured number beside the paper's. Every number is read from the result tables the reports
wrote (results/<area>/*.csv), never typed here: each headline names a table, the row and the
columns to read; one whose table or row is missing is left out."""
import csv
from dataclasses import dataclass
from typing import Callable, List, Optional

from pipeline.paths import RESULTS
from pipeline.tables import fmt, markdown_table

Row = dict
Pick = Callable[[List[Row]], Optional[Row]]


def _number(text) -> Optional[float]:
    try:
        return float(text)
    except (TypeError, ValueError):
        return None


def where(**equal) -> Pick:
    """The first row whose columns hold these values."""
    return lambda rows: next((r for r in rows if all(r.get(k) == v for k, v in equal.items())), None)


def starting(column: str, prefix: str) -> Pick:
    return lambda rows: next((r for r in rows if (r.get(column) or "").startswith(prefix)), None)


def last_with(column: str) -> Pick:
    """The last row where `column` holds a number (the paper's largest tabulated case)."""
    return lambda rows: next((r for r in reversed(rows) if _number(r.get(column)) is not None), None)


@dataclass
class Headline:
    paper: str                 # "000 Table 1"
    claim: str                 # what is compared; {label} is the chosen row's label_column
    table: str                 # results/<table>.csv
    ours: str                  # column of our number
    theirs: Optional[str]      # column of the paper's number (None: the paper gives none we can read)
    pick_ours: Pick
    pick_theirs: Optional[Pick] = None   # another row for the paper's number (default: the same row)
    unit: str = ""
    label_column: str = ""
    no_paper: str = "–"        # what the paper column says when `theirs` is None
    extra: Optional[str] = None          # a second column of ours, shown after the first
    extra_unit: str = ""


HEADLINES = [
    Headline("000 Table 1", "explicit step with r = {label} linear elements: speed-up over all-TLED "
             "(cuboid of 14 450 tets; the paper's from its frame rates)", "dhd/table1",
             "speed-up vs r = 0 (ours)", "speed-up vs r = 0 (paper)", last_with("speed-up vs r = 0 (paper)"),
             unit="×", label_column="share of linear elements r"),
    Headline("000 Table 2", "mean displacement error e of DHD-FEA against all-TLED, r = {label}, 0.6 cm press",
             "dhd/table2", "mean error e (ours, %)", "mean error (paper, %)",
             last_with("mean error (paper, %)"), unit="%", label_column="share of linear elements r"),
    Headline("000 Table 3", "the same, 1 cm press, r = {label}", "dhd/table3", "mean error e (ours, %)",
             "mean error (paper, %)", last_with("mean error (paper, %)"), unit="%",
             label_column="share of linear elements r"),
    Headline("001 Table 1", "linked regions on the 1-D bar, n = 30 primary nodes, secondary every 2 frames: "
             "speed gain, and RMS force error against the whole model", "async/table1_E5kPa",
             "speed gain", None, where(**{"n (primary nodes)": "30", "every (frames)": "2"}), unit="×",
             no_paper="not legible in the paper's text; its findings are compared in the section",
             extra="RMS error vs whole (%)", extra_unit="%"),
    Headline("001 §5 (3-D)", "linked regions on the liver, 8 fixed-interface modes: RMS force error against "
             "the whole model, growing sine", "haptic/regions_modal", "RMS error (%)", None,
             where(scene="liver", input="growing sine", **{"far field": "8 modes"}), unit="%",
             no_paper="the paper shows 1-D results only"),
    Headline("002 eq. 49", "slope of the loaded node's z displacement against F_z (plate)", "rpim/fit_eq49",
             "our r1 [mm/N]", "paper r1 [mm/N]", where(relation="force along z"), unit="mm/N"),
    Headline("002 Table 3", "RMS error of the fitted surface per newton, force along z, z component "
             "(the paper's polynomial orders)", "rpim/fit_table3_rmse", "RMSE/F z [mm/N]", "paper z [mm/N]",
             where(fit="paper orders", force="force along z"), unit="mm/N"),
    Headline("002 §5.2", "node 61's u_z under F = (0.9, −0.7, −0.22) N: our RPIM against the paper's",
             "rpim/rpim_ansys_check", "u_z (mm)", "u_z (mm)", starting("model", "RPIM (this project)"),
             pick_theirs=where(model="paper: RPIM (002 §5.2)"), unit="mm"),
]


def _read(table: str) -> Optional[List[Row]]:
    path = RESULTS / f"{table}.csv"
    if not path.exists():
        return None
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def _value(row: Optional[Row], column: str, unit: str) -> Optional[str]:
    if row is None or column not in row:
        return None
    number = _number(row[column])
    if number is None:
        return None
    return fmt(number) + ("×" if unit == "×" else f" {unit}" if unit else "")


def headline_row(h: Headline) -> Optional[list]:
    rows = _read(h.table)
    if not rows:
        return None
    mine = h.pick_ours(rows)
    ours = _value(mine, h.ours, h.unit)
    if ours is None:
        return None
    if h.extra:
        extra = _value(mine, h.extra, h.extra_unit)
        if extra is None:
            return None
        ours = f"{ours}; {extra}"
    if h.theirs is None:
        theirs = h.no_paper
    else:
        theirs = _value((h.pick_theirs or h.pick_ours)(rows), h.theirs, h.unit)
        if theirs is None:
            return None
    claim = h.claim.format(label=(mine.get(h.label_column, "") if h.label_column else ""))
    link = f"[{h.table.split('/')[-1]}]({h.table}.md)" if (RESULTS / f"{h.table}.md").exists() else \
        f"[{h.table.split('/')[-1]}]({h.table}.csv)"
    return [h.paper, claim, ours, theirs, link]


def summary_table() -> str:
    """The summary as Markdown, or "" when no headline table exists yet."""
    rows = [r for r in (headline_row(h) for h in HEADLINES) if r is not None]
    if not rows:
        return ""
    return markdown_table(["paper", "what is compared", "ours (measured)", "the paper's", "table"], rows)
