"""dhd_sim's element kinds on the locking scenes -> "incompressible_elements" v1.

The scenes of pipeline.stages.incompressible_reference ("punch", "cantilever"), solved by
dhd_sim's static solver with every listed element kind (uniform partition, decoupled
neo-Hookean law) on every listed tet mesh (mesher cuboids of the scene's box), at every ν.
Answer: the force on the loaded nodes (N, the z reaction of the prescribed entry, positive
pushing into the body). With `explicit_steps` > 0 the stage also runs, on the first mesh, a
short undamped explicit run per kind and ν (one thread) on the last mesh: its `steps_per_second` and the
critical step by power iteration (2/ω_max of the lumped system at rest) and by the altitude
rule. Timings are taken in one stage, kinds interleaved, on whatever machine runs it.

Config: scene, meshes [paths of tet_mesh artifacts], elements, nus, E, density, depth,
punch_half_width, explicit_steps (default 0), repeats (timing repeats, default 3).
"""
# Executables this stage runs: part of its cache key (pipeline/runner.py).
TOOLS = ("dhd_sim",)

import numpy as np

from pipeline.artifacts import write_artifact
from pipeline.config_reader import ConfigReader
from pipeline.stages.stability_common import read_payload, run_tool, tool_hashes

SCHEMA = "incompressible_elements"
TOOL = "pipeline.stages.incompressible_elements"


def boundary(scene, box, depth, half_width):
    """dhd_sim's boundary block of the scene on a box [0, box]."""
    if scene == "punch":
        cx, cy, top = 0.5 * box[0], 0.5 * box[1], box[2]
        loaded = {"box": {"min": [cx - half_width, cy - half_width, top], "max": [cx + half_width, cy + half_width, top]},
                  "displacement": [0, 0, -depth]}
        return {"fixed": ["bottom"], "prescribed": [loaded]}
    return {"fixed": ["x_min"], "prescribed": [{"set": "x_max", "displacement": [0, 0, -depth], "components": "z"}]}


def config(mesh, element, nu, E, rho, bc, solver):
    return {"mesh": mesh, "material": {"model": "neo_hookean_decoupled", "E": E, "nu": nu, "density": rho},
            "partition": {"kind": "uniform", "element": element}, "boundary": bc, "solver": solver,
            "output": {"displacement": False}}


def loaded_force(payload):
    found = [r["force"] for r in payload["reactions"] if r["name"].startswith("prescribed")]
    return -float(found[0][2])


def run(ctx):
    r = ConfigReader(ctx.config, "")
    scene = r.choice("scene", ["punch", "cantilever"])
    meshes = r.raw("meshes", required=True)
    elements = r.raw("elements", required=True)
    nus = [float(x) for x in r.raw("nus", required=True)]
    E = r.number("E", 5000.0, positive=True)
    rho = r.number("density", 1000.0, positive=True)
    depth = r.number("depth", positive=True)
    half_width = r.number("punch_half_width", 0.0025, positive=True)
    steps = r.integer("explicit_steps", 0, minimum=0)
    repeats = r.integer("repeats", 3, minimum=1)
    rows = []
    for path in meshes:
        mesh = read_payload(path)
        X = np.array(mesh["nodes"])
        box = (X.max(axis=0) - X.min(axis=0)).tolist()
        bc = boundary(scene, box, depth, half_width)
        # Newton's residual cannot fall far below the round-off of forces that carry K (J − 1).
        solver = {"kind": "static", "increments": 5, "tolerance": 1e-8}
        for nu in nus:
            for element in elements:
                out = run_tool("dhd_sim", config(path, element, nu, E, rho, bc, solver), timeout=3600)
                row = {"mesh": path, "cells": mesh["source"]["cells"], "tets": len(mesh["tets"]),
                       "h": float(box[0] / mesh["source"]["cells"][0]), "nu": nu, "element": element,
                       "outcome": out.as_json()}
                if out.ok:
                    row["force"] = loaded_force(out.payload)
                    row["solve_seconds"] = out.payload["timing"]["solve_seconds"]
                ctx.log(f"{scene} {mesh['source']['cells']} nu={nu} {element}: {row.get('force')}")
                rows.append(row)
    timing = []
    if steps > 0:
        mesh = read_payload(meshes[-1])
        X = np.array(mesh["nodes"])
        bc = boundary(scene, (X.max(axis=0) - X.min(axis=0)).tolist(), depth, half_width)
        bc["prescribed"][0]["ramp_time"] = 1.0  # a slow start: the few timed steps see a smooth load
        for nu in nus:
            for rep in range(repeats):
                for element in elements:  # interleaved: a change in the machine's load hits every kind
                    solver = {"kind": "explicit", "steps": steps, "critical_step": "power_iteration",
                              "energy_interval": steps}
                    cfg = config(meshes[-1], element, nu, E, rho, bc, solver)
                    cfg["damping"] = {"alpha": 0.0}
                    cfg["threads"] = 1
                    out = run_tool("dhd_sim", cfg, timeout=3600)
                    row = {"nu": nu, "element": element, "repeat": rep, "outcome": out.as_json()}
                    if out.ok:
                        s = out.payload["solver"]
                        row.update({"steps_per_second": out.payload["timing"]["steps_per_second"],
                                    "dt_critical_power_iteration": s["dt_critical_power_iteration"]["dt"],
                                    "dt_critical_altitude": s["dt_critical"]})
                    timing.append(row)
                    ctx.log(f"timing nu={nu} {element}: {row.get('steps_per_second')} steps/s")
    payload = {"scene": scene, "elements": elements, "nus": nus, "E": E, "depth": depth,
               "punch_half_width": half_width, "rows": rows, "timing": timing, "tets_timed": None,
               "tools": tool_hashes(TOOLS)}
    if timing:
        payload["tets_timed"] = len(read_payload(meshes[-1])["tets"])
    write_artifact(ctx.out_path, SCHEMA, 1, TOOL, ctx.config, payload, inputs=list(meshes))
