"""Named node sets added to a mesh by geometry, for scenes whose mesh has none (an imported
organ has only "boundary"): a fixed patch on one side, the surface node a tool pushes.

Pipeline stage:
    {"python": "pipeline.stages.dhd_node_sets",
     "config": {"mesh": "@mesh",
                "sets": {"fixed": {"select": "half_space", "point_in_box": [0.12, 0, 0],
                                   "normal": [-1, 0, 0], "boundary_only": true},
                         "push":  {"select": "nearest", "point_in_box": [0.45, 0.5, 1.5],
                                   "boundary_only": true}}}}

Selectors (every point is either "point" in metres or "point_in_box", fractions of the mesh's
bounding box per axis: 0 is the minimum, 1 the maximum, values outside [0, 1] lie outside):
  half_space  nodes with (x − p) · n ≥ 0: the side the normal points to
  sphere      nodes with |x − c| ≤ radius (m)
  nearest     the `count` nodes (default 1) nearest to p
"boundary_only" (default false) restricts a selector to nodes of the boundary triangles.

The mesh artifact is written again with the new sets; a name the mesh already has, or a set
that selects no node, is a config error (pipeline.config_reader.ConfigError, naming the JSON
pointer). For every new set the payload's "source.node_sets"
records the count, the centroid and, for boundary nodes, the mean outward normal (area-weighted
normals of the incident boundary triangles), so a report can check that a push is inward.
"""
from pathlib import Path

import numpy as np

from pipeline.artifacts import read_artifact, write_artifact
from pipeline.config_reader import ConfigReader

TOOL = "pipeline.stages.dhd_node_sets"
MESH_SCHEMA = "tet_mesh"
SELECTORS = ("half_space", "sphere", "nearest")


def boundary_nodes(boundary: np.ndarray, n_nodes: int) -> np.ndarray:
    mask = np.zeros(n_nodes, dtype=bool)
    if len(boundary):
        mask[np.unique(boundary)] = True
    return mask


def vertex_normals(nodes: np.ndarray, boundary: np.ndarray) -> np.ndarray:
    """Area-weighted outward normals at boundary nodes (zero elsewhere), unit length."""
    n = np.zeros_like(nodes)
    if len(boundary):
        p = nodes[boundary]
        face = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])  # 2 × area × unit normal
        for k in range(3):
            np.add.at(n, boundary[:, k], face)
    length = np.linalg.norm(n, axis=1, keepdims=True)
    return np.divide(n, length, out=np.zeros_like(n), where=length > 0)


def resolve_point(spec: ConfigReader, nodes: np.ndarray) -> np.ndarray:
    if spec.has("point") == spec.has("point_in_box"):
        spec.fail('exactly one of "point" and "point_in_box"')
    if spec.has("point"):
        return np.asarray(spec.vector("point", 3))
    lo, hi = nodes.min(axis=0), nodes.max(axis=0)
    return lo + np.asarray(spec.vector("point_in_box", 3)) * (hi - lo)


def select(spec, nodes: np.ndarray, boundary: np.ndarray, where: str = "") -> np.ndarray:
    """Sorted node indices the selector picks (`spec` a dict, `where` its JSON pointer)."""
    r = ConfigReader(spec, where).require_object()
    kind = r.choice("select", SELECTORS)
    only_boundary = r.boolean("boundary_only", default=False)
    candidates = np.flatnonzero(boundary_nodes(boundary, len(nodes))) if only_boundary \
        else np.arange(len(nodes))
    p = resolve_point(r, nodes)
    x = nodes[candidates]
    if kind == "half_space":
        normal = np.asarray(r.vector("normal", 3))
        if not np.linalg.norm(normal) > 0:
            r.fail("a non-zero vector", "normal")
        picked = candidates[(x - p) @ normal >= 0.0]
    elif kind == "sphere":
        picked = candidates[np.linalg.norm(x - p, axis=1) <= r.number("radius", positive=True)]
    else:
        count = r.integer("count", default=1, minimum=1)
        d = np.linalg.norm(x - p, axis=1)
        order = np.lexsort((candidates, d))  # nearest first, ties by node index
        picked = candidates[order[:count]]
    r.reject_unknown()  # a key of another selector is unknown here
    if len(picked) == 0:
        r.fail("a selector that picks at least one node")
    return np.sort(picked)


def add_node_sets(payload: dict, sets: dict):
    """(new payload, per-set record); the input payload is not modified."""
    nodes = np.asarray(payload["nodes"], dtype=float)
    boundary = np.asarray(payload.get("boundary", []), dtype=int).reshape(-1, 3)
    normals = vertex_normals(nodes, boundary)
    on_boundary = boundary_nodes(boundary, len(nodes))
    existing = payload.get("node_sets", {})
    new_sets = dict(existing)
    records = {}
    if not isinstance(sets, dict) or not sets:
        ConfigReader(sets, "/sets").fail("a non-empty object of name -> selector")
    for name, spec in sets.items():
        if name in existing:
            ConfigReader(sets, "/sets").fail("a name the mesh does not already use for a node set", name)
        ids = select(spec, nodes, boundary, f"/sets/{name}")
        new_sets[name] = [int(i) for i in ids]
        rec = {"count": int(len(ids)), "centroid": nodes[ids].mean(axis=0).tolist(),
               "selector": spec}
        b = ids[on_boundary[ids]]
        if len(b):
            mean_normal = normals[b].sum(axis=0)
            length = np.linalg.norm(mean_normal)
            rec["outward_normal"] = (mean_normal / length).tolist() if length > 0 else None
        records[name] = rec
    out = dict(payload)
    out["node_sets"] = new_sets
    source = dict(payload.get("source", {}))
    source["node_sets"] = {**source.get("node_sets", {}), **records}
    out["source"] = source
    return out, records


def run(ctx):
    cfg = ctx.config
    r = ConfigReader(cfg).require_object()
    mesh_path = Path(ctx.root / r.string("mesh"))
    sets = r.raw("sets", required=True)
    r.reject_unknown()
    payload = read_artifact(mesh_path, MESH_SCHEMA)["payload"]
    out, records = add_node_sets(payload, sets)
    for name, rec in records.items():
        ctx.log(f"{name}: {rec['count']} nodes around {np.round(rec['centroid'], 4).tolist()}")
    write_artifact(ctx.out_path, MESH_SCHEMA, 1, TOOL, cfg, out, inputs=[mesh_path])
