"""Damping and long runs -> "stability_longrun" v1.

A small block (bottom held, the top-centre node stepped down at t = 0 and held) integrated by
dhd_sim for `steps` (10⁶) central-difference steps at the automatic step, for every element
kind: undamped (the energy must stay put: drift and its trend over the run) and with
mass-proportional damping (the motion must settle on the static equilibrium, which CalculiX
computes independently on the same tets: C3D4, linear material for the linear and corotational
elements, the decoupled neo-Hookean solid with NLGEOM for TLED).

Config:
  mesh, E, nu, density, kinds: {kind: dhd material model}, push (fraction of the height),
  steps, energy_interval, damping (α, 1/s)
"""
# Executables this stage runs: part of its cache key (pipeline/runner.py).
TOOLS = ("dhd_sim",)

import numpy as np

from pipeline.artifacts import write_artifact
from pipeline.stages.calculix import solve_tet_mesh
from pipeline.stages.stability_common import (extent, read_payload, run_tool, tool_hashes, top_centre_node,
                                              total_energy)

SCHEMA = "stability_longrun"
TOOL = "pipeline.stages.stability_longrun"


def run(ctx):
    cfg = ctx.config
    mesh = read_payload(cfg["mesh"])
    X = np.array(mesh["nodes"])
    _, _, height = extent(X)
    pushed = top_centre_node(X)
    boundary = {"fixed": ["bottom"], "prescribed": [{"nodes": [pushed], "displacement": [0, 0, -cfg["push"] * height]}]}
    rows = []
    for kind, model in cfg["kinds"].items():
        material = {"model": model, "E": cfg["E"], "nu": cfg["nu"], "density": cfg["density"]}
        ccx_model = "neo_hookean_decoupled" if model == "neo_hookean_decoupled" else "linear"
        ref = solve_tet_mesh(mesh, {"model": ccx_model, "E": cfg["E"], "nu": cfg["nu"]}, boundary,
                             {"nlgeom": ccx_model != "linear"})
        u_ref = np.array(ref["displacement"])
        for alpha in (0.0, cfg["damping"]):
            out = run_tool("dhd_sim", {
                "mesh": cfg["mesh"], "material": material, "damping": {"alpha": alpha},
                "partition": {"kind": "uniform", "element": kind}, "boundary": boundary,
                "solver": {"kind": "explicit", "steps": cfg["steps"], "energy_interval": cfg["energy_interval"]}},
                timeout=3600)
            row = {"kind": kind, "model": model, "damping": alpha, **out.as_json()}
            if out.ok:
                p = out.payload
                e = p["energies"]
                energy = np.array(total_energy(p))
                t = np.array(e["time"])
                row.update({"dt": p["solver"]["dt"], "dt_critical": p["solver"]["dt_critical"],
                            "simulated_time": p["solver"]["time"], "steps": p["solver"]["steps"],
                            "steps_per_second": p["timing"]["steps_per_second"],
                            # Samples thinned to ≤ 400 for the plot.
                            "time": t[::max(1, len(t) // 400)].tolist(),
                            "energy": energy[::max(1, len(t) // 400)].tolist()})
                e0 = energy[0]
                if alpha == 0.0:
                    rel = (energy - e0) / e0
                    half = len(rel) // 2
                    row["max_drift"] = float(np.abs(rel).max())
                    # Drift as a trend: the mean of the second half against the first (oscillation
                    # averages out, a systematic gain or loss does not).
                    row["trend"] = float(rel[half:].mean() - rel[:half].mean())
                else:
                    u = np.array(p["displacement"])
                    scale = np.abs(u_ref).max()
                    row["final_energy_ratio"] = float(energy[-1] / e0)
                    row["strain_energy_final"] = float(e["strain"][-1])
                    row["kinetic_final"] = float(e["kinetic"][-1])
                    row["vs_calculix_max"] = float(np.abs(u - u_ref).max() / scale)
            rows.append(row)
            ctx.log(f"{kind} alpha={alpha}: exit {out.code} {row.get('max_drift', row.get('vs_calculix_max'))}")
    payload = {"rows": rows, "mesh": {"nodes": len(X), "tets": len(mesh["tets"])}, "push": cfg["push"],
               "height": height, "precision": "double (dhd_sim has no single-precision path)",
               "tools": tool_hashes(TOOLS)}
    write_artifact(ctx.out_path, SCHEMA, 1, TOOL, cfg, payload, inputs=[cfg["mesh"]])
