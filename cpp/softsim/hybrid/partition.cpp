#include "softsim/hybrid/partition.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>

#include "softsim/io/errors.hpp"

namespace softsim::hybrid {

Eigen::Vector3d default_operating_point(const mesh::TetMesh& mesh) {
  const auto [lo, hi] = mesh::bounding_box(mesh);
  return Eigen::Vector3d(0.5 * (lo.x() + hi.x()), 0.5 * (lo.y() + hi.y()), hi.z());
}

std::vector<Eigen::Vector3d> element_centroids(const mesh::TetMesh& mesh) {
  std::vector<Eigen::Vector3d> c(mesh.num_tets());
  for (int e = 0; e < mesh.num_tets(); ++e) {
    const auto& t = mesh.tets[e];
    c[e] = 0.25 * (mesh.nodes[t[0]] + mesh.nodes[t[1]] + mesh.nodes[t[2]] + mesh.nodes[t[3]]);
  }
  return c;
}

namespace {

// Each strategy's operational set: one flag per element, true for the nonlinear kind.
//
// Exactly round(r · m) elements are non-operational: those with the largest `key`; ties go to
// the lower element index.
std::vector<char> operational_by_rank(const std::vector<double>& key, double linear_fraction) {
  if (!(linear_fraction >= 0 && linear_fraction <= 1))
    throw InputError("partition: linear_fraction must lie in [0, 1]");
  const int m = static_cast<int>(key.size());
  const int n_linear = static_cast<int>(std::llround(linear_fraction * m));
  std::vector<int> order(m);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return key[a] > key[b]; });
  std::vector<char> op(m, 1);
  for (int i = 0; i < n_linear; ++i) op[order[i]] = 0;
  return op;
}

std::vector<char> operational_by_layers(const mesh::TetMesh& mesh, const std::string& tag, int nonlinear_layers) {
  const auto it = mesh.element_tags.find(tag);
  if (it == mesh.element_tags.end()) throw InputError("partition: the mesh has no element tag \"" + tag + "\"");
  if (nonlinear_layers < 0) throw InputError("partition: nonlinear_layers must not be negative");
  std::set<int> values(it->second.begin(), it->second.end());
  std::set<int> top;
  for (auto v = values.rbegin(); v != values.rend() && static_cast<int>(top.size()) < nonlinear_layers; ++v) top.insert(*v);
  std::vector<char> op(mesh.num_tets());
  for (int e = 0; e < mesh.num_tets(); ++e) op[e] = top.count(it->second[e]) ? 1 : 0;
  return op;
}

std::vector<char> operational_by_tags(const mesh::TetMesh& mesh, const std::string& tag, const std::vector<int>& values) {
  const auto it = mesh.element_tags.find(tag);
  if (it == mesh.element_tags.end()) throw InputError("partition: the mesh has no element tag \"" + tag + "\"");
  const std::set<int> wanted(values.begin(), values.end());
  std::vector<char> op(mesh.num_tets());
  for (int e = 0; e < mesh.num_tets(); ++e) op[e] = wanted.count(it->second[e]) ? 1 : 0;
  return op;
}

std::vector<char> operational_in_sphere(const mesh::TetMesh& mesh, const Eigen::Vector3d& center, double radius) {
  const auto c = element_centroids(mesh);
  std::vector<char> op(mesh.num_tets());
  for (int e = 0; e < mesh.num_tets(); ++e) op[e] = (c[e] - center).norm() <= radius ? 1 : 0;
  return op;
}

}  // namespace

std::vector<fem::ElementKind> make_partition(const mesh::TetMesh& mesh, const PartitionSpec& spec) {
  const int m = mesh.num_tets();
  if (spec.kind == PartitionKind::uniform) return std::vector<fem::ElementKind>(m, spec.uniform_element);
  std::vector<char> op;
  switch (spec.kind) {
    case PartitionKind::layers: op = operational_by_layers(mesh, spec.tag, spec.nonlinear_layers); break;
    case PartitionKind::linear_fraction: {
      const Eigen::Vector3d p = spec.operating_point.value_or(default_operating_point(mesh));
      const auto c = element_centroids(mesh);
      std::vector<double> key(m);
      for (int e = 0; e < m; ++e)
        key[e] = spec.distance == DistanceMetric::euclidean ? (c[e] - p).norm() : p.z() - c[e].z();
      op = operational_by_rank(key, spec.linear_fraction);
      break;
    }
    case PartitionKind::tags: op = operational_by_tags(mesh, spec.tag, spec.nonlinear_values); break;
    case PartitionKind::sphere: op = operational_in_sphere(mesh, spec.center, spec.radius); break;
    case PartitionKind::strain: {
      if (spec.reference_displacement.size() != 3 * mesh.nodes.size())
        throw InputError("partition: the strain reference has " + std::to_string(spec.reference_displacement.size() / 3) +
                         " nodes, the mesh " + std::to_string(mesh.num_nodes()));
      const std::vector<double> strain = element_strain(mesh, spec.reference_displacement, spec.measure);
      if (spec.threshold) {
        op.resize(m);
        for (int e = 0; e < m; ++e) op[e] = strain[e] > *spec.threshold ? 1 : 0;
      } else {
        std::vector<double> key(m);
        for (int e = 0; e < m; ++e) key[e] = -strain[e];  // least strained become linear first
        op = operational_by_rank(key, spec.linear_fraction);
      }
      break;
    }
    case PartitionKind::uniform: break;
  }
  std::vector<fem::ElementKind> kinds(m);
  for (int e = 0; e < m; ++e) kinds[e] = op[e] ? spec.nonlinear_element : spec.linear_element;
  return kinds;
}

}  // namespace softsim::hybrid
