#pragma once
// Isotropic linear elasticity (Hooke), for verification cases: sigma_dot = lambda tr(D) I + 2 G D.

#include "constitutive/model.hpp"
#include "constitutive/registry.hpp"

namespace duet::constitutive {

struct ElasticParameters {
  double youngs_modulus = 0.0;  // E, Pa
  double poisson_ratio = 0.0;   // nu, -

  double shear_modulus() const { return youngs_modulus / (2.0 * (1.0 + poisson_ratio)); }
  double bulk_modulus() const { return youngs_modulus / (3.0 * (1.0 - 2.0 * poisson_ratio)); }
  double lame_lambda() const { return bulk_modulus() - 2.0 / 3.0 * shear_modulus(); }

  /// Reads E (Pa, > 0) and nu ([0, 0.5)).
  static ElasticParameters read(Parameters& parameters);
};

/// Elastic stress increment lambda tr(de) I + 2 G de.
Mat3 elastic_increment(const ElasticParameters& elastic, const Mat3& d_strain);

/// Isotropic elastic stiffness in Voigt form (engineering shear).
Mat6 elastic_stiffness(const ElasticParameters& elastic);

class LinearElastic final : public Model {
 public:
  explicit LinearElastic(ElasticParameters elastic) : elastic_(elastic) {}

  std::string_view name() const override { return "linear-elastic"; }
  void integrate(const Mat3& d_strain, Mat3& stress, std::span<double> internal) const override;
  Mat3 objective_rate(const Mat3& stretching, const Mat3& stress,
                      std::span<const double> internal) const override;
  Mat6 tangent(const Mat3& d_strain, const Mat3& stress,
               std::span<const double> internal) const override;
  void integrate_with_tangent(const Mat3& d_strain, Mat3& stress, std::span<double> internal,
                              Mat6& tangent) const override;
  ElasticModuli moduli(const Mat3& stress, std::span<const double> internal) const override;

 private:
  ElasticParameters elastic_;
};

void register_linear_elastic(ModelRegistry& registry);

}  // namespace duet::constitutive
