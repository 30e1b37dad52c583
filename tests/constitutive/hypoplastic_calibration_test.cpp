// Tests of the hypoplastic calibration (constitutive/hypoplastic_calibration.cpp): c1..c4 from
// (E_i, nu_i, phi, psi) at sigma_3 = -100 kPa against Peng 2015 Table 1, and the two triaxial
// states the derivation imposes, checked on the rate of eq 15 itself.
#include "constitutive/hypoplastic_calibration.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "constitutive/hypoplastic.hpp"

namespace duet::constitutive {
namespace {

struct TableRow {
  const char* test;
  TriaxialProperties triaxial;
  HypoplasticConstants published;
};

// Peng 2015 Table 1 (E_i in Pa, angles in degrees; sigma_3 = -100 kPa as stated in sec 3.2).
const TableRow kTable1[] = {
    {"oedometer", {21e6, 0.2, 29.5, 1.0}, {-58.3, -178.5, -589.0, -182.7}},
    {"sand collapse", {20e6, 0.2, 30.0, 1.0}, {-55.6, -171.2, -540.9, -170.9}},
    {"slope stability", {30e6, 0.2, 30.0, 0.0}, {-83.3, -264.9, -781.3, -255.2}},
};

TEST(HypoplasticCalibration, ReproducesAllThreeRowsOfPengTable1) {
  for (const TableRow& row : kTable1) {
    // Act
    const HypoplasticConstants c = calibrate_hypoplastic(row.triaxial);
    // Assert: Table 1 prints one decimal
    EXPECT_NEAR(c.c1, row.published.c1, 0.1) << row.test;
    EXPECT_NEAR(c.c2, row.published.c2, 0.1) << row.test;
    EXPECT_NEAR(c.c3, row.published.c3, 0.1) << row.test;
    EXPECT_NEAR(c.c4, row.published.c4, 0.1) << row.test;
  }
}

TEST(HypoplasticCalibration, FailureStressRatioOfThirtyDegreesIsThree) {
  // Peng 2015 eq 17: (1 + 1/2)/(1 - 1/2) = 3
  EXPECT_NEAR(failure_stress_ratio(30.0), 3.0, 1e-12);
}

TEST(HypoplasticCalibration, ZeroDilatancyMeansIsochoricFailure) {
  // Peng 2015 eq 18: nu_f = 1/2, deps_v = deps_1 (1 - 2 nu_f) = 0
  EXPECT_NEAR(failure_poisson_ratio(0.0), 0.5, 1e-15);
  EXPECT_NEAR(failure_poisson_ratio(45.0), 1.0, 1e-12);
}

TEST(HypoplasticCalibration, InitialStateGivesTheTangentModulusAndPoissonRatio) {
  // Arrange: a row with dilatancy and a non-default stress level
  TriaxialProperties triaxial{35e6, 0.3, 34.0, 6.0, -250e3};
  const HypoplasticConstants c = calibrate_hypoplastic(triaxial);
  Mat3 d = Mat3::Zero();
  d.diagonal() << -1.0, triaxial.initial_poisson_ratio, triaxial.initial_poisson_ratio;
  // Act: eq 15 at sigma = sigma_3 I
  const Mat3 rate = hypoplastic_rate(c, triaxial.confining_stress * Mat3::Identity(), d);
  // Assert: the cell pressure is held, the deviator stiffness is E_i
  EXPECT_NEAR(rate(1, 1) / triaxial.initial_modulus, 0.0, 1e-12);
  EXPECT_NEAR((rate(0, 0) - rate(1, 1)) / d(0, 0), triaxial.initial_modulus,
              1e-9 * triaxial.initial_modulus);
}

TEST(HypoplasticCalibration, FailureStateIsStationaryAtTheDilatancyOfEq18) {
  // Arrange
  TriaxialProperties triaxial{35e6, 0.3, 34.0, 6.0, -250e3};
  const HypoplasticConstants c = calibrate_hypoplastic(triaxial);
  const double R_f = failure_stress_ratio(triaxial.friction_angle);
  const double nu_f = failure_poisson_ratio(triaxial.dilatancy_angle);
  Mat3 sigma = Mat3::Zero();
  sigma.diagonal() << R_f, 1.0, 1.0;
  sigma *= triaxial.confining_stress;
  Mat3 d = Mat3::Zero();
  d.diagonal() << -1.0, nu_f, nu_f;
  // Act
  const Mat3 rate = hypoplastic_rate(c, sigma, d);
  // Assert: zero stress rate under continued straining, relative to the stress level
  EXPECT_LT(rate.norm(), 1e-10 * std::abs(c.c1) * sigma.norm());
}

TEST(HypoplasticCalibration, StressLevelScalesOnlyC1) {
  // Arrange: eq 15 is homogeneous of degree one in stress, so only the E_i condition sees sigma_3
  TriaxialProperties at100{20e6, 0.2, 30.0, 1.0, -100e3};
  TriaxialProperties at200 = at100;
  at200.confining_stress = -200e3;
  at200.initial_modulus = 40e6;
  // Act
  const HypoplasticConstants a = calibrate_hypoplastic(at100);
  const HypoplasticConstants b = calibrate_hypoplastic(at200);
  // Assert
  EXPECT_NEAR(a.c1, b.c1, 1e-9);
  EXPECT_NEAR(a.c2, b.c2, 1e-9);
  EXPECT_NEAR(a.c3, b.c3, 1e-9);
  EXPECT_NEAR(a.c4, b.c4, 1e-9);
}

TEST(HypoplasticCalibration, OedometerK0OfTable1IsPengsValue) {
  // Peng 2015 sec 5.1: eq 38 with the oedometer row gives K0 = 0.5109
  EXPECT_NEAR(oedometer_k0(kTable1[0].published), 0.5109, 1e-4);
}

}  // namespace
}  // namespace duet::constitutive
