"""Running CalculiX (`ccx`) and reading its results: the part shared by the tetrahedral-mesh
runner (pipeline/stages/calculix.py) and the hexahedral plate runner (calculix_plate.py).

CalculiX is an independent solver: the project uses it only as a reference for its own
solvers. Everything here is plain text in and out:
  * the input deck is written into a fresh temporary directory and `ccx -i job` runs there;
  * results come from the .dat file (*NODE PRINT), which holds 7 significant digits;
  * the .sta file tells how many increments and iterations the step took.
A failure never leaves a half-written artifact: callers write their artifact only after every
number has been parsed and checked.
"""
import math
import os
import re
import shutil
import subprocess
import tempfile
from pathlib import Path

CCX_EXECUTABLE = "ccx"
JOB_NAME = "job"


class CalculixError(RuntimeError):
    """CalculiX is missing, rejected the deck or crashed (not a numerical failure)."""


class CalculixNumericalError(ArithmeticError):
    """CalculiX ran but the solution failed: no convergence, an inverted element, a singular
    system, a step that did not reach its end time, or a non-finite number in the results."""


# --------------------------------------------------------------------------- deck writing
CCX_FIELD_WIDTH = 20


def fmt(x: float) -> str:
    """A float in the deck. CalculiX reads only the first 20 characters of a data field
    (Fortran f20.0) and silently ignores the rest, so the shortest round-trip representation
    is used when it fits and otherwise as many significant digits as fit (>= 13)."""
    x = float(x)
    if not math.isfinite(x):
        raise ValueError(f"non-finite number {x!r} in a CalculiX deck")
    text = repr(x)
    digits = 16
    while len(text) > CCX_FIELD_WIDTH:
        text = f"{x:.{digits}g}"
        digits -= 1
    return text


def mesh_lines(positions, element_type: str, elements) -> list:
    """*NODE (set NALL) and *ELEMENT (set EALL) lines; `elements` hold 1-based node ids."""
    L = ["*NODE, NSET=NALL"]
    L += [f"{n + 1}, {fmt(x)}, {fmt(y)}, {fmt(z)}" for n, (x, y, z) in enumerate(positions)]
    L.append(f"*ELEMENT, TYPE={element_type}, ELSET=EALL")
    for e, conn in enumerate(elements):
        ids = [str(e + 1)] + [str(n) for n in conn]
        # A data line holds at most 16 entries; C3D20 continues on the next line.
        L.append(", ".join(ids[:16]) + ("," if len(ids) > 16 else ""))
        if len(ids) > 16:
            L.append(", ".join(ids[16:]))
    return L


def _id_lines(ids) -> list:
    """Ids 16 to a data line (the most a line holds)."""
    ids = [str(n) for n in ids]
    return [", ".join(ids[k:k + 16]) for k in range(0, len(ids), 16)]


def nset_lines(name: str, ccx_nodes) -> list:
    return [f"*NSET, NSET={name}"] + _id_lines(ccx_nodes)


def elset_lines(name: str, ccx_elements) -> list:
    return [f"*ELSET, ELSET={name}"] + _id_lines(ccx_elements)


def material_lines(info: dict, name: str = "MAT") -> list:
    """*MATERIAL of a material read by calculix_scene.read_material: its card and constants."""
    lines = [f"*MATERIAL, NAME={name}", info["ccx_card"]]
    constants = info["ccx_constants"]
    for k in range(0, len(constants), 8):  # at most eight constants a data line
        lines.append(", ".join(fmt(c) for c in constants[k:k + 8]))
    return lines


def field_controls_lines(residual_tolerance: float, correction_tolerance: float) -> list:
    """*CONTROLS, PARAMETERS=FIELD: the first two entries are CalculiX's R^alpha_n (residual
    force relative to the average force) and C^alpha_n (largest correction relative to the
    largest incremental displacement); their defaults (0.005, 0.01) are meant for engineering
    use, a reference solution needs tighter ones."""
    return ["*CONTROLS, PARAMETERS=FIELD",
            f"{fmt(residual_tolerance)}, {fmt(correction_tolerance)}"]


def static_step_lines(nlgeom: bool, increments: int, max_increments: int, min_increment: float,
                      fixed_increments: bool) -> list:
    """*STEP + *STATIC. Without NLGEOM CalculiX solves the linear problem in one increment."""
    if not nlgeom:
        return ["*STEP", "*STATIC"]
    inc = 1.0 / increments
    return [f"*STEP, NLGEOM, INC={max_increments}",
            "*STATIC, DIRECT" if fixed_increments else "*STATIC",
            f"{fmt(inc)}, 1.0, {fmt(min(min_increment, inc))}, {fmt(inc)}"]


def section_and_step_lines(material: dict, analysis: dict) -> list:
    """The material (named MAT) as the solid section of every element (EALL), then the opening
    of the static step (`analysis` as read by calculix.read_analysis) and, with NLGEOM, its
    Newton tolerances."""
    L = material_lines(material)
    L.append("*SOLID SECTION, ELSET=EALL, MATERIAL=MAT")
    L += static_step_lines(analysis["nlgeom"], analysis["increments"], analysis["max_increments"],
                           analysis["min_increment"], analysis["fixed_increments"])
    if analysis["nlgeom"]:
        L += field_controls_lines(analysis["residual_tolerance"], analysis["correction_tolerance"])
    return L


# --------------------------------------------------------------------------- running
def find_ccx() -> str:
    path = shutil.which(CCX_EXECUTABLE)
    if path is None:
        raise CalculixError("CalculiX executable `ccx` not found on PATH "
                            "(Debian package calculix-ccx; `make setup` installs it)")
    return path


_version_cache = {}


def ccx_version(exe=None) -> str:
    """The version CalculiX reports (`ccx -v` prints "This is Version 2.20")."""
    exe = exe or find_ccx()
    if exe not in _version_cache:
        proc = subprocess.run([exe, "-v"], capture_output=True, text=True, timeout=60)
        m = re.search(r"Version\s+(\S+)", proc.stdout + proc.stderr)
        _version_cache[exe] = m.group(1) if m else "unknown"
    return _version_cache[exe]


_NUMERICAL_MARKERS = (
    "jacobian", "increment size smaller than minimum", "too many cutbacks", "divergence",
    "no convergence", "did not converge", "singular", "zero pivot",
)


def run_deck(deck: str, timeout: float = 1800.0):
    """Runs one input deck in a fresh temporary directory. Returns (dat_text, sta_text, log).
    Raises CalculixError (missing ccx, rejected deck, crash) or CalculixNumericalError."""
    exe = find_ccx()
    env = dict(os.environ)
    # One thread: the machine is shared and the result must not depend on the thread count.
    env["OMP_NUM_THREADS"] = "1"
    env["CCX_NPROC_STIFFNESS"] = "1"
    env["CCX_NPROC_EQUATION_SOLVER"] = "1"
    env["CCX_NPROC_RESULTS"] = "1"
    with tempfile.TemporaryDirectory(prefix="ccx_") as tmp:
        Path(tmp, JOB_NAME + ".inp").write_text(deck)
        try:
            proc = subprocess.run([exe, "-i", JOB_NAME], cwd=tmp, env=env, capture_output=True,
                                  text=True, timeout=timeout)
        except subprocess.TimeoutExpired:
            raise CalculixError(f"ccx did not finish within {timeout:g} s") from None
        log = proc.stdout + proc.stderr
        dat_path = Path(tmp, JOB_NAME + ".dat")
        sta_path = Path(tmp, JOB_NAME + ".sta")
        dat = dat_path.read_text(errors="replace") if dat_path.exists() else ""
        sta = sta_path.read_text(errors="replace") if sta_path.exists() else ""
    errors = [l.strip() for l in log.splitlines() if "*ERROR" in l]
    if proc.returncode != 0 or errors:
        # The line after "*ERROR ..." often completes the message (e.g. the element number).
        lines = log.splitlines()
        detail = ""
        for i, l in enumerate(lines):
            if "*ERROR" in l:
                detail = " ".join(x.strip() for x in lines[i:i + 3] if x.strip())
                break
        detail = detail or (lines[-1].strip() if lines else "no output")
        message = f"ccx exited with code {proc.returncode}: {detail}"
        if any(m in detail.lower() for m in _NUMERICAL_MARKERS):
            raise CalculixNumericalError(message)
        raise CalculixError(message)
    return dat, sta, log


# --------------------------------------------------------------------------- result parsing
_HEADER = re.compile(r"^\s*(.+?)\s+\(([^)]*)\)\s+for set\s+(\S+)\s+and time\s+(\S+)\s*$")
# Fortran's E13.6 drops the "E" when the exponent has three digits: 1.234567-100.
_FORTRAN_EXP = re.compile(r"^([+-]?\d*\.?\d+)([+-]\d{3})$")


def _parse_float(token: str) -> float:
    m = _FORTRAN_EXP.match(token)
    if m:
        token = m.group(1) + "E" + m.group(2)
    return float(token)


def parse_dat(text: str) -> list:
    """Blocks of a .dat file: dicts with `quantity` ("displacements", "forces",
    "total force", ...), `set` (upper case), `time`, `rows` ({ccx node: [3 floats]}) and
    `total` (3 floats, for TOTALS blocks)."""
    blocks = []
    current = None
    for line in text.splitlines():
        m = _HEADER.match(line)
        if m:
            current = {"quantity": m.group(1).strip(), "set": m.group(3).upper(),
                       "time": _parse_float(m.group(4)), "rows": {}, "total": None}
            blocks.append(current)
            continue
        tokens = line.split()
        if current is None or not tokens:
            continue
        try:
            if len(tokens) == 4:
                current["rows"][int(tokens[0])] = [_parse_float(t) for t in tokens[1:]]
            elif len(tokens) == 3:
                current["total"] = [_parse_float(t) for t in tokens]
        except ValueError:
            raise CalculixError(f"unreadable line in the ccx .dat file: {line.strip()!r}") from None
    return blocks


def last_block(blocks: list, quantity: str, set_upper: str, end_time: float = 1.0) -> dict:
    """The block of `quantity` for `set` at the end of the step; a step that stopped before its
    end time is a numerical failure."""
    found = [b for b in blocks if b["quantity"] == quantity and b["set"] == set_upper]
    if not found:
        raise CalculixError(f"ccx wrote no \"{quantity}\" for set {set_upper}")
    block = found[-1]
    if abs(block["time"] - end_time) > 1e-6 * max(1.0, end_time):
        raise CalculixNumericalError(
            f"ccx stopped at step time {block['time']:g} before the end time {end_time:g}")
    for row in list(block["rows"].values()) + ([block["total"]] if block["total"] else []):
        if not all(math.isfinite(v) for v in row):
            raise CalculixNumericalError(f"ccx wrote a non-finite {quantity} for set {set_upper}")
    return block


def parse_sta(text: str) -> dict:
    """Increments and Newton iterations of the step from the .sta summary (rows: STEP INC ATT
    ITRS TOT-TIME STEP-TIME INC-TIME; an attempt marked "U" was cut back)."""
    increments = iterations = cutbacks = 0
    for line in text.splitlines():
        tokens = line.split()
        if len(tokens) != 7 or not tokens[0].isdigit():
            continue
        if tokens[2].endswith("U"):
            cutbacks += 1
            continue
        increments += 1
        try:
            iterations += int(tokens[3])
        except ValueError:
            pass
    return {"increments_taken": increments, "iterations": iterations, "cutbacks": cutbacks}


def step_statistics(sta_text: str, nlgeom: bool) -> dict:
    """parse_sta for a NLGEOM step; a linear step is one increment with one solve."""
    if not nlgeom:
        return {"increments_taken": 1, "iterations": 1, "cutbacks": 0}
    return parse_sta(sta_text)


def sorted_rows(block: dict, ccx_nodes) -> list:
    """The rows of a block in the given ccx-node order; a missing node is an error."""
    out = []
    for n in ccx_nodes:
        row = block["rows"].get(n)
        if row is None:
            raise CalculixError(f"ccx wrote no {block['quantity']} for node {n}")
        out.append(row)
    return out
