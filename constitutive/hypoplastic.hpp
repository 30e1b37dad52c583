#pragma once
// The Wang/Wu 4-parameter hypoplastic model with cohesion (Peng et al. 2015, section 3, eqs 15,
// 16, 24, 25): a rate equation, no yield surface, no strain decomposition. Theory, integration
// scheme and tests: constitutive/docs/hypoplastic.md.
//
// Tension positive. The model acts on the translated stress eta = sigma - c I (eq 24); its
// admissible region is tr eta < 0 (compression beyond the cohesion). Outside it (tension beyond
// the cohesion, or a mean translated stress within half the apex pressure of zero) the stress is
// returned to the apex eta = -apex_pressure I and the internal variable `corrections` counts it.

#include "constitutive/hypoplastic_calibration.hpp"
#include "constitutive/model.hpp"
#include "constitutive/registry.hpp"

namespace duet::constitutive {

struct HypoplasticParameters {
  HypoplasticConstants constants;  // c1..c4 of eq 15, -
  double cohesion = 0.0;           // c of eq 24, Pa

  /// Reads either `c1 c2 c3 c4` or `Ei nu phi psi` (then c1..c4 from calibrate_hypoplastic at
  /// sigma_3 = -100 kPa, recorded in `parameters`), and `c` (default 0). Throws InputError.
  static HypoplasticParameters read(Parameters& parameters);
};

/// Mean translated pressure of the apex state, Pa: hypoplastic stiffness is proportional to the
/// stress, so a zero stress would never recover; the apex keeps a small isotropic compression.
inline constexpr double apex_pressure = 1.0;

/// Peng 2015 eq 15 split as in eq 14: rate = L(eta) : D + N(eta) |D|.
/// linear_rate: c1 (tr eta) D + c2 (tr D) eta + c3 tr(eta D)/tr(eta) eta.
Mat3 linear_rate(const HypoplasticConstants& c, const Mat3& eta, const Mat3& stretching);
/// nonlinear_direction: N(eta) = c4 (eta + eta*) (eq 16: eta* the deviator of eta).
Mat3 nonlinear_direction(const HypoplasticConstants& c, const Mat3& eta);
/// The full rate of eq 15/25 on the translated stress.
Mat3 hypoplastic_rate(const HypoplasticConstants& c, const Mat3& eta, const Mat3& stretching);

/// True when eta lies in the model's admissible region (finite, tr eta <= -1.5 apex_pressure).
bool admissible(const Mat3& eta);

class Hypoplastic final : public Model {
 public:
  explicit Hypoplastic(HypoplasticParameters parameters);

  std::string_view name() const override { return "hypoplastic"; }
  std::vector<InternalVariable> internal_variables() const override;
  void integrate(const Mat3& d_strain, Mat3& stress, std::span<double> internal) const override;
  Mat3 objective_rate(const Mat3& stretching, const Mat3& stress,
                      std::span<const double> internal) const override;
  Mat6 tangent(const Mat3& d_strain, const Mat3& stress,
               std::span<const double> internal) const override;
  ElasticModuli moduli(const Mat3& stress, std::span<const double> internal) const override;
  void correct(Mat3& stress, std::span<double> internal) const override;

  const HypoplasticParameters& parameters() const { return parameters_; }
  /// Number of explicit sub-steps integrate() uses for an increment of norm |d_strain|; 0 when it
  /// would need more than 10,000 (integrate() then sets the stress to NaN, which the solver
  /// reports, rather than run a million sub-steps).
  int substeps(double strain_norm) const;

 private:
  /// The translated stress of `stress`, at the apex when not admissible.
  Mat3 admissible_eta(const Mat3& stress) const;

  HypoplasticParameters parameters_;
  double rate_bound_;  // bound of |rate|/|eta| for a unit |D| inside the failure cone, -
};

void register_hypoplastic(ModelRegistry& registry);

}  // namespace duet::constitutive
