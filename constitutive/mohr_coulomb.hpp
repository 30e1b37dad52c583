#pragma once
// Mohr-Coulomb perfect plasticity, non-associated (psi <= phi), with the apex return in tension.
// Theory page: constitutive/docs/mohr_coulomb.md.
//
// Yield f = (sigma1 - sigma3) + (sigma1 + sigma3) sin(phi) - 2 c cos(phi) (tension positive,
// sigma1 >= sigma2 >= sigma3), plastic potential g the same with psi; return mapping in
// principal stress space: one-vector return to the main plane, two-vector returns to the left
// and right edges, return to the apex c cot(phi) (de Souza Neto, Peric & Owen 2008, Boxes
// 8.4-8.7), consistent tangent in spectral form (Box A.2). The principal-space machinery is
// shared with Tresca (constitutive/principal_return.hpp).

#include "constitutive/linear_elastic.hpp"
#include "constitutive/model.hpp"
#include "constitutive/principal_return.hpp"
#include "constitutive/registry.hpp"

namespace duet::constitutive {

/// The Mohr-Coulomb hexagonal pyramid as a faceted surface; phi, psi in degrees, c in Pa.
/// No apex when phi = 0 (the Tresca prism with c_u = c).
FacetedSurface mohr_coulomb_surface(double phi_deg, double psi_deg, double c);

class MohrCoulomb final : public Model {
 public:
  /// phi, psi in degrees (0 <= psi <= phi < 90), c in Pa (>= 0).
  MohrCoulomb(ElasticParameters elastic, double phi_deg, double psi_deg, double c);

  std::string_view name() const override { return "mohr-coulomb"; }
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
  /// Returns a drifted state (a rate-form integrator's step) to the surface with the same
  /// return mapping, treating the given stress as the trial state.
  void correct(Mat3& stress, std::span<double> internal) const override;

  /// The return mapping of an elastic trial stress (public for the tests of each regime).
  StressReturn return_mapping(const Mat3& trial) const;

  /// f = (sigma1 - sigma3) + (sigma1 + sigma3) sin(phi) - 2 c cos(phi), Pa (<= 0 admissible).
  double yield_function(const Mat3& stress) const;
  /// Stress level for relative tolerances: |p| + sqrt(J2) + c, Pa.
  double stress_scale(const Mat3& stress) const;
  const FacetedSurface& surface() const { return surface_; }

 private:
  /// The body of integrate(): predictor, return, internal variables; gives back the return.
  StressReturn integrate_returning(const Mat3& d_strain, Mat3& stress,
                                   std::span<double> internal) const;
  void record_plastic_step(const Mat3& trial, const StressReturn& result,
                           std::span<double> internal) const;

  ElasticParameters elastic_;
  double cohesion_;  // c, Pa
  FacetedSurface surface_;
};

/// Storage order of the internal variables.
inline constexpr int mohr_coulomb_plastic_strain = 0;  // accumulated equivalent plastic strain, -
inline constexpr int mohr_coulomb_corrections = 1;     // number of plastic returns

void register_mohr_coulomb(ModelRegistry& registry);

}  // namespace duet::constitutive
