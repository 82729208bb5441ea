"""Mesh quality -> "stability_quality" v1.

Distorted versions of a regular cuboid mesh, and real liver meshes, and what their worst
elements do to the explicit step and to accuracy:

- `perturb`: every interior node moved by a uniform random vector of amplitude a·h (h the
  cell edge; seeded), a swept; a perturbation that inverts an element is kept as a case: the
  mesh goes to dhd_sim as it is and must be refused (exit 2);
- `sliver`: one interior node moved a fraction s of the way towards the plane of the opposite
  face of one of its tets, s → 1 (a single flat element in an otherwise perfect mesh).

Per mesh: smallest dihedral angle and altitude, the paper's Δt_cr = h_min/c (000 eqs. 34–35,
as dhd_sim reports it), the exact limit 2/ω_max (stability_fem), dhd_sim's power-iteration
limit (solver.critical_step "power_iteration"), the measured outcome of a run at each automatic
step, and the accuracy of a static shear test (bottom clamped, top face moved
sideways by `shear` × height): the total reaction force against the regular mesh and against a
twice finer regular mesh.

Config:
  base, fine:  tet_mesh artifacts (regular cuboid, and the same box with cells × 2)
  meshes:      {name: tet_mesh artifact} further meshes (no shear test: not boxes)
  material, perturb, sliver, seed, shear, explicit_steps
"""
# Executables this stage runs: part of its cache key (pipeline/runner.py).
TOOLS = ("dhd_sim",)

import copy
import json
import tempfile
from pathlib import Path

import numpy as np

from pipeline.artifacts import write_artifact
from pipeline.stages import stability_fem as fem
from pipeline.stages.stability_common import extent, nodes_at_or_below, read_payload, run_tool, tool_hashes

SCHEMA = "stability_quality"
TOOL = "pipeline.stages.stability_quality"


def write_mesh(folder, name, payload):
    path = Path(folder) / f"{name}.json"
    p = copy.deepcopy(payload)
    p.pop("quality", None)  # no longer true for the distorted nodes
    doc = {"schema": {"name": "tet_mesh", "version": 1},
           "provenance": {"tool": TOOL, "version": "python", "git_commit": "unknown", "config": {},
                          "inputs": {}, "seed": None},
           "payload": p}
    path.write_text(json.dumps(doc))
    return str(path)


def perturbed(base, amplitude, seed):
    X = np.array(base["nodes"])
    boundary = set(base["node_sets"]["boundary"])
    h = fem.tet_geometry(X, np.array(base["tets"]))["min_edge"].min()
    rng = np.random.default_rng(seed)
    move = rng.uniform(-1.0, 1.0, X.shape) * amplitude * h
    for i in boundary:
        move[i] = 0.0
    p = copy.deepcopy(base)
    p["nodes"] = (X + move).tolist()
    return p


def sliver(base, s):
    """One interior node moved towards the opposite face of the first tet that contains it."""
    X = np.array(base["nodes"])
    T = np.array(base["tets"])
    boundary = set(base["node_sets"]["boundary"])
    centre = X.mean(axis=0)
    interior = [i for i in range(len(X)) if i not in boundary]
    n = min(interior, key=lambda i: np.linalg.norm(X[i] - centre))
    e = int(np.flatnonzero((T == n).any(axis=1))[0])
    a, b, c = [int(v) for v in T[e] if v != n]
    normal = np.cross(X[b] - X[a], X[c] - X[a])
    normal /= np.linalg.norm(normal)
    foot = X[n] - np.dot(X[n] - X[a], normal) * normal
    p = copy.deepcopy(base)
    p["nodes"][n] = (X[n] + s * (foot - X[n])).tolist()
    return p, n, e


def shear_reaction(mesh_path, material, height, shear):
    cfg = {"mesh": mesh_path, "material": {**material, "model": "linear"},
           "partition": {"kind": "uniform", "element": "linear"},
           "boundary": {"fixed": ["bottom"], "prescribed": [{"set": "top", "displacement": [shear * height, 0, 0]}]},
           "solver": {"kind": "static", "increments": 1},
           "output": {"displacement": False}}  # only the reaction is read
    out = run_tool("dhd_sim", cfg)
    if not out.ok:
        return None, out
    r = [x for x in out.payload["reactions"] if x["name"].startswith("prescribed")][0]["force"]
    return float(r[0]), out


def measure(name, payload, path, cfg, kind_of_case, parameter, height=None, references=None):
    X, T = np.array(payload["nodes"]), np.array(payload["tets"])
    geo = fem.tet_geometry(X, T)
    mat = cfg["material"]
    row = {"mesh": name, "case": kind_of_case, "parameter": parameter, "tets": len(T),
           "min_volume": float(geo["volume"].min()),
           "min_dihedral_deg": float(geo["min_dihedral_deg"].min()),
           "max_dihedral_deg": float(geo["max_dihedral_deg"].max()),
           "min_altitude": float(geo["altitude"].min())}
    bottom = payload["node_sets"].get("bottom")
    if bottom is None:
        lo, _, mesh_height = extent(X)
        bottom = nodes_at_or_below(X, lo[2] + 0.15 * mesh_height)
    boundary = {"fixed": [{"nodes": bottom}]}
    run = run_tool("dhd_sim", {"mesh": path, "material": mat, "boundary": boundary,
                               "solver": {"kind": "explicit", "steps": cfg["explicit_steps"]}})
    row["explicit"] = run.as_json()
    if run.ok:
        row["dt_critical"] = run.payload["solver"]["dt_critical"]
    # The same run with the step from the largest eigenvalue (solver.critical_step
    # "power_iteration"): its limit beside the altitude estimate, and whether the run holds at
    # 0.9 × that limit.
    spectral = run_tool("dhd_sim", {"mesh": path, "material": mat, "boundary": boundary,
                                    "solver": {"kind": "explicit", "steps": cfg["explicit_steps"],
                                               "critical_step": "power_iteration"}})
    row["explicit_power_iteration"] = spectral.as_json()
    if spectral.ok:
        pi = spectral.payload["solver"]["dt_critical_power_iteration"]
        row["dt_power_iteration"] = pi["dt"]
        row["power_iteration"] = pi
    if row["min_volume"] > 0:
        omega = fem.max_frequency(X, T, mat["E"], mat["nu"], mat["density"], bottom)
        row["dt_exact_linear"] = 2.0 / omega
    if height is not None and row["min_volume"] > 0:
        force, out = shear_reaction(path, mat, height, cfg["shear"])
        row["shear_reaction"] = force
        row["shear_outcome"] = out.as_json()
        if force is not None and references.get("regular") and references.get("fine"):
            row["error_vs_regular"] = force / references["regular"] - 1.0
            row["error_vs_fine"] = force / references["fine"] - 1.0
    return row


def run(ctx):
    cfg = ctx.config
    base = read_payload(cfg["base"])
    _, _, height = extent(np.array(base["nodes"]))
    refs = {}
    for key in ("base", "fine"):
        force, out = shear_reaction(cfg[key], cfg["material"], height, cfg["shear"])
        refs["regular" if key == "base" else "fine"] = force
        refs[("regular" if key == "base" else "fine") + "_outcome"] = out.as_json()
    rows = []
    with tempfile.TemporaryDirectory(prefix="stability_quality_") as tmp:
        for a in cfg["perturb"]:
            p = perturbed(base, a, cfg["seed"])
            rows.append(measure("cuboid", p, write_mesh(tmp, f"perturb_{a}", p), cfg, "perturb", a, height, refs))
            ctx.log(f"perturb {a}: {rows[-1].get('dt_critical')} {rows[-1]['explicit']['message']}")
        for s in cfg["sliver"]:
            p, node, element = sliver(base, s)
            row = measure("cuboid", p, write_mesh(tmp, f"sliver_{s}", p), cfg, "sliver", s, height, refs)
            row["sliver_node"], row["sliver_element"] = node, element
            rows.append(row)
            ctx.log(f"sliver {s}: {rows[-1].get('dt_critical')} {rows[-1]['explicit']['message']}")
    for name, path in cfg.get("meshes", {}).items():
        rows.append(measure(name, read_payload(path), path, cfg, "as read", None))
    payload = {"rows": rows, "references": refs, "height": height, "shear": cfg["shear"],
               "material": cfg["material"], "seed": cfg["seed"], "tools": tool_hashes(TOOLS)}
    write_artifact(ctx.out_path, SCHEMA, 1, TOOL, cfg, payload,
                   inputs=[cfg["base"], cfg["fine"]] + list(cfg.get("meshes", {}).values()), seed=cfg["seed"])
