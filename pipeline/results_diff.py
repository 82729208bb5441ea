"""`pipeline diff`: a rerun's results/ against the committed ones (git), sorted into real changes
and timing noise.

A rerun on another machine (or the same one, busier) rewrites every table that holds a measured
time, so `git status` lists files where nothing but timings moved. This compares each changed
text file with its committed version value by value:
  - CSV and Markdown tables: a cell that differs counts as timing when its column's header names
    a time, a rate or a speed (TIMING_HEADER), else as a real change;
  - prose (summaries): a differing number counts as timing when a time unit follows it
    (TIMING_UNIT), else as a real change; the provenance lines (which commit ran what) are
    bookkeeping;
  - the manifest and binary files (plots, VTU) are listed apart, not judged.
A number that moved by less than ROUNDOFF of its column's largest magnitude (of its own, in
prose), or by less than ZERO, is round-off: another compiler, CPU or summation order gives such last-digit changes in
every floating-point result, and they are counted apart, not as real changes.
With --restore, the files whose only changes are timings and round-off are checked out again, so
that `git status` then shows the real changes alone."""
import csv
import io
import re
import subprocess
from pathlib import Path
from typing import Dict, List, Optional, Tuple

from pipeline.paths import RESULTS, ROOT

TIMING_HEADER = re.compile(
    r"time|µs|\bus\b|\bms\b|\(s\)|\bs\)|seconds|\bs per\b|per s\b|/s\b|speed|gain|rate|\bhz\b|wall|late|"
    r"p50|p99|median|real-time factor|throughput|set-?up|build|duration|frames? over|\bns\b|(vs|/) all-TLED",
    re.IGNORECASE)
TIMING_UNIT = re.compile(r"^\s?(ns|[µμ]s|us|ms|s|min|h|hz|khz|×|x|steps/s)(?!\w)", re.IGNORECASE)
NUMBER = re.compile(r"[-+]?(?:\d+(?:[.,]\d+)*(?:\.\d+)?|\.\d+)(?:e[-+]?\d+)?", re.IGNORECASE)
BOOKKEEPING = re.compile(r"commit `|at commit|\"commit\":|\bdirty\b|pipeline run ")
# The machine a timing ran on, as the reports name it (its CPU model): not a result.
CPU = re.compile(r"\b(?:Intel|AMD|Apple|ARM|Ampere)\b(?:\((?:R|TM)\)|[^;).])*?(?=\)|;|\. |$)")
TEXT_SUFFIXES = {".csv", ".md", ".txt", ".json"}
ROUNDOFF = 1e-6
ZERO = 1e-12  # below this a difference is round-off whatever the scale (a quantity that is zero)


def _git(*args) -> str:
    return subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True, check=True).stdout


def changed_files(ref: str) -> List[str]:
    """Repository-relative paths under results/ that differ from `ref` (and new, untracked ones)."""
    folder = str(RESULTS.resolve().relative_to(ROOT.resolve()))
    changed = _git("diff", "--name-only", ref, "--", folder).split()
    new = _git("ls-files", "--others", "--exclude-standard", "--", folder).split()
    return sorted(set(changed) | set(new))


def committed_text(ref: str, path: str) -> Optional[str]:
    r = subprocess.run(["git", "show", f"{ref}:{path}"], cwd=ROOT, capture_output=True)
    return r.stdout.decode("utf-8", errors="replace") if r.returncode == 0 else None


# ----------------------------------------------------------------------------- comparison
ROUNDOFF_KEY = "round-off"


def _float(text: str) -> Optional[float]:
    try:
        return float(text.replace(",", "")) if text.strip() else None
    except ValueError:
        return None


def _column_scales(rows: List[List[str]], width: int) -> List[float]:
    scales = [0.0] * width
    for row in rows:
        for i, cell in enumerate(row[:width]):
            x = _float(cell)
            if x is not None and abs(x) != float("inf"):
                scales[i] = max(scales[i], abs(x))
    return scales


def _add(counts: Dict[str, int], key: str, n: int = 1) -> None:
    counts[key] = counts.get(key, 0) + n


def compare_rows(old_rows: List[List[str]], new_rows: List[List[str]]) -> Tuple[int, Dict[str, int]]:
    """(timing cells changed, {header: real cells changed, "round-off": cells}) of two tables
    whose first row is the header; a changed header or row count is a real change of the whole
    table."""
    if not old_rows or not new_rows or old_rows[0] != new_rows[0] or len(old_rows) != len(new_rows):
        return 0, {"the table's shape or header": 1}
    header = new_rows[0]
    scales = _column_scales(old_rows[1:] + new_rows[1:], len(header))
    timing, real = 0, {}
    for old, new in zip(old_rows[1:], new_rows[1:]):
        if len(old) != len(new):
            _add(real, "a row's length")
            continue
        for name, scale, a, b in zip(header, scales, old, new):
            if a == b:
                continue
            x, y = _float(a), _float(b)
            # A time is named by its column, or by its row where the first column names the quantity.
            if TIMING_HEADER.search(name) or TIMING_HEADER.search(old[0]):
                timing += 1
            elif x is not None and y is not None and abs(x - y) <= max(ROUNDOFF * scale, ZERO):
                _add(real, ROUNDOFF_KEY)
            else:
                _add(real, name)
    return timing, real


def compare_prose(old: str, new: str) -> Tuple[int, Dict[str, int]]:
    """Lines of text outside tables: numbers that differ, timing when a time unit follows."""
    old_lines, new_lines = old.splitlines(), new.splitlines()
    if len(old_lines) != len(new_lines):
        return 0, {"the text's lines": abs(len(old_lines) - len(new_lines)) or 1}
    timing, real = 0, {}
    for a, b in zip(old_lines, new_lines):
        a, b = CPU.sub("<cpu>", a), CPU.sub("<cpu>", b)
        if a == b or BOOKKEEPING.search(a) and BOOKKEEPING.search(b):
            continue
        ta, tb = NUMBER.split(a), NUMBER.split(b)
        na, nb = NUMBER.findall(a), NUMBER.findall(b)
        if ta != tb or len(na) != len(nb):
            real["text"] = real.get("text", 0) + 1
            continue
        for i, (x, y) in enumerate(zip(na, nb)):
            if x == y:
                continue
            fx, fy = _float(x), _float(y)
            if _unit_follows(ta, i):
                timing += 1
            elif fx is not None and fy is not None and abs(fx - fy) <= max(ROUNDOFF * max(abs(fx), abs(fy)), ZERO):
                _add(real, ROUNDOFF_KEY)
            else:
                _add(real, "numbers in the text")
    return timing, real


def _cells(line: str) -> List[str]:
    """A Markdown table row's cells. Our tables are written "| a | b |" (pipeline.tables), so
    " | " separates cells and a "|" inside one (|u_x/F_x|) stays in it."""
    line = line.strip()
    if line.startswith("| ") and line.endswith(" |"):
        return [c.strip() for c in line[2:-2].split(" | ")]
    return [c.strip() for c in line.strip("|").split("|")]


def _unit_follows(texts: List[str], i: int) -> bool:
    """Whether number i of a line split at its numbers (texts[i] before it, texts[i + 1] after)
    is a time: a time unit follows it, perhaps after a range's second number ("0.711-0.841 µs"),
    or words that name a time or a speed stand just before it."""
    before = re.split(r"[;,.:(]", texts[i][-24:])[-1]  # within the same clause
    if TIMING_HEADER.search(before):  # "speed gain 1.13", "a speed-up of 1.35"
        return True
    j = i + 1
    while j < len(texts) - 1 and texts[j].strip() in ("", "-", "–", "to", "and"):
        j += 1
    return j < len(texts) and bool(TIMING_UNIT.match(texts[j]))


def split_markdown(text: str) -> Tuple[List[List[List[str]]], str]:
    """The Markdown tables of `text` (rows of cells, separator rows dropped) and the rest of the
    text with each table replaced by one marker line."""
    tables, rest, current = [], [], None
    for line in text.splitlines():
        if line.startswith("|"):
            cells = _cells(line)
            if current is None:
                current = []
                tables.append(current)
                rest.append("<table>")
            if not all(re.fullmatch(r":?-{3,}:?", c) for c in cells):
                current.append(cells)
        else:
            current = None
            rest.append(line)
    return tables, "\n".join(rest)


def compare_text(suffix: str, old: str, new: str) -> Tuple[int, Dict[str, int]]:
    if suffix == ".csv":
        return compare_rows(list(csv.reader(io.StringIO(old))), list(csv.reader(io.StringIO(new))))
    tables_old, prose_old = split_markdown(old)
    tables_new, prose_new = split_markdown(new)
    timing, real = compare_prose(prose_old, prose_new)
    if len(tables_old) != len(tables_new):
        real["tables"] = real.get("tables", 0) + 1
        return timing, real
    for a, b in zip(tables_old, tables_new):
        t, r = compare_rows(a, b)
        timing += t
        for k, n in r.items():
            real[k] = real.get(k, 0) + n
    return timing, real


# ----------------------------------------------------------------------------- the command
def classify(ref: str = "HEAD") -> Dict[str, list]:
    """{"real": [(path, {what: count})], "timing": [(path, values: timings and round-off)], "unchanged": [path],
    "new": [path], "not compared": [path]} for every file under results/ that differs from ref."""
    out = {"real": [], "timing": [], "unchanged": [], "new": [], "not compared": []}
    for path in changed_files(ref):
        file = ROOT / path
        suffix = Path(path).suffix
        old = committed_text(ref, path)
        if old is None:
            out["new"].append(path)
        elif not file.exists():
            out["real"].append((path, {"removed": 1}))
        elif suffix not in TEXT_SUFFIXES or Path(path).name == "manifest.json":
            out["not compared"].append(path)
        else:
            timing, real = compare_text(suffix, old, file.read_text(errors="replace"))
            roundoff = real.pop(ROUNDOFF_KEY, 0)
            if real:
                out["real"].append((path, real))
            elif timing or roundoff:
                out["timing"].append((path, timing + roundoff))
            else:
                out["unchanged"].append(path)  # only bookkeeping or formatting moved
    return out


def report(found: Dict[str, list], ref: str) -> str:
    lines = [f"pipeline diff: results/ against {ref}"]
    if found["real"]:
        lines.append(f"real changes ({len(found['real'])} files):")
        for path, what in found["real"]:
            lines.append(f"  {path}: " + ", ".join(f"{k} ({n})" for k, n in what.items()))
    for key, label in (("new", "new files"), ("not compared", "changed, not compared (manifest, plots, binaries)")):
        if found[key]:
            lines.append(f"{label} ({len(found[key])}): " + ", ".join(found[key]))
    if found["timing"]:
        lines.append(f"timings and round-off only ({len(found['timing'])} files, "
                     f"{sum(n for _, n in found['timing'])} values): " + ", ".join(p for p, _ in found["timing"]))
    if found["unchanged"]:
        lines.append(f"bookkeeping only (commits in provenance lines; {len(found['unchanged'])}): "
                     + ", ".join(found["unchanged"]))
    if len(lines) == 1:
        lines.append("no file under results/ differs")
    return "\n".join(lines)


def one_line(ref: str = "HEAD") -> str:
    """After a run: how results/ now differs from the committed results, in one line ("" when
    results/ is not a tracked folder of this repository, or git cannot tell)."""
    try:
        RESULTS.resolve().relative_to(ROOT.resolve())
        found = classify(ref)
    except (ValueError, OSError, subprocess.CalledProcessError):
        return ""
    if not any(found.values()):
        return "results/ as committed"
    return (f"results/ against {ref}: {len(found['real'])} files with real changes, {len(found['timing'])} with "
            f"timings alone, {len(found['new'])} new, {len(found['not compared'])} not compared "
            "(`pipeline diff` lists them; `pipeline diff --restore` keeps only the real changes)")


def restore(found: Dict[str, list], ref: str) -> List[str]:
    """Checks out again the files whose changes are timings, round-off or bookkeeping alone."""
    paths = [p for p, _ in found["timing"]] + found["unchanged"]
    if paths:
        _git("checkout", ref, "--", *paths)
    return paths
