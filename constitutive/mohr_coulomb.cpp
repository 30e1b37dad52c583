#include "constitutive/mohr_coulomb.hpp"

#include <cassert>
#include <cmath>
#include <numbers>

namespace duet::constitutive {

namespace {

constexpr double degree = std::numbers::pi / 180.0;

/// A trial state within this fraction of the stress level of the surface counts as on it.
constexpr double on_surface_tolerance = 1e-12;

/// The plane (1 + sin) sigma_i - (1 - sin) sigma_j - 2 c cos(phi) between sorted indices i > j.
PrincipalPlane coulomb_plane(int i, int j, double sin_phi, double sin_psi, double level) {
  PrincipalPlane plane;
  plane.normal(i) = 1.0 + sin_phi;
  plane.normal(j) = -(1.0 - sin_phi);
  plane.flow(i) = 1.0 + sin_psi;
  plane.flow(j) = -(1.0 - sin_psi);
  plane.level = level;
  return plane;
}

}  // namespace

FacetedSurface mohr_coulomb_surface(double phi_deg, double psi_deg, double c) {
  const double sin_phi = std::sin(phi_deg * degree);
  const double sin_psi = std::sin(psi_deg * degree);
  // de Souza Neto 2008 sec. 8.2: Phi = (sigma1 - sigma3) + (sigma1 + sigma3) sin(phi)
  // - 2 c cos(phi), Psi the same with psi, in the sextant sigma1 >= sigma2 >= sigma3.
  const double level = 2.0 * c * std::cos(phi_deg * degree);
  FacetedSurface s;
  s.main = coulomb_plane(0, 2, sin_phi, sin_psi, level);
  s.right = coulomb_plane(0, 1, sin_phi, sin_psi, level);  // with main: edge sigma2 = sigma3
  s.left = coulomb_plane(1, 2, sin_phi, sin_psi, level);   // with main: edge sigma1 = sigma2
  if (sin_phi > 0.0) s.apex = c * std::cos(phi_deg * degree) / sin_phi;  // p = c cot(phi)
  return s;
}

MohrCoulomb::MohrCoulomb(ElasticParameters elastic, double phi_deg, double psi_deg, double c)
    : elastic_(elastic), cohesion_(c), surface_(mohr_coulomb_surface(phi_deg, psi_deg, c)) {}

std::vector<InternalVariable> MohrCoulomb::internal_variables() const {
  return {{"plastic_strain", 0.0, "-"}, {"corrections", 0.0, "-"}};
}

double MohrCoulomb::yield_function(const Mat3& stress) const {
  return surface_.main.value(spectral_decomposition(stress).values);
}

double MohrCoulomb::stress_scale(const Mat3& stress) const {
  return std::abs(mean_stress(stress)) + std::sqrt(j2(stress)) + cohesion_;
}

StressReturn MohrCoulomb::return_mapping(const Mat3& trial) const {
  const Mat3 D = principal_elasticity(elastic_.bulk_modulus(), elastic_.shear_modulus());
  return constitutive::return_mapping(trial, surface_, D,
                                      on_surface_tolerance * stress_scale(trial));
}

void MohrCoulomb::record_plastic_step(const Mat3& trial, const StressReturn& result,
                                      std::span<double> internal) const {
  if (result.principal.regime == PrincipalRegime::elastic) return;
  internal[mohr_coulomb_plastic_strain] += equivalent_plastic_strain_increment(
      trial, result.stress, elastic_.bulk_modulus(), elastic_.shear_modulus());
  internal[mohr_coulomb_corrections] += 1.0;
}

StressReturn MohrCoulomb::integrate_returning(const Mat3& d_strain, Mat3& stress,
                                              std::span<double> internal) const {
  const Mat3 trial = stress + elastic_increment(elastic_, d_strain);  // elastic predictor
  StressReturn result = return_mapping(trial);
  record_plastic_step(trial, result, internal);
  stress = result.stress;
  assert(yield_function(stress) <= 1e-10 * stress_scale(stress));
  return result;
}

void MohrCoulomb::integrate(const Mat3& d_strain, Mat3& stress, std::span<double> internal) const {
  integrate_returning(d_strain, stress, internal);
}

void MohrCoulomb::integrate_with_tangent(const Mat3& d_strain, Mat3& stress,
                                         std::span<double> internal, Mat6& tangent) const {
  // The tangent of tangent(d_strain, stress_before), formed from the return just taken.
  tangent = consistent_tangent(integrate_returning(d_strain, stress, internal),
                               elastic_stiffness(elastic_));
}

void MohrCoulomb::correct(Mat3& stress, std::span<double> internal) const {
  const StressReturn result = return_mapping(stress);
  record_plastic_step(stress, result, internal);
  stress = result.stress;
}

Mat6 MohrCoulomb::tangent(const Mat3& d_strain, const Mat3& stress, std::span<const double>) const {
  const Mat3 trial = stress + elastic_increment(elastic_, d_strain);
  return consistent_tangent(return_mapping(trial), elastic_stiffness(elastic_));
}

Mat3 MohrCoulomb::objective_rate(const Mat3& stretching, const Mat3& stress,
                                 std::span<const double>) const {
  const Mat3 D = principal_elasticity(elastic_.bulk_modulus(), elastic_.shear_modulus());
  return continuum_rate(stress, elastic_increment(elastic_, stretching), surface_, D,
                        on_surface_tolerance * stress_scale(stress));
}

ElasticModuli MohrCoulomb::moduli(const Mat3&, std::span<const double>) const {
  return {elastic_.bulk_modulus(), elastic_.shear_modulus()};
}

void register_mohr_coulomb(ModelRegistry& registry) {
  registry.add({"mohr-coulomb",
                "Mohr-Coulomb perfect plasticity, non-associated, apex return (E, nu, phi, psi, c)",
                [](Parameters& p) -> std::unique_ptr<Model> {
                  const ElasticParameters elastic = ElasticParameters::read(p);
                  const double phi =
                      p.require("phi", Range::closed_open(0.0, 90.0), "deg", "friction angle");
                  const double psi = p.require("psi", Range::closed(0.0, phi).following("[0, phi]"),
                                               "deg", "dilatancy angle (at most phi)");
                  // Without friction the cohesion is the whole strength: it must then be positive.
                  const double c = p.require("c",
                                             (phi > 0.0 ? Range::non_negative() : Range::positive())
                                                 .following(">= 0 (> 0 when phi = 0)"),
                                             "Pa", "cohesion");
                  return std::make_unique<MohrCoulomb>(elastic, phi, psi, c);
                },
                // A sand-like example: E 10 MPa, nu 0.3, phi 30, psi 0, cohesionless.
                {{"E", 10e6}, {"nu", 0.3}, {"phi", 30.0}, {"psi", 0.0}, {"c", 0.0}},
                {},
                /*softens=*/false});
}

}  // namespace duet::constitutive
