"""results/rpim_stiffness/: why the RPIM plate is stiffer than the paper's RPIM (002 eq. 49).

Inputs (experiments/rpim_stiffness.json): rpim_precompute "check" runs that change one thing of
the default plate (quadrature, support radius, penalty, shape parameter, node spacing) and
calculix_plate runs of the same plate under unit forces on the RPIM node lattices.

Two measures per run, both per unit force:
  - node 61's compliance |u_a / F_a| (a = z, x): the quantity of 002 eq. 49. Under a point
    force it has no converged value (u ∝ 1/h in 3-D), so it is compared at equal node spacing;
  - the far field: u_z at the free midpoint of an edge, (24, 0, 6) mm, under a vertical unit
    force: 24 mm from the load, it converges under refinement and shows whether the plate as a
    whole is too stiff.

The finding is written from the numbers: which change moves node 61 how far, whether any
reading at the paper's 11 × 11 × 3 nodes reaches the paper's slope, and where CalculiX stands.
"""
import numpy as np

from pipeline.tables import fmt, write_table

MM = 1e3
FAR_POINT = np.array([0.024, 0.0, 0.006])  # free edge midpoint on every lattice of the study
NEAR = 0.10                                # "reproduces": within 10 % of the paper's slope


# --------------------------------------------------------------------------- measures
def _nearest(positions, point):
    d = np.linalg.norm(np.asarray(positions, dtype=float) - point, axis=1)
    i = int(np.argmin(d))
    if d[i] > 1e-6:
        raise ValueError(f"no node at {point.tolist()} m (nearest {d[i]:.3g} m away)")
    return i


def rpim_measures(p):
    """(|u_z/F_z|, |u_x/F_x| at node 61, far-field |u_z/F_z|) in mm/N from the unit solutions."""
    n = p["loaded_node"] - 1
    u = p["unit_solutions"]
    far = _nearest(p["top_nodes"], FAR_POINT)
    return abs(u[2][n][2]) * MM, abs(u[0][n][0]) * MM, abs(u[2][far][2]) * MM


def _lattice(nodes):
    return "×".join(str(v) for v in nodes)


def _rpim_label(p):
    m, pl = p["model"], p["plate"]
    req = m["d_c_requested"]
    dc = f"{req['length'] * MM:g} mm" if "length" in req else f"{req['spacing_factor']:g} h"
    sup = m["support"]
    support = f"r = {sup['radius'] * MM:.3g} mm ({sup['radius'] / m['mean_spacing']:.3g} h)" if "radius" in sup \
        else f"{sup['count']} nearest"
    pen = m["penalty"]
    poly = "" if m.get("polynomial", "none") == "none" else f" + {m['polynomial']} polynomial"
    return (f"{_lattice(pl['nodes'])} nodes; cells {_lattice(pl['background_cells'])} × {pl['gauss_order']}³; "
            f"α_c {m['alpha_c']:g}, d_c {dc}{poly}; {support}; penalty {pen['kind']} {pen['lambda']:g}")


def calculix_measures(runs):
    """{(element, divisions): {"z": .., "x": .., "far": .., "lattice": ..}} in mm/N."""
    out = {}
    for p in runs:
        f = np.asarray(p["force"], dtype=float)
        a = int(np.argmax(np.abs(f)))
        key = (p["element_type"], tuple(p["divisions"]))
        e = out.setdefault(key, {})
        u = np.asarray(p["top_centre"]["displacement"], dtype=float)
        e["xyz"[a]] = abs(u[a] / f[a]) * MM
        if a == 2:
            far = _nearest(p["top_surface"]["positions"], FAR_POINT)
            e["far"] = abs(p["top_surface"]["displacement"][far][2] / f[2]) * MM
        r = 2 if p["element_type"].startswith("C3D20") else 1
        e["lattice"] = [r * d + 1 for d in p["divisions"]]
    return out


# --------------------------------------------------------------------------- tables
def _study_rows(ctx, stages):
    rows, points = [], []
    for stage in stages:
        for run in ctx.runs(stage):
            p = run.payload
            z, x, far = rpim_measures(p)
            rows.append([stage, _rpim_label(p), z, x, far, p["timing"]["total_s"]])
            points.append({"stage": stage, "label": _rpim_label(p), "nodes": p["plate"]["nodes"], "z": z, "x": x,
                           "far": far, "default": _is_default(p)})
    return rows, points


def _is_default(p):
    m, pl = p["model"], p["plate"]
    return (pl["nodes"] == [11, 11, 3] and pl["background_cells"] == [8, 8, 1] and pl["gauss_order"] == 4
            and m["alpha_c"] == 1.0 and m["d_c_requested"] == {"length": 0.002}
            and m["support"].get("radius") is not None and abs(m["support"]["radius"] / m["mean_spacing"] - 3) < 1e-9
            and m["penalty"]["kind"] == "scale_block" and m["penalty"]["lambda"] == 1e7
            and m.get("polynomial", "none") == "none")


def _calculix_rows(ccx):
    rows = []
    for (element, div), e in sorted(ccx.items(), key=lambda kv: (kv[0][0], kv[0][1])):
        rows.append([f"CalculiX {element} {_lattice(div)} elements", _lattice(e["lattice"]),
                     e.get("z"), e.get("x"), e.get("far")])
    return rows


def _paper_rows(paper):
    rows = []
    eq49 = paper.get("eq49_mm_per_N")
    if eq49:
        rows.append(["paper: RPIM, 002 eq. 49 slopes", "11×11×3", eq49["z"], eq49["x"], None])
    ansys = paper.get("ansys_check")
    if ansys:
        f, u = ansys["force_N"], ansys["ansys_mm"]
        rows.append(["paper: ANSYS, 002 §5.2 (|u/F| of its check force)", "–", abs(u[2] / f[2]), abs(u[0] / f[0]), None])
    return rows


# --------------------------------------------------------------------------- finding
def finding(points, ccx, paper):
    """Plain-words lines that follow the numbers."""
    slope = (paper.get("eq49_mm_per_N") or {}).get("z")
    base = next((q for q in points if q["default"]), None)
    lines = []
    if base is None:
        return ["- The default plate is not among the runs: no finding."]
    lines.append(f"- Default plate (11 × 11 × 3 nodes): node 61 |u_z/F_z| = {fmt(base['z'])} mm/N"
                 + (f"; the paper's eq. 49 slope ({fmt(slope)} mm/N) is {fmt(slope / base['z'])} × as compliant." if slope else "."))
    for stage, what in (("quadrature", "quadrature density"), ("support", "support radius"),
                        ("penalty", "penalty factor and form"), ("shape", "shape parameter (α_c, d_c) and polynomial")):
        zs = [q["z"] for q in points if q["stage"] == stage]
        if zs:
            lines.append(f"- {what}: node 61 ranges over {fmt(min(zs))}–{fmt(max(zs))} mm/N "
                         f"({fmt(100 * (min(zs) / base['z'] - 1), 2)} % to {fmt(100 * (max(zs) / base['z'] - 1), 2)} % "
                         "of the default).")
    paper_lattice = [q for q in points if q["nodes"] == [11, 11, 3]]
    best = max(paper_lattice, key=lambda q: q["z"])
    if slope:
        hit = [q for q in paper_lattice if abs(q["z"] / slope - 1) <= NEAR]
        if hit:
            lines.append(f"- At the paper's 11 × 11 × 3 nodes, {len(hit)} reading(s) come within {NEAR:.0%} of "
                         f"the paper's slope: " + "; ".join(q["label"] for q in hit) + ".")
        else:
            lines.append(f"- No reading at the paper's 11 × 11 × 3 nodes reproduces the paper's slope: the most "
                         f"compliant, {best['label']}, gives {fmt(best['z'])} mm/N ({fmt(best['z'] / slope)} × "
                         f"the paper's {fmt(slope)}).")
    spacing = sorted((q for q in points if q["stage"] == "spacing"), key=lambda q: q["nodes"][0])
    for dc in ("d_c 2 mm", "d_c 2 h"):
        series = [q for q in spacing if dc in q["label"]]
        if len(series) > 1:
            lines.append(f"- Node spacing ({dc}): node 61 " + " → ".join(
                f"{fmt(q['z'])} ({_lattice(q['nodes'])})" for q in series) + " mm/N, far field " + " → ".join(
                fmt(q["far"]) for q in series) + " mm/N: the loaded node softens as the point force is resolved "
                "more finely, as a point load on a 3-D solid must (u ∝ 1/h).")
            if slope:
                reach = [q for q in series if abs(q["z"] / slope - 1) <= NEAR]
                if reach:
                    lines.append(f"  - {dc}: {_lattice(reach[0]['nodes'])} nodes reach the paper's slope within {NEAR:.0%}.")
    for q in spacing:
        c8 = next((e for (el, _), e in ccx.items() if el == "C3D8I" and e["lattice"] == q["nodes"]), None)
        c20 = next((e for (el, _), e in ccx.items() if el == "C3D20R" and e["lattice"] == q["nodes"]), None)
        if (c8 or c20) and "d_c 2 mm" in q["label"]:
            parts = []
            for name, e in (("C3D8I", c8), ("C3D20R", c20)):
                if e and e.get("z"):
                    parts.append(f"{fmt(q['z'] / e['z'])} of {name} at node 61, {fmt(q['far'] / e['far'])} in the far field")
            lines.append(f"- On the {_lattice(q['nodes'])} lattice, RPIM is " + "; ".join(parts) + ".")
    finest = max(ccx.values(), key=lambda e: np.prod(e["lattice"]), default=None)
    if finest and slope and finest.get("z"):
        lines.append(f"- CalculiX on its finest lattice ({_lattice(finest['lattice'])} nodes) gives {fmt(finest['z'])} mm/N "
                     f"at node 61 ({fmt(finest['z'] / slope)} × the paper's slope) and {fmt(finest['far'])} mm/N in the far field.")
    lines += _plain_words(points, ccx, slope, base, best, spacing)
    return lines


def _plain_words(points, ccx, slope, base, best, spacing):
    """The conclusion, each clause only where the numbers above support it."""
    if not slope:
        return []
    out = []
    if abs(best["z"] / slope - 1) > NEAR:
        out.append(f"In plain words: no reading of the paper tried here (quadrature, support, penalty, shape "
                   f"parameter, polynomial) gives its slope on its own 11 × 11 × 3 nodes; the largest change, "
                   f"{fmt(best['z'] / base['z'])} × the default, leaves node 61 at {fmt(best['z'] / slope)} of it.")
    else:
        out.append(f"In plain words: the paper's slope is reproduced on its own nodes by: {best['label']}.")
    def growing(values):
        return len(values) > 1 and all(b > a for a, b in zip(values, values[1:]))
    zs = [q["z"] for q in sorted(spacing, key=lambda q: q["nodes"][0]) if "d_c 2 mm" in q["label"]]
    ccx_series = [[e["z"] for _, e in sorted((np.prod(e["lattice"]), e) for (el, _), e in ccx.items()
                                             if el == element and e.get("z"))]
                  for element in sorted({el for el, _ in ccx})]
    if growing(zs) and all(growing(c) for c in ccx_series if len(c) > 1):
        out.append("Node 61's compliance is a property of the discretisation, not of the plate: it grows with every "
                   "refinement in RPIM and CalculiX alike (a point force has no finite displacement under it).")
    reach = sorted((e for e in ccx.values() if e.get("z") and abs(e["z"] / slope - 1) <= NEAR),
                   key=lambda e: np.prod(e["lattice"]))
    if reach:
        out.append(f"CalculiX reaches the paper's slope within {NEAR:.0%} only on {_lattice(reach[0]['lattice'])} nodes, "
                   f"so {fmt(slope)} mm/N reads as a much finer resolution of the load than 11 × 11 × 3 nodes.")
    ratios = []
    for q in spacing:
        c8 = next((e for (el, _), e in ccx.items() if el == "C3D8I" and e["lattice"] == q["nodes"]), None)
        if c8 and c8.get("z") and "d_c 2 mm" in q["label"]:
            ratios.append((np.prod(q["nodes"]), q["z"] / c8["z"]))
    if len(ratios) > 1:
        ratios.sort()
        trend = "approaching it under refinement" if ratios[-1][1] > ratios[0][1] else "without approaching it"
        out.append(f"On the same nodes RPIM is {fmt(ratios[0][1], 2)}–{fmt(ratios[-1][1], 2)} × as compliant as "
                   f"CalculiX's C3D8I, {trend}: the remaining stiffness is that of a coarse Galerkin model, "
                   "not a misread parameter.")
    return ["", " ".join(out)] if out else []


def report(ctx):
    paper = ctx.experiment.get("paper", {})
    rows, points = _study_rows(ctx, ["quadrature", "support", "penalty", "shape", "spacing"])
    write_table(ctx, "rpim_stiffness_study",
                ["study", "model", "node 61 |u_z/F_z| (mm/N)", "node 61 |u_x/F_x| (mm/N)",
                 "far field |u_z/F_z| at (24, 0, 6) mm (mm/N)", "precompute (s)"], rows,
                "RPIM plate of 002 §4.1 with one thing changed from the default at a time (unit solutions at node 61).")
    ccx = calculix_measures([r.payload for r in ctx.runs("calculix")])
    write_table(ctx, "rpim_stiffness_calculix",
                ["model", "node lattice", "node 61 |u_z/F_z| (mm/N)", "node 61 |u_x/F_x| (mm/N)",
                 "far field |u_z/F_z| at (24, 0, 6) mm (mm/N)"],
                _calculix_rows(ccx) + _paper_rows(paper),
                "The same plate and supports in CalculiX under unit forces at the top centre; the paper's figures "
                "beside them, labelled.")
    text = ["## Why the RPIM plate is stiffer than the paper's", "",
            "Tables: [rpim_stiffness_study.md](rpim_stiffness_study.md), "
            "[rpim_stiffness_calculix.md](rpim_stiffness_calculix.md).", ""]
    text += finding(points, ccx, paper)
    ctx.out("summary.md").write_text("\n".join(text) + "\n")
