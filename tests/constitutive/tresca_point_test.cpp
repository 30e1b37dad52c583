// Material-point paths for constitutive/tresca.cpp: plane-strain (eps_zz = 0) biaxial compression
// at constant lateral stress, plane-strain simple shear through the element-test driver, and
// axisymmetric compression (the edge sigma1 = sigma2). Undrained clay fails at
// sigma1 - sigma3 = 2 c_u on every path (the Tresca criterion; Zhang 2018, papers/004).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "constitutive/element_test.hpp"
#include "constitutive/tresca.hpp"
#include "tests/constitutive/held_stress_compression.hpp"

namespace duet::constitutive {
namespace {

constexpr double E = 10e6;  // Pa
constexpr double nu = 0.49;
constexpr double cu = 100e3;        // Pa (E / c_u = 100, the Zhang 2018 footing)
constexpr double lateral = -200e3;  // confining stress, Pa

std::unique_ptr<Model> make() {
  return make_model("tresca", {{"E", E}, {"nu", nu}, {"cu", cu}}, "material.clay");
}

struct PathEnd {
  Mat3 stress = Mat3::Zero();
  std::vector<double> deviator;  // sigma_xx - sigma_yy after each increment, Pa
  int max_newton_iterations = 0;
};

/// Compression along y from lateral * I; the components in `held` (0 and/or 2) are iterated
/// with Newton on the consistent tangent until their stress equals `lateral`, the others are
/// prescribed (zero strain).
PathEnd compress(const Model& model, double axial_strain, int n_increments,
                 const std::vector<int>& held) {
  PathEnd end;
  end.stress = lateral * Mat3::Identity();
  end.max_newton_iterations = compress_holding_lateral_stress(
      model, lateral, axial_strain, n_increments, held, [&end](const Mat3& stress, const Mat3&) {
        end.stress = stress;
        end.deviator.push_back(stress(0, 0) - stress(1, 1));
      });
  return end;
}

double principal_difference(const Mat3& stress) {
  const Vec3 s = spectral_decomposition(stress).values;
  return s(0) - s(2);
}

TEST(TrescaPoint, PlaneStrainBiaxialCompressionFailsAtTwiceUndrainedStrength) {
  // Arrange: eps_zz = 0, sigma_xx = lateral held, eps_yy to -3 % (yield near -1.5 %).
  const auto model = make();
  // Act
  const PathEnd end = compress(*model, -0.03, 300, {0});
  // Assert: sigma1 - sigma3 = 2 c_u at failure, reached and kept (perfect plasticity).
  EXPECT_NEAR(principal_difference(end.stress), 2.0 * cu, 1e-10 * 2.0 * cu);
  EXPECT_NEAR(end.deviator.back(), 2.0 * cu, 1e-10 * 2.0 * cu);
  EXPECT_LE(*std::max_element(end.deviator.begin(), end.deviator.end()), 2.0 * cu * (1.0 + 1e-10));
  // sigma_zz is the intermediate stress (the main plane, not an edge).
  EXPECT_LT(end.stress(2, 2), end.stress(0, 0) - 1e3);
  EXPECT_GT(end.stress(2, 2), end.stress(1, 1) + 1e3);
  // The consistent tangent makes the lateral Newton iteration converge in a few steps.
  EXPECT_LE(end.max_newton_iterations, 4);
}

TEST(TrescaPoint, PlaneStrainSimpleShearFailsAtShearStressEqualToUndrainedStrength) {
  // Arrange: the element driver's simple shear keeps eps_xx = eps_zz = 0 (plane strain) and holds
  // sigma_yy; gamma_xy to 5 % (yield at gamma = c_u / G = 3 %).
  const auto model = make();
  ElementTest test;
  test.kind = ElementTestKind::simple_shear;
  test.initial_stress = lateral;
  test.strain = 0.05;
  test.increments = 100;
  // Act
  const std::vector<ElementRow> rows = run_element_test(*model, test);
  // Assert: Mohr circle radius = tau_xy = c_u at failure (sigma_xx = sigma_yy throughout).
  const ElementRow& last = rows.back();
  EXPECT_NEAR(last.shear_stress, cu, 1e-10 * cu);
  Mat3 stress = Vec3(last.lateral_stress, last.axial_stress, last.out_of_plane_stress).asDiagonal();
  stress(0, 1) = stress(1, 0) = last.shear_stress;
  EXPECT_NEAR(principal_difference(stress), 2.0 * cu, 1e-10 * 2.0 * cu);
  // Before failure the response is elastic: tau = G gamma.
  const double G = E / (2.0 * (1.0 + nu));
  EXPECT_NEAR(rows[10].shear_stress, G * rows[10].shear_strain, 1e-9 * cu);
}

TEST(TrescaPoint, AxisymmetricCompressionFailsOnEdgeAtTwiceUndrainedStrength) {
  // Arrange: sigma_xx = sigma_zz = lateral held (sigma1 = sigma2: the left edge).
  const auto model = make();
  // Act
  const PathEnd end = compress(*model, -0.03, 300, {0, 2});
  // Assert
  EXPECT_NEAR(end.deviator.back(), 2.0 * cu, 1e-10 * 2.0 * cu);
  EXPECT_NEAR(principal_difference(end.stress), 2.0 * cu, 1e-10 * 2.0 * cu);
  EXPECT_NEAR(end.stress(2, 2), lateral, 1e-10 * std::abs(lateral));
}

}  // namespace
}  // namespace duet::constitutive
