"""The automatic explicit step under large deformation -> "stability_large_deformation" v1.

A cantilever clamped at x = 0 hangs under its own weight and deflects by a large share of its
length. For each element kind dhd_sim runs it with the automatic step (safety factor 0.9, no dt
given) twice: as dhd_sim runs it by default (the critical step re-estimated on the deformed mesh,
solver.dt_check_interval 10) and with the undeformed mesh's step throughout
(dt_check_interval 0), the behaviour before the re-estimate. A static solve of the same scene
gives the equilibrium that the damped run must settle on.

Config:
  mesh:      tet_mesh artifact of the beam (x along its length)
  kinds:     element kinds run uniformly (nonlinear ones: "tled", "anp")
  material:  dhd_sim material block
  damping:   mass-proportional damping alpha (1/s)
  gravity:   [gx, gy, gz] (m/s²)
  steps:     explicit steps per run
  increments: static load increments
"""
# Executables this stage runs: part of its cache key (pipeline/runner.py).
TOOLS = ("dhd_sim",)

import numpy as np

from pipeline.artifacts import write_artifact
from pipeline.stages.stability_common import read_payload, run_tool, tool_hashes

SCHEMA = "stability_large_deformation"
TOOL = "pipeline.stages.stability_large_deformation"


def run(ctx):
    cfg = ctx.config
    mesh = read_payload(cfg["mesh"])
    X = np.array(mesh["nodes"])
    length = float(X[:, 0].max() - X[:, 0].min())
    # The free end's node farthest from the clamp and lowest: the tip.
    tip = int(np.lexsort((X[:, 2], X[:, 1], -X[:, 0]))[0])
    base = {"mesh": cfg["mesh"], "material": cfg["material"],
            "boundary": {"fixed": ["x_min"], "gravity": cfg["gravity"]}}
    result = {"length": length, "tip_node": tip, "steps": cfg["steps"], "kinds": {}, "tools": tool_hashes(TOOLS)}
    for kind in cfg["kinds"]:
        part = {"partition": {"kind": "uniform", "element": kind}}
        static = run_tool("dhd_sim", {**base, **part, "solver": {"kind": "static", "increments": cfg["increments"]}})
        if not static.ok:
            raise RuntimeError(f"the static cantilever ({kind}) failed: {static.message}")
        u_static = np.array(static.payload["displacement"][tip])
        runs = {}
        for name, interval in (("re-estimated", 10), ("constant", 0)):
            out = run_tool("dhd_sim", {**base, **part, "damping": {"alpha": cfg["damping"]},
                                       "solver": {"kind": "explicit", "steps": cfg["steps"],
                                                  "dt_check_interval": interval}})
            row = {**out.as_json(), "stable": out.ok, "dt_check_interval": interval}
            if out.ok:
                s = out.payload["solver"]
                u = np.array(out.payload["displacement"][tip])
                row.update({"dt": s["dt"], "dt_final": s["dt_final"], "reestimates": len(s["dt_history"]) - 1,
                            "time": s["time"], "tip": u.tolist(),
                            "tip_error": float(np.linalg.norm(u - u_static) / np.linalg.norm(u_static))})
            runs[name] = row
        result["kinds"][kind] = {"static_tip": u_static.tolist(),
                                 "deflection_over_length": float(np.linalg.norm(u_static) / length), "runs": runs}
        ctx.log(f"{kind}: " + ", ".join(f"{n} {'ok' if r['stable'] else 'failed'}" for n, r in runs.items()))
    write_artifact(ctx.out_path, SCHEMA, 1, TOOL, cfg, result, inputs=[cfg["mesh"]])
