"""The solvers of 001 §4 in the haptic loop, whole and mixed per region
-> results/async/solvers.md/csv, solvers_mixed.md/csv and summary_solvers.md."""
from pipeline.reports import async_common as C
from pipeline.tables import write_table
from pipeline.artifacts import write_text_atomic


def report(ctx):
    whole = C.rows(ctx, "whole")
    mixed = C.rows(ctx, "mixed")
    order = ["static", "implicit/backward_euler", "implicit/newmark", "explicit/central", "explicit/backward_damping"]
    whole.sort(key=lambda r: order.index(r["whole_solver"]) if r["whole_solver"] in order else 99)
    m = whole[0]["run"].payload["model"]
    out = []
    for r in whole:
        limit = r["run"].payload.get("explicit_step_limit_in_use")
        out.append([r["whole_solver"], 1e3 * limit if limit else None, C.us(r["whole_time"]), C.mn(r["whole_peak"]),
                    C.mn(r["exact_peak"]), C.pct(r["whole_vs_exact"]["rms_relative"]),
                    C.pct(r["whole_vs_exact"]["peak_relative"])])
    headers = ["solver (whole model at 1 kHz)", "explicit step limit (ms)", "time/frame (µs)", "peak force (mN)",
               "peak force exact (mN)", "RMS error vs exact (%)", "peak error vs exact (%)"]
    cap = (f"Bar of {m['nodes']} nodes, E = {m['youngs_modulus'] / 1000:g} kPa, probe spring "
           f"{whole[0]['run'].payload['haptics']['probe_stiffness']:g} N/m, chirp 1 mm 0-5 Hz. 001 eq. 4 gives "
           f"{1e3 * m['eq4_step_limit']:.3g} ms for this bar; the enforced limits use Gershgorin's bound on the largest "
           f"frequency ({m['omega_max_bound']:.4g} rad/s). Static: the inertia is neglected, so its error is the dynamic "
           "response itself.")
    md = write_table(ctx, "solvers", headers, out, cap)
    out = []
    for r in sorted(mixed, key=lambda r: (r["primary_solver"], r["secondary_solver"])):
        out.append([r["primary_solver"], r["secondary_solver"], r["every"], C.us(r["async_time"]), C.us(r["whole_time"]),
                    r["speed_gain"], C.pct(r["vs_whole"]["rms_relative"]), C.pct(r["vs_exact"]["rms_relative"])])
    headers = ["primary solver (1 kHz)", "secondary solver", "every (frames)", "time/frame regions (µs)",
               "time/frame whole (µs)", "speed gain", "RMS error vs whole (%)", "RMS error vs exact (%)"]
    md2 = write_table(ctx, "solvers_mixed", headers, out,
                      "Primary region of 5 nodes at 1 kHz and a secondary region of 14 nodes every 10th frame, each with "
                      "its own solver; the whole model is solved with backward Euler.")
    text = ["## Solvers (001 §4) in the haptic loop\n", md, md2,
            "An explicit secondary region at 10 frames per step would be far above its stability limit: the tool "
            "refuses such a configuration (exit code 2) before computing anything.\n"]
    write_text_atomic(ctx.out("summary_solvers.md"), "\n".join(text))
    C.gather_summary(ctx)
