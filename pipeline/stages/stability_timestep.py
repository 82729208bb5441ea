"""Explicit time-step map -> "stability_timestep" v1.

For each mesh and element kind (linear, TLED, corotational) dhd_sim runs an undamped free
vibration — the bottom held, the top-centre node moved by a small step at t = 0, which excites
every mode including the highest — for a fixed number of steps at Δt = f · Δt_cr, f swept from
0.5 to 1.5 (forced past the limit with solver.force_dt). A run is stable when it completes:
dhd_sim stops an unstable one with exit 3 (energy growth beyond twice the initial energy,
non-finite values, or an inverted element). Between the last stable and the first unstable
factor the limit is bisected.

Beside the measured limit: the paper's estimate Δt_cr = L_e / c (000 eqs. 34–35) with L_e the
smallest altitude 3V/A (what dhd_sim uses) and with L_e the shortest edge, and the exact limit of
the linear undamped scheme, 2/ω_max, from the highest eigenvalue of M⁻¹K (stability_fem, an
independent numpy assembly). Finally the automatic step (safety factor 0.9, no dt given) is run
for a long time at a small and at a large displacement: it must never be unstable.

Config:
  meshes:        {name: tet_mesh artifact}
  kinds:         ["linear", "tled", "corotational"]
  material:      dhd_sim material block (E, nu, density, model)
  factors:       Δt/Δt_cr values of the coarse sweep
  extend:        further factors, tried in order while the last run was still stable
  steps:         steps per sweep run
  bisection:     bisection steps between the last stable and the first unstable factor
  push:          the step displacement of the top-centre node, as a fraction of the height
  fixed_fraction: nodes with z below zmin + fixed_fraction·height are held (0: the lowest layer)
  auto:          {"steps": n, "compressions": [fractions of the height]}: the automatic step on the
                 small-step scene and under large ramped compressions of the top
"""
# Executables this stage runs: part of its cache key (pipeline/runner.py).
TOOLS = ("dhd_sim",)

import numpy as np

from pipeline.artifacts import write_artifact
from pipeline.stages import stability_fem as fem
from pipeline.stages.stability_common import (extent, nodes_at_or_below, read_payload, run_tool, tool_hashes,
                                              top_centre_node, total_energy)

SCHEMA = "stability_timestep"
TOOL = "pipeline.stages.stability_timestep"


def scene(mesh, fixed_fraction, push):
    X = np.array(mesh["nodes"])
    lo, _, height = extent(X)
    fixed = nodes_at_or_below(X, lo[2] + max(fixed_fraction * height, 1e-9 * height))
    pushed = top_centre_node(X)
    boundary = {"fixed": [{"nodes": fixed}],
                "prescribed": [{"nodes": [pushed], "displacement": [0, 0, -push * height]}]}
    return boundary, fixed, pushed, height


def compression_scene(mesh, fixed_fraction, compression, ramp_time):
    """Bottom held, the top region (the same height fraction as the held one, at least the top
    layer) moved down by `compression` × height with a smooth ramp: a large, nearly homogeneous
    deformation under which a TLED element's wave speed changes."""
    X = np.array(mesh["nodes"])
    lo, hi, height = extent(X)
    zfix = lo[2] + max(fixed_fraction * height, 1e-9 * height)
    ztop = hi[2] - max(fixed_fraction * height, 1e-9 * height)
    return {"fixed": [{"nodes": nodes_at_or_below(X, zfix)}],
            "prescribed": [{"nodes": [int(i) for i in np.flatnonzero(X[:, 2] >= ztop)],
                            "displacement": [0, 0, -compression * height], "ramp_time": ramp_time, "ramp": "smooth"}]}


def one_run(mesh_path, material, kind, boundary, steps, dt_critical, factor, conservative=True):
    cfg = {"mesh": mesh_path, "material": material, "damping": {"alpha": 0.0},
           "partition": {"kind": "uniform", "element": kind}, "boundary": boundary,
           "solver": {"kind": "explicit", "steps": steps, "energy_interval": 20},
           "output": {"displacement": False}}  # energies and the step are read, not the field
    if factor is not None:
        cfg["solver"].update({"dt": factor * dt_critical, "force_dt": True})
    out = run_tool("dhd_sim", cfg)
    row = {"factor": factor, **out.as_json(), "stable": out.ok}
    if out.ok:
        if conservative:  # no work done on the body after t = 0: the energy must stay put
            energy = total_energy(out.payload)
            row["energy_drift"] = max(abs(e - energy[0]) for e in energy) / energy[0]
        row["dt"] = out.payload["solver"]["dt"]
        row["dt_critical"] = out.payload["solver"]["dt_critical"]
    else:
        row["failure"] = classify(out.message)
    return row


def classify(message):
    m = message.lower()
    if "inverted" in m:
        return "inverted element"
    if "energy" in m:
        return "energy growth"
    if "finite" in m or "nan" in m:
        return "non-finite"
    return "other"


def run(ctx):
    cfg = ctx.config
    material = cfg["material"]
    E, nu, rho = material["E"], material["nu"], material["density"]
    c = float(fem.wave_speed(E, nu, rho))
    result = {"meshes": {}, "wave_speed": c, "material": material, "steps": cfg["steps"],
              "push": cfg["push"], "tools": tool_hashes(TOOLS)}
    inputs = []
    for name, path in cfg["meshes"].items():
        inputs.append(path)
        mesh = read_payload(path)
        X, T = np.array(mesh["nodes"]), np.array(mesh["tets"])
        geo = fem.tet_geometry(X, T)
        boundary, fixed, pushed, height = scene(mesh, cfg.get("fixed_fraction", 0.0), cfg["push"])
        omega = fem.max_frequency(X, T, E, nu, rho, fixed + [pushed])
        est = {
            "min_altitude": float(geo["altitude"].min()),
            "min_edge": float(geo["min_edge"].min()),
            "min_dihedral_deg": float(geo["min_dihedral_deg"].min()),
            "dt_altitude": float(geo["altitude"].min() / c),
            "dt_edge": float(geo["min_edge"].min() / c),
            "omega_max": omega,
            "dt_exact_linear": 2.0 / omega,
        }
        dt_cr = est["dt_altitude"]
        entry = {"estimates": est, "nodes": len(X), "tets": len(T), "fixed_nodes": len(fixed),
                 "pushed_node": pushed, "height": height, "kinds": {}}
        for kind in cfg["kinds"]:
            rows = [one_run(path, material, kind, boundary, cfg["steps"], dt_cr, f) for f in cfg["factors"]]
            # A mesh whose estimate is very conservative is still stable at the last factor:
            # go on with the extension factors until the first unstable one.
            for f in cfg.get("extend", []):
                if not rows[-1]["stable"]:
                    break
                rows.append(one_run(path, material, kind, boundary, cfg["steps"], dt_cr, f))
            stable = [r["factor"] for r in rows if r["stable"]]
            unstable = [r["factor"] for r in rows if not r["stable"]]
            lo = max([f for f in stable if not unstable or f < min(unstable)], default=None)
            hi = min(unstable) if unstable else None
            bisect = []
            if lo is not None and hi is not None:
                for _ in range(cfg["bisection"]):
                    mid = 0.5 * (lo + hi)
                    r = one_run(path, material, kind, boundary, cfg["steps"], dt_cr, mid)
                    bisect.append(r)
                    if r["stable"]:
                        lo = mid
                    else:
                        hi = mid
            auto = []
            steps = cfg["auto"]["steps"]
            r = one_run(path, material, kind, boundary, steps, dt_cr, None)
            r["case"] = f"top-centre node stepped by {cfg['push']:g} of the height"
            auto.append(r)
            for compression in cfg["auto"].get("compressions", []):
                b = compression_scene(mesh, cfg.get("fixed_fraction", 0.0), compression, steps * 0.9 * dt_cr / 2)
                r = one_run(path, material, kind, b, steps, dt_cr, None, conservative=False)
                r["case"] = f"top compressed by {compression:g} of the height (smooth ramp over half the run)"
                r["compression"] = compression
                auto.append(r)
            entry["kinds"][kind] = {"sweep": rows, "bisection": bisect, "auto": auto,
                                    "limit": {"stable": lo, "unstable": hi}}
            ctx.log(f"{name} {kind}: stable up to {lo}, unstable from {hi} (x dt_cr); exact linear "
                    f"{est['dt_exact_linear'] / dt_cr:.4f}")
        result["meshes"][name] = entry
    write_artifact(ctx.out_path, SCHEMA, 1, TOOL, cfg, result, inputs=inputs)
