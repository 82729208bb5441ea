"""CalculiX references for nearly incompressible loadings -> "incompressible_reference" v1.

The scenes of the locking study (experiments/validation_incompressible.json), solved with
quadratic hexahedra (C3D20R, reduced integration: free of volumetric locking) under the decoupled
neo-Hookean law with NLGEOM, on a refinement series of structured meshes, so the report can
show where the answer stops moving:

- "punch": a block (`size`), bottom clamped, a bonded square flat punch of half width
  `punch_half_width` centred on the top face pushed down by `depth` (its nodes prescribed in
  all three components). Answer: the punch force (N, the z reaction on its nodes, positive
  pushing into the body).
- "cantilever": a bar along x clamped at x = 0; its end face x = L is moved down by `depth` in z
  (its x and y left free). Answer: the end-face force (N).

Config: scene, size [m], divisions (the coarsest hex divisions), refinements [ints: each a
multiple of the divisions], nus, E, depth, punch_half_width, element_type (default C3D20R),
increments (NLGEOM increments, default 5).
"""
import time

import numpy as np

from pipeline.artifacts import write_artifact
from pipeline.config_reader import ConfigReader
from pipeline.stages.calculix import read_analysis
from pipeline.stages.calculix_ccx import (ccx_version, fmt, last_block, mesh_lines, nset_lines, parse_dat, run_deck,
                                          section_and_step_lines)
from pipeline.stages.calculix_plate import PlateMesh
from pipeline.stages.calculix_scene import read_material

SCHEMA = "incompressible_reference"
TOOL = "pipeline.stages.incompressible_reference"
SCENES = ("punch", "cantilever")


def scene_nodes(P, size, scene, half_width):
    """(clamped, loaded) 0-based node indices of the scene on positions P."""
    tol = 1e-9 * max(size)
    if scene == "punch":
        clamped = np.flatnonzero(P[:, 2] <= tol)
        c = 0.5 * np.asarray(size[:2])
        inside = np.all(np.abs(P[:, :2] - c) <= half_width * (1 + 1e-9), axis=1)
        loaded = np.flatnonzero((P[:, 2] >= size[2] - tol) & inside)
    else:
        clamped = np.flatnonzero(P[:, 0] <= tol)
        loaded = np.flatnonzero(P[:, 0] >= size[0] - tol)
    return clamped, loaded


def deck(scene, size, divisions, element_type, E, nu, depth, half_width, increments):
    mesh = PlateMesh(size, divisions, element_type)
    clamped, loaded = scene_nodes(mesh.positions, size, scene, half_width)
    L = [f"** {TOOL}: {scene}, divisions {divisions}, nu = {nu}"]
    L += mesh_lines(mesh.positions, element_type, mesh.elements)
    L += nset_lines("CLAMPED", clamped + 1) + nset_lines("LOADED", loaded + 1)
    material = read_material(ConfigReader({"model": "neo_hookean_decoupled", "E": E, "nu": nu}, "/material"))
    analysis = read_analysis(ConfigReader({"increments": increments}, "/analysis"), "neo_hookean_decoupled")
    L += section_and_step_lines(material, analysis)
    L += ["*BOUNDARY", "CLAMPED, 1, 3, 0.0"]
    L += ["LOADED, 1, 2, 0.0"] if scene == "punch" else []
    L += [f"LOADED, 3, 3, {fmt(-depth)}"]
    L += ["*NODE PRINT, NSET=LOADED, TOTALS=ONLY, FREQUENCY=100000000", "RF", "*END STEP"]
    return "\n".join(L) + "\n", mesh


def solve(scene, size, divisions, element_type, E, nu, depth, half_width, increments):
    text, mesh = deck(scene, size, divisions, element_type, E, nu, depth, half_width, increments)
    started = time.monotonic()
    dat, _, _ = run_deck(text, timeout=3600)
    wall = time.monotonic() - started
    total = last_block(parse_dat(dat), "total force", "LOADED")["total"]
    # The reaction on the loaded nodes holds them down: the force the body pushes back with.
    return {"force": -float(total[2]), "nodes": len(mesh.positions), "elements": len(mesh.elements),
            "h": float(max(np.asarray(size) / np.asarray(divisions))), "wall_s": wall}


def run(ctx):
    r = ConfigReader(ctx.config, "")
    scene = r.choice("scene", list(SCENES))
    size = [float(x) for x in r.raw("size", required=True)]
    divisions = [int(x) for x in r.raw("divisions", required=True)]
    refinements = [int(x) for x in r.raw("refinements", required=True)]
    nus = [float(x) for x in r.raw("nus", required=True)]
    E = r.number("E", 5000.0, positive=True)
    depth = r.number("depth", positive=True)
    half_width = r.number("punch_half_width", 0.0025, positive=True)
    element_type = r.choice("element_type", ["C3D20R", "C3D20", "C3D8I"], "C3D20R")
    increments = r.integer("increments", 5, minimum=1)
    rows = []
    for nu in nus:
        for k in refinements:
            div = [d * k for d in divisions]
            row = {"nu": nu, "refine": k, "divisions": div,
                   **solve(scene, size, div, element_type, E, nu, depth, half_width, increments)}
            ctx.log(f"{scene} nu={nu} refine={k}: force {row['force']:.6g} N ({row['wall_s']:.0f} s)")
            rows.append(row)
    payload = {"scene": scene, "size": size, "E": E, "depth": depth, "punch_half_width": half_width,
               "element_type": element_type, "ccx_version": ccx_version(), "rows": rows}
    write_artifact(ctx.out_path, SCHEMA, 1, TOOL, ctx.config, payload)
