#include "softsim/material/viscoelastic.hpp"

#include <cmath>

#include "softsim/io/errors.hpp"

namespace softsim::material {

namespace {

ElasticLaw isochoric_base(const ElasticLaw& base) {
  return std::visit([](const auto& l) -> ElasticLaw { return isochoric_part(l); }, base);
}

Eigen::Matrix3d base_first_piola(const ElasticLaw& base, const Eigen::Matrix3d& F) {
  return std::visit([&](const auto& l) -> Eigen::Matrix3d { return first_piola(l, F); }, base);
}

Eigen::Matrix3d base_second_piola(const ElasticLaw& base, const Eigen::Matrix3d& C) {
  return std::visit([&](const auto& l) -> Eigen::Matrix3d { return second_piola(l, C); }, base);
}

}  // namespace

std::string law_name(const Viscoelastic& law) {
  return std::visit([](const auto& l) { return law_name(l); }, law.base) + "+prony";
}

void validate_moduli(const Viscoelastic& law) {
  if (law.terms < 1 || law.terms > Viscoelastic::kMaxTerms)
    throw InputError("material: a Prony series needs 1 to 4 terms, got " + std::to_string(law.terms));
  if (const auto* nh = std::get_if<NeoHookean>(&law.base); nh && nh->form == NeoHookeanForm::paper)
    throw InputError("material: a Prony series needs a base law with an isochoric part (not neo_hookean_paper)");
  for (int i = 0; i < law.terms; ++i) {
    if (!(law.g[i] >= 0) || !std::isfinite(law.g[i]))
      throw InputError("material: Prony g must be non-negative, got " + std::to_string(law.g[i]));
    if (!(law.tau[i] > 0) || !std::isfinite(law.tau[i]))
      throw InputError("material: Prony tau must be positive, got " + std::to_string(law.tau[i]));
  }
  if (!(law.long_term() > 0))
    throw InputError("material: the Prony weights must sum to less than 1 (g_inf = 1 - sum g > 0)");
}

Eigen::Matrix3d isochoric_second_piola(const Viscoelastic& law, const Eigen::Matrix3d& C) {
  return base_second_piola(isochoric_base(law.base), C);
}

double strain_energy_density(const Viscoelastic& law, const Eigen::Matrix3d& F) {
  const auto W = [&](const ElasticLaw& l) { return std::visit([&](const auto& x) { return strain_energy_density(x, F); }, l); };
  return W(law.base) - (1.0 - law.long_term()) * W(isochoric_base(law.base));
}

Eigen::Matrix3d second_piola(const Viscoelastic& law, const Eigen::Matrix3d& C) {
  return base_second_piola(law.base, C) - (1.0 - law.long_term()) * isochoric_second_piola(law, C);
}

Eigen::Matrix3d first_piola(const Viscoelastic& law, const Eigen::Matrix3d& F) {
  return base_first_piola(law.base, F) - (1.0 - law.long_term()) * base_first_piola(isochoric_base(law.base), F);
}

ViscoelasticLinearisation linearise(const Viscoelastic& law, const Eigen::Matrix3d& F) {
  const auto lin = [&](const ElasticLaw& l) {
    return std::visit([&](const auto& x) -> ElasticLinearisation { return linearise(x, F); }, l);
  };
  return {lin(law.base), lin(isochoric_base(law.base))};
}

Eigen::Matrix3d first_piola_increment(const Viscoelastic& law, const ViscoelasticLinearisation& at,
                                      const Eigen::Matrix3d& dF) {
  const auto inc = [&](const ElasticLaw& l, const ElasticLinearisation& a) {
    return std::visit(
        [&](const auto& x) -> Eigen::Matrix3d {
          using Linearisation = decltype(linearise(x, dF));
          return first_piola_increment(x, std::get<Linearisation>(a), dF);
        },
        l);
  };
  return inc(law.base, at.base) - (1.0 - law.long_term()) * inc(isochoric_base(law.base), at.iso);
}

double volumetric_modulus(const Viscoelastic& law) {
  return std::visit([](const auto& l) { return volumetric_modulus(l); }, law.base);
}

Viscoelastic isochoric_part(const Viscoelastic& law) {
  Viscoelastic iso = law;
  iso.base = isochoric_base(law.base);
  return iso;
}

PronyStep prony_step(const Viscoelastic& law, double dt) {
  PronyStep p;
  p.isochoric = isochoric_base(law.base);
  p.bulk = volumetric_modulus(law);
  for (int i = 0; i < law.terms; ++i) {
    p.decay[i] = std::exp(-dt / law.tau[i]);
    p.weight[i] = law.g[i] * (1.0 - p.decay[i]);
  }
  return p;
}

Eigen::Matrix3d relaxed_first_piola(const Viscoelastic& law, const PronyStep& step, const Eigen::Matrix3d& F,
                                    const double* state_in, double* state_out) {
  const Eigen::Matrix3d C = F.transpose() * F;
  const Eigen::Matrix3d Cinv = C.inverse();
  const double J = F.determinant();
  Eigen::Matrix3d S;
  if (const auto* nh = std::get_if<NeoHookean>(&step.isochoric)) {
    // The decoupled neo-Hookean S_iso = μ J^(−2/3) (I − I₁/3 C⁻¹) inline: the common case.
    const double x = 1.0 / std::cbrt(J);
    S = nh->mu * x * x * (Eigen::Matrix3d::Identity() - (C.trace() / 3.0) * Cinv);
  } else {
    S = base_second_piola(step.isochoric, C);
  }
  const double s[6] = {S(0, 0), S(1, 1), S(2, 2), S(0, 1), S(1, 2), S(0, 2)};
  double sum[6] = {0, 0, 0, 0, 0, 0};
  for (int i = 0; i < law.terms; ++i)
    for (int c = 0; c < 6; ++c) {
      const double a = step.decay[i] * state_in[6 * i + c] + step.weight[i] * s[c];
      state_out[6 * i + c] = a;
      sum[c] += a;
    }
  Eigen::Matrix3d A;
  A << sum[0], sum[3], sum[5], sum[3], sum[1], sum[4], sum[5], sum[4], sum[2];
  return F * (S + step.bulk * J * (J - 1.0) * Cinv - A);
}

const Eigen::Vector3d* fibre_of(const ElasticLaw& law) {
  const auto* ti = std::get_if<TransverselyIsotropic>(&law);
  return ti ? &ti->fibre : nullptr;
}
const Eigen::Vector3d* fibre_of(const Viscoelastic& law) { return fibre_of(law.base); }

void set_fibre(ElasticLaw& law, const Eigen::Vector3d& a) {
  if (auto* ti = std::get_if<TransverselyIsotropic>(&law)) ti->fibre = a;
}
void set_fibre(Viscoelastic& law, const Eigen::Vector3d& a) { set_fibre(law.base, a); }

void set_fibre(Viscoelastic& law, PronyStep& step, const Eigen::Vector3d& a) {
  set_fibre(law.base, a);
  set_fibre(step.isochoric, a);
}

}  // namespace softsim::material
