#pragma once
// The module softsim._core is bound one concern per file; module.cpp calls each in turn.
#include <pybind11/pybind11.h>

namespace softsim::python {

void bind_errors(pybind11::module_& m);  // InputError, NumericalError
void bind_mesh(pybind11::module_& m);    // Mesh, cuboid, load_mesh, mesh_from_config
void bind_solve(pybind11::module_& m);   // solve_static, run_dhd (dhd_sim)
void bind_rpim(pybind11::module_& m);    // rpim_precompute
void bind_fit(pybind11::module_& m);     // FitModel, play_fit (marquardt_fit play)
void bind_scene(pybind11::module_& m);   // Scene: the step-by-step explicit engine

}  // namespace softsim::python
