#include "constitutive/linear_elastic.hpp"

namespace duet::constitutive {

ElasticParameters ElasticParameters::read(Parameters& parameters) {
  ElasticParameters e;
  e.youngs_modulus = parameters.require("E", Range::positive(), "Pa", "Young's modulus");
  e.poisson_ratio = parameters.require("nu", Range::closed_open(0.0, 0.5), "-", "Poisson's ratio");
  return e;
}

Mat3 elastic_increment(const ElasticParameters& elastic, const Mat3& d_strain) {
  return elastic.lame_lambda() * d_strain.trace() * Mat3::Identity() +
         2.0 * elastic.shear_modulus() * d_strain;
}

Mat6 elastic_stiffness(const ElasticParameters& elastic) {
  const double G = elastic.shear_modulus();
  const double lambda = elastic.lame_lambda();
  Mat6 C = Mat6::Zero();
  C.topLeftCorner<3, 3>().setConstant(lambda);
  C.topLeftCorner<3, 3>().diagonal().array() += 2.0 * G;
  C.bottomRightCorner<3, 3>().diagonal().setConstant(G);
  return C;
}

void LinearElastic::integrate(const Mat3& d_strain, Mat3& stress, std::span<double>) const {
  stress += elastic_increment(elastic_, d_strain);
}

Mat3 LinearElastic::objective_rate(const Mat3& stretching, const Mat3&,
                                   std::span<const double>) const {
  return elastic_increment(elastic_, stretching);
}

Mat6 LinearElastic::tangent(const Mat3&, const Mat3&, std::span<const double>) const {
  return elastic_stiffness(elastic_);
}

void LinearElastic::integrate_with_tangent(const Mat3& d_strain, Mat3& stress,
                                           std::span<double> internal, Mat6& tangent) const {
  tangent = elastic_stiffness(elastic_);
  integrate(d_strain, stress, internal);
}

ElasticModuli LinearElastic::moduli(const Mat3&, std::span<const double>) const {
  return {elastic_.bulk_modulus(), elastic_.shear_modulus()};
}

void register_linear_elastic(ModelRegistry& registry) {
  registry.add({"linear-elastic",
                "isotropic linear elasticity (E, nu)",
                [](Parameters& p) -> std::unique_ptr<Model> {
                  return std::make_unique<LinearElastic>(ElasticParameters::read(p));
                },
                {{"E", 10e6}, {"nu", 0.3}},
                {},
                /*softens=*/false});
}

}  // namespace duet::constitutive
