#include "softsim/regions/dof_blocks.hpp"

namespace softsim::regions {

Eigen::SparseMatrix<double> dof_block(const Eigen::SparseMatrix<double>& K, const std::vector<int>& rows,
                                      const std::vector<int>& cols) {
  std::vector<int> row_of(K.rows(), -1);
  for (std::size_t r = 0; r < rows.size(); ++r) row_of[rows[r]] = static_cast<int>(r);
  std::vector<Eigen::Triplet<double>> t;
  for (std::size_t c = 0; c < cols.size(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, cols[c]); it; ++it)
      if (row_of[it.row()] >= 0) t.emplace_back(row_of[it.row()], static_cast<int>(c), it.value());
  Eigen::SparseMatrix<double> B(static_cast<int>(rows.size()), static_cast<int>(cols.size()));
  B.setFromTriplets(t.begin(), t.end());
  return B;
}

}  // namespace softsim::regions
