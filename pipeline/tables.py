"""Tables as Markdown (for reading) and CSV (for reuse), written side by side."""
import csv
import math


def fmt(value, digits=4):
    """Compact, honest formatting: significant digits, no false precision."""
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
        if 1e-3 <= abs(value) < 1e5:
            return f"{value:.{digits}g}"
        return f"{value:.{max(1, digits - 1)}e}"
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
    ctx.out(f"{name}.md").write_text(md)
    with open(ctx.out(f"{name}.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(headers)
        for row in rows:
            w.writerow(["" if v is None else v for v in row])
    return md
