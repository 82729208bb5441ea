"""Near incompressibility -> "stability_incompressible" v1.

A box of a nearly incompressible material under a small load, ν swept towards 0.5, in one of
two scenes:

- "cantilever": clamped at x = 0, uniform pressure on the top face; compared: the mean vertical
  deflection of the free end (x = L);
- "indentation": bottom clamped, pressure on a centred square patch of the top face (a blunt
  probe); compared: the mean vertical displacement of the patch's nodes.

Solved by:

- dhd_sim's static solve with its tetrahedra (the elements listed in `elements`: the
  constant-strain `linear` tet with the linear material; `tled` and the average-nodal-pressure
  `anp` tet with the decoupled neo-Hookean law, which at these small strains is the same
  material);
- CalculiX C3D4 on the very same tets (the same discrete problem: confirms that a stiff answer
  is the element's locking and not our code);
- CalculiX C3D20R hexahedra (quadratic, reduced integration: free of volumetric locking) on the
  same box, the reference.

The compared nodes are cell corners, which both meshes share. Also reported per ν: the paper's critical step Δt_cr = h_min/c
(000 eqs. 34–35), the exact linear limit 2/ω_max of the tet mesh (stability_fem), and dhd_sim's
own Δt_cr from a short explicit run with the automatic step for each nonlinear element (it must
run).

Config:
  mesh:      tet_mesh artifact of the box (a mesher cuboid)
  scene:     "cantilever" (default) or "indentation"
  patch_half_width: m, the loaded square of the indentation scene
  E, density, nus: material
  pressure:  Pa on the loaded area (downwards)
  elements:  dhd_sim partition elements to try (uniform partition, static solver)
  ccx:       {"element_type": "C3D20R", "refine": 1} (hex divisions = the cuboid cells × refine)
  explicit_steps: steps of the short explicit run per ν and nonlinear element (0: none)
"""
# Executables this stage runs: part of its cache key (pipeline/runner.py).
TOOLS = ("dhd_sim",)

import numpy as np

from pipeline.artifacts import write_artifact
from pipeline.config_reader import ConfigReader
from pipeline.stages import stability_fem as fem
from pipeline.stages.calculix import read_analysis, solve_tet_mesh
from pipeline.stages.calculix_ccx import (elset_lines, fmt, last_block, mesh_lines, nset_lines, parse_dat,
                                          run_deck, section_and_step_lines, sorted_rows)
from pipeline.stages.calculix_plate import PlateMesh
from pipeline.stages.calculix_scene import read_material
from pipeline.stages.stability_common import nodes_at_or_below, read_payload, run_tool, tool_hashes

SCHEMA = "stability_incompressible"
TOOL = "pipeline.stages.stability_incompressible"


def in_patch(points, center, half_width):
    """Which points (n × 2 or 2) lie in the square patch (closed, with a tolerance)."""
    if half_width is None:
        return np.ones(len(np.atleast_2d(points)), dtype=bool)
    d = np.abs(np.atleast_2d(points) - np.asarray(center))
    return np.all(d <= half_width * (1 + 1e-9), axis=1)


def top_face_loads(X, boundary, pressure, center=None, half_width=None):
    """Consistent nodal loads of a uniform pressure on the boundary triangles of the top face,
    or of the part of it inside the square patch (linear triangles: a third of the triangle's
    force to each corner)."""
    ztop = X[:, 2].max()
    tol = 1e-9 * (X[:, 2].max() - X[:, 2].min())
    f = np.zeros(len(X))
    for tri in boundary:
        if (all(abs(X[n, 2] - ztop) <= tol for n in tri)
                and in_patch(X[list(tri), :2].mean(axis=0), center, half_width)[0]):
            a = 0.5 * np.linalg.norm(np.cross(X[tri[1]] - X[tri[0]], X[tri[2]] - X[tri[0]]))
            for n in tri:
                f[n] -= pressure * a / 3.0
    return {int(n): float(v) for n, v in enumerate(f) if v != 0.0}


def boundary_block(fixed, loads):
    """dhd_sim's boundary block (the CalculiX stage reads the same syntax)."""
    return {"fixed": [{"nodes": fixed}],
            "forces": [{"nodes": [n], "force": [0, 0, f]} for n, f in loads.items()]}


# Elements of the small-strain material; the others take the decoupled neo-Hookean law.
SMALL_STRAIN = ("linear", "corotational")


def dhd_static(mesh_path, element, E, nu, rho, fixed, loads):
    model = "linear" if element in SMALL_STRAIN else "neo_hookean_decoupled"
    # Newton's residual cannot fall below the round-off of forces that carry λ(J − 1) (or λ tr ε),
    # and λ/μ reaches 5000 at ν = 0.4999: the default 1e-9 relative tolerance is out of reach.
    solver = {"kind": "static", "increments": 1, "tolerance": 1e-7}
    cfg = {"mesh": mesh_path, "material": {"model": model, "E": E, "nu": nu, "density": rho},
           "partition": {"kind": "uniform", "element": element},
           "boundary": boundary_block(fixed, loads),
           "solver": solver}
    return run_tool("dhd_sim", cfg)


def ccx_hex_deck(box, divisions, element_type, E, nu, pressure, scene, half_width):
    mesh = PlateMesh(box, divisions, element_type)
    P = mesh.positions
    tol = 1e-9 * max(box)
    axis = 0 if scene == "cantilever" else 2
    fixed = [i + 1 for i in np.flatnonzero(np.abs(P[:, axis]) <= tol)]
    L = [f"** pipeline.stages.stability_incompressible: {scene} under top pressure"]
    L += mesh_lines(P, element_type, mesh.elements)
    nx, ny, nz = divisions
    dx, dy = box[0] / nx, box[1] / ny
    center = (0.5 * box[0], 0.5 * box[1])
    top_layer = [1 + i + nx * (j + ny * (nz - 1)) for j in range(ny) for i in range(nx)
                 if in_patch(((i + 0.5) * dx, (j + 0.5) * dy), center, half_width)[0]]
    L += elset_lines("ETOP", top_layer)
    L += nset_lines("FIXED", fixed)
    # The linear material and a linear step, as the C3D4 solve of the tets gets them.
    material = read_material(ConfigReader({"model": "linear", "E": E, "nu": nu}, "/material"))
    L += section_and_step_lines(material, read_analysis(ConfigReader({}, "/analysis"), "linear"))
    L += ["*BOUNDARY", "FIXED, 1, 3, 0.0", "*DLOAD", f"ETOP, P2, {fmt(pressure)}",
          "*NODE PRINT, NSET=NALL, FREQUENCY=100000000", "U", "*END STEP"]
    return "\n".join(L) + "\n", mesh


def ccx_hex_tip(box, divisions, element_type, E, nu, pressure, tip_points, scene, half_width):
    deck, mesh = ccx_hex_deck(box, divisions, element_type, E, nu, pressure, scene, half_width)
    dat, _, _ = run_deck(deck, timeout=600)
    block = last_block(parse_dat(dat), "displacements", "NALL")
    ids = []
    for p in tip_points:
        n = mesh.node_at(np.asarray(p))
        if n is None:
            raise ValueError(f"the hexahedral mesh has no node at {p}")
        ids.append(n)
    u = np.array(sorted_rows(block, ids))
    return float(u[:, 2].mean()), len(mesh.elements)


def run(ctx):
    cfg = ctx.config
    mesh = read_payload(cfg["mesh"])
    X, T = np.array(mesh["nodes"]), np.array(mesh["tets"])
    lo, hi = X.min(axis=0), X.max(axis=0)
    box = (hi - lo).tolist()
    if np.linalg.norm(lo) > 1e-12:
        raise ValueError("the cantilever box must start at the origin")
    tol = 1e-9 * max(box)
    scene = cfg.get("scene", "cantilever")
    if scene not in ("cantilever", "indentation"):
        raise ValueError(f"scene: \"cantilever\" or \"indentation\", not {scene!r}")
    half_width = cfg["patch_half_width"] if scene == "indentation" else None
    center = (0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]))
    if scene == "cantilever":
        fixed = [int(i) for i in np.flatnonzero(X[:, 0] <= lo[0] + tol)]
        tip = [int(i) for i in np.flatnonzero(X[:, 0] >= hi[0] - tol)]
    else:
        fixed = nodes_at_or_below(X, lo[2] + tol)
        top = X[:, 2] >= hi[2] - tol
        tip = [int(i) for i in np.flatnonzero(top & in_patch(X[:, :2], center, half_width))]
    # Loads on the clamped nodes would go straight into the reaction: left out.
    loads = {n: f for n, f in top_face_loads(X, mesh["boundary"], cfg["pressure"], center, half_width).items()
             if n not in set(fixed)}
    cells = mesh.get("source", {}).get("cells")
    refine = cfg["ccx"].get("refine", 1)
    divisions = [c * refine for c in cells]
    E, rho = cfg["E"], cfg["density"]
    geo = fem.tet_geometry(X, T)
    # Euler–Bernoulli cantilever under a uniform line load q = p b: δ = q L⁴ / (8 E I).
    Lx, b, h = box
    beam = {"deflection_per_E": -cfg["pressure"] * b * Lx ** 4 / (8 * (b * h ** 3 / 12))} if scene == "cantilever" else None
    rows = []
    for nu in cfg["nus"]:
        row = {"nu": nu}
        for element in cfg["elements"]:
            out = dhd_static(cfg["mesh"], element, E, nu, rho, fixed, loads)
            row[element] = (float(np.mean([out.payload["displacement"][n][2] for n in tip])) if out.ok
                            else None)
            row[f"{element}_outcome"] = out.as_json()
        c4 = solve_tet_mesh(mesh, {"model": "linear", "E": E, "nu": nu}, boundary_block(fixed, loads))
        row["ccx_C3D4"] = float(np.mean([c4["displacement"][n][2] for n in tip]))
        ref, n_hex = ccx_hex_tip(box, divisions, cfg["ccx"]["element_type"], E, nu, cfg["pressure"], X[tip].tolist(),
                                 scene, half_width)
        row["ccx_" + cfg["ccx"]["element_type"]] = ref
        if beam:
            row["euler_bernoulli"] = beam["deflection_per_E"] / E
        c = float(fem.wave_speed(E, nu, rho))
        row["wave_speed"] = c
        row["dt_critical"] = float(geo["altitude"].min() / c)
        omega = fem.max_frequency(X, T, E, nu, rho, fixed)
        row["dt_exact_linear"] = 2.0 / omega
        if cfg.get("explicit_steps", 0) > 0:
            # A short undamped run with the automatic step, per nonlinear element: it must run.
            for element in [e for e in cfg["elements"] if e not in SMALL_STRAIN]:
                ex = run_tool("dhd_sim", {"mesh": cfg["mesh"],
                                          "material": {"model": "neo_hookean_decoupled", "E": E, "nu": nu, "density": rho},
                                          "partition": {"kind": "uniform", "element": element},
                                          "damping": {"alpha": 0.0},
                                          "boundary": boundary_block(fixed, loads),
                                          "solver": {"kind": "explicit", "steps": cfg["explicit_steps"]}})
                key = f"explicit_auto_{element}"
                row[key] = ex.as_json()
                if ex.ok:
                    row[key]["dt"] = ex.payload["solver"]["dt"]
                    row[key]["dt_critical"] = ex.payload["solver"]["dt_critical"]
        rows.append(row)
        ctx.log(f"nu={nu}: " + ", ".join(f"{k}={row[k]}" for k in cfg["elements"] + ["ccx_C3D4"]) + f", ref={ref}")
    payload = {"rows": rows, "scene": scene, "patch_half_width": half_width, "box": box, "cells": cells, "hex_divisions": divisions, "hex_elements": n_hex,
               "hex_element_type": cfg["ccx"]["element_type"], "tets": len(T), "nodes": len(X),
               "tip_nodes": len(tip), "fixed_nodes": len(fixed), "pressure": cfg["pressure"],
               "E": E, "density": rho, "elements": cfg["elements"], "tools": tool_hashes(TOOLS)}
    write_artifact(ctx.out_path, SCHEMA, 1, TOOL, cfg, payload, inputs=[cfg["mesh"]])
