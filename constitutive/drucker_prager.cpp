#include "constitutive/drucker_prager.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>

namespace duet::constitutive {

namespace {

constexpr double degree = std::numbers::pi / 180.0;
const double sqrt2 = std::sqrt(2.0);

/// A trial state within this fraction of the stress level of the surface counts as on it.
constexpr double on_surface_tolerance = 1e-12;

/// Voigt (xx yy zz xy yz zx) form of the second-order identity.
Vec6 voigt_identity() {
  Vec6 one;
  one << 1.0, 1.0, 1.0, 0.0, 0.0, 0.0;
  return one;
}

/// K I (x) I + 2 G I_dev in Voigt form (engineering shear).
Mat6 isotropic_stiffness(double bulk, double shear) {
  Mat6 C = Mat6::Zero();
  C.topLeftCorner<3, 3>().setConstant(bulk - 2.0 / 3.0 * shear);
  C.topLeftCorner<3, 3>().diagonal().array() += 2.0 * shear;
  C.bottomRightCorner<3, 3>().diagonal().setConstant(shear);
  return C;
}

}  // namespace

DruckerPragerCone DruckerPragerCone::from_coulomb(double phi_deg, double psi_deg, double c) {
  const double tan_phi = std::tan(phi_deg * degree);
  const double tan_psi = std::tan(psi_deg * degree);
  DruckerPragerCone cone;
  cone.alpha_phi = tan_phi / std::sqrt(9.0 + 12.0 * tan_phi * tan_phi);  // Bui 2008 eq 6
  cone.k_c = 3.0 * c / std::sqrt(9.0 + 12.0 * tan_phi * tan_phi);        // Bui 2008 eq 6
  cone.alpha_psi = tan_psi / std::sqrt(9.0 + 12.0 * tan_psi * tan_psi);  // eq 7, psi like phi
  return cone;
}

double DruckerPragerCone::yield_function(const Mat3& stress) const {
  return alpha_phi * stress.trace() + std::sqrt(j2(stress)) - k_c;  // Bui 2008 eq 5
}

double DruckerPragerCone::apex_mean_stress() const {
  if (alpha_phi <= 0.0) return std::numeric_limits<double>::infinity();
  return k_c / (3.0 * alpha_phi);  // f(p I) = 0: 3 alpha_phi p = k_c
}

DruckerPrager::DruckerPrager(ElasticParameters elastic, DruckerPragerCone cone,
                             double tension_cutoff)
    : elastic_(elastic), cone_(cone), tension_cutoff_(tension_cutoff) {}

std::vector<InternalVariable> DruckerPrager::internal_variables() const {
  return {{"plastic_strain", 0.0, "-"}, {"corrections", 0.0, "-"}};
}

double DruckerPrager::stress_scale(const Mat3& stress) const {
  return std::abs(mean_stress(stress)) + std::sqrt(j2(stress)) + cone_.k_c;
}

DruckerPragerReturn DruckerPrager::return_mapping(const Mat3& trial) const {
  const double K = elastic_.bulk_modulus();
  const double G = elastic_.shear_modulus();
  const double alpha_phi = cone_.alpha_phi;
  const double alpha_psi = cone_.alpha_psi;
  const double p_t = tension_cutoff_;

  DruckerPragerReturn r;
  const double p_trial = mean_stress(trial);
  const Mat3 s_trial = deviator(trial);
  const double rho_trial = std::sqrt(0.5 * contract(s_trial, s_trial));  // sqrt(J2)
  r.rho_trial = rho_trial;

  // stress_scale(trial), from the invariants at hand
  const double tolerance = on_surface_tolerance * (std::abs(p_trial) + rho_trial + cone_.k_c);
  const double f_trial = 3.0 * alpha_phi * p_trial + rho_trial - cone_.k_c;  // eq 5, I1 = 3 p
  if (f_trial <= tolerance && p_trial <= p_t + tolerance) {
    r.regime = DruckerPragerRegime::elastic;
    r.stress = trial;
    return r;
  }

  if (f_trial > tolerance) {
    // Smooth return along the non-associated flow direction dg/dsigma = alpha_psi I +
    // s / (2 sqrt(J2)) (eqs 4, 7): dp = -3 K alpha_psi dl, d sqrt(J2) = -G dl, so f = 0 gives
    // dl = f_trial / (9 K alpha_phi alpha_psi + G), the incremental form of eq 9.
    const double H = 9.0 * K * alpha_phi * alpha_psi + G;
    const double d_lambda = f_trial / H;
    const double p = p_trial - 3.0 * K * alpha_psi * d_lambda;
    const double rho = rho_trial - G * d_lambda;
    if (p <= p_t && rho >= 0.0) {
      r.regime = DruckerPragerRegime::cone;
      r.d_lambda = d_lambda;
      r.stress = p * Mat3::Identity() + (rho / rho_trial) * s_trial;  // radial in the deviator
      return r;
    }
  }

  // The cone return would pass the cut-off (or the apex): the mean stress is capped at p_t.
  assert(std::isfinite(p_t));
  const double rho_corner = std::max(cone_.k_c - 3.0 * alpha_phi * p_t, 0.0);  // f(p_t, rho) = 0
  if (rho_corner > tolerance && rho_trial <= rho_corner) {  // none when p_t is the apex
    r.regime = DruckerPragerRegime::cutoff;  // flow normal to the plane p = p_t: volumetric only
    r.stress = p_t * Mat3::Identity() + s_trial;
    return r;
  }
  r.regime = DruckerPragerRegime::corner;  // both cone and cut-off active; the apex if rho_c = 0
  r.d_lambda = (rho_trial - rho_corner) / G;
  r.stress = p_t * Mat3::Identity();
  if (rho_trial > 0.0) r.stress += (rho_corner / rho_trial) * s_trial;
  return r;
}

void DruckerPrager::record_plastic_step(const Mat3& trial, const DruckerPragerReturn& result,
                                        std::span<double> internal) const {
  if (result.regime == DruckerPragerRegime::elastic) return;
  // Plastic strain increment = C^-1 : (sigma_trial - sigma_{n+1}) (eq 3 integrated).
  // |d_plastic|^2 = |dev d_stress|^2 / (2 G)^2 + 3 (mean d_stress / (3 K))^2, with
  // |dev d_stress|^2 = |d_stress|^2 - 3 mean^2 (the stress does not depend on it: one square root
  // and no tensor division per plastic step)
  const Mat3 d_stress = trial - result.stress;
  const double mean = mean_stress(d_stress);
  const double deviatoric = std::max(contract(d_stress, d_stress) - 3.0 * mean * mean, 0.0);
  const double two_g = 2.0 * elastic_.shear_modulus();
  const double three_k = 3.0 * elastic_.bulk_modulus();
  const double squared = deviatoric / (two_g * two_g) + 3.0 * (mean * mean) / (three_k * three_k);
  internal[drucker_prager_plastic_strain] += std::sqrt(2.0 / 3.0 * squared);
  if (result.regime != DruckerPragerRegime::cone) internal[drucker_prager_corrections] += 1.0;
}

DruckerPragerReturn DruckerPrager::integrate_returning(const Mat3& d_strain, Mat3& stress,
                                                       std::span<double> internal,
                                                       Mat3& trial) const {
  trial = stress + elastic_increment(elastic_, d_strain);  // elastic predictor
  DruckerPragerReturn result = return_mapping(trial);
  record_plastic_step(trial, result, internal);
  stress = result.stress;
  assert(cone_.yield_function(stress) <= 1e-10 * stress_scale(stress));
  return result;
}

void DruckerPrager::integrate(const Mat3& d_strain, Mat3& stress,
                              std::span<double> internal) const {
  Mat3 trial;
  integrate_returning(d_strain, stress, internal, trial);
}

void DruckerPrager::integrate_with_tangent(const Mat3& d_strain, Mat3& stress,
                                           std::span<double> internal, Mat6& tangent) const {
  // The tangent of tangent(d_strain, stress_before), formed from the return just taken.
  Mat3 trial;
  const DruckerPragerReturn result = integrate_returning(d_strain, stress, internal, trial);
  tangent = consistent_tangent(trial, result);
}

void DruckerPrager::correct(Mat3& stress, std::span<double> internal) const {
  // integrate() leaves the stress on or inside the surface; only a stress from elsewhere (a
  // rate-form update) needs the return. The admissibility test of return_mapping, first.
  const double p = mean_stress(stress);
  const double rho = std::sqrt(j2(stress));
  const double tolerance = on_surface_tolerance * (std::abs(p) + rho + cone_.k_c);
  if (3.0 * cone_.alpha_phi * p + rho - cone_.k_c <= tolerance &&
      p <= tension_cutoff_ + tolerance) {
    return;
  }
  const DruckerPragerReturn result = return_mapping(stress);
  record_plastic_step(stress, result, internal);
  stress = result.stress;
}

Mat6 DruckerPrager::tangent(const Mat3& d_strain, const Mat3& stress,
                            std::span<const double>) const {
  const Mat3 trial = stress + elastic_increment(elastic_, d_strain);
  return consistent_tangent(trial, return_mapping(trial));
}

Mat6 DruckerPrager::consistent_tangent(const Mat3& trial, const DruckerPragerReturn& r) const {
  const double K = elastic_.bulk_modulus();
  const double G = elastic_.shear_modulus();
  // s_trial / |s_trial| (zero when the trial is isotropic)
  const Vec6 n = r.rho_trial > 0.0
                     ? stress_to_voigt((1.0 / (sqrt2 * r.rho_trial)) * deviator(trial))
                     : Vec6::Zero();
  const Vec6 one = voigt_identity();

  switch (r.regime) {
    case DruckerPragerRegime::elastic:
      return isotropic_stiffness(K, G);
    case DruckerPragerRegime::cone: {
      // Linearised radial return (see docs): s = s_trial (1 - G dl / rho_trial),
      // p = p_trial - 3 K alpha_psi dl, dl = f_trial / H.
      const double H = 9.0 * K * cone_.alpha_phi * cone_.alpha_psi + G;
      const double beta = G * r.d_lambda / r.rho_trial;
      const Vec6 flow = sqrt2 * G * n + 3.0 * K * cone_.alpha_psi * one;    // C : dg/dsigma
      const Vec6 normal = sqrt2 * G * n + 3.0 * K * cone_.alpha_phi * one;  // df_trial/d eps
      return isotropic_stiffness(K, G * (1.0 - beta)) + 2.0 * G * beta * n * n.transpose() -
             flow * normal.transpose() / H;
    }
    case DruckerPragerRegime::cutoff:  // p fixed, deviator elastic
      return isotropic_stiffness(0.0, G);
    case DruckerPragerRegime::corner: {
      // p fixed, |s| fixed: only the direction of s_trial turns. At the apex (rho_corner = 0)
      // the stress is fixed and the consistent tangent is exactly zero.
      const double ratio =  // rho_corner / rho_trial
          r.rho_trial > 0.0 ? (r.rho_trial - G * r.d_lambda) / r.rho_trial : 0.0;
      return isotropic_stiffness(0.0, G * ratio) - 2.0 * G * ratio * n * n.transpose();
    }
  }
  return isotropic_stiffness(K, G);
}

Mat3 DruckerPrager::objective_rate(const Mat3& stretching, const Mat3& stress,
                                   std::span<const double>) const {
  const double K = elastic_.bulk_modulus();
  const double G = elastic_.shear_modulus();
  const double alpha_phi = cone_.alpha_phi;
  const double alpha_psi = cone_.alpha_psi;
  const Mat3 d_dev = deviator(stretching);
  const Mat3 elastic_rate = K * stretching.trace() * identity3() + 2.0 * G * d_dev;

  const double scale = stress_scale(stress);
  const double tolerance = 1e-10 * scale;
  const bool on_cone = cone_.yield_function(stress) >= -tolerance;
  const bool on_cutoff =
      std::isfinite(tension_cutoff_) && mean_stress(stress) >= tension_cutoff_ - tolerance;
  if (!on_cone && !on_cutoff) return elastic_rate;

  // Flow direction of the deviator: s/|s| on the cone; at the apex (s = 0) the direction of the
  // deviatoric stretching, along which the elastic rate leaves the apex.
  const Mat3 s = deviator(stress);
  const double rho = std::sqrt(0.5 * contract(s, s));
  Mat3 n = Mat3::Zero();
  if (rho > tolerance) {
    n = s / (sqrt2 * rho);
  } else if (norm(d_dev) > 0.0) {
    n = d_dev / norm(d_dev);
  }

  // Elastic rates of the two constraints f1 = cone (eq 5) and f2 = p - p_t.
  const Vec2 f_elastic(3.0 * alpha_phi * K * stretching.trace() + sqrt2 * G * contract(n, d_dev),
                       K * stretching.trace());
  // f_dot = f_elastic - A lambda_dot with A from the flows (eq 4, 7 and dp/dlambda_2 = -K).
  Mat2 A;
  A << 9.0 * K * alpha_phi * alpha_psi + G, 3.0 * alpha_phi * K, 3.0 * K * alpha_psi, K;
  const bool on[2] = {on_cone, on_cutoff};
  const double rate_tolerance = 1e-12 * (K + G) * norm(stretching);

  // Kuhn-Tucker conditions in rate form (a 2x2 linear complementarity problem; A has positive
  // diagonal and det A = G K > 0, so exactly one active set fits): try each active set.
  Vec2 lambda_dot = Vec2::Zero();
  for (int active = 0; active < 4; ++active) {
    const bool act[2] = {(active & 1) != 0, (active & 2) != 0};
    if ((act[0] && !on[0]) || (act[1] && !on[1])) continue;
    Vec2 trial = Vec2::Zero();
    if (act[0] && act[1]) {
      trial = A.inverse() * f_elastic;
    } else if (act[0]) {
      trial(0) = f_elastic(0) / A(0, 0);  // Bui 2008 eq 9
    } else if (act[1]) {
      trial(1) = f_elastic(1) / A(1, 1);
    }
    const Vec2 f_dot = f_elastic - A * trial;
    bool fits = trial.minCoeff() >= -rate_tolerance / (K + G);
    for (int i = 0; i < 2; ++i) {
      if (on[i] && !act[i] && f_dot(i) > rate_tolerance) fits = false;
    }
    if (fits) {
      lambda_dot = trial;
      break;
    }
  }
  // Bui 2008 eq 8: elastic rate minus lambda_dot times C : dg/dsigma (G s / sqrt(J2) =
  // sqrt2 G n), plus the cut-off's volumetric flow.
  return elastic_rate - lambda_dot(0) * (3.0 * alpha_psi * K * identity3() + sqrt2 * G * n) -
         lambda_dot(1) * K * identity3();
}

ElasticModuli DruckerPrager::moduli(const Mat3&, std::span<const double>) const {
  return {elastic_.bulk_modulus(), elastic_.shear_modulus()};
}

void register_drucker_prager(ModelRegistry& registry) {
  registry.add(
      {"drucker-prager",
       "Drucker-Prager, non-associated, plane-strain fit to Mohr-Coulomb (Bui 2008), tension "
       "cut-off (E, nu, phi, psi, c, tension_cutoff)",
       [](Parameters& p) -> std::unique_ptr<Model> {
         const ElasticParameters elastic = ElasticParameters::read(p);
         const double phi =
             p.require("phi", Range::closed_open(0.0, 90.0), "deg", "friction angle");
         const double psi = p.require("psi", Range::closed(0.0, phi).following("[0, phi]"), "deg",
                                      "dilatancy angle (at most phi)");
         const double c = p.require("c", Range::non_negative(), "Pa", "cohesion");
         const DruckerPragerCone cone = DruckerPragerCone::from_coulomb(phi, psi, c);
         const double apex = cone.apex_mean_stress();
         const Range cutoff_range =
             (std::isfinite(apex) ? Range::closed(0.0, apex) : Range::non_negative())
                 .following("[0, c cot(phi)] (>= 0 when phi = 0)");
         const double cutoff = p.optional("tension_cutoff", apex, cutoff_range, "Pa",
                                          "tension cut-off on the mean stress (at most the apex "
                                          "c cot(phi))",
                                          "c cot(phi), the apex");
         return std::make_unique<DruckerPrager>(elastic, cone, cutoff);
       },
       // Bui 2008 aluminium bars.
       {{"E", 5.84e6}, {"nu", 0.3}, {"phi", 19.8}, {"psi", 0.0}, {"c", 0.0}},
       {},
       /*softens=*/false});
}

}  // namespace duet::constitutive
