#include "softsim/meshless/assembly.hpp"

#include <algorithm>
#include <array>
#include <vector>

namespace softsim::meshless {

namespace {

// For each node, the table entries (in table order) whose support holds it.
struct NodeEntries {
  std::vector<int> ptr;
  std::vector<int> entry;
  std::vector<int> point;
};

NodeEntries node_entries(const ShapeTable& t, int num_nodes) {
  NodeEntries ne;
  ne.ptr.assign(num_nodes + 1, 0);
  for (int n : t.nodes) ++ne.ptr[n + 1];
  for (int i = 0; i < num_nodes; ++i) ne.ptr[i + 1] += ne.ptr[i];
  ne.entry.resize(t.nodes.size());
  ne.point.resize(t.nodes.size());
  std::vector<int> fill(ne.ptr.begin(), ne.ptr.end() - 1);
  for (int g = 0; g < t.num_points(); ++g)
    for (int e = t.offsets[g]; e < t.offsets[g + 1]; ++e) {
      const int slot = fill[t.nodes[e]]++;
      ne.entry[slot] = e;
      ne.point[slot] = g;
    }
  return ne;
}

}  // namespace

SparseMatrix assemble_stiffness(const ShapeTable& t, int num_nodes, const LameParameters& material) {
  const NodeEntries ne = node_entries(t, num_nodes);

  // Block sparsity: row I couples to every node sharing a support with it.
  std::vector<std::vector<int>> cols(num_nodes);
#pragma omp parallel
  {
    std::vector<int> mark(num_nodes, -1);
#pragma omp for schedule(dynamic, 8)
    for (int i = 0; i < num_nodes; ++i) {
      auto& c = cols[i];
      for (int s = ne.ptr[i]; s < ne.ptr[i + 1]; ++s) {
        const int g = ne.point[s];
        for (int e = t.offsets[g]; e < t.offsets[g + 1]; ++e) {
          const int j = t.nodes[e];
          if (mark[j] != i) {
            mark[j] = i;
            c.push_back(j);
          }
        }
      }
      std::sort(c.begin(), c.end());
    }
  }
  std::vector<int> block_ptr(num_nodes + 1, 0);
  for (int i = 0; i < num_nodes; ++i) block_ptr[i + 1] = block_ptr[i] + static_cast<int>(cols[i].size());
  std::vector<double> blocks(9 * static_cast<std::size_t>(block_ptr[num_nodes]), 0.0);

  // Block values, gathered per row I: Σ_g w_g B_Iᵀ D B_J (002 eq. 19).
#pragma omp parallel
  {
    std::vector<int> slot_of(num_nodes, -1);
#pragma omp for schedule(dynamic, 8)
    for (int i = 0; i < num_nodes; ++i) {
      for (int s = block_ptr[i]; s < block_ptr[i + 1]; ++s) slot_of[cols[i][s - block_ptr[i]]] = s;
      for (int s = ne.ptr[i]; s < ne.ptr[i + 1]; ++s) {
        const int g = ne.point[s];
        const double* gi = &t.dphi[3 * static_cast<std::size_t>(ne.entry[s])];
        const double w = t.weights[g];
        for (int e = t.offsets[g]; e < t.offsets[g + 1]; ++e) {
          const double* gj = &t.dphi[3 * static_cast<std::size_t>(e)];
          add_stiffness_block(gi, gj, w, material, &blocks[9 * static_cast<std::size_t>(slot_of[t.nodes[e]])]);
        }
      }
    }
  }

  // Scalar CSC. Column 3I + a holds row 3J + b = K_IJ[a][b]: the transpose of block row I,
  // which equals column 3I + a of K because K is symmetric.
  const int n = 3 * num_nodes;
  SparseMatrix k(n, n);
  const std::size_t nnz = 9 * static_cast<std::size_t>(block_ptr[num_nodes]);
  k.resizeNonZeros(static_cast<Eigen::Index>(nnz));
  int* outer = k.outerIndexPtr();
  int* inner = k.innerIndexPtr();
  double* values = k.valuePtr();
  std::size_t pos = 0;
  for (int i = 0; i < num_nodes; ++i)
    for (int a = 0; a < 3; ++a) {
      outer[3 * i + a] = static_cast<int>(pos);
      for (int s = block_ptr[i]; s < block_ptr[i + 1]; ++s) {
        const int j = cols[i][s - block_ptr[i]];
        for (int b = 0; b < 3; ++b) {
          inner[pos] = 3 * j + b;
          values[pos] = blocks[9 * static_cast<std::size_t>(s) + 3 * a + b];
          ++pos;
        }
      }
    }
  outer[n] = static_cast<int>(pos);
  return k;
}

Eigen::VectorXd assemble_body_force(const ShapeTable& t, int num_nodes, const BodyForceField& b) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * num_nodes);
  for (int g = 0; g < t.num_points(); ++g) {
    const Eigen::Vector3d bg = b(t.points[g]) * t.weights[g];
    for (int e = t.offsets[g]; e < t.offsets[g + 1]; ++e)
      f.segment<3>(3 * t.nodes[e]) += t.phi[e] * bg;  // 002 eq. 24
  }
  return f;
}

}  // namespace softsim::meshless
