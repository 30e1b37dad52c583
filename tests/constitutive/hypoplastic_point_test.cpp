// One material point of the hypoplastic model (constitutive/hypoplastic.cpp) driven through the
// element tests of Peng 2015: the oedometer of sec 5.1 (K0 of eq 38, unloading) and a drained
// triaxial compression to the failure state the calibration (eqs 17-18) builds in.
// Axes as in constitutive/element_test.hpp: axial = y, lateral = x and z.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "constitutive/hypoplastic.hpp"

namespace duet::constitutive {
namespace {

// Peng 2015 Table 1, oedometer row (c1..c4 as published).
const HypoplasticConstants kOedometerRow{-58.3, -178.5, -589.0, -182.7};

// Peng 2015 eq 38 solved here, independently of the library: the root in (0, 1) of
// (6 c1 + 2 c4) K0^2 + (3 c1 - c4) K0 - c4 = 0.
double k0_of_eq38(const HypoplasticConstants& c) {
  const double a = 6.0 * c.c1 + 2.0 * c.c4, b = 3.0 * c.c1 - c.c4, constant = -c.c4;
  const double root = std::sqrt(b * b - 4.0 * a * constant);
  const double k_plus = (-b + root) / (2.0 * a), k_minus = (-b - root) / (2.0 * a);
  return (k_plus > 0.0 && k_plus < 1.0) ? k_plus : k_minus;
}

Mat3 axial_increment(double d_axial) {
  Mat3 d = Mat3::Zero();
  d(1, 1) = d_axial;
  return d;
}

double lateral_ratio(const Mat3& stress) {
  return stress(0, 0) / stress(1, 1);
}

TEST(HypoplasticOedometer, Eq38WithTable1GivesPengsK0) {
  EXPECT_NEAR(k0_of_eq38(kOedometerRow), 0.5109, 1e-4);
}

TEST(HypoplasticOedometer, LoadingFromIsotropicStressTendsToK0OfEq38) {
  // Arrange: -100 kPa isotropic, lateral strains zero, 4 % axial compression in 4000 increments.
  // Eq 15 is homogeneous of degree one in stress, so the ratio path does not depend on the start
  // level (the stress itself grows exponentially with the strain).
  const Hypoplastic model({kOedometerRow, 0.0});
  Mat3 stress = -100e3 * Mat3::Identity();
  std::vector<double> internal{0.0};
  // Act
  for (int k = 0; k < 2000; ++k) model.integrate(axial_increment(-1e-5), stress, internal);
  const double halfway = lateral_ratio(stress);
  for (int k = 0; k < 2000; ++k) model.integrate(axial_increment(-1e-5), stress, internal);
  // Assert: converging towards eq 38; plane strain keeps sigma_zz = sigma_xx by symmetry
  EXPECT_LT(std::abs(lateral_ratio(stress) - 0.5109), std::abs(halfway - 0.5109));
  EXPECT_NEAR(lateral_ratio(stress), 0.5109, 1e-3);
  EXPECT_NEAR(lateral_ratio(stress), k0_of_eq38(kOedometerRow), 1e-3);
  EXPECT_NEAR(stress(2, 2), stress(0, 0), 1e-9 * std::abs(stress(0, 0)));
  EXPECT_LT(stress(1, 1), -10 * 100e3);  // compressed well beyond the start
  EXPECT_EQ(internal[0], 0.0);
}

TEST(HypoplasticOedometer, UnloadingRaisesK0) {
  // Arrange: load to K0 as above, then reverse the axial strain in small steps
  const Hypoplastic model({kOedometerRow, 0.0});
  Mat3 stress = -100e3 * Mat3::Identity();
  std::vector<double> internal{0.0};
  for (int k = 0; k < 4000; ++k) model.integrate(axial_increment(-1e-5), stress, internal);
  const double k_loading = lateral_ratio(stress);
  const double axial_loaded = stress(1, 1);
  // Act: unload until the axial stress has dropped to a quarter
  std::vector<double> ratios{k_loading};
  int steps = 0;
  while (stress(1, 1) < 0.25 * axial_loaded && steps < 100000) {
    model.integrate(axial_increment(1e-6), stress, internal);
    if (++steps % 100 == 0) ratios.push_back(lateral_ratio(stress));
  }
  // Assert: K rises monotonically, the axial stress falls faster than the lateral (Peng sec 5.1)
  ASSERT_GE(stress(1, 1), 0.25 * axial_loaded);
  for (std::size_t i = 1; i < ratios.size(); ++i) EXPECT_GT(ratios[i], ratios[i - 1]) << i;
  EXPECT_GT(lateral_ratio(stress), k_loading + 0.1);
  EXPECT_EQ(internal[0], 0.0);
}

// Drained triaxial compression: sigma_xx = sigma_zz held at sigma_3 by Newton on the lateral
// strain increment with the model's tangent (dsigma_xx/deps_xx + dsigma_xx/deps_zz).
struct TriaxialEnd {
  Mat3 stress;
  double dilatancy;  // -deps_v/deps_1 over the last increment
};

TriaxialEnd drained_triaxial(const Hypoplastic& model, double sigma3, double d_axial, int n) {
  Mat3 stress = sigma3 * Mat3::Identity();
  std::vector<double> internal{0.0};
  double lateral = 0.0, dilatancy = 0.0;
  for (int k = 0; k < n; ++k) {
    Mat3 trial;
    for (int it = 0; it < 20; ++it) {
      Mat3 d = Mat3::Zero();
      d.diagonal() << lateral, d_axial, lateral;
      trial = stress;
      model.integrate(d, trial, internal);
      const double residual = trial(0, 0) - sigma3;
      if (std::abs(residual) < 1e-10 * std::abs(sigma3)) break;
      const Mat6 t = model.tangent(d, stress, internal);
      lateral -= residual / (t(0, 0) + t(0, 2));
    }
    stress = trial;
    dilatancy = -(2.0 * lateral + d_axial) / d_axial;
  }
  return {stress, dilatancy};
}

TEST(HypoplasticTriaxial, DrainedCompressionReachesTheFailureRatioAndDilatancyOfTable1) {
  // Arrange: Table 1 sand-collapse row from its material constants (phi 30, psi 1 deg)
  Parameters parameters("material.sand", {{"Ei", 20e6}, {"nu", 0.2}, {"phi", 30.0}, {"psi", 1.0}});
  const Hypoplastic model(HypoplasticParameters::read(parameters));
  // Act: 20 % axial strain in 1e-4 increments at sigma_3 = -100 kPa
  const TriaxialEnd end = drained_triaxial(model, -100e3, -1e-4, 2000);
  // Assert: eq 17, R_f = (1 + sin 30)/(1 - sin 30) = 3; eq 18, -deps_v/deps_1 = tan psi
  EXPECT_NEAR(end.stress(1, 1) / end.stress(0, 0), 3.0, 1e-6);
  EXPECT_NEAR(end.stress(2, 2), -100e3, 1e-3);
  EXPECT_NEAR(end.dilatancy, std::tan(1.0 * std::numbers::pi / 180.0), 1e-6);
}

}  // namespace
}  // namespace duet::constitutive
