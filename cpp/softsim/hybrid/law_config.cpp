#include "softsim/hybrid/law_config.hpp"

#include <cmath>
#include <set>
#include <string>

namespace softsim::hybrid {

namespace {

Eigen::Vector3d read_direction(const io::JsonReader& r, const std::string& key) {
  const auto v = r.get_doubles(key, 3);
  const Eigen::Vector3d a(v[0], v[1], v[2]);
  const double n = a.norm();
  r.require(n > 0 && std::isfinite(n), key, "a non-zero direction [x, y, z] (it is normalised)");
  return a / n;
}

}  // namespace

material::TransverselyIsotropic read_transversely_isotropic(const io::JsonReader& m) {
  material::TransverselyIsotropic law;
  law.mu = m.get_positive("mu");
  law.eta = m.get_double("eta");
  m.require(law.eta >= 0, "eta", "a non-negative fibre stiffness (Pa)");
  law.bulk = m.get_positive("K");
  if (m.has("fibre")) law.fibre = read_direction(m, "fibre");
  return law;
}

std::shared_ptr<const std::vector<Eigen::Vector3d>> read_fibre_regions(const io::JsonReader& m,
                                                                       const mesh::TetMesh& mesh,
                                                                       const Eigen::Vector3d& fibre) {
  if (!m.has("fibre_regions")) return nullptr;
  const io::JsonReader regions = m.at("fibre_regions");
  if (!regions.raw().is_array() || regions.size() == 0) regions.fail("a non-empty array of {tag, values, fibre}");
  auto fibres = std::make_shared<std::vector<Eigen::Vector3d>>(mesh.num_tets(), fibre);
  for (std::size_t i = 0; i < regions.size(); ++i) {
    const io::JsonReader r = regions[i];
    const std::string tag = r.get_string("tag");
    const auto it = mesh.element_tags.find(tag);
    r.require(it != mesh.element_tags.end(), "tag", "the name of an element tag of the mesh");
    const std::vector<std::int64_t> values = r.get_ints("values");
    r.require(!values.empty(), "values", "a non-empty array of tag values");
    const std::set<std::int64_t> wanted(values.begin(), values.end());
    const Eigen::Vector3d a = read_direction(r, "fibre");
    r.reject_unknown();
    int matched = 0;
    for (int e = 0; e < mesh.num_tets(); ++e)
      if (wanted.count(it->second[e])) {
        (*fibres)[e] = a;
        ++matched;
      }
    r.require(matched > 0, "values", "tag values that at least one element has");
  }
  return fibres;
}

material::Viscoelastic read_prony(const io::JsonReader& prony, const material::ElasticLaw& base) {
  material::Viscoelastic law;
  law.base = base;
  const std::vector<double> g = prony.get_doubles("g");
  prony.require(!g.empty() && g.size() <= material::Viscoelastic::kMaxTerms, "g", "an array of 1 to 4 numbers");
  const std::vector<double> tau = prony.get_doubles("tau");
  prony.require(tau.size() == g.size(), "tau", "an array of the same length as g");
  law.terms = static_cast<int>(g.size());
  for (int i = 0; i < law.terms; ++i) {
    if (!(g[i] >= 0)) prony.at("g")[i].fail("a non-negative relative modulus");
    if (!(tau[i] > 0)) prony.at("tau")[i].fail("a positive relaxation time (s)");
    law.g[i] = g[i];
    law.tau[i] = tau[i];
  }
  prony.require(law.long_term() > 0, "g", "relative moduli summing to less than 1 (g_inf = 1 - sum g > 0)");
  prony.reject_unknown();
  return law;
}

}  // namespace softsim::hybrid
