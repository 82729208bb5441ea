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
With --restore, the files whose only changes are timings are checked out again, so that
`git status` then shows the real changes alone."""
import csv
import io
import re
import subprocess
from pathlib import Path
from typing import Dict, List, Optional, Tuple

from pipeline.paths import RESULTS, ROOT

TIMING_HEADER = re.compile(
    r"time|µs|\bus\b|\bms\b|\(s\)|\bs\)|seconds|\bs per\b|per s\b|/s\b|speed|gain|rate|\bhz\b|wall|late|"
    r"p50|p99|median|real-time factor|throughput|set-?up|build|duration|frames? over",
    re.IGNORECASE)
TIMING_UNIT = re.compile(r"^\s?(ns|µs|us|ms|s|min|h|hz|khz|×|x)\b", re.IGNORECASE)
NUMBER = re.compile(r"[-+]?(?:\d+(?:[.,]\d+)*(?:\.\d+)?|\.\d+)(?:e[-+]?\d+)?", re.IGNORECASE)
BOOKKEEPING = re.compile(r"commit `|at commit|\bdirty\b|pipeline run ")
TEXT_SUFFIXES = {".csv", ".md", ".txt", ".json"}


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
def _numbers_equal(a: str, b: str) -> bool:
    try:
        return float(a) == float(b)
    except ValueError:
        return a == b


def compare_rows(old_rows: List[List[str]], new_rows: List[List[str]]) -> Tuple[int, Dict[str, int]]:
    """(timing cells changed, {header: real cells changed}) of two tables whose first row is the
    header; a changed header or row count is a real change of the whole table."""
    if not old_rows or not new_rows or old_rows[0] != new_rows[0] or len(old_rows) != len(new_rows):
        return 0, {"the table's shape or header": 1}
    header = new_rows[0]
    timing, real = 0, {}
    for old, new in zip(old_rows[1:], new_rows[1:]):
        if len(old) != len(new):
            real["a row's length"] = real.get("a row's length", 0) + 1
            continue
        for name, a, b in zip(header, old, new):
            if a == b or _numbers_equal(a, b):
                continue
            if TIMING_HEADER.search(name):
                timing += 1
            else:
                real[name] = real.get(name, 0) + 1
    return timing, real


def compare_prose(old: str, new: str) -> Tuple[int, Dict[str, int]]:
    """Lines of text outside tables: numbers that differ, timing when a time unit follows."""
    old_lines, new_lines = old.splitlines(), new.splitlines()
    if len(old_lines) != len(new_lines):
        return 0, {"the text's lines": abs(len(old_lines) - len(new_lines)) or 1}
    timing, real = 0, {}
    for a, b in zip(old_lines, new_lines):
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
            if TIMING_UNIT.match(ta[i + 1]):
                timing += 1
            else:
                real["numbers in the text"] = real.get("numbers in the text", 0) + 1
    return timing, real


def split_markdown(text: str) -> Tuple[List[List[List[str]]], str]:
    """The Markdown tables of `text` (rows of cells, separator rows dropped) and the rest of the
    text with each table replaced by one marker line."""
    tables, rest, current = [], [], None
    for line in text.splitlines():
        if line.startswith("|"):
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
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
    """{"real": [(path, {what: count})], "timing": [(path, cells)], "unchanged": [path],
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
            if real:
                out["real"].append((path, real))
            elif timing:
                out["timing"].append((path, timing))
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
        lines.append(f"timings only ({len(found['timing'])} files, "
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
    """Checks out again the files whose changes are timings or bookkeeping alone."""
    paths = [p for p, _ in found["timing"]] + found["unchanged"]
    if paths:
        _git("checkout", ref, "--", *paths)
    return paths
