#include "constitutive/tresca.hpp"

#include <cassert>
#include <cmath>

namespace duet::constitutive {

namespace {

/// A trial state within this fraction of the stress level of the surface counts as on it.
constexpr double on_surface_tolerance = 1e-12;

}  // namespace

FacetedSurface tresca_surface(double undrained_strength) {
  FacetedSurface s;
  // de Souza Neto 2008 sec. 8.1 (Tresca in principal stresses), sextant sigma1 >= sigma2 >= sigma3:
  // f = sigma1 - sigma3 - sigma_y with sigma_y = 2 c_u; associated flow N = n.
  s.main.normal = Vec3(1.0, 0.0, -1.0);
  s.right.normal = Vec3(1.0, -1.0, 0.0);  // sigma1 - sigma2 = 2 c_u: edge sigma2 = sigma3
  s.left.normal = Vec3(0.0, 1.0, -1.0);   // sigma2 - sigma3 = 2 c_u: edge sigma1 = sigma2
  for (PrincipalPlane* plane : {&s.main, &s.right, &s.left}) {
    plane->flow = plane->normal;
    plane->level = 2.0 * undrained_strength;
  }
  s.apex.reset();  // a prism: no apex
  return s;
}

Tresca::Tresca(ElasticParameters elastic, double undrained_strength)
    : elastic_(elastic),
      undrained_strength_(undrained_strength),
      surface_(tresca_surface(undrained_strength)) {}

std::vector<InternalVariable> Tresca::internal_variables() const {
  return {{"plastic_strain", 0.0, "-"}, {"corrections", 0.0, "-"}};
}

double Tresca::yield_function(const Mat3& stress) const {
  return surface_.main.value(spectral_decomposition(stress).values);
}

double Tresca::stress_scale(const Mat3& stress) const {
  return std::abs(mean_stress(stress)) + std::sqrt(j2(stress)) + undrained_strength_;
}

StressReturn Tresca::return_mapping(const Mat3& trial) const {
  const Mat3 D = principal_elasticity(elastic_.bulk_modulus(), elastic_.shear_modulus());
  return constitutive::return_mapping(trial, surface_, D,
                                      on_surface_tolerance * stress_scale(trial));
}

void Tresca::record_plastic_step(const Mat3& trial, const StressReturn& result,
                                 std::span<double> internal) const {
  if (result.principal.regime == PrincipalRegime::elastic) return;
  internal[tresca_plastic_strain] += equivalent_plastic_strain_increment(
      trial, result.stress, elastic_.bulk_modulus(), elastic_.shear_modulus());
  internal[tresca_corrections] += 1.0;
}

StressReturn Tresca::integrate_returning(const Mat3& d_strain, Mat3& stress,
                                         std::span<double> internal) const {
  const Mat3 trial = stress + elastic_increment(elastic_, d_strain);  // elastic predictor
  StressReturn result = return_mapping(trial);
  record_plastic_step(trial, result, internal);
  stress = result.stress;
  assert(yield_function(stress) <= 1e-10 * stress_scale(stress));
  return result;
}

void Tresca::integrate(const Mat3& d_strain, Mat3& stress, std::span<double> internal) const {
  integrate_returning(d_strain, stress, internal);
}

void Tresca::integrate_with_tangent(const Mat3& d_strain, Mat3& stress, std::span<double> internal,
                                    Mat6& tangent) const {
  // The tangent of tangent(d_strain, stress_before), formed from the return just taken.
  tangent = consistent_tangent(integrate_returning(d_strain, stress, internal),
                               elastic_stiffness(elastic_));
}

void Tresca::correct(Mat3& stress, std::span<double> internal) const {
  const StressReturn result = return_mapping(stress);
  record_plastic_step(stress, result, internal);
  stress = result.stress;
}

Mat6 Tresca::tangent(const Mat3& d_strain, const Mat3& stress, std::span<const double>) const {
  const Mat3 trial = stress + elastic_increment(elastic_, d_strain);
  return consistent_tangent(return_mapping(trial), elastic_stiffness(elastic_));
}

Mat3 Tresca::objective_rate(const Mat3& stretching, const Mat3& stress,
                            std::span<const double>) const {
  const Mat3 D = principal_elasticity(elastic_.bulk_modulus(), elastic_.shear_modulus());
  return continuum_rate(stress, elastic_increment(elastic_, stretching), surface_, D,
                        on_surface_tolerance * stress_scale(stress));
}

ElasticModuli Tresca::moduli(const Mat3&, std::span<const double>) const {
  return {elastic_.bulk_modulus(), elastic_.shear_modulus()};
}

void register_tresca(ModelRegistry& registry) {
  registry.add({"tresca",
                "Tresca perfect plasticity, undrained clay (E, nu, cu)",
                [](Parameters& p) -> std::unique_ptr<Model> {
                  const ElasticParameters elastic = ElasticParameters::read(p);
                  const double cu =
                      p.require("cu", Range::positive(), "Pa", "undrained shear strength");
                  return std::make_unique<Tresca>(elastic, cu);
                },
                // Zhang 2018 footing (slides fig 12a): rigidity index I_r = G/c_u = 33.4;
                // E/c_u = 100 with nu = 0.49 gives I_r = 33.6.
                {{"E", 1e7}, {"nu", 0.49}, {"cu", 1e5}},
                {},
                /*softens=*/false});
}

}  // namespace duet::constitutive
