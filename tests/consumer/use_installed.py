"""The installed Python package on its own (consumer_package runs this with PYTHONPATH set to
the install's Python folder and the working directory outside the source and build trees).

Checks that softsim is imported from the install, and physics through it: uniaxial tension of a
linear-material block on rollers gives the top reaction E A eps exactly (linear tetrahedra
represent a homogeneous strain exactly), and the stepping Scene from the same install, with a
damped explicit run, settles on that static solution.
"""
import sys
from pathlib import Path

import numpy as np

import softsim

install = Path(sys.argv[1]).resolve()
where = Path(softsim.__file__).resolve()
if install not in where.parents:
    sys.exit(f"softsim was imported from {where}, not from the install {install}")

E, L, H, strain = 5000.0, 0.02, 0.03, 0.01
mesh = softsim.cuboid(cells=[2, 2, 3], size=[L, L, H])
config = {
    "material": {"model": "linear", "E": E, "nu": 0.3, "density": 1000},
    "boundary": {
        "fixed": [{"set": "bottom", "components": "z"}, {"set": "x_min", "components": "x"},
                  {"set": "y_min", "components": "y"}],
        "prescribed": [{"set": "top", "displacement": [0, 0, strain * H], "components": "z"}],
    },
}
static = softsim.solve_static(mesh, dict(config, solver={"kind": "static", "increments": 1}))
top = static.reactions[static.reaction_names.index("prescribed top")][2]
expected = E * L * L * strain
if abs(top - expected) > 1e-8 * expected:
    sys.exit(f"uniaxial tension: top reaction {top} N, expected E A eps = {expected} N")

scene = softsim.Scene(dict(config, damping={"alpha": 400.0}, solver={"kind": "explicit"}), mesh)
scene.step(4000)
gap = np.abs(scene.displacement() - static.displacement).max()
if gap > 1e-6 * strain * H:
    sys.exit(f"the damped explicit scene ends {gap} m from the static solution")
print(f"python: softsim {softsim.__version__} from the install: reaction {top:.6g} N = E A eps, "
      f"explicit scene settled within {gap:.2g} m")
