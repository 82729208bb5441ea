#include "softsim/meshless/gauss_legendre.hpp"

#include <gsl/gsl_integration.h>

#include <memory>
#include <new>
#include <stdexcept>

namespace softsim::meshless {

GaussRule gauss_legendre(int n) {
  if (n < 1 || n > 32) throw std::invalid_argument("gauss_legendre: order must lie in [1, 32]");
  // GSL's rules for n = 2..20 and 32 are tables correctly rounded to double; a Newton iteration
  // on P_n in double arithmetic leaves the weights up to 20 ulp off. Other n GSL computes.
  const std::unique_ptr<gsl_integration_glfixed_table, decltype(&gsl_integration_glfixed_table_free)> table(
      gsl_integration_glfixed_table_alloc(static_cast<std::size_t>(n)), &gsl_integration_glfixed_table_free);
  if (!table) throw std::bad_alloc();
  GaussRule rule;
  rule.points.resize(n);
  rule.weights.resize(n);
  // gsl_integration_glfixed_point unpacks the table's symmetric half into ascending points.
  for (int i = 0; i < n; ++i)
    gsl_integration_glfixed_point(-1.0, 1.0, static_cast<std::size_t>(i), &rule.points[i], &rule.weights[i],
                                  table.get());
  return rule;
}

}  // namespace softsim::meshless
