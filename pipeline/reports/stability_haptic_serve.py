"""haptic_sim serve under adversarial sessions -> results/stability/haptic_serve.md/csv and
summary_haptic_serve.md."""
from pipeline.artifacts import write_text_atomic
from pipeline.reports.stability_common import gather_summary
from pipeline.tables import write_table

# What cpp/apps/haptic_sim.md promises for each class: the exit code and whether the record is written.
EXPECTED = {"bad lines": (0, True), "reader leaves": (4, True), "SIGTERM": (5, True), "SIGINT": (5, True),
            "second UDP sender": (0, True), "oversized datagram": (0, True), "silent UDP client": (4, True),
            "force limit": (0, True), "epoch-seconds t": (0, True), "visual reader leaves": (0, True),
            "stream names the config": (2, False)}


def kept(r):
    return (r["exit"], r["artifact"]) == EXPECTED[r["class"]]


def report(ctx):
    rows = ctx.runs("sessions")[0].payload["rows"]
    write_table(ctx, "haptic_serve", ["class", "what the session got", "exit", "expected exit", "artifact written",
                                      "messages", "answers", "as documented", "what the record or answer says"],
                [[r["class"], r["what"], r["exit"], EXPECTED[r["class"]][0], "yes" if r["artifact"] else "no",
                  r["messages"], r["answers"], "yes" if kept(r) else "no", r["detail"]] for r in rows],
                "haptic_sim serve driven by an adversarial bridge, a second process and signals, through real pipes, "
                "sockets and signals (exit codes and rules: cpp/apps/haptic_sim.md, \"The protocol\").")
    good = sum(kept(r) for r in rows)
    failing = [r["class"] for r in rows if not kept(r)]
    text = ["## The live server", "",
            f"{len(rows)} adversarial sessions of `haptic_sim serve` ([table](haptic_serve.md)): malformed, oversized "
            "and absurd messages, a reader that leaves, SIGTERM and SIGINT, a second UDP sender, a silent client, "
            "a tip far from the organ and a stiff press against the force limit, an epoch-seconds clock, the visual "
            "stream's reader leaving and a stream naming the config.", "",
            f"In plain words: {good} of {len(rows)} end as documented, with the record of what was answered "
            "written (every frame computed) wherever a session ran" + (f"; not yet: {', '.join(failing)}." if failing else ".")]
    write_text_atomic(ctx.out("summary_haptic_serve.md"), "\n".join(text) + "\n\n")
    gather_summary(ctx)
