"""Cutting by element removal and by separation along faces -> results/cutting/: events.md/csv (what each cut removed and what
its parts cost), cost.md/csv (the cut event against a step, the engine's set-up and a precomputing
method's refactorisation, 000's claim measured), stability.md (energy and step after the cut),
press_cut.png and through_cut.png (the cut mesh deformed), energy.png, haptic.md/csv (a blade on the
haptic tool), summary.md."""
import numpy as np

from pipeline import plots
from pipeline.bench import cpu_description
from pipeline.element_kinds import element_kind_names
from pipeline.reports import dhd_common as common
from pipeline.tables import either, fmt, write_table
from pipeline.artifacts import write_text_atomic

US = 1e6


def remaining_boundary(tets, removed):
    """Boundary triangles of the elements left (faces that belong to exactly one of them)."""
    gone = set(int(e) for e in removed)
    faces = {}
    for e, t in enumerate(tets):
        if e in gone:
            continue
        for f in ((t[1], t[2], t[3]), (t[0], t[2], t[3]), (t[0], t[1], t[3]), (t[0], t[1], t[2])):
            key = tuple(sorted(int(v) for v in f))
            faces[key] = None if key in faces else f
    return np.array([f for f in faces.values() if f is not None], dtype=int)


def partition_label(config):
    part = config.get("partition", {"kind": "uniform", "element": "tled"})
    if part.get("kind") == "uniform":
        return f"all {part.get('element', 'tled')}"
    return f"{fmt(100 * part['linear_fraction'])} % linear"


SEPARATE = "_separate"


def cut_mode(stage):
    return "separate" if stage.endswith(SEPARATE) else "remove"


def event_rows(ctx):
    rows = []
    for base in ("press_cut", "through_cut", "liver_cut"):
        for stage in (base, base + SEPARATE):
            for run in ctx.runs(stage):
                for ev in run.payload["cuts"]:
                    rows.append({"scene": f"{base}, {partition_label(run.config)}" if base == "press_cut" else base,
                                 "mode": cut_mode(stage), "run": run, "event": ev})
    return rows


def cut_mesh(mesh, payload):
    """Nodes and tets of the mesh a run's cuts left: node copies appended at their originals' places,
    the moved elements re-pointed (a removal run: the mesh itself)."""
    nodes = np.asarray(mesh["nodes"], dtype=float)
    tets = np.array(mesh["tets"], dtype=int)
    copies = payload.get("node_copies", [])
    if copies:
        nodes = np.vstack([nodes, nodes[[c[0] for c in copies]]])
    for row in payload.get("moved_elements", []):
        tets[row[0]] = row[1:]
    return nodes, tets


def write_events(ctx, rows):
    header = ["scene", "cut", "t (s)", "elements removed", "faces opened", "node copies", "mass removed (g)",
              "strain energy removed (mJ)", "pieces", "loose pieces", "search (µs)", "local update (µs)",
              "pieces pass (µs)"]
    table = []
    for r in rows:
        ev = r["event"]
        update = ev["separation_seconds"] if r["mode"] == "separate" else ev["update_seconds"]
        table.append([r["scene"], r["mode"], fmt(ev["time"]), ev["elements_removed"], ev.get("faces_opened", 0),
                      ev.get("node_copies", 0), fmt(1000 * ev["mass_removed"]), fmt(1000 * ev["strain_energy_removed"]),
                      ev["pieces"], ev["loose_pieces"], fmt(US * ev["search_seconds"]), fmt(US * update),
                      fmt(US * ev["pieces_seconds"])])
    write_table(ctx, "events", header, table,
                caption="What each cut removed or opened, and the wall time of its parts in the run (one machine, "
                        "shared). A separating cut's local update includes finding the faces and the node splits "
                        "(and, at the scene's first one, building the face topology).")


def cost_rows(ctx):
    out = []
    for stage, label in (("bench_cube", "cuboid"), ("bench_paper", "000 Table 1 mesh"), ("bench_liver", "liver"),
                         ("bench_cube" + SEPARATE, "cuboid"), ("bench_liver" + SEPARATE, "liver")):
        p = ctx.runs(stage)[0].payload
        e, pre = p["explicit"], p["precomputed"]
        cut = e["cut_search_seconds"] + e["cut_update_seconds"]
        out.append({"mesh": label, "mode": cut_mode(stage), "copies": p.get("node_copies", 0),
                    "faces": p.get("faces_opened", 0), "nodes": p["mesh"]["nodes"], "tets": p["mesh"]["tets"],
                    "removed": p["elements_removed"], "step": e["step_seconds"], "setup": e["setup_seconds"],
                    "search": e["cut_search_seconds"], "update": e["cut_update_seconds"], "cut": cut,
                    "full_setup": e["full_setup_on_cut_mesh_seconds"], "cholesky": pre["cholesky_seconds"],
                    "dt_before": e["stable_step_before"], "dt_after": e["stable_step_after"],
                    "response": pre["refactor_and_response_seconds"], "response_dofs": pre["response_dofs"],
                    "free_dofs": pre["free_dofs"]})
    return out


def write_cost(ctx, rows):
    header = ["mesh", "cut", "nodes", "tets", "elements removed", "faces opened / node copies", "one step (µs)",
              "cut: search (µs)", "cut: local update (µs)",
              "full set-up on the cut mesh (µs)", "sparse Cholesky of the cut mesh (µs)",
              "Cholesky + precomputed response (µs)", "Cholesky / cut", "full set-up / cut",
              "stable step 2/ω_max before / after (µs)"]
    table = [[r["mesh"], r["mode"], r["nodes"], r["tets"], r["removed"], f"{r['faces']} / {r['copies']}",
              fmt(US * r["step"]), fmt(US * r["search"]),
              fmt(US * r["update"]), fmt(US * r["full_setup"]), fmt(US * r["cholesky"]), fmt(US * r["response"]),
              fmt(r["cholesky"] / r["cut"]), fmt(r["full_setup"] / r["cut"]),
              f"{fmt(US * r['dt_before'])} / {fmt(US * r['dt_after'])}"] for r in rows]
    write_table(ctx, "cost", header, table,
                caption=f"Best of 5 (`dhd_sim --cut-bench`) on {cpu_description()}; compare within a row. "
                        "The cut is search + local update (for a separation: the faces, the node splits and the "
                        "mesh and engine updates; the one-time face topology is built before, `cut_prepare_seconds`); the Cholesky is assembling and factorising the linear "
                        "stiffness of the cut mesh with its constrained dofs eliminated (Eigen SimplicialLLT), what an "
                        "implicit or condensed model redoes at a topology change; the precomputed response adds one "
                        "solve per free dof of the top face (cuboids) or of the whole surface (liver).")


def stability_facts(ctx, mesh):
    """Per press_cut run: energy before and after, the step, and the largest |u| at the end."""
    nodes = np.asarray(mesh["nodes"], dtype=float)
    tets = np.asarray(mesh["tets"], dtype=int)
    before = min_altitude(nodes, tets)
    out = []
    for stage, run in [(s, r) for s in ("press_cut", "press_cut" + SEPARATE) for r in ctx.runs(s)]:
        p = run.payload
        en = p["energies"]
        t = np.asarray(en["time"])
        total = np.asarray(en["kinetic"]) + np.asarray(en["strain"])
        cut_t = p["cuts"][0]["time"]
        after = t > cut_t
        removed = set(p["removed_elements"])
        left = [e for e in range(len(tets)) if e not in removed]
        alt = min_altitude(nodes, tets[left])
        out.append({"label": f"{partition_label(run.config)}, {cut_mode(stage)}", "steps": p["solver"]["steps"], "time": p["solver"]["time"],
                    "cut_time": cut_t,
                    # dhd_sim's default re-estimate interval (cpp/apps/dhd_sim.md, dt_check_interval)
                    "dt_check": (run.config.get("solver") or {}).get("dt_check_interval", 10),
                    "peak_after": float(total[after].max()), "final": float(total[-1]),
                    "kinetic_final": float(en["kinetic"][-1]), "dissipated": float(en["dissipated"][-1]),
                    "dt_first": p["solver"]["dt"], "dt_final": p["solver"]["dt_final"],
                    "dt_changes_after_cut": sum(1 for s in p["solver"]["dt_history"] if s[1] > cut_t),
                    "min_altitude_before": before, "min_altitude_after": alt,
                    "max_u": float(np.abs(np.asarray(p["displacement"])).max()), "run": run})
    return out


def min_altitude(nodes, tets):
    x = nodes[tets]
    best = np.inf
    for a in range(4):
        o = [b for b in range(4) if b != a]
        n = np.cross(x[:, o[1]] - x[:, o[0]], x[:, o[2]] - x[:, o[0]])
        h = np.abs(np.einsum("ij,ij->i", n, x[:, a] - x[:, o[0]])) / np.linalg.norm(n, axis=1)
        best = min(best, float(h.min()))
    return best


def _either(rows, key, unit) -> str:
    """The rows' values of `key` with their unit: "0.3 s", or "0.3 or 0.4 s" where they differ."""
    return either([r.get(key) for r in rows], lambda v: f"{v:,g}".replace(",", " "), unit)


def write_stability(ctx, facts):
    header = ["run", "steps", "simulated (s)", "peak K + W after the cut (mJ)", "K + W at the end (mJ)",
              "kinetic at the end (J)", "dissipated (mJ)", "Δt first (ms)", "Δt at the end (ms)",
              "step changes after the cut", "smallest altitude before / after (mm)", "max |u| (mm)"]
    table = [[f["label"], f["steps"], fmt(f["time"]), fmt(1000 * f["peak_after"]), fmt(1000 * f["final"]),
              fmt(f["kinetic_final"]), fmt(1000 * f["dissipated"]), fmt(1000 * f["dt_first"]), fmt(1000 * f["dt_final"]),
              f["dt_changes_after_cut"], f"{fmt(1000 * f['min_altitude_before'])} / {fmt(1000 * f['min_altitude_after'])}",
              fmt(1000 * f["max_u"])] for f in facts]
    write_table(ctx, "stability", header, table,
                caption=f"The pressed cuboid cut at {_either(facts, 'cut_time', 's')} and run on to "
                        f"{_either(facts, 'steps', 'steps')}: energy (kinetic K + strain W), "
                        f"the automatic step (re-estimated on the deformed mesh every {_either(facts, 'dt_check', 'steps')}) "
                        "and the smallest "
                        "element altitude of the mesh before and after the cut.")


def free_fall_check(ctx, stage="through_cut"):
    """The free half's tracked node after the through cut against the damped free fall of a rigid
    body released at the cut, z(τ) = z_c + v_c (1 − e^(−ατ))/α − (g/α)(τ − (1 − e^(−ατ))/α)."""
    run = ctx.runs(stage)[0]
    p = run.payload
    t = np.asarray(p["trajectories"]["time"])
    z = np.asarray(p["trajectories"]["displacement"])[0][:, 2]
    alpha = run.config["damping"]["alpha"]
    g = -run.config["boundary"]["gravity"]["acceleration"][2]
    tc = p["cuts"][0]["time"]
    k = int(np.searchsorted(t, tc))
    vc = (z[k] - z[k - 1]) / (t[k] - t[k - 1])
    tau = t[k:] - t[k]
    decay = (1 - np.exp(-alpha * tau)) / alpha
    fall = z[k] + vc * decay - g / alpha * (tau - decay)
    return {"t": t, "z": z, "k": k, "fall": fall, "drop": float(z[k] - z[-1]),
            "model_drop": float(z[k] - fall[-1]), "tau": float(tau[-1]),
            "difference": float(abs(z[-1] - fall[-1]))}


def pictures(ctx, mesh):
    out = []
    for stage, name, view, mesh_stage in (("press_cut", "press_cut.png", (28, -62), "mesh"),
                                          ("through_cut", "through_cut.png", (12, -80), "mesh"),
                                          ("liver_cut", "liver_cut.png", (35, -70), "liver")):
        m = ctx.runs(mesh_stage)[0].payload
        runs = [(s, run) for s in (stage, stage + SEPARATE) for run in ctx.runs(s)]
        fig = plots.plt.figure(figsize=(4.6 * len(runs), 4.2), dpi=110)
        for i, (s, run) in enumerate(runs):
            p = run.payload
            nodes, tets = cut_mesh(m, p)
            u = np.asarray(p["displacement"], dtype=float)
            ax = fig.add_subplot(1, len(runs), i + 1, projection="3d")
            tri = remaining_boundary(tets, p["removed_elements"])
            kinds = element_kind_names(p)
            common.draw_deformed(ax, nodes, tets, tri, u, kinds, view=view)
            label = {"press_cut": partition_label(run.config), "through_cut": "held at x = 0, under gravity",
                     "liver_cut": "hanging from its fixed end"}[stage]
            ax.set_title(f"{stage}: {label}, {cut_mode(s)}, t = {fmt(p['solver']['time'])} s", fontsize=8)
        plots.save(fig, ctx.out(name))
        out.append(name)
    return out


def plot_energy(ctx, facts, fall, fall_separate):
    fig, axes = plots.plt.subplots(1, 2, figsize=(10, 3.4), dpi=110)
    ax = axes[0]
    for f in facts:
        en = f["run"].payload["energies"]
        t = np.asarray(en["time"])
        ax.plot(t, 1000 * (np.asarray(en["kinetic"]) + np.asarray(en["strain"])), lw=1, label=f"K + W, {f['label']}")
        ax.plot(t, 1000 * np.asarray(en["removed"]), lw=1, ls="--", label=f"removed, {f['label']}")
    ax.set_xscale("log")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("energy (mJ)")
    ax.set_title(f"press_cut: energy over {_either(facts, 'steps', 'steps')} (cut at {_either(facts, 'cut_time', 's')})",
                 fontsize=8)
    ax.legend(fontsize=6)
    ax.grid(True, alpha=0.3)
    ax = axes[1]
    for f, mode in ((fall, "remove"), (fall_separate, "separate")):
        ax.plot(f["t"], 1000 * f["z"], lw=1, label=f"tracked node of the free half ({mode})")
        ax.plot(f["t"][f["k"]:], 1000 * f["fall"], lw=1, ls="--", label=f"damped rigid free fall from the cut ({mode})")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("u_z (mm)")
    ax.set_title("through_cut: the free half falls", fontsize=8)
    ax.legend(fontsize=6)
    ax.grid(True, alpha=0.3)
    plots.save(fig, ctx.out("energy.png"))


def haptic_rows(ctx):
    out = []
    for stage, label in (("cube_blade", "cuboid"), ("liver_blade", "liver"), ("cube_blade" + SEPARATE, "cuboid")):
        p = ctx.runs(stage)[0].payload
        cuts = p["cuts"]
        blade = p["blade"]
        t = p["timing"]
        out.append({"scene": label, "mode": cut_mode(stage), "copies": sum(c.get("node_copies", 0) for c in cuts),
                    "tets": p["model"]["tets"], "frames": p["frames"], "substeps": p["substeps"],
                    "sweeps": blade["sweeps"], "cut_frames": len(cuts), "removed": sum(c["elements_removed"] for c in cuts),
                    "loose": cuts[-1]["loose_pieces"] if cuts else 0, "cut_mean": blade["seconds_mean"],
                    "cut_max": blade["seconds_max"], "p50": t["frame_seconds_p50"], "p99": t["frame_seconds_p99"],
                    "misses": t["deadline_misses"], "events": len(p["events"]),
                    "peak": float(np.linalg.norm(np.array(p["force"]), axis=1).max()),
                    "rate_khz": 1e-3 / p["frame_step"] if p.get("frame_step") else None})
    return out


def write_haptic(ctx, rows):
    header = ["scene", "cut", "tets", "frames", "substeps", "blade sweeps", "sweeps that cut", "elements removed",
              "node copies", "loose pieces", "sweep mean (µs)", "sweep max (µs)", "frame p50 (ms)", "frame p99 (ms)", "deadline misses",
              "numerical events", "peak force (N)"]
    table = [[r["scene"], r["mode"], r["tets"], r["frames"], r["substeps"], r["sweeps"], r["cut_frames"], r["removed"],
              r["copies"], r["loose"],
              fmt(US * r["cut_mean"]), fmt(US * r["cut_max"]), fmt(1000 * r["p50"]), fmt(1000 * r["p99"]),
              r["misses"], r["events"], fmt(r["peak"])] for r in rows]
    write_table(ctx, "haptic", header, table,
                caption=f"haptic_sim at {_either(rows, 'rate_khz', 'kHz')} with a blade on the tool, one thread, on "
                        f"{cpu_description()} (shared): "
                        "a sweep is the search over the elements (every frame the tool moves) and, when it removes "
                        "elements or opens faces, the local update and the pieces pass.")


def summary(ctx, events, costs, facts, fall, fall_separate, haptic):
    press = [r for r in events if r["scene"].startswith("press_cut") and r["mode"] == "remove"]
    through = next(r for r in events if r["scene"] == "through_cut" and r["mode"] == "remove")
    through_sep = next(r for r in events if r["scene"] == "through_cut" and r["mode"] == "separate")
    lines = ["## Cutting\n",
             "A cut by element removal deletes the elements a blade's swept surface crosses; a cut by separation "
             "opens the mesh along the faces nearest the swept surface by duplicating their nodes (a face opens when "
             "the segment joining its two elements' centroids crosses the sweep; a node splits into one copy per "
             "face-connected group of its elements, so nothing hangs across the cut by a node or an edge, and mass "
             "moves with the elements, none is lost). Both are local updates of the explicit engine (nothing is set "
             "up again; `dhd_sim` config `cuts` with `\"mode\"`, cpp/apps/dhd_sim.md). "
             "Tables: [events](cutting/events.md), [cost](cutting/cost.md), [stability](cutting/stability.md); "
             "pictures: [pressed cuboid](cutting/press_cut.png), [through cut](cutting/through_cut.png), "
             "[liver](cutting/liver_cut.png), "
             "[energy and fall](cutting/energy.png).\n"]
    for c in costs:
        what = f"{c['removed']} removed" if c["mode"] == "remove" else f"{c['faces']} faces opened, {c['copies']} node copies"
        lines.append(f"- **{c['mesh']}, {c['mode']}** ({c['tets']} tets, {what}): the cut event took "
                     f"{fmt(US * c['cut'])} µs ({fmt(c['cut'] / c['step'])} explicit steps); a full set-up of the "
                     f"engine on the cut mesh {fmt(US * c['full_setup'])} µs ({fmt(c['full_setup'] / c['cut'])}× the cut); "
                     f"refactorising the linear stiffness {fmt(1000 * c['cholesky'])} ms "
                     f"(**{fmt(c['cholesky'] / c['cut'])}×** the cut) and with a precomputed response of "
                     f"{c['response_dofs']} dofs {fmt(1000 * c['response'])} ms ({fmt(c['response'] / c['cut'])}×); "
                     f"the lumped system's own stable step 2/ω_max (power iteration) {fmt(US * c['dt_before'])} µs "
                     f"before the cut and {fmt(US * c['dt_after'])} µs after ({fmt(100 * (c['dt_after'] / c['dt_before'] - 1))} %; "
                     f"it may approach the element bound, which does not change, so a power-iteration step is "
                     f"measured again after a cut).")
    lines.append("")
    for f in facts:
        grew = f["final"] > f["peak_after"] * (1 + 1e-9)
        lines.append(f"- **Stability, {f['label']}:** over {f['steps']} steps ({fmt(f['time'])} s) after the cut the "
                     f"kinetic + strain energy {'grew' if grew else 'did not grow'} (peak after the cut "
                     f"{fmt(1000 * f['peak_after'])} mJ, {fmt(1000 * f['final'])} mJ at the end, kinetic "
                     f"{fmt(f['kinetic_final'])} J); the step changed {f['dt_changes_after_cut']} times after the cut "
                     f"(neither kind of cut changes the element bound of 000 eq. 34, each element keeps its own "
                     f"mass share at its corners: the smallest altitude was "
                     f"{fmt(1000 * f['min_altitude_before'])} mm before and {fmt(1000 * f['min_altitude_after'])} mm after).")
    lines.append(f"- **Through cut:** {through['event']['elements_removed']} elements removed left "
                 f"{through['event']['pieces']} pieces, {through['event']['loose_pieces']} of them loose; over "
                 f"{fmt(fall['tau'])} s the free half's tracked node fell {fmt(1000 * fall['drop'])} mm against "
                 f"{fmt(1000 * fall['model_drop'])} mm for a damped rigid body released at the cut (difference "
                 f"{fmt(1000 * fall['difference'])} mm: the half also vibrates as its bending stress is released).")
    lines.append(f"- **Through cut by separation:** {through_sep['event']['faces_opened']} faces opened with "
                 f"{through_sep['event']['node_copies']} node copies and nothing removed, leaving "
                 f"{through_sep['event']['pieces']} pieces, {through_sep['event']['loose_pieces']} of them loose; the free "
                 f"half's tracked node fell {fmt(1000 * fall_separate['drop'])} mm against "
                 f"{fmt(1000 * fall_separate['model_drop'])} mm for the damped rigid fall (difference "
                 f"{fmt(1000 * fall_separate['difference'])} mm).")
    for h in haptic:
        did = (f"{h['cut_frames']} of them removed elements ({h['removed']} in all)" if h["mode"] == "remove" else
               f"{h['cut_frames']} of them opened faces ({h['copies']} node copies in all)")
        lines.append(f"- **Haptic blade, {h['scene']}, {h['mode']}** ({h['tets']} tets): {h['sweeps']} blade sweeps, "
                     f"{did}; a sweep took "
                     f"{fmt(US * h['cut_mean'])} µs on average "
                     f"(at most {fmt(US * h['cut_max'])} µs); frames {fmt(1000 * h['p50'])} ms median, "
                     f"{fmt(1000 * h['p99'])} ms p99, {h['misses']} of {h['frames']} over the 1 ms deadline "
                     f"([haptic](cutting/haptic.md)).")
    lines.append(f"- The search for crossed elements tests only the elements a uniform grid over their "
                 f"reference boxes finds near the sweep, widened by the largest nodal displacement "
                 f"(cpp/softsim/cutting/element_grid.hpp); a separating cut looks at the faces of those elements "
                 f"only (cpp/softsim/cutting/separation.hpp). A scene that separates computes its linear elements "
                 f"element by element (an assembled row cannot follow a node split). The pressed-cuboid cuts removed {sum(r['event']['elements_removed'] for r in press)} elements "
                 f"over {len(press)} runs.\n")
    write_text_atomic(ctx.out("summary.md"), "\n".join(lines) + "\n")


def report(ctx):
    mesh = ctx.runs("mesh")[0].payload
    events = event_rows(ctx)
    write_events(ctx, events)
    costs = cost_rows(ctx)
    write_cost(ctx, costs)
    facts = stability_facts(ctx, mesh)
    write_stability(ctx, facts)
    fall = free_fall_check(ctx)
    fall_separate = free_fall_check(ctx, "through_cut" + SEPARATE)
    pictures(ctx, mesh)
    plot_energy(ctx, facts, fall, fall_separate)
    haptic = haptic_rows(ctx)
    write_haptic(ctx, haptic)
    summary(ctx, events, costs, facts, fall, fall_separate, haptic)
