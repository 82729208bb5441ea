"""CalculiX reference of a rigid sphere pressed into a tetrahedral block ("tet_mesh" artifact)
→ "calculix_contact" v1: the force on the sphere against its depth.

Pipeline stage:   {"python": "pipeline.stages.calculix_contact", "config": {"mesh": "@mesh", ...}}

The block's tets are C3D4 elements as in pipeline.stages.calculix (same mesh, same node
numbers, the decoupled neo-Hookean law as *HYPERELASTIC, NEO HOOKE, NLGEOM). The sphere is a
rigid body (*RIGID BODY on its elements, one reference node driven down by `depth`): a solid of
C3D4 elements made of an icosahedron subdivided `subdivisions` times about a centre node (only
the lower cap, the part that can touch), whose outer faces are the master surface. The block's
faces on node set `contact_set` are the slave surface of a surface-to-surface *CONTACT PAIR
with a *SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR penalty (`penalty`, N/m³: contact
pressure per metre of overclosure; frictionless). The force on the sphere is minus the
reaction at its reference node, printed at every increment; the step's time runs 0 → 1 as the
depth does (the static step ramps the prescribed motion linearly).
"""
import math
import time
from pathlib import Path

import numpy as np

from pipeline.config_reader import ConfigReader
from pipeline.stages.calculix import _read_mesh_artifact, check_mesh, check_not_inverted
from pipeline.stages.calculix_ccx import (
    CalculixNumericalError, ccx_version, field_controls_lines, fmt, material_lines, mesh_lines,
    nset_lines, parse_dat, parse_sta, run_deck)
from pipeline.stages.calculix_scene import read_material

SCHEMA = "calculix_contact"
SCHEMA_VERSION = 1
TOOL = "pipeline.stages.calculix_contact"
# C3D4 faces as CalculiX numbers them (S1..S4), by local corner.
C3D4_FACES = ((0, 1, 2), (0, 3, 1), (1, 3, 2), (2, 3, 0))


def icosphere(subdivisions: int):
    """Unit vertices and outward triangles of an icosahedron subdivided `subdivisions` times."""
    t = (1.0 + math.sqrt(5.0)) / 2.0
    verts = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t),
             (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    verts = [np.array(v, float) / np.linalg.norm(v) for v in verts]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
             (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
             (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(subdivisions):
        middle = {}

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in middle:
                m = verts[a] + verts[b]
                verts.append(m / np.linalg.norm(m))
                middle[key] = len(verts) - 1
            return middle[key]
        nxt = []
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            nxt += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = nxt
    return np.array(verts), faces


def read_config(config: dict, source="config"):
    r = ConfigReader(config, "", source).require_object()
    out = {
        "mesh": r.string("mesh"),
        "material": read_material(r.at("material")),
        "fixed": r.string("fixed", "bottom"),
        "contact_set": r.string("contact_set", "top"),
        "penalty": r.number("penalty", positive=True),
        "increments": r.integer("increments", 20, minimum=2, maximum=10000),
        "timeout_s": r.number("timeout_s", 3600.0, positive=True),
    }
    s = r.at("sphere").require_object()
    out["radius"] = s.number("radius", positive=True)
    out["lowest_point"] = s.vector("lowest_point", 3)
    out["depth"] = s.number("depth", positive=True)
    out["subdivisions"] = s.integer("subdivisions", 4, minimum=1, maximum=7)
    s.reject_unknown()
    r.reject_unknown()
    if out["material"]["model"] != "neo_hookean_decoupled":
        r.fail("material.model \"neo_hookean_decoupled\" (the contact reference is finite-strain)",
               "material")
    return out


def build_deck(nodes, tets, node_sets, cfg) -> str:
    n_block = len(nodes)
    for name in (cfg["fixed"], cfg["contact_set"]):
        if not node_sets.get(name):
            raise ValueError(f"mesh: node set {name!r} missing or empty")
    top = set(node_sets[cfg["contact_set"]])
    slave = [(e + 1, f + 1) for e, tet in enumerate(tets) for f, face in enumerate(C3D4_FACES)
             if all(int(tet[k]) in top for k in face)]
    R = cfg["radius"]
    centre = np.asarray(cfg["lowest_point"], float) + np.array([0.0, 0.0, R])
    unit, faces = icosphere(cfg["subdivisions"])
    cap = [f for f in faces if min(unit[v][2] for v in f) < 0.2]  # the lower cap (z < 0.2 R)
    used = sorted({v for f in cap for v in f})
    centre_id = n_block + 1
    ids = {v: centre_id + 1 + k for k, v in enumerate(used)}
    ref, rot = centre_id + len(used) + 1, centre_id + len(used) + 2
    L = ["** Generated by pipeline.stages.calculix_contact: rigid sphere into a C3D4 block"]
    L += mesh_lines(nodes, "C3D4", np.asarray(tets) + 1)
    L.append("*NODE, NSET=SPHERENODES")
    L.append(f"{centre_id}, {fmt(centre[0])}, {fmt(centre[1])}, {fmt(centre[2])}")
    for v in used:
        x = centre + R * unit[v]
        L.append(f"{ids[v]}, {fmt(x[0])}, {fmt(x[1])}, {fmt(x[2])}")
    L.append("*NODE, NSET=REF")
    L += [f"{n}, {fmt(centre[0])}, {fmt(centre[1])}, {fmt(centre[2])}" for n in (ref, rot)]
    L.append("*ELEMENT, TYPE=C3D4, ELSET=SPHERE")
    master = []
    for k, f in enumerate(cap):
        e = len(tets) + 1 + k
        a, b, c = (centre + R * unit[v] for v in f)
        # Corner 1 the centre; the outer face is S3 (corners 2, 4, 3) when the tet is positive.
        corners = [ids[f[0]], ids[f[1]], ids[f[2]]] if np.dot(np.cross(a - centre, b - centre), c - centre) > 0 \
            else [ids[f[0]], ids[f[2]], ids[f[1]]]
        L.append(f"{e}, {centre_id}, {corners[0]}, {corners[1]}, {corners[2]}")
        master.append(e)
    L += nset_lines("FIXED", [n + 1 for n in node_sets[cfg["fixed"]]])
    L.append("*SURFACE, NAME=BLOCKTOP, TYPE=ELEMENT")
    L += [f"{e}, S{f}" for e, f in slave]
    L.append("*SURFACE, NAME=SPHERESURF, TYPE=ELEMENT")
    L += [f"{e}, S3" for e in master]
    L += material_lines(cfg["material"], "MAT")
    L += ["*MATERIAL, NAME=RIGID", "*ELASTIC", "2e11, 0.3",
          "*SOLID SECTION, ELSET=EALL, MATERIAL=MAT",
          "*SOLID SECTION, ELSET=SPHERE, MATERIAL=RIGID",
          f"*RIGID BODY, ELSET=SPHERE, REF NODE={ref}, ROT NODE={rot}",
          "*SURFACE INTERACTION, NAME=TOUCH",
          "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR",
          f"{fmt(cfg['penalty'])}, 0.0, 0.0",
          "*CONTACT PAIR, INTERACTION=TOUCH, TYPE=SURFACE TO SURFACE",
          "BLOCKTOP, SPHERESURF",
          "*BOUNDARY", "FIXED, 1, 3, 0.0", f"{rot}, 1, 3, 0.0", f"{ref}, 1, 2, 0.0"]
    inc = 1.0 / cfg["increments"]
    L += ["*STEP, NLGEOM, INC=100000", "*STATIC", f"{fmt(inc)}, 1.0, {fmt(inc * 1e-4)}, {fmt(inc)}"]
    L += field_controls_lines(1e-6, 1e-6)
    L += ["*BOUNDARY", f"{ref}, 3, 3, {fmt(-cfg['depth'])}",
          # One print frequency holds for every *NODE PRINT of the step: each increment, so that
          # the force is known along the way (the displacements are checked at the end only).
          "*NODE PRINT, NSET=REF, FREQUENCY=1", "RF",
          "*NODE PRINT, NSET=NALL, FREQUENCY=1", "U", "*END STEP"]
    return "\n".join(L) + "\n", ref, len(cap)


def solve(mesh: dict, cfg: dict) -> dict:
    nodes, tets = check_mesh(mesh)
    deck, ref, cap = build_deck(nodes, tets, mesh.get("node_sets", {}) or {}, cfg)
    started = time.monotonic()
    dat, sta, _ = run_deck(deck, timeout=cfg["timeout_s"])
    wall = time.monotonic() - started
    blocks = [b for b in parse_dat(dat) if b["quantity"] == "forces" and b["set"] == "REF"]
    if not blocks or abs(blocks[-1]["time"] - 1.0) > 1e-6:
        raise CalculixNumericalError("ccx stopped before the sphere reached its full depth")
    depth, force = [0.0], [0.0]
    for b in blocks:
        f = -b["rows"][ref][2]  # the body's force on the sphere: minus the holding reaction
        if not math.isfinite(f):
            raise CalculixNumericalError("ccx wrote a non-finite reaction on the sphere")
        depth.append(b["time"] * cfg["depth"])
        force.append(f)
    u_blocks = [b for b in parse_dat(dat) if b["quantity"] == "displacements" and b["set"] == "NALL"]
    u = np.array([u_blocks[-1]["rows"][n + 1] for n in range(len(nodes))])
    check_not_inverted(nodes, tets, u)
    return {"units": "SI", "solver": "CalculiX", "ccx_version": ccx_version(),
            "element_type": "C3D4", "element_count": int(len(tets)), "node_count": int(len(nodes)),
            "sphere_cap_elements": cap, "material": cfg["material"], "radius": cfg["radius"],
            "penalty": cfg["penalty"], "depth": depth, "force": force,
            "analysis": parse_sta(sta), "wall_time_s": wall}


def run(ctx):
    """Pipeline entry point: ctx.config (references resolved), ctx.out_path, ctx.root."""
    from pipeline.artifacts import write_artifact
    cfg = read_config(ctx.config)
    mesh_path = Path(cfg["mesh"])
    if ctx.root is not None and not mesh_path.is_absolute():
        mesh_path = Path(ctx.root) / mesh_path
    payload = solve(_read_mesh_artifact(mesh_path), cfg)
    recorded = Path(ctx.config["mesh"]) if Path(ctx.config["mesh"]).exists() else mesh_path
    write_artifact(ctx.out_path, SCHEMA, SCHEMA_VERSION, TOOL, ctx.config, payload, inputs=[recorded])
    a = payload["analysis"]
    ctx.log(f"calculix {payload['ccx_version']} contact: {payload['element_count']} C3D4, "
            f"{a['increments_taken']} increments, {a['iterations']} iterations, "
            f"{payload['wall_time_s']:.1f} s")
