"""The rigid tools' broad phase (dynamics/contact_search.hpp) against testing every boundary node
each step -> results/contact/search.md/csv and search_summary.md: the contact phase's time per
step, the whole step's, and whether both runs gave the same force. Timings name the CPU."""
from pipeline.bench import cpu_description
from pipeline.tables import fmt, write_table

SCENES = (("liver_press", "liver"), ("cuboid_press", "fine cuboid"))


def scene_rows(ctx, stage, scene):
    by_mode = {r.sweep["solver.contact_search"]: r for r in ctx.runs(stage)}
    out = {}
    for mode, r in by_mode.items():
        timing = r.payload["timing"]
        tool = r.payload["tools"][0]
        out[mode] = {"contact_us": 1e6 * timing["contact_seconds"] / timing["steps"],
                     "step_us": 1e6 / timing["steps_per_second"], "force": tool["force"][-1],
                     "nodes": tool["nodes"], "contacts": tool["contacts"][-1], "tets": r.payload["mesh"]["tets"]}
    return out


def report(ctx):
    rows, lines = [], []
    for stage, scene in SCENES:
        m = scene_rows(ctx, stage, scene)
        grid, every = m["grid"], m["all"]
        same = grid["force"] == every["force"]
        rows.append([scene, grid["nodes"], grid["contacts"], every["contact_us"], grid["contact_us"],
                     every["contact_us"] / grid["contact_us"] if grid["contact_us"] > 0 else None,
                     every["step_us"], grid["step_us"], "yes" if same else "no"])
        lines.append(f"- {scene}: {grid['nodes']} boundary nodes, {grid['contacts']} in contact at the end; the contact "
                     f"phase took {fmt(every['contact_us'], 3)} µs per step testing every node and "
                     f"{fmt(grid['contact_us'], 3)} µs with the grid ({fmt(rows[-1][5], 3)}× less), of a step of "
                     f"{fmt(grid['step_us'], 3)} µs; the final force on the tool is "
                     + ("the same bit for bit." if same else "NOT the same (a defect)."))
    cpu = cpu_description()
    write_table(ctx, "search",
                ["scene", "boundary nodes", "in contact at the end", "contact µs/step, every node",
                 "contact µs/step, grid", "ratio", "step µs, every node", "step µs, grid", "same force"], rows,
                f"A sphere pressed into each body, one thread, on {cpu}: the rigid tool's contact phase (broad and "
                "narrow phase, sampled on one step in eight) per step, with the broad phase (solver.contact_search "
                "\"grid\") and testing every boundary node each step (\"all\"), and the whole step. A loaded machine "
                "shifts both columns alike.")
    text = ["## Contact: the broad phase", "",
            "The rigid tools' contact searches a grid over the tool's nodes and tests only the nodes near the tool "
            "([table](search.md); dynamics/contact_search.hpp), on " + cpu + ". With the grid a step still reads "
            "every boundary node's position once (has it moved half the margin since the grid was built?); the "
            "distance tests, projections and work booking follow the nodes near the tool. Timings on a shared, "
            "loaded machine vary by tens of percent from run to run:", "", *lines, ""]
    ctx.out("search_summary.md").write_text("\n".join(text) + "\n")
