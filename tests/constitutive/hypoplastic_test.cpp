// Tests of the Wang/Wu hypoplastic model (constitutive/hypoplastic.cpp): the rate of Peng 2015
// eq 15/25, its sub-stepped integration, objectivity, the tangent, the apex return and the
// parameter checks. Table 1 and the calibration: hypoplastic_calibration_test.cpp; the oedometer
// K0 (eq 38): hypoplastic_point_test.cpp.
#include "constitutive/hypoplastic.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "common/input_error.hpp"
#include "constitutive/objective.hpp"
#include "tests/constitutive/same_return.hpp"

namespace duet::constitutive {
namespace {

// Peng 2015 Table 1, oedometer row.
HypoplasticParameters oedometer_row(double cohesion = 0.0) {
  return {{-58.3, -178.5, -589.0, -182.7}, cohesion};
}

Mat3 anisotropic_stress() {
  Mat3 s;
  s << -120e3, 8e3, -3e3, 8e3, -80e3, 5e3, -3e3, 5e3, -60e3;
  return s;
}

double relative(double a, double b) {
  return std::abs(a - b) / std::max(std::abs(b), 1e-300);
}

std::string message_of(const std::map<std::string, ParameterValue>& values) {
  try {
    Parameters parameters("material.sand", values);
    HypoplasticParameters::read(parameters);
    parameters.finish();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Hypoplastic, ZeroStrainIncrementLeavesStressUnchanged) {
  // Arrange
  const Hypoplastic model(oedometer_row());
  const Mat3 start = anisotropic_stress();
  Mat3 stress = start;
  std::vector<double> internal{0.0};
  // Act
  model.integrate(Mat3::Zero(), stress, internal);
  // Assert
  EXPECT_EQ((stress - start).norm(), 0.0);
  EXPECT_EQ(internal[0], 0.0);
}

TEST(Hypoplastic, RigidRotationKeepsPQAndLodeAngle) {
  // Arrange: 1000 steps of 1e-3 rad spin about an oblique axis, zero stretching
  const Hypoplastic model(oedometer_row());
  Mat3 stress = anisotropic_stress();
  const double p0 = mean_stress(stress), q0 = von_mises(stress), theta0 = lode_angle(stress);
  Vec3 axis(1.0, 2.0, 3.0);
  axis = 1e-3 * axis.normalized();
  Mat3 d_spin;
  d_spin << 0, -axis(2), axis(1), axis(2), 0, -axis(0), -axis(1), axis(0), 0;
  std::vector<double> internal{0.0};
  // Act
  for (int k = 0; k < 1000; ++k) update_stress(model, Mat3::Zero(), d_spin, stress, internal);
  // Assert: the stress did turn, its invariants did not
  EXPECT_GT((stress - anisotropic_stress()).norm(), 1e3);
  EXPECT_LT(relative(mean_stress(stress), p0), 1e-10);
  EXPECT_LT(relative(von_mises(stress), q0), 1e-10);
  EXPECT_LT(relative(lode_angle(stress), theta0), 1e-10);
}

TEST(Hypoplastic, CompressionInARotatingFrameGivesTheSameInvariantsAsWithoutRotation) {
  // Arrange: the same material strain increment, once fixed, once carried by a rigid spin
  // (frame indifference of eq 15: H(Q eta Q^T, Q D Q^T) = Q H(eta, D) Q^T)
  const Hypoplastic model(oedometer_row());
  Mat3 d_strain;
  d_strain << -1e-5, 2e-6, 0, 2e-6, 3e-6, 0, 0, 0, 0;
  Mat3 d_spin = Mat3::Zero();
  d_spin(0, 1) = -1e-3;
  d_spin(1, 0) = 1e-3;
  const Mat3 R = rotation_increment(d_spin);
  Mat3 fixed = anisotropic_stress(), rotating = anisotropic_stress(), frame = Mat3::Identity();
  std::vector<double> internal{0.0};
  // Act
  for (int k = 0; k < 1000; ++k) {
    model.integrate(d_strain, fixed, internal);
    frame = R * frame;
    update_stress(model, frame * d_strain * frame.transpose(), d_spin, rotating, internal);
  }
  // Assert
  EXPECT_GT(relative(mean_stress(fixed), mean_stress(anisotropic_stress())), 0.05);
  EXPECT_LT(relative(mean_stress(rotating), mean_stress(fixed)), 1e-10);
  EXPECT_LT(relative(von_mises(rotating), von_mises(fixed)), 1e-10);
  EXPECT_LT(relative(lode_angle(rotating), lode_angle(fixed)), 1e-10);
  EXPECT_EQ(internal[0], 0.0);
}

TEST(Hypoplastic, TangentMatchesFiniteDifferenceOfIntegrateWithShear) {
  // Arrange: a small increment with all six components (engineering shear in Voigt form)
  const Hypoplastic model(oedometer_row(5e3));
  Mat3 d_strain;
  d_strain << -4e-9, 1.5e-9, -1e-9, 1.5e-9, 2e-9, 0.5e-9, -1e-9, 0.5e-9, 1e-9;
  const std::vector<double> internal{0.0};
  // Act
  const Mat6 analytic = model.tangent(d_strain, anisotropic_stress(), internal);
  const Mat6 numeric = finite_difference_tangent(model, d_strain, anisotropic_stress(), internal);
  // Assert: equal up to the O(|d_eps|) change of L and N over the increment
  EXPECT_LT((analytic - numeric).norm(), 1e-5 * analytic.norm()) << "analytic\n"
                                                                 << analytic << "\nnumeric\n"
                                                                 << numeric;
}

TEST(Hypoplastic, IntegrateWithTangentByDefaultMatchesSeparateCalls) {
  // Hypoplastic keeps Model's default: tangent() on the state before, then integrate().
  const Hypoplastic model(oedometer_row(5e3));
  Mat3 d_strain;
  d_strain << -4e-9, 1.5e-9, -1e-9, 1.5e-9, 2e-9, 0.5e-9, -1e-9, 0.5e-9, 1e-9;
  expect_integrate_with_tangent_matches(model, d_strain, anisotropic_stress(), {0.0});
}

TEST(Hypoplastic, TangentAppliedToTheIncrementGivesTheRateOfEq15) {
  // Arrange: D (x) D/|D| contracted with D gives |D|, so tangent . D = L:D + N |D|
  const Hypoplastic model(oedometer_row());
  Mat3 d;
  d << -1.0, 0.3, 0.0, 0.3, 0.2, -0.1, 0.0, -0.1, 0.4;
  const std::vector<double> internal{0.0};
  // Act
  const Vec6 from_tangent = model.tangent(d, anisotropic_stress(), internal) * strain_to_voigt(d);
  const Vec6 from_rate = stress_to_voigt(model.objective_rate(d, anisotropic_stress(), internal));
  // Assert
  EXPECT_LT((from_tangent - from_rate).norm(), 1e-12 * from_rate.norm());
}

TEST(Hypoplastic, OneLargeIncrementMatchesManySmallOnes) {
  // Arrange: 3 % axial compression with lateral extension, from -100 kPa isotropic
  const Hypoplastic model(oedometer_row());
  Mat3 total = Mat3::Zero();
  total.diagonal() << -0.03, 0.004, 0.004;
  Mat3 one = -100e3 * Mat3::Identity(), many = one;
  std::vector<double> internal{0.0};
  // Act
  model.integrate(total, one, internal);
  for (int k = 0; k < 30000; ++k) model.integrate(total / 30000, many, internal);
  // Assert
  EXPECT_GT(model.substeps(norm(total)), 100);
  EXPECT_LT((one - many).norm(), 1e-6 * many.norm());
  EXPECT_EQ(internal[0], 0.0);
}

TEST(Hypoplastic, AnIncrementBeyondTheSubstepCapIsNotIntegratedButSaidNonFinite) {
  // Arrange: a constant of -1e8 (a scene typo the fuzzer makes: c2 = -1e308 ran a million
  // sub-steps per particle and step) and an ordinary increment
  HypoplasticParameters p = oedometer_row();
  p.constants.c2 = -1e8;
  const Hypoplastic model(p);
  Mat3 d = Mat3::Zero();
  d.diagonal() << -1e-4, 0.0, 0.0;
  Mat3 stress = -100e3 * Mat3::Identity();
  std::vector<double> internal{0.0};
  // Act
  model.integrate(d, stress, internal);
  // Assert: NaN, for the solver to report; the sand's own constants integrate the same increment
  EXPECT_EQ(model.substeps(norm(d)), 0);
  EXPECT_FALSE(stress.allFinite());
  Mat3 ordinary = -100e3 * Mat3::Identity();
  Hypoplastic(oedometer_row()).integrate(d, ordinary, internal);
  EXPECT_TRUE(ordinary.allFinite());
}

TEST(Hypoplastic, CohesionTranslatesTheStress) {
  // Arrange: Peng 2015 eq 24-25, the rate of sigma with cohesion c is the rate of eta = sigma - cI
  const Hypoplastic cohesive(oedometer_row(5e3));
  const Hypoplastic cohesionless(oedometer_row());
  Mat3 d;
  d << -1.0, 0.3, 0.0, 0.3, 0.2, -0.1, 0.0, -0.1, 0.4;
  const std::vector<double> internal{0.0};
  const Mat3 sigma = anisotropic_stress();
  // Act
  const Mat3 with = cohesive.objective_rate(d, sigma, internal);
  const Mat3 without = cohesionless.objective_rate(d, sigma - 5e3 * Mat3::Identity(), internal);
  // Assert
  EXPECT_LT((with - without).norm(), 1e-12 * without.norm());
}

TEST(Hypoplastic, ModuliAtAnIsotropicStateFollowFromEq15) {
  // Arrange: at eta = s I eq 15 gives dsigma = 3 c1 s D + (c2 + c3/3) s tr(D) I + N |D|, so
  // G = 3 c1 s / 2 and K = s (c1 + c2 + c3/3).
  const HypoplasticParameters row = oedometer_row();
  const Hypoplastic model(row);
  const double s = -100e3;
  const auto& c = row.constants;
  // Act
  const ElasticModuli m = model.moduli(s * Mat3::Identity(), std::vector<double>{0.0});
  // Assert
  EXPECT_NEAR(m.shear, 1.5 * c.c1 * s, 1e-9 * m.shear);
  EXPECT_NEAR(m.bulk, s * (c.c1 + c.c2 + c.c3 / 3.0), 1e-9 * m.bulk);
}

TEST(Hypoplastic, ZeroStressReturnsToTheApexAndCountsACorrection) {
  // Arrange
  const Hypoplastic model(oedometer_row());
  Mat3 stress = Mat3::Zero();
  std::vector<double> internal{0.0};
  Mat3 d_strain = Mat3::Zero();
  d_strain(1, 1) = -1e-3;
  // Act
  model.integrate(d_strain, stress, internal);
  // Assert: finite, compressive, one correction
  EXPECT_TRUE(stress.allFinite());
  EXPECT_LT(stress.trace(), 0.0);
  EXPECT_EQ(internal[0], 1.0);
}

TEST(Hypoplastic, TensileStressReturnsToTheApexAndCountsACorrection) {
  // Arrange
  const Hypoplastic model(oedometer_row(2e3));
  Mat3 stress = anisotropic_stress() + 150e3 * Mat3::Identity();  // tr = 190 kPa > 3c
  std::vector<double> internal{0.0};
  Mat3 d_strain = Mat3::Zero();
  d_strain(0, 0) = 1e-4;
  // Act
  model.integrate(d_strain, stress, internal);
  // Assert: translated stress back inside tr eta < 0, no NaN
  EXPECT_TRUE(stress.allFinite());
  EXPECT_LT((stress - 2e3 * Mat3::Identity()).trace(), 0.0);
  EXPECT_EQ(internal[0], 1.0);
}

TEST(Hypoplastic, TensionWithinTheCohesionNeedsNoCorrection) {
  // Arrange: sigma = +1 kPa isotropic with c = 5 kPa is eta = -4 kPa I, admissible
  const Hypoplastic model(oedometer_row(5e3));
  Mat3 stress = 1e3 * Mat3::Identity();
  std::vector<double> internal{0.0};
  Mat3 d_strain = Mat3::Zero();
  d_strain(1, 1) = -1e-5;
  // Act
  model.integrate(d_strain, stress, internal);
  // Assert
  EXPECT_EQ(internal[0], 0.0);
  EXPECT_LT(stress(1, 1), 1e3);
}

TEST(Hypoplastic, ExtensionFromTheApexStaysFinite) {
  // Arrange: keep pulling a stress-free point; every call starts outside and is corrected once
  const Hypoplastic model(oedometer_row());
  Mat3 stress = Mat3::Zero();
  std::vector<double> internal{0.0};
  // Act
  for (int k = 0; k < 100; ++k) model.integrate(1e-3 * Mat3::Identity(), stress, internal);
  // Assert
  EXPECT_TRUE(stress.allFinite());
  EXPECT_LE(stress.trace(), 0.0);
  EXPECT_GE(internal[0], 1.0);
}

TEST(Hypoplastic, CorrectReturnsATensileStateToTheApex) {
  // Arrange
  const Hypoplastic model(oedometer_row());
  Mat3 stress = 10.0 * Mat3::Identity();
  std::vector<double> internal{0.0};
  // Act
  model.correct(stress, internal);
  // Assert
  EXPECT_NEAR(stress.trace(), -3.0 * apex_pressure, 1e-12);
  EXPECT_EQ(internal[0], 1.0);
}

TEST(HypoplasticParameters, OutOfRangeValueIsRefusedWithKeyAndRange) {
  // Act
  const std::string message = message_of({{"Ei", 20e6}, {"nu", 0.62}, {"phi", 30.0}, {"psi", 1.0}});
  // Assert
  EXPECT_NE(message.find("material.sand.nu = 0.62"), std::string::npos) << message;
  EXPECT_NE(message.find("[0, 0.5)"), std::string::npos) << message;
}

TEST(HypoplasticParameters, PositiveC1IsRefusedWithKeyAndRange) {
  // Act
  const std::string message =
      message_of({{"c1", 58.3}, {"c2", -178.5}, {"c3", -589.0}, {"c4", -182.7}});
  // Assert
  EXPECT_NE(message.find("material.sand.c1 = 58.3"), std::string::npos) << message;
  EXPECT_NE(message.find("< 0"), std::string::npos) << message;
}

TEST(HypoplasticParameters, FrictionAngleOutOfRangeIsRefused) {
  // Act
  const std::string message = message_of({{"Ei", 20e6}, {"nu", 0.2}, {"phi", 95.0}, {"psi", 0.0}});
  // Assert
  EXPECT_NE(message.find("material.sand.phi = 95"), std::string::npos) << message;
  EXPECT_NE(message.find("(0, 90)"), std::string::npos) << message;
  EXPECT_NE(message.find("deg"), std::string::npos) << message;
}

TEST(HypoplasticParameters, BothParameterSetsAreRefusedNamingTheKeys) {
  // Act
  const std::string message = message_of(
      {{"c1", -58.3}, {"c2", -178.5}, {"c3", -589.0}, {"c4", -182.7}, {"Ei", 21e6}, {"phi", 29.5}});
  // Assert
  EXPECT_NE(message.find("not both"), std::string::npos) << message;
  EXPECT_NE(message.find("c1, c2, c3, c4"), std::string::npos) << message;
  EXPECT_NE(message.find("Ei, phi"), std::string::npos) << message;
}

TEST(HypoplasticParameters, IncompleteSetIsRefusedNamingTheMissingKeys) {
  // Act
  const std::string message = message_of({{"Ei", 21e6}, {"nu", 0.2}, {"phi", 29.5}});
  // Assert
  EXPECT_NE(message.find("psi missing"), std::string::npos) << message;
}

TEST(HypoplasticParameters, NoParametersIsRefused) {
  // Act
  const std::string message = message_of({{"c", 1e3}});
  // Assert
  EXPECT_NE(message.find("c1 c2 c3 c4 or Ei nu phi psi"), std::string::npos) << message;
}

TEST(HypoplasticParameters, DerivedConstantsAreRecordedForElementJson) {
  // Arrange: Peng 2015 Table 1, sand collapse row
  std::map<std::string, ParameterValue> resolved;
  // Act
  const auto model =
      make_model("hypoplastic", {{"Ei", 20e6}, {"nu", 0.2}, {"phi", 30.0}, {"psi", 1.0}},
                 "material.sand", &resolved);
  // Assert
  EXPECT_EQ(model->name(), "hypoplastic");
  ASSERT_TRUE(resolved.count("c1") && resolved.count("c4") && resolved.count("c"));
  EXPECT_NEAR(std::get<double>(resolved.at("c1")), -55.6, 0.1);
  EXPECT_NEAR(std::get<double>(resolved.at("c4")), -170.9, 0.1);
  EXPECT_EQ(std::get<double>(resolved.at("c")), 0.0);
}

TEST(HypoplasticParameters, RegistryExampleBuildsAModelWithOneInternalVariable) {
  // Arrange
  const ModelInfo& info = builtin_models().find("hypoplastic");
  // Act
  const auto model = make_model("hypoplastic", info.example, "material.sand");
  // Assert
  const auto variables = model->internal_variables();
  ASSERT_EQ(variables.size(), 1u);
  EXPECT_EQ(variables[0].name, "corrections");
}

}  // namespace
}  // namespace duet::constitutive
