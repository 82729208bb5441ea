#pragma once
// Blocks of a sparse matrix over chosen degrees of freedom: the row and column sets of the
// region solvers (secondary, interior, interface), each a list of global dofs.
#include <vector>

#include <Eigen/SparseCore>

namespace softsim::regions {

// K restricted to rows `rows` and columns `cols` (global dof lists), in that order.
Eigen::SparseMatrix<double> dof_block(const Eigen::SparseMatrix<double>& K, const std::vector<int>& rows,
                                      const std::vector<int>& cols);

// The free dofs (not `constrained`) of the nodes for which `take(node)` holds, ascending.
template <class Take>
std::vector<int> free_dofs(int num_nodes, const std::vector<char>& constrained, Take take) {
  std::vector<int> dofs;
  for (int i = 0; i < num_nodes; ++i)
    if (take(i))
      for (int k = 0; k < 3; ++k)
        if (!constrained[3 * i + k]) dofs.push_back(3 * i + k);
  return dofs;
}

}  // namespace softsim::regions
