#include "softsim/meshless/shape_table.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <stdexcept>

#include "softsim/io/errors.hpp"
#include "softsim/meshless/node_search.hpp"

namespace softsim::meshless {

namespace {

double bucket_size(const SupportRule& support, const std::vector<Eigen::Vector3d>& nodes) {
  if (support.kind == SupportRule::Kind::radius) return support.radius;
  // k nearest: a bucket holding a few nodes on average.
  Eigen::Vector3d lo = nodes[0], hi = nodes[0];
  for (const auto& p : nodes) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Eigen::Vector3d ext = (hi - lo).cwiseMax(1e-12);
  return std::cbrt(ext.prod() / static_cast<double>(nodes.size())) * 1.5;
}

void query(const NodeSearch& search, const SupportRule& support, const Eigen::Vector3d& x,
           std::vector<int>& out) {
  if (support.kind == SupportRule::Kind::radius) {
    search.within(x, support.radius, out);
  } else {
    search.nearest(x, support.count, out);
    std::sort(out.begin(), out.end());
  }
}

}  // namespace

ShapeTable build_shape_table(const std::vector<Eigen::Vector3d>& nodes, const QuadraturePoints& quadrature,
                             const SupportRule& support, const RbfParams& rbf) {
  if (support.kind == SupportRule::Kind::nearest &&
      (support.count < 1 || support.count > static_cast<int>(nodes.size())))
    throw NumericalError("support domain: k = " + std::to_string(support.count) +
                         " nearest nodes requested but the model has " + std::to_string(nodes.size()));
  const int g_count = static_cast<int>(quadrature.points.size());
  const NodeSearch search(nodes, bucket_size(support, nodes));

  // Pass 1: supports (cheap, serial, gives the offsets).
  ShapeTable t;
  t.points = quadrature.points;
  t.weights = quadrature.weights;
  t.offsets.assign(g_count + 1, 0);
  {
    std::vector<int> s;
    for (int g = 0; g < g_count; ++g) {
      query(search, support, t.points[g], s);
      t.offsets[g + 1] = t.offsets[g] + static_cast<int>(s.size());
      t.nodes.insert(t.nodes.end(), s.begin(), s.end());
    }
  }
  const std::size_t entries = t.nodes.size();
  t.phi.resize(entries);
  t.dphi.resize(3 * entries);
  t.moment_condition.assign(g_count, 0.0);

  // Pass 2: shape functions, one independent solve per point (parallel, no shared writes).
  int first_failure = std::numeric_limits<int>::max();
  std::string failure_message;
  bool failure_is_numerical = true;
#pragma omp parallel
  {
    RpimShapeEvaluator evaluator(rbf);
    ShapeValues values;
    Eigen::MatrixX3d coords;
#pragma omp for schedule(dynamic, 16)
    for (int g = 0; g < g_count; ++g) {
      const int begin = t.offsets[g], n = t.offsets[g + 1] - begin;
      try {
        coords.resize(n, 3);
        for (int a = 0; a < n; ++a) coords.row(a) = nodes[t.nodes[begin + a]].transpose();
        evaluator.evaluate(t.points[g], coords, true, values);
        for (int a = 0; a < n; ++a) {
          t.phi[begin + a] = values.phi[a];
          for (int k = 0; k < 3; ++k) t.dphi[3 * (begin + a) + k] = values.dphi(a, k);
        }
        t.moment_condition[g] = values.moment_condition;
      } catch (const std::exception& e) {
        const bool numerical = dynamic_cast<const NumericalError*>(&e) != nullptr;
#pragma omp critical(rpim_shape_failure)
        if (g < first_failure) {
          first_failure = g;
          failure_message = e.what();
          failure_is_numerical = numerical;
        }
      }
    }
  }
  if (first_failure != std::numeric_limits<int>::max() && !failure_is_numerical)
    throw std::runtime_error(failure_message);
  if (first_failure != std::numeric_limits<int>::max())
    throw NumericalError("shape functions at Gauss point " + std::to_string(first_failure) + ": " +
                         failure_message);
  return t;
}

ShapeTableStats shape_table_stats(const ShapeTable& table, const std::vector<Eigen::Vector3d>& nodes,
                                  double spacing) {
  ShapeTableStats s;
  s.points = table.num_points();
  if (s.points == 0) return s;
  s.min_support = std::numeric_limits<int>::max();
  double sum = 0;
  for (int g = 0; g < s.points; ++g) {
    const int n = table.support_size(g);
    s.min_support = std::min(s.min_support, n);
    s.max_support = std::max(s.max_support, n);
    sum += n;
  }
  s.mean_support = sum / s.points;
  std::vector<double> c = table.moment_condition;
  std::sort(c.begin(), c.end());
  s.min_condition = c.front();
  s.max_condition = c.back();
  s.median_condition = c[c.size() / 2];
  for (int g = 0; g < s.points; ++g) {
    double sum_phi = 0;
    Eigen::Vector3d sum_x = Eigen::Vector3d::Zero();
    Eigen::Matrix3d sum_grad = Eigen::Matrix3d::Zero();
    for (int e = table.offsets[g]; e < table.offsets[g + 1]; ++e) {
      const Eigen::Vector3d& x = nodes[table.nodes[e]];
      const Eigen::Vector3d grad(table.dphi[3 * e], table.dphi[3 * e + 1], table.dphi[3 * e + 2]);
      sum_phi += table.phi[e];
      sum_x += table.phi[e] * (x - table.points[g]);
      sum_grad += (x - table.points[g]) * grad.transpose();
    }
    s.partition_error = std::max(s.partition_error, std::abs(sum_phi - 1.0));
    s.linear_error = std::max(s.linear_error, sum_x.norm() / spacing);
    s.gradient_error = std::max(s.gradient_error, (sum_grad - Eigen::Matrix3d::Identity()).norm());
  }
  return s;
}

}  // namespace softsim::meshless
