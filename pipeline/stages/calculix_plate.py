"""CalculiX reference for paper 002's plate check -> "calculix_plate" v1.

002 §5.2: a 48 × 48 × 6 mm plate (E = 0.32 MPa, ν = 0.49), a point force (0.9, −0.7, −0.22) N
at the centre of the top surface (node 61 of the paper's 11 × 11 top grid); the paper reports
the ANSYS displacement of that node. This module meshes the plate with structured hexahedra,
fixes one of three support variants, solves with CalculiX and reports the loaded node's
displacement and the top-layer displacement on the paper's 11 × 11 grid (4.8 mm spacing).

Pipeline stage:   {"python": "pipeline.stages.calculix_plate", "config": {...}}
From Python:      solve_plate(config) -> payload dict;  run_plate(config, out_path) -> payload

Element choice (default C3D20R, see pipeline/stages/calculix.md): with ν = 0.49 and a plate
loaded in bending, fully integrated linear hexahedra (C3D8) lock both volumetrically and in
shear and come out far too stiff; quadratic hexahedra with reduced integration (C3D20R) are
free of both and converge fastest. C3D8, C3D8I and C3D20 stay selectable for comparison.
"""
import time

import numpy as np

from pipeline.config_reader import ConfigReader
from pipeline.stages.calculix import read_analysis
from pipeline.stages.calculix_ccx import (
    CalculixNumericalError, ccx_version, fmt, last_block, mesh_lines, nset_lines, parse_dat,
    run_deck, section_and_step_lines, sorted_rows, step_statistics)
from pipeline.stages.calculix_scene import read_material

SCHEMA = "calculix_plate"
SCHEMA_VERSION = 1
TOOL = "pipeline.stages.calculix_plate"
ELEMENT_TYPES = ("C3D20R", "C3D20", "C3D8I", "C3D8")
SUPPORTS = ("side_faces", "bottom_edges", "vertical_corner_edges")

# Corner offsets of a hexahedron in CalculiX/Abaqus order (nodes 1–8: bottom face z−
# counter-clockwise seen from z+, then the top face), and the 12 edges whose midpoints are
# nodes 9–20 of C3D20/C3D20R (bottom edges, top edges, then the vertical edges).
HEX_CORNERS = ((0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0),
               (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1))
HEX_EDGES = ((0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4),
             (0, 4), (1, 5), (2, 6), (3, 7))


# --------------------------------------------------------------------------- mesh
class PlateMesh:
    """A structured hexahedral mesh of the box [0, a] × [0, b] × [0, c].

    Nodes live on a lattice of `r` points per element edge (r = 1 for 8-node, 2 for 20-node
    elements: lattice point (I, J, K) sits at (I, J, K) · h / r). For 20-node elements only
    lattice points with at most one odd index are nodes (corners and edge midpoints)."""

    def __init__(self, size, divisions, element_type):
        self.size = np.asarray(size, dtype=float)
        self.div = tuple(int(d) for d in divisions)
        self.element_type = element_type
        self.r = 2 if element_type.startswith("C3D20") else 1
        self.lat = tuple(self.r * d for d in self.div)  # largest lattice index per axis
        self.step = self.size / np.asarray(self.lat, dtype=float)
        self.node_of = {}
        positions = []
        for K in range(self.lat[2] + 1):
            for J in range(self.lat[1] + 1):
                for I in range(self.lat[0] + 1):
                    if self.r == 2 and (I % 2) + (J % 2) + (K % 2) > 1:
                        continue
                    self.node_of[(I, J, K)] = len(positions) + 1  # CalculiX numbers from 1
                    positions.append(np.array([I, J, K], dtype=float) * self.step)
        self.positions = np.array(positions)
        self.elements = []
        for k in range(self.div[2]):
            for j in range(self.div[1]):
                for i in range(self.div[0]):
                    base = np.array([i, j, k]) * self.r
                    corners = [tuple(base + np.array(c) * self.r) for c in HEX_CORNERS]
                    conn = [self.node_of[c] for c in corners]
                    if self.r == 2:
                        for a, b in HEX_EDGES:
                            mid = tuple((np.array(corners[a]) + np.array(corners[b])) // 2)
                            conn.append(self.node_of[mid])
                    self.elements.append(conn)

    def lattice_index(self, point, tol=1e-9):
        """The lattice index of a point, or None when it is not a lattice point."""
        q = np.asarray(point, dtype=float) / self.step
        idx = np.rint(q)
        if np.any(np.abs(q - idx) > tol * max(self.lat)) or np.any(idx < 0) or np.any(
                idx > np.asarray(self.lat)):
            return None
        return tuple(int(v) for v in idx)

    def node_at(self, point):
        """The CalculiX node at a point, or None."""
        idx = self.lattice_index(point)
        return None if idx is None else self.node_of.get(idx)

    def support_nodes(self, support):
        I1, J1, _ = self.lat
        out = []
        for (I, J, K), n in self.node_of.items():
            side = I in (0, I1) or J in (0, J1)
            if support == "side_faces":
                keep = side
            elif support == "bottom_edges":
                keep = side and K == 0
            else:  # vertical_corner_edges
                keep = I in (0, I1) and J in (0, J1)
            if keep:
                out.append(n)
        return sorted(out)

    def top_nodes(self):
        return sorted(n for (I, J, K), n in self.node_of.items() if K == self.lat[2])


# --------------------------------------------------------------------------- config
def read_plate_config(config: dict, source="config") -> dict:
    r = ConfigReader(config, "", source).require_object()
    size = r.vector("size", 3)
    if min(size) <= 0:
        r.fail("three positive edge lengths in metres", "size")
    divisions = r.raw("divisions", required=True)
    if not (isinstance(divisions, list) and len(divisions) == 3
            and all(isinstance(d, int) and not isinstance(d, bool) and 1 <= d <= 200
                    for d in divisions)):
        r.fail("[nx, ny, nz]: element counts between 1 and 200", "divisions")
    element_type = r.choice("element_type", list(ELEMENT_TYPES), "C3D20R")
    material = read_material(r.at("material"))
    support = r.choice("support", list(SUPPORTS))
    force = r.vector("force", 3)
    analysis = read_analysis(r.at("analysis", default={}, required=False), material["model"])
    g = r.at("grid", default={}, required=False).require_object()
    count = g.raw("count", [11, 11])
    if not (isinstance(count, list) and len(count) == 2
            and all(isinstance(c, int) and not isinstance(c, bool) and c >= 1 for c in count)):
        g.fail("[nx, ny]: positive point counts", "count")
    spacing = g.number("spacing", size[0] / (count[0] - 1) if count[0] > 1 else size[0],
                       positive=True)
    g.reject_unknown()
    r.reject_unknown()
    return {"size": size, "divisions": divisions, "element_type": element_type,
            "material": material, "support": support, "force": force, "analysis": analysis,
            "grid": {"count": count, "spacing": spacing}}


# --------------------------------------------------------------------------- the solve
def build_plate_deck(mesh: PlateMesh, cfg: dict, loaded: int, supported: list) -> str:
    L = ["** Generated by pipeline.stages.calculix_plate: 002 plate check"]
    L += mesh_lines(mesh.positions, mesh.element_type, mesh.elements)
    L += nset_lines("SUPPORT", supported)
    L += nset_lines("TOP", mesh.top_nodes())
    L += section_and_step_lines(cfg["material"], cfg["analysis"])
    L += ["*BOUNDARY", "SUPPORT, 1, 3, 0.0"]
    L.append("*CLOAD")
    L += [f"{loaded}, {d + 1}, {fmt(f)}" for d, f in enumerate(cfg["force"]) if f != 0.0]
    L += ["*NODE PRINT, NSET=TOP, FREQUENCY=100000000", "U",
          "*NODE PRINT, NSET=SUPPORT, TOTALS=ONLY, FREQUENCY=100000000", "RF", "*END STEP"]
    return "\n".join(L) + "\n"


def solve_plate(config: dict, source="config") -> dict:
    """Builds, solves and reads back the plate problem; returns the "calculix_plate" payload."""
    cfg = read_plate_config(config, source)
    mesh = PlateMesh(cfg["size"], cfg["divisions"], cfg["element_type"])
    size = np.asarray(cfg["size"])
    centre = np.array([size[0] / 2, size[1] / 2, size[2]])
    loaded = mesh.node_at(centre)
    if loaded is None:
        ConfigReader(config, "", source).fail(
            "divisions that put a node at the top centre (even nx and ny)", "divisions")
    supported = mesh.support_nodes(cfg["support"])
    deck = build_plate_deck(mesh, cfg, loaded, supported)
    started = time.monotonic()
    dat, sta, _ = run_deck(deck, timeout=cfg["analysis"]["timeout_s"])
    wall = time.monotonic() - started
    blocks = parse_dat(dat)
    top_block = last_block(blocks, "displacements", "TOP")
    reaction = last_block(blocks, "total force", "SUPPORT")["total"]
    top = mesh.top_nodes()
    top_u = sorted_rows(top_block, top)

    count, spacing = cfg["grid"]["count"], cfg["grid"]["spacing"]
    grid_positions, grid_numbers, grid_u, grid_nodes = [], [], [], []
    for gj in range(count[1]):
        for gi in range(count[0]):
            p = np.array([gi * spacing, gj * spacing, size[2]])
            n = mesh.node_at(p)
            grid_positions.append(p.tolist())
            grid_numbers.append(gi + count[0] * gj + 1)  # 002 §4: N = x/4.8 + 11 y/4.8 + 1
            grid_nodes.append(n)
            grid_u.append(None if n is None else top_block["rows"][n])
    # The supports carry the whole load in a static solve: a mismatch means a wrong deck.
    f = np.asarray(cfg["force"])
    imbalance = float(np.linalg.norm(np.asarray(reaction) + f))
    if not cfg["analysis"]["nlgeom"] and imbalance > 1e-4 * max(np.linalg.norm(f), 1e-300):
        raise CalculixNumericalError(f"support reactions {reaction} do not balance the force "
                                     f"{cfg['force']} (|sum| = {imbalance:.3e} N)")
    return {
        "units": "SI",
        "solver": "CalculiX",
        "ccx_version": ccx_version(),
        "element_type": cfg["element_type"],
        "size": cfg["size"],
        "divisions": cfg["divisions"],
        "element_size": (size / np.asarray(cfg["divisions"])).tolist(),
        "node_count": int(len(mesh.positions)),
        "element_count": len(mesh.elements),
        "material": cfg["material"],
        "support": cfg["support"],
        "supported_nodes": len(supported),
        "force": cfg["force"],
        "analysis": {**cfg["analysis"], **step_statistics(sta, cfg["analysis"]["nlgeom"])},
        "top_centre": {"position": centre.tolist(), "displacement": top_block["rows"][loaded]},
        "support_reaction_total": reaction,
        "top_grid": {"count": count, "spacing": spacing, "positions": grid_positions,
                     "paper_node_numbers": grid_numbers,
                     "on_mesh": [n is not None for n in grid_nodes],
                     "displacement": grid_u},
        "top_surface": {"positions": mesh.positions[np.asarray(top) - 1].tolist(),
                        "displacement": top_u},
        "wall_time_s": wall,
    }


def run_plate(config: dict, out_path) -> dict:
    from pipeline.artifacts import write_artifact

    payload = solve_plate(config)
    write_artifact(out_path, SCHEMA, SCHEMA_VERSION, TOOL, config, payload)
    return payload


def run(ctx):
    """Pipeline entry point: ctx.config, ctx.out_path."""
    payload = run_plate(ctx.config, ctx.out_path)
    u = np.asarray(payload["top_centre"]["displacement"]) * 1e3
    ctx.log(f"calculix {payload['ccx_version']} plate {payload['element_type']} "
            f"{payload['divisions']} {payload['support']}: top centre u = "
            f"({u[0]:.4f}, {u[1]:.4f}, {u[2]:.4f}) mm, {payload['wall_time_s']:.2f} s")
