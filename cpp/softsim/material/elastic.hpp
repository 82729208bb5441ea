#pragma once
// Isotropic elastic constants: (E, ν) ↔ (μ, λ, K) and the longitudinal wave speed that sets
// the explicit time step (000 eqs. 34–35). SI units: Pa, kg/m³, m/s.
namespace softsim::material {

struct ElasticParameters {
  double youngs_modulus = 5000.0;  // E (Pa); 000 §3.1
  double poisson_ratio = 0.35;     // ν; 000 §3.1
  double density = 1000.0;         // ρ (kg/m³); 000 §3.1
};

struct LameParameters {
  double mu = 0;      // shear modulus G = E / (2 (1 + ν))
  double lambda = 0;  // λ = E ν / ((1 + ν)(1 − 2ν))
};

// Throws InputError unless E > 0, −1 < ν < 0.5 and ρ > 0.
void validate(const ElasticParameters& p);

LameParameters lame_parameters(const ElasticParameters& p);
// Bulk modulus K = λ + 2μ/3 = E / (3 (1 − 2ν)).
double bulk_modulus(const ElasticParameters& p);
// Inverse map: (μ, λ) -> (E, ν) with the given density.
ElasticParameters from_lame(double mu, double lambda, double density);
// The same from the shear and bulk moduli (λ = K − 2μ/3): the small-strain constants of the laws
// given by (μ, K) (Mooney–Rivlin, Ogden, transversely isotropic).
ElasticParameters from_shear_bulk(double mu, double bulk, double density);
// c = sqrt(E (1 − ν) / (ρ (1 + ν)(1 − 2ν)))  (000 eq. 35): the P-wave speed λ + 2μ over ρ.
double dilatational_wave_speed(const ElasticParameters& p);

}  // namespace softsim::material
