"""Mesh table (counts and quality) and a picture of every mesh: results/mesh/."""
import numpy as np
from mpl_toolkits.mplot3d.art3d import Poly3DCollection

from pipeline import plots
from pipeline.tables import write_table
from pipeline.artifacts import write_text_atomic

HEADERS = ["mesh", "source", "nodes", "tets", "boundary triangles", "volume (cm³)",
           "min tet volume (mm³)", "min dihedral (°)", "max dihedral (°)",
           "min altitude 3V/A (mm)", "slivers (< 5°)", "paper"]


def _picture(path, name, payload):
    nodes = np.asarray(payload["nodes"]) * 1000.0  # mm for the axes
    tris = np.asarray(payload["boundary"])
    fig = plots.plt.figure(figsize=(5, 4.2), dpi=110)
    ax = fig.add_subplot(projection="3d")
    light = np.array([0.4, -0.5, 0.75])
    light /= np.linalg.norm(light)
    p = nodes[tris]
    n = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    n /= np.linalg.norm(n, axis=1, keepdims=True) + 1e-300
    shade = 0.35 + 0.65 * np.clip(n @ light, 0, 1)
    colors = np.column_stack([0.85 * shade, 0.45 * shade, 0.40 * shade, np.ones_like(shade)])
    coll = Poly3DCollection(p, facecolors=colors, edgecolors=(0, 0, 0, 0.25), linewidths=0.2)
    ax.add_collection3d(coll)
    lo, hi = nodes.min(axis=0), nodes.max(axis=0)
    c, r = (lo + hi) / 2, (hi - lo).max() / 2
    ax.set_xlim(c[0] - r, c[0] + r)
    ax.set_ylim(c[1] - r, c[1] + r)
    ax.set_zlim(c[2] - r, c[2] + r)
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_zlabel("z (mm)")
    q = payload["quality"]
    ax.set_title(f"{name}: {q['nodes']} nodes, {q['tets']} tets", fontsize=9)
    plots.save(fig, path)


def report(ctx):
    paper = ctx.experiment.get("paper", {})
    rows = []
    pictures = []
    for stage in ctx.params.get("order", None) or [s for s in ctx.experiment["stages"] if s != "table"]:
        for run in ctx.runs(stage):
            pl = run.payload
            q = pl["quality"]
            src = pl["source"]
            source = (f"cuboid {src['cells'][0]}×{src['cells'][1]}×{src['cells'][2]} cells"
                      if src["kind"] == "cuboid" else src["path"].split("/")[-1])
            ref = paper.get(stage)
            paper_text = ""
            if ref:
                counts = ([f"{ref['nodes']} nodes"] if "nodes" in ref else []) + \
                         ([f"{ref['tets']} tets"] if "tets" in ref else []) + \
                         ([f"~{ref['tets_approx']} tets"] if "tets_approx" in ref else [])
                paper_text = " / ".join(counts) + f" ({ref['source']})"
            rows.append([stage, source, q["nodes"], q["tets"], q["boundary_triangles"],
                         q["total_volume"] * 1e6, q["min_volume"] * 1e9, q["min_dihedral_deg"],
                         q["max_dihedral_deg"], q["min_altitude"] * 1e3, q["sliver_count"], paper_text])
            png = f"mesh_{stage}.png"
            _picture(ctx.out(png), stage, pl)
            pictures.append(png)
    md = write_table(ctx, "meshes", HEADERS, rows,
                     "Meshes used by the experiments. Counts and quality are measured on the "
                     "written mesh artifacts; the last column gives the paper's stated counts.")
    gallery = "\n".join(f"![{p}]({p})" for p in pictures)
    write_text_atomic(ctx.out("summary.md"),
        "## Meshes\n\n" + md + "\nThe minimum altitude 3V/A is the length that limits the explicit "
        "time step (000 eq. 34). Pictures: " + ", ".join(f"[{p}](mesh/{p})" for p in pictures) + ".\n")
    write_text_atomic(ctx.out("README.md"), "# Meshes\n\n" + md + "\n" + gallery + "\n")
