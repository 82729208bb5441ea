"""Tables as Markdown (for reading) and CSV (for reuse), written side by side."""
import csv
import math

from pipeline.artifacts import write_atomic, write_text_atomic


# Magnitudes written as plain numbers; outside them exponent notation reads better (condition
# numbers, residuals at round-off).
PLAIN_RANGE = (1e-3, 1e6)


def either(values, fmt_one=lambda v: f"{v:g}", unit="") -> str:
    """The values a sentence about several runs states: "10 N/m", or "10 or 20 N/m" where the runs
    differ, "unknown" where none recorded one (None values are left out)."""
    vals = sorted({v for v in values if v is not None}, key=lambda v: (isinstance(v, str), v))
    if not vals:
        return "unknown"
    return " or ".join(fmt_one(v) for v in vals) + (f" {unit}" if unit else "")


def fmt(value, digits=4):
    """Compact, honest formatting: `digits` significant digits, no false precision. Numbers in
    PLAIN_RANGE are written plainly: from 10**(digits - 1) on with their whole integer part
    (12345.6 -> 12346; `g` would switch to exponent notation at 10**digits, and rounding the
    integer part to zeros, 12350, would hide digits that were measured)."""
    if value is None:
        return "–"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            return str(value)
        if value == 0:
            return "0"
        magnitude = abs(value)
        if not PLAIN_RANGE[0] <= magnitude < PLAIN_RANGE[1]:
            return f"{value:.{max(1, digits - 1)}e}"
        if magnitude >= 10 ** (digits - 1):
            return f"{value:.0f}"
        return f"{value:.{digits}g}"
    return str(value)


def markdown_table(headers, rows) -> str:
    lines = ["| " + " | ".join(str(h) for h in headers) + " |",
             "| " + " | ".join("---" for _ in headers) + " |"]
    for row in rows:
        lines.append("| " + " | ".join(fmt(v) for v in row) + " |")
    return "\n".join(lines) + "\n"


def write_table(ctx, name: str, headers, rows, caption: str = "") -> str:
    """Writes results/<sub>/<name>.md and <name>.csv; returns the Markdown text."""
    md = (f"{caption}\n\n" if caption else "") + markdown_table(headers, rows)
    write_text_atomic(ctx.out(f"{name}.md"), md)

    def write_csv(tmp):
        with open(tmp, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(headers)
            for row in rows:
                w.writerow(["" if v is None else v for v in row])
    write_atomic(ctx.out(f"{name}.csv"), write_csv)
    return md
