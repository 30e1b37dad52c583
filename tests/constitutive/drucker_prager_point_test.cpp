// Material-point element paths for constitutive/drucker_prager.cpp: drained triaxial compression
// and plane-strain compression at constant lateral stress, driven by strain increments with the
// held stresses found by Newton iteration on the consistent tangent. Peak strengths are checked
// against the closed forms derived in constitutive/docs/drucker_prager.md.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "constitutive/drucker_prager.hpp"
#include "tests/constitutive/held_stress_compression.hpp"

namespace duet::constitutive {
namespace {

constexpr double E = 20e6;  // Pa
constexpr double nu = 0.3;
constexpr double phi = 30.0;       // deg
constexpr double c = 10e3;         // Pa
constexpr double sigma3 = -100e3;  // lateral (confining) stress, Pa
constexpr double degree = std::numbers::pi / 180.0;

std::unique_ptr<Model> make(double psi) {
  return make_model("drucker-prager", {{"E", E}, {"nu", nu}, {"phi", phi}, {"psi", psi}, {"c", c}},
                    "material.soil");
}

struct PathEnd {
  Mat3 stress = Mat3::Zero();
  Mat3 strain = Mat3::Zero();
  Mat3 last_d_strain = Mat3::Zero();
  double peak_deviator = 0.0;  // largest sigma_xx - sigma_yy met on the path, Pa
  int max_newton_iterations = 0;
};

/// Compression along y (axial) from sigma3 I. The lateral components in `held` (indices 0 and/or
/// 2) are iterated with Newton on the consistent tangent until their stress equals sigma3; the
/// others are prescribed (zero).
PathEnd compress(const Model& model, double axial_strain, int n_increments,
                 const std::vector<int>& held) {
  PathEnd end;
  end.stress = sigma3 * Mat3::Identity();
  end.max_newton_iterations = compress_holding_lateral_stress(
      model, sigma3, axial_strain, n_increments, held,
      [&end](const Mat3& stress, const Mat3& d_strain) {
        end.stress = stress;
        end.last_d_strain = d_strain;
        end.strain += d_strain;
        end.peak_deviator = std::max(end.peak_deviator, stress(0, 0) - stress(1, 1));
      });
  return end;
}

PathEnd drained_triaxial(const Model& model, double axial_strain, int n_increments) {
  return compress(model, axial_strain, n_increments, {0, 2});  // sigma_xx = sigma_zz = sigma3
}

PathEnd plane_strain(const Model& model, double axial_strain, int n_increments) {
  return compress(model, axial_strain, n_increments, {0});  // eps_zz = 0, sigma_xx = sigma3
}

/// Docs eq (T): peak q = sigma3 - sigma1 of the cone in axisymmetric compression.
double triaxial_peak(const DruckerPragerCone& cone) {
  return (cone.k_c - 3.0 * cone.alpha_phi * sigma3) / (1.0 / std::sqrt(3.0) - cone.alpha_phi);
}

/// Docs eq (P): peak t = (sigma3 - sigma1)/2 in plane strain for any psi <= phi.
double plane_strain_peak(const DruckerPragerCone& cone) {
  const double a = cone.alpha_phi, b = cone.alpha_psi;
  const double R = std::sqrt(1.0 - 3.0 * b * b) / (1.0 - 3.0 * a * b);
  return R * (cone.k_c - 3.0 * a * sigma3) / (1.0 - 3.0 * a * R);
}

TEST(DruckerPragerPoint, DrainedTriaxialPeakEqualsConeClosedForm) {
  for (const double psi : {0.0, 10.0, phi}) {
    // Arrange
    const auto model = make(psi);
    const auto cone = DruckerPragerCone::from_coulomb(phi, psi, c);
    // Act
    const PathEnd end = drained_triaxial(*model, -0.05, 500);
    // Assert
    const double expected = triaxial_peak(cone);  // 135081 Pa for phi = 30, c = 10 kPa
    EXPECT_NEAR(end.stress(0, 0) - end.stress(1, 1), expected, 1e-10 * expected) << psi;
    EXPECT_LE(end.peak_deviator, expected * (1.0 + 1e-10)) << psi;  // no overshoot
    EXPECT_NEAR(end.stress(0, 0), sigma3, 1e-11 * std::abs(sigma3));
    EXPECT_NEAR(end.stress(2, 2), sigma3, 1e-11 * std::abs(sigma3));
    EXPECT_LE(end.max_newton_iterations, 4) << psi;  // consistent tangent: quadratic Newton
  }
}

TEST(DruckerPragerPoint, DrainedTriaxialDilatancyAtPeakFollowsFlowRule) {
  // At the peak every increment is plastic: d eps_v / d eps_axial = 3 alpha_psi /
  // (alpha_psi - 1/sqrt(3)) (Bui 2008 eqs 4, 7 with s_yy / (2 sqrt J2) = -1/sqrt(3)).
  for (const double psi : {0.0, 10.0, phi}) {
    const auto model = make(psi);
    const double b = DruckerPragerCone::from_coulomb(phi, psi, c).alpha_psi;
    const PathEnd end = drained_triaxial(*model, -0.05, 500);
    const double ratio = end.last_d_strain.trace() / end.last_d_strain(1, 1);
    EXPECT_NEAR(ratio, 3.0 * b / (b - 1.0 / std::sqrt(3.0)), 1e-8) << psi;
  }
}

TEST(DruckerPragerPoint, PlaneStrainPeakEqualsMohrCoulombForAssociatedFlow) {
  // Arrange
  const auto model = make(phi);
  // Act
  const PathEnd end = plane_strain(*model, -0.3, 3000);
  // Assert: t = (c cos phi - sigma3 sin phi) / (1 - sin phi) = 117321 Pa (Mohr-Coulomb).
  const double t_mohr_coulomb = (c * std::cos(phi * degree) - sigma3 * std::sin(phi * degree)) /
                                (1.0 - std::sin(phi * degree));
  const double t = 0.5 * (end.stress(0, 0) - end.stress(1, 1));
  EXPECT_NEAR(t, t_mohr_coulomb, 1e-9 * t_mohr_coulomb);
  EXPECT_NEAR(end.stress(0, 0), sigma3, 1e-11 * std::abs(sigma3));
  EXPECT_EQ(end.strain(2, 2), 0.0);
}

TEST(DruckerPragerPoint, PlaneStrainPeakEqualsClosedFormForNonAssociatedFlow) {
  for (const double psi : {0.0, 10.0}) {
    // Arrange
    const auto model = make(psi);
    const auto cone = DruckerPragerCone::from_coulomb(phi, psi, c);
    // Act
    const PathEnd end = plane_strain(*model, -0.3, 3000);
    // Assert: peak (docs eq P) and the out-of-plane stress sigma_zz = s_m - 3 alpha_psi sqrt(J2)
    // that makes the plastic eps_zz vanish.
    const double expected = plane_strain_peak(cone);
    const double t = 0.5 * (end.stress(0, 0) - end.stress(1, 1));
    EXPECT_NEAR(t, expected, 1e-9 * expected) << psi;
    const double s_m = 0.5 * (end.stress(0, 0) + end.stress(1, 1));
    const double sigma_zz = s_m - 3.0 * cone.alpha_psi * std::sqrt(j2(end.stress));
    EXPECT_NEAR(end.stress(2, 2), sigma_zz, 1e-9 * std::abs(sigma_zz)) << psi;
  }
}

TEST(DruckerPragerPoint, PlaneStrainNonDilatantPeakIsBelowMohrCoulomb) {
  // The Bui fit matches Mohr-Coulomb only with psi = phi; with psi = 0 the plane-strain peak is
  // lower (docs: 3 / sqrt(9 + 12 tan^2 phi) < cos phi). Measured on the path, not the formula.
  const PathEnd associated = plane_strain(*make(phi), -0.3, 3000);
  const PathEnd non_dilatant = plane_strain(*make(0.0), -0.3, 3000);
  const double t_a = associated.stress(0, 0) - associated.stress(1, 1);
  const double t_0 = non_dilatant.stress(0, 0) - non_dilatant.stress(1, 1);
  EXPECT_LT(t_0, 0.95 * t_a);
}

}  // namespace
}  // namespace duet::constitutive
