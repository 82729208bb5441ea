"""softsim: real-time soft-tissue simulation (tetrahedral FEM, RPIM meshless models, fitted
surface playback) from Python.

The same library as the executables, fed the same JSON configs (as dicts or file paths) and
returning the payloads they write:

    mesher           cuboid, load_mesh, mesh_from_config -> Mesh (Mesh.save writes tet_mesh)
    dhd_sim          solve_static -> StaticSolution, run_dhd -> dhd_result payload,
                     Scene: the explicit engine stepped from Python (move the tool, step,
                     read the force)
    rpim_precompute  rpim_precompute -> rpim_dataset / rpim_stability / rpim_convergence payload
    marquardt_fit    FitModel (play forces -> surface displacements), play_fit -> surface_playback

Bad input raises InputError (a ValueError), a numerical failure NumericalError (an
ArithmeticError); their messages are the executables' (file or "<dict>", JSON pointer, what
was expected). Long computations release the GIL. See cpp/python/README.md.
"""
import os as _os

from ._core import (
    ELEMENT_KIND_LEGEND,
    FitModel,
    InputError,
    Mesh,
    NumericalError,
    Scene,
    StaticSolution,
    __version__,
    cuboid,
    load_mesh,
    mesh_from_config,
    play_fit,
    rpim_precompute,
    run_dhd,
    solve_static,
)

# Errors and objects show as softsim.InputError, softsim.Mesh, ... in tracebacks and reprs.
for _public in (FitModel, InputError, Mesh, NumericalError, StaticSolution):
    _public.__module__ = __name__


def load_fit_model(source):
    """A FitModel from a marquardt_fit artifact's path, or from the dict of its payload["model"]."""
    if isinstance(source, dict):
        return FitModel.from_dict(source)
    return FitModel.load(_os.fspath(source))


__all__ = [
    "ELEMENT_KIND_LEGEND",
    "FitModel",
    "InputError",
    "Mesh",
    "NumericalError",
    "Scene",
    "StaticSolution",
    "__version__",
    "cuboid",
    "load_fit_model",
    "load_mesh",
    "mesh_from_config",
    "play_fit",
    "rpim_precompute",
    "run_dhd",
    "solve_static",
]
