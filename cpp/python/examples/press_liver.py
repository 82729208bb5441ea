"""Press a probe into a liver and plot the force against the depth.

A walkthrough of the step-by-step API (cpp/python/README.md): the SOFA liver (Gmsh volume mesh,
decimetres, converted to metres on import), its thick end held, a tool tip coupled by a spring
to the surface node on top, moved down a little every frame of 1 ms while the explicit engine
steps, and the spring force (what a haptic device would render) read back every frame.

    PYTHONPATH=build/python /usr/bin/python3 cpp/python/examples/press_liver.py [out.png]
"""
import sys

import numpy as np

import softsim

# 1. The mesh, through mesher's own reader (scale: decimetres -> metres).
mesh = softsim.mesh_from_config(
    {"source": {"kind": "file", "path": "experiments/data/meshes/sofa_liver2.msh", "scale": 0.1}}
)
nodes = mesh.nodes  # N x 3, a read-only view of the mesh's own array
lo, hi = nodes.min(axis=0), nodes.max(axis=0)

# 2. Hold the boundary nodes of the thick (-x) end; press the top-surface node nearest the middle.
boundary = np.unique(mesh.boundary)  # nodes of the boundary triangles
held = [int(i) for i in boundary if nodes[i, 0] < lo[0] + 0.12 * (hi[0] - lo[0])]
middle = 0.5 * (lo + hi)
top = np.array([middle[0], middle[1], hi[2] + 1.0])
config = {
    "material": {"model": "neo_hookean_decoupled", "E": 5000, "nu": 0.35, "density": 1000},
    "damping": {"alpha": 30.0},
    "boundary": {
        "fixed": [{"nodes": held}],
        "probe": {"nearest": top.tolist(), "stiffness": 200.0, "displacement": [0, 0, 0]},
    },
    "solver": {"kind": "explicit", "safety_factor": 0.8},
}
scene = softsim.Scene(config, mesh)
start = scene.probe_position
print(f"{scene.num_nodes} nodes, dt = {scene.dt:.3g} s, probe at {np.round(start, 4)} m")

# 3. The haptic loop: frames of about 1 ms (whole steps), the tip pushed 1 cm down over 1500
# frames, then held for 500 while the tissue settles.
steps_per_frame = max(1, int(round(1e-3 / scene.dt)))
print(f"{steps_per_frame} steps per frame of {1e3 * steps_per_frame * scene.dt:.2f} ms")
depth, force = [], []
for k in range(2000):
    d = 0.01 * min(1.0, k / 1500)
    scene.probe_position = start - np.array([0.0, 0.0, d])
    scene.step(steps_per_frame)
    depth.append(d)
    force.append(-scene.probe_force()[2])  # the spring pushes the tissue down: force on the tool is up
depth, force = np.array(depth), np.array(force)
print(f"{scene.steps_done} steps to t = {scene.time:.2f} s; force at 1 cm: {force[-1]:.4f} N")
print("reactions:", {name: np.round(r, 5).tolist() for name, r in scene.reactions().items()})

# 4. The plot.
out = sys.argv[1] if len(sys.argv) > 1 else "press_liver.png"
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

fig, ax = plt.subplots(figsize=(5, 3.5))
press = slice(0, 1500)
ax.plot(1e3 * depth[press], force[press], label="while pressing")
ax.plot([1e3 * depth[-1]], [force[-1]], "o", label="held, settled")
ax.legend()
ax.set_xlabel("probe tip depth (mm)")
ax.set_ylabel("force on the tool (N)")
ax.set_title("Probe pressed into the liver")
fig.tight_layout()
fig.savefig(out, dpi=120)
print("wrote", out)
