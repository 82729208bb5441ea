"""Bad-input corpus -> results/stability/bad_input.md/csv (by executable), bad_input_cases.md/csv
(every case with its exit and line) and summary_bad_input.md."""
from pipeline.reports.stability_common import gather_summary
from pipeline.tables import write_table
from pipeline.artifacts import write_text_atomic


def passed(r):
    if r["good"]:
        return r["exit"] == 0
    return r["exit"] == 2 and r["lines"] == 1 and r["named"] and not r["output_left"]


def report(ctx):
    p = ctx.runs("corpus")[0].payload
    rows = p["rows"]
    table = []
    for tool in sorted({r["tool"] for r in rows}):
        mine = [r for r in rows if r["tool"] == tool and not r["good"]]
        table.append([tool, len(mine), sum(passed(r) for r in mine), sum(r["exit"] == 2 for r in mine),
                      sum(r["exit"] == 3 for r in mine), sum(r["exit"] not in (2, 3) for r in mine),
                      sum(r["output_left"] and r["exit"] != 0 for r in mine), sum(bool(r["known_issue"]) for r in mine)])
    write_table(ctx, "bad_input", ["executable", "bad cases", "contract kept", "exit 2", "exit 3", "other exit",
                                   "output left behind", "known issues"], table,
                "The bad-input corpus (tests/bad_input/): the contract is exit 2, one line naming the file, the JSON "
                "pointer and what was expected, and no output file.")
    write_table(ctx, "bad_input_cases", ["executable", "case", "what is wrong", "exit", "contract kept", "message"],
                [[r["tool"], r["case"], r["why"], r["exit"], "yes" if passed(r) else "no", r["message"]]
                 for r in rows if not r["good"]],
                "Every case of the bad-input corpus (tests/bad_input/<executable>/cases.json) with the exit code and "
                "the one line its executable gave.")
    failing = [r for r in rows if not r["good"] and not passed(r)]
    write_table(ctx, "bad_input_failures", ["executable", "case", "what is wrong", "exit", "message", "known issue"],
                [[r["tool"], r["case"], r["why"], r["exit"], r["message"], r["known_issue"] or ""] for r in failing],
                "Cases where an executable does not keep the contract yet.")
    total = sum(1 for r in rows if not r["good"])
    text = ["## Bad input", "",
            f"{total} malformed inputs for the {len(table)} executables ([summary](bad_input.md), "
            "[every case](bad_input_cases.md), "
            f"[exceptions](bad_input_failures.md)): truncated and empty JSON, NaN and out-of-range numbers, missing, "
            "unknown and mistyped fields, ν ≥ 0.5, E ≤ 0, zero or negative sizes and volumes, repeated or "
            "out-of-range node indices, empty node sets, loads on fixed nodes, Δt above the limit, files that are "
            "not meshes, configs and artifacts nested tens of thousands deep, devices given as inputs "
            "(/dev/zero), sizes whose run would exceed the memory limit (dense factorisations and series of "
            "async_sim included), runs that would take hours (the work limit), meshes whose tetrahedra round to zero "
            "volume, integers beyond their 32-bit field, outputs that name an input.", "",
            f"In plain words: {total - len(failing)} of {total} are refused the way they should be — exit 2, one "
            "line naming the file, the JSON pointer and what was expected, no output file."]
    if failing:
        ran = sum(r["exit"] == 0 for r in failing)
        internal = sum(r["exit"] == 1 for r in failing)
        crashed = sum(r["exit"] not in (0, 1, 2, 3) for r in failing)
        others = "The other one is" if len(failing) == 1 else f"The {len(failing)} others are"
        text.append(f"{others} listed with their cause and fix ([exceptions](bad_input_failures.md)): "
                    f"{ran} are accepted and run (exit 0), {internal} end as an internal error (exit 1) instead of "
                    f"exit 2" + (f", {crashed} crash" if crashed else "; none crashes") + ".")
    write_text_atomic(ctx.out("summary_bad_input.md"), "\n".join(text) + "\n\n")
    gather_summary(ctx)
