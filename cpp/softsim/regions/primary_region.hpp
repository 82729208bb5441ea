#pragma once
// Where the linked asynchronous regions of 001 §5 lie on a tetrahedral mesh. The primary region
// is the elements with a node within a Euclidean distance of the contact node (reference
// positions, 001 §5: "elements within a distance of the contact node"); the secondary region is
// every other element. Nodes split three ways:
//   interior  nodes only primary elements touch: solved every haptic frame;
//   interface nodes both kinds touch (001's "connection nodes"): where the regions exchange
//             displacement (001 eq. 7) or where the secondary is condensed onto the primary;
//   secondary nodes only secondary elements touch.
// The primary elements form a sub-mesh (nodes renumbered in ascending global order), which the
// explicit engine steps like any dhd_sim model.
#include <vector>

#include "softsim/mesh/tet_mesh.hpp"

namespace softsim::regions {

struct PrimaryRegion {
  int centre = -1;                 // the contact node it was built around
  double radius = 0;               // m
  std::vector<int> elements;       // primary elements, ascending (global indices)
  std::vector<int> nodes;          // their nodes, ascending: sub-mesh node k is global nodes[k]
  std::vector<int> local;          // per global node: its sub-mesh index, or -1
  std::vector<int> interface;      // global interface nodes, ascending
  std::vector<int> interface_local;  // their sub-mesh indices
  std::vector<char> interior;      // per global node: an interior node of the primary region
  mesh::TetMesh submesh;           // the primary elements on their own nodes

  int removed_elements = 0;        // elements a cut took out before the region was built
  int num_secondary_elements(const mesh::TetMesh& mesh) const {
    return mesh.num_tets() - static_cast<int>(elements.size()) - removed_elements;
  }
};

// The primary region around node `centre` (InputError for a node out of range or a radius that
// is not positive). A radius covering the mesh gives every element and no interface: the
// whole model. `removed` (per element, optional): elements a cut took out, in neither region.
PrimaryRegion select_primary_region(const mesh::TetMesh& mesh, int centre, double radius,
                                    const std::vector<char>* removed = nullptr);

}  // namespace softsim::regions
