#pragma once
// The rigid tools of a dhd_sim config (issue 23), in its "boundary" object:
//   "tools": [{"name": "ball", "shape": "sphere", "radius": 0.005,
//              "position": [x, y, z], "travel": [dx, dy, dz], "ramp_time": 0.05, "ramp": "linear",
//              "nodes": "boundary"}, ...]
// shape "sphere" (radius), "capsule" (radius and "axis": the vector from one end of its segment
// to the other) or "plane" ("normal": pointing out of the tool into the body; `position` is a
// point on it). The tool starts at `position` and moves by `travel` × ramp(t). It touches the
// nodes of node set `nodes` (default: every node of the mesh's boundary surface); nodes with a
// constrained component are left to their constraint. Frictionless kinematic contact
// (dynamics::RigidTool); explicit runs only.
// shape "mesh": "file" (a closed triangle surface, .stl ASCII or binary, or .obj; relative to the
// config's folder) with "scale" (file units to metres, default 1); its file coordinates are the
// tool's frame (turned by "rotation": {"axis": [x, y, z], "degrees": a} about its origin if given),
// placed at `position` (the frame's origin) and moved like the others.
// "search_margin" (m): the broad phase's margin (dynamics/contact_search.hpp; default a quarter
// of the tool's size).
#include <vector>

#include "softsim/dynamics/scene.hpp"
#include "softsim/io/json_reader.hpp"
#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::hybrid {

// Reads boundary["tools"] (absent: none).
std::vector<dynamics::RigidTool> read_tools(const io::JsonReader& boundary, const mesh::TetMesh& mesh);

}  // namespace softsim::hybrid
