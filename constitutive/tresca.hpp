#pragma once
// Tresca perfect plasticity for undrained clay (total stress, cohesion c_u), the soil of the
// Zhang et al. 2018 footing and cavity benchmarks. Theory page: constitutive/docs/tresca.md.
//
// Yield f = sigma1 - sigma3 - 2 c_u (tension positive, sigma1 >= sigma2 >= sigma3), associated
// flow; return mapping in principal stress space with the one-vector return to the main plane
// and the two-vector returns to the left and right edges (de Souza Neto, Peric & Owen 2008,
// Boxes 8.1-8.3), consistent tangent in spectral form (sec. 8.1.5, Box A.2). The principal-space
// machinery is shared with Mohr-Coulomb (constitutive/principal_return.hpp): Tresca is its
// phi = psi = 0 case, which has no apex.

#include "constitutive/linear_elastic.hpp"
#include "constitutive/model.hpp"
#include "constitutive/principal_return.hpp"
#include "constitutive/registry.hpp"

namespace duet::constitutive {

/// The Tresca hexagonal prism as a faceted surface (main plane sigma1 - sigma3 = 2 c_u).
FacetedSurface tresca_surface(double undrained_strength);

class Tresca final : public Model {
 public:
  /// undrained_strength: c_u, Pa (> 0).
  Tresca(ElasticParameters elastic, double undrained_strength);

  std::string_view name() const override { return "tresca"; }
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

  /// f = sigma1 - sigma3 - 2 c_u, Pa (<= 0 admissible).
  double yield_function(const Mat3& stress) const;
  /// Stress level for relative tolerances: |p| + sqrt(J2) + c_u, Pa.
  double stress_scale(const Mat3& stress) const;
  double undrained_strength() const { return undrained_strength_; }

 private:
  /// The body of integrate(): predictor, return, internal variables; gives back the return.
  StressReturn integrate_returning(const Mat3& d_strain, Mat3& stress,
                                   std::span<double> internal) const;
  void record_plastic_step(const Mat3& trial, const StressReturn& result,
                           std::span<double> internal) const;

  ElasticParameters elastic_;
  double undrained_strength_;  // c_u, Pa
  FacetedSurface surface_;
};

/// Storage order of the internal variables.
inline constexpr int tresca_plastic_strain = 0;  // accumulated equivalent plastic strain, -
inline constexpr int tresca_corrections = 1;     // number of plastic returns

void register_tresca(ModelRegistry& registry);

}  // namespace duet::constitutive
