// The Hughes-Winget rotation increment of the objective update (constitutive/objective.hpp).
#include "constitutive/objective.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace duet::constitutive {
namespace {

Mat3 skew_from_axial(double x, double y, double z) {
  Mat3 w;
  w << 0.0, -z, y, z, 0.0, -x, -y, x, 0.0;
  return w;
}

TEST(RotationIncrement, EqualsTheCayleyTransformOfAGeneralSpin) {
  // Arrange: a 3D spin increment with all three components, not small.
  const Mat3 d_spin = skew_from_axial(0.3, -0.7, 1.1);
  const Mat3 I = Mat3::Identity();
  const Mat3 cayley = (I - 0.5 * d_spin).inverse() * (I + 0.5 * d_spin);
  // Act
  const Mat3 R = rotation_increment(d_spin);
  // Assert
  EXPECT_LT((R - cayley).norm(), 1e-14);
  EXPECT_LT((R * R.transpose() - I).norm(), 1e-14);
  EXPECT_NEAR(R.determinant(), 1.0, 1e-14);
}

TEST(RotationIncrement, TurnsAPlaneSpinByTheHalfAngleTangentRule) {
  // Arrange: in-plane spin w dt; the Cayley rotation angle theta obeys tan(theta / 2) = w dt / 2.
  const double w_dt = 0.2;
  const Mat3 d_spin = skew_from_axial(0.0, 0.0, w_dt);
  // Act
  const Mat3 R = rotation_increment(d_spin);
  // Assert
  const double theta = 2.0 * std::atan(0.5 * w_dt);
  EXPECT_NEAR(R(0, 0), std::cos(theta), 1e-15);
  EXPECT_NEAR(R(1, 0), std::sin(theta), 1e-15);
  EXPECT_NEAR(R(2, 2), 1.0, 1e-15);
}

}  // namespace
}  // namespace duet::constitutive
