// Unit tests of constitutive/linear_elastic.cpp: zero increment, the uniaxial-strain (oedometric)
// closed form, the tangent against finite differences, integrate_with_tangent against integrate
// and tangent, and parameter refusal.

#include "constitutive/linear_elastic.hpp"

#include <gtest/gtest.h>

#include <string>

#include "common/input_error.hpp"
#include "tests/constitutive/refusal.hpp"
#include "tests/constitutive/same_return.hpp"

namespace duet::constitutive {
namespace {

constexpr double E = 10e6;  // Pa
constexpr double nu = 0.3;

std::unique_ptr<Model> make() {
  return make_model("linear-elastic", {{"E", E}, {"nu", nu}}, "material.block");
}

TEST(LinearElastic, ZeroStrainIncrementLeavesStressUnchanged) {
  // Arrange
  const auto model = make();
  Mat3 stress;
  stress << -1e5, 2e4, 0.0, 2e4, -5e4, 1e3, 0.0, 1e3, -7e4;
  const Mat3 before = stress;
  // Act
  model->integrate(Mat3::Zero(), stress, {});
  // Assert
  EXPECT_EQ(stress, before);
}

TEST(LinearElastic, UniaxialStrainGivesConstrainedModulusAndK0) {
  // Arrange: eps_yy only (oedometer). Closed form: sigma_yy = E (1 - nu) / ((1 + nu)(1 - 2 nu))
  // eps_yy, sigma_xx = sigma_zz = nu / (1 - nu) sigma_yy.
  const auto model = make();
  Mat3 stress = Mat3::Zero();
  Mat3 d_strain = Mat3::Zero();
  d_strain(1, 1) = -1e-3;
  // Act
  model->integrate(d_strain, stress, {});
  // Assert
  const double constrained = E * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
  EXPECT_NEAR(stress(1, 1), -1e-3 * constrained, 1e-9 * constrained * 1e-3);
  EXPECT_NEAR(stress(0, 0), nu / (1.0 - nu) * stress(1, 1), 1e-12 * std::abs(stress(1, 1)));
  EXPECT_NEAR(stress(2, 2), stress(0, 0), 1e-12 * std::abs(stress(1, 1)));
  EXPECT_EQ(stress(0, 1), 0.0);
}

TEST(LinearElastic, UniaxialStressGivesYoungsModulusAndPoissonContraction) {
  // Strain (eps, -nu eps, -nu eps) is the uniaxial stress state sigma_xx = E eps.
  const auto model = make();
  Mat3 stress = Mat3::Zero();
  const Mat3 d_strain = Vec3(1e-3, -nu * 1e-3, -nu * 1e-3).asDiagonal();
  model->integrate(d_strain, stress, {});
  EXPECT_NEAR(stress(0, 0), E * 1e-3, 1e-9 * E * 1e-3);
  EXPECT_NEAR(stress(1, 1), 0.0, 1e-9 * E * 1e-3);
  EXPECT_NEAR(stress(2, 2), 0.0, 1e-9 * E * 1e-3);
}

TEST(LinearElastic, SimpleShearGivesShearModulus) {
  const auto model = make();
  Mat3 stress = Mat3::Zero();
  Mat3 d_strain = Mat3::Zero();
  d_strain(0, 1) = d_strain(1, 0) = 0.5e-3;  // engineering gamma = 1e-3
  model->integrate(d_strain, stress, {});
  EXPECT_NEAR(stress(0, 1), E / (2.0 * (1.0 + nu)) * 1e-3, 1e-6);
}

TEST(LinearElastic, TangentEqualsFiniteDifference) {
  // Arrange
  const auto model = make();
  Mat3 stress;
  stress << -1e5, 2e4, 0.0, 2e4, -5e4, 1e3, 0.0, 1e3, -7e4;
  Mat3 d_strain;
  d_strain << 1e-4, 2e-5, -3e-5, 2e-5, -2e-4, 1e-5, -3e-5, 1e-5, 5e-5;
  // Act
  const Mat6 analytic = model->tangent(d_strain, stress, {});
  const Mat6 numeric = finite_difference_tangent(*model, d_strain, stress, {});
  // Assert
  EXPECT_LT((analytic - numeric).norm(), 1e-6 * analytic.norm());
}

TEST(LinearElastic, IntegrateWithTangentMatchesSeparateCalls) {
  const auto model = make();
  Mat3 stress;
  stress << -1e5, 2e4, 0.0, 2e4, -5e4, 1e3, 0.0, 1e3, -7e4;
  Mat3 d_strain;
  d_strain << 1e-4, 2e-5, -3e-5, 2e-5, -2e-4, 1e-5, -3e-5, 1e-5, 5e-5;
  expect_integrate_with_tangent_matches(*model, d_strain, stress, {});
}

TEST(LinearElastic, RateEqualsIncrementPerUnitTime) {
  const auto model = make();
  Mat3 stretching;
  stretching << 1e-4, 2e-5, -3e-5, 2e-5, -2e-4, 1e-5, -3e-5, 1e-5, 5e-5;
  Mat3 stress = Mat3::Zero();
  model->integrate(stretching, stress, {});
  EXPECT_LT((model->objective_rate(stretching, Mat3::Zero(), {}) - stress).norm(),
            1e-12 * stress.norm());
}

TEST(LinearElastic, ModuliAreBulkAndShear) {
  const auto moduli = make()->moduli(Mat3::Zero(), {});
  EXPECT_DOUBLE_EQ(moduli.bulk, E / (3.0 * (1.0 - 2.0 * nu)));
  EXPECT_DOUBLE_EQ(moduli.shear, E / (2.0 * (1.0 + nu)));
}

TEST(LinearElastic, IncompressiblePoissonRatioIsRefusedWithKeyAndRange) {
  expect_model_refused("linear-elastic", {{"E", E}, {"nu", 0.5}}, "material.block",
                       {"material.block.nu = 0.5", "[0, 0.5)"});
}

TEST(LinearElastic, NonPositiveYoungsModulusIsRefused) {
  EXPECT_THROW(make_model("linear-elastic", {{"E", 0.0}, {"nu", nu}}, "material.block"),
               InputError);
}

}  // namespace
}  // namespace duet::constitutive
