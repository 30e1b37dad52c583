#pragma once
// Drucker-Prager perfect plasticity with non-associated flow and a mean-stress tension cut-off
// (Bui et al. 2008 eqs 3-9, as Bui et al. 2013 restates them; theory page constitutive/docs/
// drucker_prager.md). Tension positive: I1 = tr(sigma) < 0 in compression, so the cone
// f = alpha_phi I1 + sqrt(J2) - k_c is negative in the elastic domain under compression.
//
// Composed of small parts, each tested alone: the cone (yield function and plastic potential
// constants from c, phi, psi), the return mapping in the (p, sqrt(J2)) plane (cone, cut-off,
// corner = apex by default) and its consistent tangent.

#include "constitutive/linear_elastic.hpp"
#include "constitutive/model.hpp"
#include "constitutive/registry.hpp"

namespace duet::constitutive {

/// Plane-strain Drucker-Prager constants from the Coulomb constants (Bui 2008 eq 6).
struct DruckerPragerCone {
  double alpha_phi = 0.0;  // friction factor, -
  double alpha_psi = 0.0;  // dilatancy factor (eq 7), -
  double k_c = 0.0;        // cohesion factor, Pa

  /// phi, psi in degrees, c in Pa.
  static DruckerPragerCone from_coulomb(double phi_deg, double psi_deg, double c);

  /// Bui 2008 eq 5: f = alpha_phi I1 + sqrt(J2) - k_c (< 0 inside, tension positive).
  double yield_function(const Mat3& stress) const;
  /// Mean stress of the apex, k_c / (3 alpha_phi) = c cot(phi); +infinity when alpha_phi = 0.
  double apex_mean_stress() const;
};

/// Which branch of the return mapping an increment took.
enum class DruckerPragerRegime {
  elastic,  // trial state inside the cone and below the cut-off
  cone,     // smooth return onto the cone along the flow direction (one multiplier)
  cutoff,   // return onto the tension cut-off p = p_t (deviator unchanged)
  corner,   // return to the intersection of cone and cut-off (the apex when p_t is the apex)
};

/// Result of one return mapping in the (p, sqrt(J2)) plane.
struct DruckerPragerReturn {
  DruckerPragerRegime regime = DruckerPragerRegime::elastic;
  Mat3 stress = Mat3::Zero();  // sigma_{n+1}
  double d_lambda = 0.0;       // cone multiplier, -
  double rho_trial = 0.0;      // sqrt(J2) of the trial state, Pa
};

class DruckerPrager final : public Model {
 public:
  /// tension_cutoff: largest admissible mean stress p_t (Pa), at most the apex mean stress.
  DruckerPrager(ElasticParameters elastic, DruckerPragerCone cone, double tension_cutoff);

  std::string_view name() const override { return "drucker-prager"; }
  std::vector<InternalVariable> internal_variables() const override;
  void integrate(const Mat3& d_strain, Mat3& stress, std::span<double> internal) const override;
  Mat3 objective_rate(const Mat3& stretching, const Mat3& stress,
                      std::span<const double> internal) const override;
  Mat6 tangent(const Mat3& d_strain, const Mat3& stress,
               std::span<const double> internal) const override;
  /// integrate() and the consistent tangent of the same return (one return mapping).
  void integrate_with_tangent(const Mat3& d_strain, Mat3& stress, std::span<double> internal,
                              Mat6& tangent) const override;
  ElasticModuli moduli(const Mat3& stress, std::span<const double> internal) const override;
  /// Returns a state that drifted outside (a rate-form integrator's step) to the surface with the
  /// same return mapping, treating the given stress as the trial state.
  void correct(Mat3& stress, std::span<double> internal) const override;

  /// The return mapping of an elastic trial stress (public for the tests of each regime).
  DruckerPragerReturn return_mapping(const Mat3& trial) const;

  const DruckerPragerCone& cone() const { return cone_; }
  double tension_cutoff() const { return tension_cutoff_; }
  /// Relative measure of the stress level used for the surface tolerance, Pa.
  double stress_scale(const Mat3& stress) const;

 private:
  /// The body of integrate(): predictor, return, internal variables. Gives back the return and
  /// the elastic trial stress it started from (in `trial`).
  DruckerPragerReturn integrate_returning(const Mat3& d_strain, Mat3& stress,
                                          std::span<double> internal, Mat3& trial) const;
  /// Consistent tangent d sigma_{n+1} / d eps of the return `r` from `trial` (Voigt).
  Mat6 consistent_tangent(const Mat3& trial, const DruckerPragerReturn& r) const;
  /// Accumulates plastic strain and corrections from trial -> returned state.
  void record_plastic_step(const Mat3& trial, const DruckerPragerReturn& result,
                           std::span<double> internal) const;

  ElasticParameters elastic_;
  DruckerPragerCone cone_;
  double tension_cutoff_;  // p_t, Pa (may be +infinity when phi = 0 and none is given)
};

/// Storage order of the internal variables.
inline constexpr int drucker_prager_plastic_strain = 0;  // accumulated equivalent plastic strain
inline constexpr int drucker_prager_corrections = 1;     // returns to the cut-off or the apex

void register_drucker_prager(ModelRegistry& registry);

}  // namespace duet::constitutive
