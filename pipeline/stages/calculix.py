"""CalculiX reference solve of a tetrahedral mesh ("tet_mesh" artifact) → "calculix_result" v1.

Pipeline stage:   {"python": "pipeline.stages.calculix", "config": {"mesh": "@mesh", ...}}
From Python:      solve_tet_mesh(mesh_payload, material, boundary, analysis) -> payload dict
                  run_calculix(config, out_path) -> payload (and writes the artifact)

The mesh's linear tetrahedra become CalculiX C3D4 elements (one integration point, constant
strain: the same element as ours, so agreement is expected to solver tolerance, not only to
discretisation error). Our tets are positively oriented (det[x1-x0, x2-x0, x3-x0] > 0), which
is exactly CalculiX's C3D4 convention (node 4 on the side the face 1-2-3 normal points to), so
node order is kept; a negative volume is rejected here before ccx would stop with
"nonpositive jacobian". Node i of the mesh is CalculiX node i + 1; element e is e + 1.

Config reference and modelling choices: pipeline/stages/calculix.md.
"""
import json
import time
from pathlib import Path

import numpy as np

from pipeline.config_reader import ConfigError, ConfigReader
from pipeline.stages.calculix_ccx import (
    CalculixNumericalError, ccx_version, fmt, last_block, mesh_lines,
    nset_lines, parse_dat, run_deck, section_and_step_lines, sorted_rows, step_statistics)
from pipeline.stages.calculix_scene import Boundary, read_boundary, read_material

SCHEMA = "calculix_result"
SCHEMA_VERSION = 1
TOOL = "pipeline.stages.calculix"
ELEMENT_TYPE = "C3D4"
MESH_SCHEMA = "tet_mesh"
CONSTRAINED_SET = "CONSTRAINED"


# --------------------------------------------------------------------------- analysis controls
def read_analysis(reader: ConfigReader, model: str) -> dict:
    reader.require_object()
    nlgeom = reader.boolean("nlgeom", model != "linear")
    if model != "linear" and not nlgeom:
        reader.fail("nlgeom true (the neo-Hookean model is a finite-strain model)", "nlgeom")
    out = {
        "nlgeom": nlgeom,
        "increments": reader.integer("increments", 10, minimum=1, maximum=100000),
        "max_increments": reader.integer("max_increments", 1000, minimum=1),
        "min_increment": reader.number("min_increment", 1e-6, positive=True, maximum=1.0),
        "fixed_increments": reader.boolean("fixed_increments", False),
        "residual_tolerance": reader.number("residual_tolerance", 1e-7, positive=True),
        "correction_tolerance": reader.number("correction_tolerance", 1e-7, positive=True),
        "timeout_s": reader.number("timeout_s", 1800.0, positive=True),
    }
    reader.reject_unknown()
    if out["max_increments"] < out["increments"]:
        reader.fail(f"max_increments >= increments ({out['increments']})", "max_increments")
    return out


# --------------------------------------------------------------------------- mesh
def check_mesh(mesh: dict, source: str = "mesh"):
    """nodes (N×3) and tets (M×4, 0-based) as arrays; rejects a non-positive tetrahedron."""
    r = ConfigReader(mesh, "/payload", source).require_object()
    units = r.raw("units", "m")
    if units != "m":
        r.fail("\"m\" (artifacts are SI)", "units")
    try:
        nodes = np.asarray(mesh["nodes"], dtype=float)
        tets = np.asarray(mesh["tets"], dtype=np.int64)
    except (KeyError, TypeError, ValueError):
        r.fail("nodes [[x, y, z], ...] and tets [[i, j, k, l], ...]")
    if nodes.ndim != 2 or nodes.shape[1] != 3 or len(nodes) == 0:
        r.fail("a non-empty array of [x, y, z]", "nodes")
    if tets.ndim != 2 or tets.shape[1] != 4 or len(tets) == 0:
        r.fail("a non-empty array of 4 node indices", "tets")
    if tets.min() < 0 or tets.max() >= len(nodes):
        r.fail(f"node indices in [0, {len(nodes) - 1}]", "tets")
    x = nodes[tets]
    vol = np.einsum("ij,ij->i", x[:, 1] - x[:, 0], np.cross(x[:, 2] - x[:, 0], x[:, 3] - x[:, 0]))
    bad = np.flatnonzero(~(vol > 0))
    if len(bad):
        r.fail(f"positively oriented tetrahedra (tet {int(bad[0])} has volume "
               f"{vol[bad[0]] / 6:.3e})", "tets")
    return nodes, tets


def check_not_inverted(nodes, tets, u):
    """CalculiX's C3D4 hyperelastic law does not stop at J <= 0: a prescribed motion that
    turns elements inside out still "converges". A finite-strain answer with an inverted
    element is a numerical failure here."""
    x = (nodes + u)[tets]
    vol = np.einsum("ij,ij->i", x[:, 1] - x[:, 0], np.cross(x[:, 2] - x[:, 0], x[:, 3] - x[:, 0]))
    x0 = nodes[tets]
    vol0 = np.einsum("ij,ij->i", x0[:, 1] - x0[:, 0],
                     np.cross(x0[:, 2] - x0[:, 0], x0[:, 3] - x0[:, 0]))
    J = vol / vol0
    bad = np.flatnonzero(~(J > 0))
    if len(bad):
        raise CalculixNumericalError(
            f"inverted element in the CalculiX solution: tet {int(bad[0])} has J = "
            f"{J[bad[0]]:.3g} (limit J > 0; {len(bad)} of {len(J)} tets inverted)")


# --------------------------------------------------------------------------- the solve
def build_deck(nodes, tets, material: dict, bc: Boundary, analysis: dict) -> str:
    L = ["** Generated by pipeline.stages.calculix: tet mesh -> C3D4 reference solve"]
    L += mesh_lines(nodes, ELEMENT_TYPE, np.asarray(tets) + 1)  # CalculiX numbers nodes from 1
    L += nset_lines(CONSTRAINED_SET, [n + 1 for n in bc.constrained_nodes()])
    L += section_and_step_lines(material, analysis)
    # Inside the step, prescribed values and loads are ramped from 0 over the step (static
    # default amplitude), so NLGEOM increments follow the loading path.
    L.append("*BOUNDARY")
    L += [f"{n + 1}, {c + 1}, {c + 1}, {fmt(v)}" for (n, c), v in sorted(bc.value.items())]
    if bc.loads:
        L.append("*CLOAD")
        L += [f"{n + 1}, {c + 1}, {fmt(v)}" for (n, c), v in sorted(bc.loads.items())]
    # FREQUENCY beyond the increment limit: only the end of the step is printed.
    L += ["*NODE PRINT, NSET=NALL, FREQUENCY=100000000", "U",
          f"*NODE PRINT, NSET={CONSTRAINED_SET}, FREQUENCY=100000000", "RF", "*END STEP"]
    return "\n".join(L) + "\n"


def solve_tet_mesh(mesh: dict, material: dict, boundary: dict, analysis: dict = None,
                   source: str = "config") -> dict:
    """Solves the static problem on the mesh payload with CalculiX and returns the
    "calculix_result" payload (SI). Raises ConfigError (bad input), CalculixError (ccx missing
    or failing) or CalculixNumericalError (no convergence, inverted element, ...)."""
    nodes, tets = check_mesh(mesh)
    mat = read_material(ConfigReader(material, "/material", source))
    bc = read_boundary(ConfigReader(boundary, "/boundary", source), nodes,
                       mesh.get("node_sets", {}) or {})
    ana = read_analysis(ConfigReader(analysis or {}, "/analysis", source), mat["model"])
    deck = build_deck(nodes, tets, mat, bc, ana)
    started = time.monotonic()
    dat, sta, _ = run_deck(deck, timeout=ana["timeout_s"])
    wall = time.monotonic() - started
    blocks = parse_dat(dat)
    u = sorted_rows(last_block(blocks, "displacements", "NALL"), range(1, len(nodes) + 1))
    rf = last_block(blocks, "forces", CONSTRAINED_SET)
    sorted_rows(rf, [n + 1 for n in bc.constrained_nodes()])  # every constrained node present
    if ana["nlgeom"]:
        check_not_inverted(nodes, tets, np.asarray(u))
    stats = step_statistics(sta, ana["nlgeom"])
    if stats["increments_taken"] == 0:
        raise CalculixNumericalError("ccx finished without a converged increment")
    return {
        "units": "SI",
        "solver": "CalculiX",
        "ccx_version": ccx_version(),
        "element_type": ELEMENT_TYPE,
        "node_count": int(len(nodes)),
        "element_count": int(len(tets)),
        "material": mat,
        "analysis": {**ana, **stats},
        "constrained_dofs": len(bc.owner),
        "loaded_dofs": len(bc.loads),
        "displacement": u,
        "reactions": bc.reactions(lambda n: rf["rows"][n + 1]),
        "wall_time_s": wall,
    }


def reaction_force(payload: dict, name: str):
    """The total reaction (N) of the constraint entry called `name` (e.g. "fixed bottom",
    "prescribed top"), as dhd_sim names them."""
    found = [r["force"] for r in payload["reactions"] if r["name"] == name]
    if len(found) != 1:
        raise KeyError(f"{len(found)} constraints named {name!r}: "
                       + ", ".join(r["name"] for r in payload["reactions"]))
    return found[0]


# --------------------------------------------------------------------------- stage entry points
def _read_mesh_artifact(path: Path) -> dict:
    try:
        with open(path) as f:
            doc = json.load(f)
    except OSError as e:
        raise ConfigError(f"{path}: cannot read the mesh artifact ({e.strerror})") from None
    except json.JSONDecodeError as e:
        raise ConfigError(f"{path}: invalid JSON: {e}") from None
    schema = doc.get("schema", {}) if isinstance(doc, dict) else {}
    if schema.get("name") != MESH_SCHEMA or schema.get("version") != 1:
        raise ConfigError(
            f"{path}: /schema: expected a \"{MESH_SCHEMA}\" v1 artifact, got {schema!r}")
    if not isinstance(doc.get("payload"), dict):
        raise ConfigError(f"{path}: /payload: expected an object")
    return doc["payload"]


def run_calculix(config: dict, out_path, root=None) -> dict:
    """Reads config["mesh"] (a "tet_mesh" artifact path, relative to `root` when given), solves
    and writes the "calculix_result" artifact atomically at out_path. Returns the payload."""
    from pipeline.artifacts import write_artifact

    r = ConfigReader(config, "", "config").require_object()
    mesh_path = Path(r.string("mesh"))
    if root is not None and not mesh_path.is_absolute():
        mesh_path = Path(root) / mesh_path
    material = r.raw("material", required=True)
    boundary = r.raw("boundary", required=True)
    analysis = r.raw("analysis", {})
    r.reject_unknown()
    mesh = _read_mesh_artifact(mesh_path)
    payload = solve_tet_mesh(mesh, material, boundary, analysis)
    # Provenance names the input as the config did when that path works from here.
    recorded = Path(config["mesh"]) if Path(config["mesh"]).exists() else mesh_path
    write_artifact(out_path, SCHEMA, SCHEMA_VERSION, TOOL, config, payload, inputs=[recorded])
    return payload


def run(ctx):
    """Pipeline entry point: ctx.config (references resolved), ctx.out_path, ctx.root."""
    payload = run_calculix(ctx.config, ctx.out_path, ctx.root)
    a = payload["analysis"]
    ctx.log(f"calculix {payload['ccx_version']}: {payload['node_count']} nodes, "
            f"{payload['element_count']} {ELEMENT_TYPE}, {a['increments_taken']} increments, "
            f"{a['iterations']} iterations, {payload['wall_time_s']:.2f} s")
