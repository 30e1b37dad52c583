#pragma once
// simhypo-sand: the void-ratio dependent critical-state hypoplastic model for sand of the
// simhypo-sand paper (simhypo-sand 2024, eqs 4-18), with the stress corrections of its sec 3.3 (eqs
// 36-38). Theory page: constitutive/docs/simhypo_sand.md.
//
// Tension positive, as the paper writes eq 4: tr(sigma) < 0 in compression and the stiffness
// factor f_s of eq 11 is negative (sigma_c there is the magnitude of the confining pressure).
// Internal variables: void_ratio (e, starts at e0), corrections (count of corrections applied,
// apex returns included).

#include <span>

#include "constitutive/model.hpp"
#include "constitutive/registry.hpp"
#include "constitutive/stress_correction.hpp"

namespace duet::constitutive {

/// Atmospheric pressure p_a of eq 6, Pa.
inline constexpr double atmospheric_pressure = 101.325e3;

struct SimhypoSandParameters {
  // The model's 7 parameters (paper sec 2, Appendix A).
  double phi_c = 30.0;  // critical state friction angle, deg (eq 16)
  double E_i = 0.0;     // initial modulus q_dot/eps_a_dot at confining pressure sigma_c, Pa (eq 11)
  double nu_i = 0.3;    // initial Poisson's ratio in drained triaxial compression, - (eq 10)
  double e_Gamma = 0.0;  // critical state line: void ratio intercept, - (eq 6)
  double lambda = 0.0;   // critical state line: slope, - (eq 6)
  double xi = 0.7;       // critical state line: exponent, - (eq 6)
  double alpha = 1.0;    // density factor exponent, - (eq 5)
  // Options.
  double theta = 1.0;      // failure surface weight: 0 Drucker-Prager, 1 SMP (eq 17)
  double sigma_c = 100e3;  // confining pressure of the calibration (magnitude), Pa (eq 11)
  double e0 = 0.0;         // initial void ratio, -
  CorrectionMethod correction = CorrectionMethod::C;
  double correction_tolerance = 1e-3;  // on the failure function f (eq 14)
  double substep_strain = 1e-3;        // largest strain norm of one explicit sub-step, -
  double p_min =
      1.0;  // apex: smallest mean effective pressure kept (tensile states return here), Pa

  /// Reads the parameters with their ranges and units (material.<name>.<key> in messages).
  static SimhypoSandParameters read(Parameters& parameters);
};

/// The state-dependent factors of eq 4 at one state.
struct SimhypoFactors {
  double f_s = 0.0;  // stiffness factor (eq 11), negative
  double f_v = 0.0;  // volumetric factor (eq 10)
  double f_d = 1.0;  // density factor (eq 5)
  double a = 0.0;    // critical stress ratio factor (eqs 16-17)
};

/// Mean effective pressure p' = -tr(sigma)/3 (positive in compression).
inline double effective_pressure(const Mat3& stress) {
  return -stress.trace() / 3.0;
}

/// Eq 6: critical void ratio e_c = e_Gamma - lambda (p'/p_a)^xi (p' < 0 read as 0).
double critical_void_ratio(const SimhypoSandParameters& m, double p_eff);
/// Eq 5: density factor f_d = (e/e_c)^alpha.
double density_factor(const SimhypoSandParameters& m, double void_ratio, double p_eff);
/// Eq 16: a_c = sqrt3 (3 - sin phi_c) / (2 sqrt2 sin phi_c), phi_c in degrees.
double critical_a(double phi_c_deg);
/// Eq 18: q_s / q_m, the triaxial-compression radius of the SMP surface through the stress over
/// the Drucker-Prager one (1 in triaxial compression, > 1 towards extension, 1 at the
/// hydrostatic axis). Principal stresses are read in compression, tensile ones as 0.
double smp_radius_ratio(const Mat3& stress);
/// Eq 17: a = a_c / (theta q_m/q_s + 1 - theta).
double a_factor(const SimhypoSandParameters& m, const Mat3& stress);
/// Eq 11: f_s = -E_i / (3 (1 + nu_i) sigma_c).
double stiffness_factor(const SimhypoSandParameters& m);
/// Eq 10: f_v = (3 nu_i + f_d a sqrt(1 + 2 nu_i^2)) / (1 - 2 nu_i) - a^2/3.
double volumetric_factor(const SimhypoSandParameters& m, double f_d, double a);
/// All factors at (stress, void ratio); f_v from eq 10 with the state's f_d and a.
SimhypoFactors simhypo_factors(const SimhypoSandParameters& m, const Mat3& stress,
                               double void_ratio);

/// Linear part of eq 4 without f_s: L:D = tr(sigma) D + f_v tr(D) sigma + a^2 tr(sigma D)/tr(sigma)
/// sigma.
Mat3 linear_part(const SimhypoFactors& k, const Mat3& stress, const Mat3& stretching);
/// Nonlinear part of eq 4 without f_s and f_d: N = a (sigma + sigma*).
Mat3 nonlinear_part(const SimhypoFactors& k, const Mat3& stress);
/// Eq 4: objective stress rate f_s [L:D + f_d N |D|].
Mat3 simhypo_rate(const SimhypoSandParameters& m, const Mat3& stress, double void_ratio,
                  const Mat3& stretching);
/// Eq 15: the tensor B of the failure criterion and flow rule (as printed it solves L:B = N).
Mat3 flow_tensor(const SimhypoFactors& k, const Mat3& stress);
/// Eq 14: failure function f = f_d |B| - 1 (zero on the surface, negative inside).
double failure_function(const SimhypoSandParameters& m, const Mat3& stress, double void_ratio);
/// Directional stiffness of eq 12 in Voigt form (stress plain, strain engineering shear):
/// f_s [L + f_d N (x) D/|D|]; for D = 0 the linear part f_s L alone.
Mat6 simhypo_tangent(const SimhypoSandParameters& m, const Mat3& stress, double void_ratio,
                     const Mat3& stretching);

class SimhypoSand final : public Model {
 public:
  explicit SimhypoSand(SimhypoSandParameters parameters) : m_(parameters) {}

  std::string_view name() const override { return "simhypo-sand"; }
  std::vector<InternalVariable> internal_variables() const override;
  /// Forward-Euler sub-steps of eq 4 (strain norm <= substep_strain each), void ratio by eq 32,
  /// apex return when p' <= p_min, then the selected correction when f > tolerance.
  void integrate(const Mat3& d_strain, Mat3& stress, std::span<double> internal) const override;
  Mat3 objective_rate(const Mat3& stretching, const Mat3& stress,
                      std::span<const double> internal) const override;
  Mat6 tangent(const Mat3& d_strain, const Mat3& stress,
               std::span<const double> internal) const override;
  /// From the linear part at an isotropic state of the same p': G = f_s tr(sigma)/2 =
  /// -1.5 f_s p', K = -f_s p' (1 + f_v + a^2/3) (f_s < 0).
  ElasticModuli moduli(const Mat3& stress, std::span<const double> internal) const override;
  /// The selected correction without a known increment (Method B then uses the stress rate of
  /// continued flow along the flow rule, which points along N).
  void correct(Mat3& stress, std::span<double> internal) const override;

  const SimhypoSandParameters& parameters() const { return m_; }

  /// Applies the apex return or the selected correction to `stress`; `stress_rate` is the
  /// direction of Method B (the increment's stress change). Returns true when it acted (and
  /// counted it in internal[1]).
  bool correct_with_rate(Mat3& stress, std::span<double> internal, const Mat3& stress_rate) const;

 private:
  SimhypoSandParameters m_;
};

void register_simhypo_sand(ModelRegistry& registry);

}  // namespace duet::constitutive
