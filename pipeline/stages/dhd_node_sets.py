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
that selects no node, is a config error. For every new set the payload's "source.node_sets"
records the count, the centroid and, for boundary nodes, the mean outward normal (area-weighted
normals of the incident boundary triangles), so a report can check that a push is inward.
"""
from pathlib import Path

import numpy as np

from pipeline.artifacts import read_artifact, write_artifact

TOOL = "pipeline.stages.dhd_node_sets"
MESH_SCHEMA = "tet_mesh"
SELECTORS = {"half_space": {"normal"}, "sphere": {"radius"}, "nearest": {"count"}}
COMMON_KEYS = {"select", "point", "point_in_box", "boundary_only"}


class NodeSetConfigError(ValueError):
    """A bad stage config: names the key and what was expected."""


def _vec3(value, where):
    if not (isinstance(value, (list, tuple)) and len(value) == 3
            and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value)):
        raise NodeSetConfigError(f"{where}: expected [x, y, z] numbers, got {value!r}")
    return np.asarray(value, dtype=float)


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


def resolve_point(spec: dict, nodes: np.ndarray, where: str) -> np.ndarray:
    has_abs, has_box = "point" in spec, "point_in_box" in spec
    if has_abs == has_box:
        raise NodeSetConfigError(f"{where}: expected exactly one of \"point\" and \"point_in_box\"")
    if has_abs:
        return _vec3(spec["point"], f"{where}/point")
    lo, hi = nodes.min(axis=0), nodes.max(axis=0)
    return lo + _vec3(spec["point_in_box"], f"{where}/point_in_box") * (hi - lo)


def select(spec: dict, nodes: np.ndarray, boundary: np.ndarray, where: str = "") -> np.ndarray:
    """Sorted node indices the selector picks."""
    if not isinstance(spec, dict):
        raise NodeSetConfigError(f"{where}: expected an object")
    kind = spec.get("select")
    if kind not in SELECTORS:
        raise NodeSetConfigError(f"{where}/select: expected one of {sorted(SELECTORS)}, got {kind!r}")
    unknown = sorted(set(spec) - COMMON_KEYS - SELECTORS[kind])
    if unknown:
        raise NodeSetConfigError(f"{where}/{unknown[0]}: unknown key for selector {kind!r}")
    only_boundary = spec.get("boundary_only", False)
    if not isinstance(only_boundary, bool):
        raise NodeSetConfigError(f"{where}/boundary_only: expected true or false")
    candidates = np.flatnonzero(boundary_nodes(boundary, len(nodes))) if only_boundary \
        else np.arange(len(nodes))
    p = resolve_point(spec, nodes, where)
    x = nodes[candidates]
    if kind == "half_space":
        normal = _vec3(spec.get("normal"), f"{where}/normal")
        if not np.linalg.norm(normal) > 0:
            raise NodeSetConfigError(f"{where}/normal: expected a non-zero vector")
        picked = candidates[(x - p) @ normal >= 0.0]
    elif kind == "sphere":
        radius = spec.get("radius")
        if not isinstance(radius, (int, float)) or isinstance(radius, bool) or not radius > 0:
            raise NodeSetConfigError(f"{where}/radius: expected a positive number (m)")
        picked = candidates[np.linalg.norm(x - p, axis=1) <= radius]
    else:
        count = spec.get("count", 1)
        if not isinstance(count, int) or isinstance(count, bool) or count < 1:
            raise NodeSetConfigError(f"{where}/count: expected a positive integer")
        d = np.linalg.norm(x - p, axis=1)
        order = np.lexsort((candidates, d))  # nearest first, ties by node index
        picked = candidates[order[:count]]
    if len(picked) == 0:
        raise NodeSetConfigError(f"{where}: the selector picks no node")
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
        raise NodeSetConfigError("/sets: expected a non-empty object of name -> selector")
    for name, spec in sets.items():
        if name in existing:
            raise NodeSetConfigError(f"/sets/{name}: the mesh already has a node set of that name")
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
    unknown = sorted(set(cfg) - {"mesh", "sets"})
    if unknown:
        raise NodeSetConfigError(f"/{unknown[0]}: unknown key (expected \"mesh\" and \"sets\")")
    if "mesh" not in cfg:
        raise NodeSetConfigError("/mesh: expected a tet_mesh artifact reference")
    mesh_path = Path(ctx.root / cfg["mesh"])
    payload = read_artifact(mesh_path, MESH_SCHEMA)["payload"]
    out, records = add_node_sets(payload, cfg.get("sets"))
    for name, rec in records.items():
        ctx.log(f"{name}: {rec['count']} nodes around {np.round(rec['centroid'], 4).tolist()}")
    write_artifact(ctx.out_path, MESH_SCHEMA, 1, TOOL, cfg, out, inputs=[mesh_path])
