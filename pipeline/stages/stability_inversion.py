"""Large deformation and inversion -> "stability_inversion" v1.

A probe is pushed into the top of a block (bottom held) until elements invert: a rigid tool
moving the nodes under it down by a depth that grows smoothly (3s² − 2s³) from 0 to
`depth` × height over the run, with mass-proportional damping so that the motion is nearly
quasi-static. Two probes: a point (the top-centre node) and a blunt one (the nodes within a
radius of the top centre). Every element kind is pushed with the explicit solver and the
automatic step; the run is expected to end with exit 3 and a message naming the step, the
element and J. The step in the message gives the depth at which the first element inverted.
The static solver is pushed to a list of depths as well.

Config:
  mesh, material, damping (α, 1/s), kinds, probes: [{"name", "radius" (m, 0: one node)}],
  depth (fraction of the height), steps, static_depths (fractions), static_increments
"""
# Executables this stage runs: part of its cache key (pipeline/runner.py).
TOOLS = ("dhd_sim",)

import re

import numpy as np

from pipeline.artifacts import write_artifact
from pipeline.stages.stability_common import (distance_to_top_centre, extent, nodes_at_or_below, read_payload,
                                              run_tool, tool_hashes, top_centre_node)

SCHEMA = "stability_inversion"
TOOL = "pipeline.stages.stability_inversion"
STEP_RE = re.compile(r"step (\d+) \(t = ([-+0-9.eE]+) s\)")
ELEMENT_RE = re.compile(r"element (\d+)")
J_RE = re.compile(r"J = ([-+0-9.eE]+)")


def smooth(s):
    s = min(max(s, 0.0), 1.0)
    return s * s * (3 - 2 * s)


def probe_nodes(X, radius):
    if radius <= 0:
        return [top_centre_node(X)]
    return [int(i) for i in np.flatnonzero(distance_to_top_centre(X) <= radius)]


def parse_failure(message):
    info = {}
    m = STEP_RE.search(message)
    if m:
        info["step"], info["time"] = int(m.group(1)), float(m.group(2))
    m = ELEMENT_RE.search(message)
    if m:
        info["element"] = int(m.group(1))
    m = J_RE.search(message)
    if m:
        info["J"] = float(m.group(1))
    low = message.lower()
    # A clear message names what failed, where (step or increment, element) and the quantity.
    info["clear"] = ("invert" in low and "element" in low and "j =" in low
                     and ("step" in low or "increment" in low))
    return info


def run(ctx):
    cfg = ctx.config
    mesh = read_payload(cfg["mesh"])
    X = np.array(mesh["nodes"])
    lo, _, height = extent(X)
    bottom = nodes_at_or_below(X, lo[2] + 1e-9 * height)
    rows, static_rows = [], []
    for probe in cfg["probes"]:
        nodes = probe_nodes(X, probe["radius"])
        for kind in cfg["kinds"]:
            # The time of the run is only known through dt: a first short run gives it.
            base = {"mesh": cfg["mesh"], "material": cfg["material"], "damping": {"alpha": cfg["damping"]},
                    "partition": {"kind": "uniform", "element": kind},
                    "boundary": {"fixed": [{"nodes": bottom}]}, "solver": {"kind": "explicit", "steps": 1}}
            first = run_tool("dhd_sim", base)
            if not first.ok:
                raise RuntimeError(f"{kind}: the unloaded block does not run: {first.message}")
            dt = first.payload["solver"]["dt"]
            ramp_time = cfg["steps"] * dt
            push = -cfg["depth"] * height
            scene = dict(base)
            scene["boundary"] = {"fixed": [{"nodes": bottom}],
                                 "prescribed": [{"nodes": nodes, "displacement": [0, 0, push],
                                                 "ramp_time": ramp_time, "ramp": "smooth"}]}
            scene["solver"] = {"kind": "explicit", "steps": cfg["steps"], "energy_interval": 10}
            out = run_tool("dhd_sim", scene)
            row = {"probe": probe["name"], "probe_nodes": len(nodes), "kind": kind, "solver": "explicit",
                   "target_depth": cfg["depth"], "dt": dt, **out.as_json()}
            if out.ok:
                row["depth_reached"] = cfg["depth"]
                u = np.array(out.payload["displacement"])
                row["max_displacement"] = float(np.linalg.norm(u, axis=1).max())
            else:
                info = parse_failure(out.message)
                row.update(info)
                if "time" in info:
                    row["depth_at_failure"] = cfg["depth"] * smooth(info["time"] / ramp_time)
            rows.append(row)
            ctx.log(f"{probe['name']} {kind}: exit {out.code} {out.message}")
            for depth in cfg["static_depths"]:
                st = dict(scene)
                st["damping"] = {"alpha": 0.0}
                st["boundary"] = {"fixed": [{"nodes": bottom}],
                                  "prescribed": [{"nodes": nodes, "displacement": [0, 0, -depth * height]}]}
                st["solver"] = {"kind": "static", "increments": cfg["static_increments"]}
                s = run_tool("dhd_sim", st)
                srow = {"probe": probe["name"], "kind": kind, "solver": "static", "depth": depth, **s.as_json()}
                if not s.ok:
                    srow.update(parse_failure(s.message))
                static_rows.append(srow)
                if not s.ok:
                    break  # deeper pushes fail as well
    payload = {"explicit": rows, "static": static_rows, "height": height, "material": cfg["material"],
               "damping": cfg["damping"], "steps": cfg["steps"], "tools": tool_hashes(TOOLS),
               "inversion_safe_variant": None}
    write_artifact(ctx.out_path, SCHEMA, 1, TOOL, cfg, payload, inputs=[cfg["mesh"]])
