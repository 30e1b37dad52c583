// Unit tests of common/tensor.hpp: invariants of stress states whose values are known in closed
// form (tension positive), and the Voigt conversions.

#include "common/tensor.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace duet {
namespace {

constexpr double pi = std::numbers::pi;

Mat3 diagonal(double xx, double yy, double zz) {
  return Vec3(xx, yy, zz).asDiagonal();
}

/// A rotation by `angle` about a unit `axis` (Rodrigues).
Mat3 rotation(const Vec3& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

TEST(TensorInvariants, MeanStressIsNegativeUnderCompression) {
  EXPECT_DOUBLE_EQ(mean_stress(diagonal(-100.0, -200.0, -300.0)), -200.0);
}

// lode_angle works from principal stresses (atan), which stays well conditioned at +-pi/6, where
// asin of the invariant ratio would lose half the digits (sqrt(2 eps) / 3 = 7e-9).
constexpr double lode_tolerance_at_meridian = 1e-14;

TEST(TensorInvariants, LodeAngleAgreesWithTheInvariantDefinitionAwayFromTheMeridians) {
  const Mat3 stress = rotation(Vec3(1.0, 2.0, 3.0), 0.7) * diagonal(-100.0, -250.0, -300.0) *
                      rotation(Vec3(1.0, 2.0, 3.0), 0.7).transpose();
  const double by_invariants =
      std::asin(-1.5 * std::sqrt(3.0) * j3(stress) / std::pow(j2(stress), 1.5)) / 3.0;
  EXPECT_NEAR(lode_angle(stress), by_invariants, 1e-12);
}

TEST(TensorInvariants, LodeAngleIsPlusPiOverSixInTriaxialCompression) {
  // Axial stress more compressive than the equal lateral stresses: sigma1 < sigma2 = sigma3 < 0.
  const Mat3 stress = diagonal(-100e3, -300e3, -100e3);
  EXPECT_NEAR(std::sin(3.0 * lode_angle(stress)), 1.0, 1e-14);
  EXPECT_NEAR(lode_angle(stress), pi / 6.0, lode_tolerance_at_meridian);
}

TEST(TensorInvariants, LodeAngleIsMinusPiOverSixInTriaxialExtension) {
  // Axial stress less compressive than the equal lateral stresses.
  const Mat3 stress = diagonal(-300e3, -100e3, -300e3);
  EXPECT_NEAR(std::sin(3.0 * lode_angle(stress)), -1.0, 1e-14);
  EXPECT_NEAR(lode_angle(stress), -pi / 6.0, lode_tolerance_at_meridian);
}

TEST(TensorInvariants, LodeAngleIsZeroInPureShear) {
  // Principal deviator (1, 0, -1): J3 = 0.
  const Mat3 stress = diagonal(-50e3, -100e3, -150e3);
  EXPECT_NEAR(lode_angle(stress), 0.0, 1e-12);
}

TEST(TensorInvariants, LodeAngleOfHydrostaticStateIsZero) {
  EXPECT_EQ(lode_angle(-1e5 * Mat3::Identity()), 0.0);
}

TEST(TensorInvariants, VonMisesStressOfUniaxialStressIsItsMagnitude) {
  // q = sqrt(3 J2) = |sigma| for uniaxial stress, whatever its sign and direction.
  const Mat3 tension = diagonal(0.0, 250e3, 0.0);
  const Mat3 compression = diagonal(0.0, 0.0, -80e3);
  EXPECT_NEAR(von_mises(tension), 250e3, 1e-9);
  EXPECT_NEAR(von_mises(compression), 80e3, 1e-9);
}

TEST(TensorInvariants, SecondInvariantOfSimpleShearIsShearSquared) {
  Mat3 stress = Mat3::Zero();
  stress(0, 1) = stress(1, 0) = 30e3;
  EXPECT_NEAR(j2(stress), 30e3 * 30e3, 1e-6);
  EXPECT_NEAR(j3(stress), 0.0, 1e-6);
}

TEST(TensorInvariants, ThirdInvariantOfTriaxialCompressionIsClosedForm) {
  // Deviator diag(d/3, -2d/3, d/3) with d = 200e3: J3 = det = -2 d^3 / 27.
  const double d = 200e3;
  EXPECT_NEAR(j3(diagonal(-100e3, -300e3, -100e3)), -2.0 * d * d * d / 27.0, 1e-12 * d * d * d);
}

TEST(TensorInvariants, InvariantsAreUnchangedByRotation) {
  // Arrange
  Mat3 stress;
  stress << -120e3, 15e3, -8e3, 15e3, -90e3, 5e3, -8e3, 5e3, -100e3;
  const Mat3 R = rotation(Vec3(1.0, -2.0, 0.5), 0.7);
  // Act
  const Mat3 rotated = R * stress * R.transpose();
  // Assert
  EXPECT_NEAR(mean_stress(rotated), mean_stress(stress), 1e-9);
  EXPECT_NEAR(j2(rotated), j2(stress), 1e-12 * j2(stress));
  EXPECT_NEAR(j3(rotated), j3(stress), 1e-10 * std::abs(j3(stress)));
  EXPECT_NEAR(lode_angle(rotated), lode_angle(stress), 1e-10);
}

TEST(TensorInvariants, DeviatorIsTraceFree) {
  Mat3 a;
  a << 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 10.0;
  EXPECT_NEAR(deviator(a).trace(), 0.0, 1e-14);
  EXPECT_DOUBLE_EQ(contract(a, Mat3::Identity()), a.trace());
  EXPECT_DOUBLE_EQ(norm(Mat3::Identity()), std::sqrt(3.0));
}

TEST(TensorVoigt, StrainRoundTripKeepsTensorAndDoublesShear) {
  // Arrange
  Mat3 strain;
  strain << 1e-3, 2e-4, -3e-4, 2e-4, -5e-4, 7e-4, -3e-4, 7e-4, 4e-4;
  // Act
  const Vec6 v = strain_to_voigt(strain);
  // Assert: order xx yy zz xy yz zx, engineering shear.
  EXPECT_DOUBLE_EQ(v(3), 2.0 * strain(0, 1));
  EXPECT_DOUBLE_EQ(v(4), 2.0 * strain(1, 2));
  EXPECT_DOUBLE_EQ(v(5), 2.0 * strain(2, 0));
  EXPECT_EQ(voigt_to_strain(v), strain);
}

TEST(TensorVoigt, StressRoundTripKeepsPlainComponents) {
  Mat3 stress;
  stress << -1e5, 2e4, -3e4, 2e4, -5e4, 7e4, -3e4, 7e4, 4e4;
  const Vec6 v = stress_to_voigt(stress);
  EXPECT_EQ(v(3), stress(0, 1));
  EXPECT_EQ(v(4), stress(1, 2));
  EXPECT_EQ(v(5), stress(2, 0));
  EXPECT_EQ(voigt_to_stress(v), stress);
}

TEST(TensorVoigt, StressDotEngineeringStrainIsWorkConjugate) {
  // sigma : eps = voigt(sigma) . voigt_eng(eps): the reason strains carry engineering shear.
  Mat3 stress, strain;
  stress << -1e5, 2e4, -3e4, 2e4, -5e4, 7e4, -3e4, 7e4, 4e4;
  strain << 1e-3, 2e-4, -3e-4, 2e-4, -5e-4, 7e-4, -3e-4, 7e-4, 4e-4;
  EXPECT_NEAR(stress_to_voigt(stress).dot(strain_to_voigt(strain)), contract(stress, strain),
              1e-12);
}

}  // namespace
}  // namespace duet
