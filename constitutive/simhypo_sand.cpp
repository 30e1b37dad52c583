#include "constitutive/simhypo_sand.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace duet::constitutive {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr int kMaxSubsteps = 10000;

}  // namespace

SimhypoSandParameters SimhypoSandParameters::read(Parameters& p) {
  SimhypoSandParameters m;
  m.phi_c = p.require("phi_c", Range::open(0.0, 90.0), "deg", "critical state friction angle");
  m.E_i = p.require("E_i", Range::positive(), "Pa", "initial triaxial modulus at sigma_c");
  m.nu_i = p.require("nu_i", Range::closed_open(0.0, 0.5), "-", "initial Poisson's ratio");
  m.e_Gamma = p.require("e_Gamma", Range::positive(), "-",
                        "critical state line intercept (void ratio at p' = 0)");
  m.lambda = p.require("lambda", Range::non_negative(), "-", "critical state line slope");
  m.xi = p.require("xi", Range::open_closed(0.0, 1.0), "-", "critical state line exponent");
  m.alpha = p.require("alpha", Range::non_negative(), "-", "density factor exponent");
  m.theta = p.optional("theta", 1.0, Range::closed(0.0, 1.0), "-",
                       "failure surface weight (0 Drucker-Prager, 1 SMP)");
  m.sigma_c = p.optional("sigma_c", 100e3, Range::positive(), "Pa",
                         "confining pressure of the calibration test");
  m.e0 = p.require("e0", Range::positive(), "-", "initial void ratio");
  m.correction = parse_correction_method(
      p.choice("correction", correction_method_names(), "C", "stress correction method"));
  m.correction_tolerance = p.optional("correction_tolerance", 1e-3, Range::open(0.0, 1.0), "-",
                                      "tolerance on the failure function");
  m.substep_strain = p.optional("substep_strain", 1e-3, Range::positive(), "-",
                                "largest strain norm of one explicit sub-step");
  m.p_min = p.optional("p_min", 1.0, Range::positive(), "Pa", "apex mean effective pressure");
  p.record("a_c", critical_a(m.phi_c));
  p.record("f_s", stiffness_factor(m));
  return m;
}

double critical_void_ratio(const SimhypoSandParameters& m, double p_eff) {
  return m.e_Gamma -
         m.lambda * std::pow(std::max(p_eff, 0.0) / atmospheric_pressure, m.xi);  // eq 6
}

double density_factor(const SimhypoSandParameters& m, double void_ratio, double p_eff) {
  // Guards: the CSL of eq 6 crosses e = 0 at very high pressure; a void ratio cannot be negative.
  const double e_c = std::max(critical_void_ratio(m, p_eff), 1e-6);
  return std::pow(std::max(void_ratio, 0.0) / e_c, m.alpha);  // eq 5
}

double critical_a(double phi_c_deg) {
  const double s = std::sin(phi_c_deg * kDegree);
  return std::sqrt(3.0) * (3.0 - s) / (2.0 * std::sqrt(2.0) * s);  // eq 16
}

double smp_radius_ratio(const Mat3& stress) {
  // Principal stresses, compression positive; tensile ones read as 0 so the SMP terms stay real.
  Eigen::SelfAdjointEigenSolver<Mat3> solver;
  solver.computeDirect(-stress, Eigen::EigenvaluesOnly);
  const Vec3 s = solver.eigenvalues().cwiseMax(0.0);
  const double I1 = s.sum();
  const double q_m2 = 0.5 * ((s(0) - s(1)) * (s(0) - s(1)) + (s(1) - s(2)) * (s(1) - s(2)) +
                             (s(2) - s(0)) * (s(2) - s(0)));
  if (!(I1 > 0.0) || q_m2 <= 1e-24 * I1 * I1) return 1.0;  // hydrostatic limit: SMP is a circle
  const double q_m = std::sqrt(q_m2);                      // eq 18: q_m = sqrt(I1^2 - 3 I2)
  // I1 I2 - I3 and I1 I2 - 9 I3 in factored form (no cancellation near the hydrostatic axis).
  const double product = (s(0) + s(1)) * (s(1) + s(2)) * (s(2) + s(0));
  const double spread = s(0) * (s(1) - s(2)) * (s(1) - s(2)) +
                        s(1) * (s(2) - s(0)) * (s(2) - s(0)) + s(2) * (s(0) - s(1)) * (s(0) - s(1));
  if (!(spread > 0.0)) return 1.0;
  // eq 18: q_s = 2 I1 / (3 sqrt((I1 I2 - I3)/(I1 I2 - 9 I3)) - 1)
  const double q_s = 2.0 * I1 * std::sqrt(spread) / (3.0 * std::sqrt(product) - std::sqrt(spread));
  return q_s / q_m;
}

double a_factor(const SimhypoSandParameters& m, const Mat3& stress) {
  const double a_c = critical_a(m.phi_c);
  return a_c / (m.theta / smp_radius_ratio(stress) + 1.0 - m.theta);  // eq 17
}

double stiffness_factor(const SimhypoSandParameters& m) {
  return -m.E_i / (3.0 * (1.0 + m.nu_i) * m.sigma_c);  // eq 11
}

double volumetric_factor(const SimhypoSandParameters& m, double f_d, double a) {
  const double nu = m.nu_i;
  return (3.0 * nu + f_d * a * std::sqrt(1.0 + 2.0 * nu * nu)) / (1.0 - 2.0 * nu) -
         a * a / 3.0;  // eq 10
}

SimhypoFactors simhypo_factors(const SimhypoSandParameters& m, const Mat3& stress,
                               double void_ratio) {
  SimhypoFactors k;
  k.f_s = stiffness_factor(m);
  k.f_d = density_factor(m, void_ratio, effective_pressure(stress));
  k.a = a_factor(m, stress);
  k.f_v = volumetric_factor(m, k.f_d, k.a);
  return k;
}

Mat3 linear_part(const SimhypoFactors& k, const Mat3& stress, const Mat3& stretching) {
  const double tr_s = stress.trace();
  return tr_s * stretching + k.f_v * stretching.trace() * stress +
         k.a * k.a * contract(stress, stretching) / tr_s * stress;  // eq 4, first three terms
}

Mat3 nonlinear_part(const SimhypoFactors& k, const Mat3& stress) {
  return k.a * (stress + deviator(stress));  // eq 4, last term without f_d |D|
}

Mat3 simhypo_rate(const SimhypoSandParameters& m, const Mat3& stress, double void_ratio,
                  const Mat3& stretching) {
  const SimhypoFactors k = simhypo_factors(m, stress, void_ratio);
  // eq 4: f_s [tr(s) D + f_v tr(D) s + a^2 tr(s D)/tr(s) s + f_d a (s + s*) |D|]
  return k.f_s * (linear_part(k, stress, stretching) +
                  k.f_d * nonlinear_part(k, stress) * norm(stretching));
}

Mat3 flow_tensor(const SimhypoFactors& k, const Mat3& stress) {
  const double tr_s = stress.trace();
  const Mat3 s = deviator(stress);
  const double a2 = k.a * k.a;
  const double ratio = (tr_s * tr_s - a2 * contract(s, s)) /
                       ((1.0 + k.f_v) * tr_s * tr_s + a2 * contract(stress, stress));
  return k.a / tr_s * (s + stress * ratio);  // eq 15
}

double failure_function(const SimhypoSandParameters& m, const Mat3& stress, double void_ratio) {
  if (!(effective_pressure(stress) > 0.0)) return std::numeric_limits<double>::infinity();
  const SimhypoFactors k = simhypo_factors(m, stress, void_ratio);
  return k.f_d * norm(flow_tensor(k, stress)) - 1.0;  // eq 14
}

Mat6 simhypo_tangent(const SimhypoSandParameters& m, const Mat3& stress, double void_ratio,
                     const Mat3& stretching) {
  const SimhypoFactors k = simhypo_factors(m, stress, void_ratio);
  Mat6 tangent;
  for (int j = 0; j < 6; ++j) {
    const Mat3 unit = voigt_to_strain(Vec6::Unit(j));
    tangent.col(j) = k.f_s * stress_to_voigt(linear_part(k, stress, unit));
  }
  const double d_norm = norm(stretching);
  if (d_norm > 0.0) {
    // eq 12: f_s f_d N (x) D/|D|; d|D|/d(gamma_xy) = D_xy/|D|, so the row holds plain components.
    const Vec6 direction = stress_to_voigt(stretching / d_norm);
    tangent += k.f_s * k.f_d * stress_to_voigt(nonlinear_part(k, stress)) * direction.transpose();
  }
  return tangent;
}

// ---------------------------------------------------------------------------------------------
// The model

namespace {

enum Slot { kVoidRatio = 0, kCorrections = 1 };

/// The stress at which the rate is evaluated: the apex -p_min I for p' <= p_min (no division by
/// tr(sigma) = 0 in eqs 4 and 15).
Mat3 evaluation_stress(const SimhypoSandParameters& m, const Mat3& stress) {
  if (effective_pressure(stress) > m.p_min && stress.allFinite()) return stress;
  return -m.p_min * Mat3::Identity();
}

}  // namespace

std::vector<InternalVariable> SimhypoSand::internal_variables() const {
  return {{"void_ratio", m_.e0, "-"}, {"corrections", 0.0, "-"}};
}

void SimhypoSand::integrate(const Mat3& d_strain, Mat3& stress, std::span<double> internal) const {
  if (d_strain.isZero(0.0)) return;
  double& e = internal[kVoidRatio];
  const Mat3 start = stress;
  const int n_substeps = static_cast<int>(std::clamp(std::ceil(norm(d_strain) / m_.substep_strain),
                                                     1.0, static_cast<double>(kMaxSubsteps)));
  const Mat3 step = d_strain / n_substeps;
  for (int k = 0; k < n_substeps; ++k) {
    if (!(effective_pressure(stress) > m_.p_min) || !stress.allFinite()) {
      stress = -m_.p_min * Mat3::Identity();  // tensile or vanishing mean stress: apex
      internal[kCorrections] += 1.0;
    }
    stress += simhypo_rate(m_, stress, e, step);  // eq 4, forward Euler over the sub-step
    e += (1.0 + e) * step.trace();                // eq 32: de = (1 + e) tr(d_eps)
  }
  correct_with_rate(stress, internal, stress - start);
}

Mat3 SimhypoSand::objective_rate(const Mat3& stretching, const Mat3& stress,
                                 std::span<const double> internal) const {
  return simhypo_rate(m_, evaluation_stress(m_, stress), internal[kVoidRatio], stretching);
}

Mat6 SimhypoSand::tangent(const Mat3& d_strain, const Mat3& stress,
                          std::span<const double> internal) const {
  return simhypo_tangent(m_, evaluation_stress(m_, stress), internal[kVoidRatio], d_strain);
}

ElasticModuli SimhypoSand::moduli(const Mat3& stress, std::span<const double> internal) const {
  const Mat3 s = evaluation_stress(m_, stress);
  const SimhypoFactors k = simhypo_factors(m_, s, internal[kVoidRatio]);
  const double p = effective_pressure(s);
  // Linear part of eq 4 at an isotropic state -p I: deviatoric D gives 2G D = f_s tr(s) D,
  // volumetric D gives K = -f_s p (1 + f_v + a^2/3).
  return {-k.f_s * p * (1.0 + k.f_v + k.a * k.a / 3.0), -1.5 * k.f_s * p};
}

void SimhypoSand::correct(Mat3& stress, std::span<double> internal) const {
  // No increment known: Method B corrects along the stress rate of continued flow along the flow
  // rule, f_s [L:(-B/|B|) + f_d N] = f_s N (f_d |B| - 1)/|B|, i.e. along N.
  const Mat3 s = evaluation_stress(m_, stress);
  const SimhypoFactors k = simhypo_factors(m_, s, internal[kVoidRatio]);
  correct_with_rate(stress, internal, nonlinear_part(k, s));
}

bool SimhypoSand::correct_with_rate(Mat3& stress, std::span<double> internal,
                                    const Mat3& stress_rate) const {
  const Mat3 apex = -m_.p_min * Mat3::Identity();
  if (!(effective_pressure(stress) > m_.p_min) || !stress.allFinite()) {
    stress = apex;  // tensile distortion (paper Fig 2): back to the apex
    internal[kCorrections] += 1.0;
    return true;
  }
  if (m_.correction == CorrectionMethod::none) return false;
  const double e = internal[kVoidRatio];
  const FailureFunction f = [&](const Mat3& s) { return failure_function(m_, s, e); };
  if (!(f(stress) > m_.correction_tolerance)) return false;

  const double tol = m_.correction_tolerance;
  bool projected = true;
  switch (m_.correction) {
    case CorrectionMethod::A: {
      // eq 36: along the flow rule B of the current iterate
      const CorrectionDirection along_b = [&](const Mat3& s) {
        return flow_tensor(simhypo_factors(m_, s, e), s);
      };
      projected = project_along(f, along_b, stress, tol);
      break;
    }
    case CorrectionMethod::B: {
      // eq 37: along the stress rate
      const CorrectionDirection along_rate = [&](const Mat3&) { return stress_rate; };
      projected = norm(stress_rate) > 0.0 && project_along(f, along_rate, stress, tol);
      break;
    }
    case CorrectionMethod::C:
      scale_deviator_to_surface(f, stress, tol);
      break;  // eq 38
    case CorrectionMethod::none:
      break;
  }
  // A direction tangent to the surface (or one that leaves it) cannot correct: fall back to C.
  if (!projected) scale_deviator_to_surface(f, stress, tol);
  if (!(effective_pressure(stress) > m_.p_min) || !stress.allFinite()) stress = apex;
  internal[kCorrections] += 1.0;
  return true;
}

void register_simhypo_sand(ModelRegistry& registry) {
  registry.add({"simhypo-sand",
                "void-ratio dependent critical-state hypoplastic sand (simhypo-sand, 7 "
                "parameters), stress correction A/B/C",
                [](Parameters& p) -> std::unique_ptr<Model> {
                  return std::make_unique<SimhypoSand>(SimhypoSandParameters::read(p));
                },
                // Table 1 of the paper is not in the text extraction: phi_c = 30 deg as in its
                // Fig 1, the critical state line of Li & Wang (1998) for Toyoura sand (the
                // paper's eq 6 source), representative E_i, nu_i, alpha (docs/simhypo_sand.md).
                {{"phi_c", 30.0},
                 {"E_i", 40e6},
                 {"nu_i", 0.3},
                 {"e_Gamma", 0.934},
                 {"lambda", 0.019},
                 {"xi", 0.7},
                 {"alpha", 4.0},
                 {"e0", 0.85}}});
}

}  // namespace duet::constitutive
