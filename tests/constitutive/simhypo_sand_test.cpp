// Unit tests of the simhypo-sand model (constitutive/simhypo_sand.hpp) and of the stress
// corrections (constitutive/stress_correction.hpp): closed forms of the paper's eqs 5-18, the
// calibration of eqs 9-11, the void ratio update of eq 32, the tangent, objectivity, the apex
// return and the input errors. Element paths are in simhypo_sand_point_test.cpp.
#include "constitutive/simhypo_sand.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "common/input_error.hpp"
#include "constitutive/objective.hpp"

namespace duet::constitutive {
namespace {

// The registry's example sand (phi_c = 30 deg, Li & Wang 1998 Toyoura critical state line).
SimhypoSandParameters example_sand() {
  SimhypoSandParameters m;
  m.phi_c = 30.0;
  m.E_i = 40e6;
  m.nu_i = 0.3;
  m.e_Gamma = 0.934;
  m.lambda = 0.019;
  m.xi = 0.7;
  m.alpha = 4.0;
  m.e0 = 0.85;
  return m;
}

// Axisymmetric stresses, tension positive, axial = y: compression has the axial stress the
// larger compression, q = sigma_xx - sigma_yy > 0.
Mat3 triaxial_compression(double p, double q) {
  return Vec3(-(p - q / 3.0), -(p + 2.0 * q / 3.0), -(p - q / 3.0)).asDiagonal();
}
Mat3 triaxial_extension(double p, double q) {
  return Vec3(-(p + q / 3.0), -(p - 2.0 * q / 3.0), -(p + q / 3.0)).asDiagonal();
}

// A general state: distinct principal stresses, all compressive, with shear components.
Mat3 general_stress() {
  Mat3 s;
  s << -120e3, 15e3, -8e3, 15e3, -210e3, 12e3, -8e3, 12e3, -150e3;
  return s;
}

double sin_deg(double deg) {
  return std::sin(deg * std::numbers::pi / 180.0);
}

// Critical state stress ratio in triaxial compression, M = 6 sin(phi) / (3 - sin(phi)).
double critical_ratio_m(double phi_deg) {
  return 6.0 * sin_deg(phi_deg) / (3.0 - sin_deg(phi_deg));
}

// ---------------------------------------------------------------------------------------------
// Eqs 5, 6, 16-18: critical state, density factor, failure surface shape

TEST(SimhypoSand, CriticalAMatchesEq16AndTheTriaxialCriticalStressRatio) {
  // Arrange: phi_c = 30 deg, sin = 1/2: a_c = sqrt3 * 2.5 / (2 sqrt2 * 0.5) = 3.0619
  const double a_c = critical_a(30.0);
  const double M = critical_ratio_m(30.0);  // 1.2
  // Act: normalised deviator |sigma*| / |tr sigma| at the critical state of triaxial compression
  const Mat3 s = triaxial_compression(100e3, M * 100e3);
  const double normalised = norm(deviator(s)) / std::abs(s.trace());
  // Assert
  EXPECT_NEAR(a_c, std::sqrt(3.0) * 2.5 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(normalised, 1.0 / a_c, 1e-12);
}

TEST(SimhypoSand, SmpAndDruckerPragerRadiiAgreeInTriaxialCompression) {
  // Arrange
  SimhypoSandParameters m = example_sand();
  const Mat3 s = triaxial_compression(150e3, 90e3);
  // Act / Assert: q_s = q_m (eq 18), so a = a_c for every weight theta (eq 17)
  EXPECT_NEAR(smp_radius_ratio(s), 1.0, 1e-12);
  for (const double theta : {0.0, 0.5, 1.0}) {
    m.theta = theta;
    EXPECT_NEAR(a_factor(m, s), critical_a(m.phi_c), 1e-12) << "theta = " << theta;
  }
}

TEST(SimhypoSand, SmpRadiusRatioMatchesEq18ByHandInTriaxialExtension) {
  // Arrange: principal compressions (3, 3, 1) * 100 kPa: I1 = 7, I2 = 15, I3 = 9 (units of
  // 100 kPa), q_m = sqrt(49 - 45) = 2, q_s = 2*7 / (3 sqrt(96/24) - 1) = 2.8 (eq 18).
  SimhypoSandParameters m = example_sand();
  const Mat3 s = Vec3(-300e3, -100e3, -300e3).asDiagonal();
  // Act
  const double ratio = smp_radius_ratio(s);
  m.theta = 1.0;
  const double a_smp = a_factor(m, s);
  m.theta = 0.0;
  const double a_dp = a_factor(m, s);
  // Assert: the SMP surface is smaller in extension, so a grows there (eq 17); DP keeps a_c.
  EXPECT_NEAR(ratio, 1.4, 1e-12);
  EXPECT_NEAR(a_smp, 1.4 * critical_a(m.phi_c), 1e-12);
  EXPECT_NEAR(a_dp, critical_a(m.phi_c), 1e-12);
}

TEST(SimhypoSand, SmpRadiusRatioTendsToOneAtTheHydrostaticAxis) {
  // Arrange: a deviator 1e-6 of the mean stress, in extension (where the ratio is largest)
  const Mat3 s = triaxial_extension(100e3, 0.1);
  // Act / Assert: the SMP cone of vanishing opening is a circle
  EXPECT_NEAR(smp_radius_ratio(s), 1.0, 1e-5);
  EXPECT_DOUBLE_EQ(smp_radius_ratio(-100e3 * Mat3::Identity()), 1.0);
}

TEST(SimhypoSand, CriticalVoidRatioAndDensityFactorFollowEqs5And6) {
  // Arrange
  const SimhypoSandParameters m = example_sand();
  // Act
  const double e_c = critical_void_ratio(m, atmospheric_pressure);
  // Assert: at p' = p_a, e_c = e_Gamma - lambda (eq 6); f_d = 1 on the line, < 1 denser (eq 5)
  EXPECT_NEAR(e_c, 0.934 - 0.019, 1e-15);
  EXPECT_NEAR(density_factor(m, e_c, atmospheric_pressure), 1.0, 1e-15);
  EXPECT_NEAR(density_factor(m, 0.9 * e_c, atmospheric_pressure), std::pow(0.9, 4.0), 1e-14);
  EXPECT_GT(density_factor(m, 1.05 * e_c, atmospheric_pressure), 1.0);
}

TEST(SimhypoSand, FlowTensorOfEq15SolvesTheLinearPart) {
  // Arrange: B of eq 15 is L^-1 : N of eq 4 (so the critical flow direction is -f_d B, eq 13)
  const SimhypoSandParameters m = example_sand();
  const Mat3 s = general_stress();
  const SimhypoFactors k = simhypo_factors(m, s, 0.8);
  // Act
  const Mat3 B = flow_tensor(k, s);
  const Mat3 LB = linear_part(k, s, B);
  // Assert
  EXPECT_LT(norm(LB - nonlinear_part(k, s)), 1e-12 * norm(nonlinear_part(k, s)));
}

TEST(SimhypoSand, FailureFunctionVanishesWithoutDilatancyAtTheCriticalState) {
  // Arrange: triaxial compression at q/p = M, void ratio on the critical state line (f_d = 1)
  const SimhypoSandParameters m = example_sand();
  const double p = 150e3;
  const Mat3 s = triaxial_compression(p, critical_ratio_m(m.phi_c) * p);
  const double e_c = critical_void_ratio(m, p);
  // Act
  const double f = failure_function(m, s, e_c);
  const Mat3 B = flow_tensor(simhypo_factors(m, s, e_c), s);
  // Assert: on the surface (eq 14) and the flow rule has no volume change
  EXPECT_NEAR(f, 0.0, 1e-12);
  EXPECT_NEAR(B.trace(), 0.0, 1e-12 * norm(B));
}

TEST(SimhypoSand, DenserSandHasTheLargerFailureSurface) {
  // Arrange: a stress above the critical ratio
  const SimhypoSandParameters m = example_sand();
  const double p = 150e3;
  const Mat3 s = triaxial_compression(p, 1.3 * critical_ratio_m(m.phi_c) * p);
  const double e_c = critical_void_ratio(m, p);
  // Act / Assert: outside the critical surface, inside the surface of a dense sample (Fig 1b)
  EXPECT_GT(failure_function(m, s, e_c), 0.0);
  EXPECT_LT(failure_function(m, s, 0.85 * e_c), 0.0);
}

// ---------------------------------------------------------------------------------------------
// Eqs 9-11: calibration; moduli

TEST(SimhypoSand, CalibrationReproducesInitialModulusAndPoissonRatio) {
  // Arrange: isotropic state at the calibration pressure, any void ratio; drained triaxial
  // compression rate with the radial strain rate -nu_i times the axial one (eq 8)
  const SimhypoSandParameters m = example_sand();
  const Mat3 s = -m.sigma_c * Mat3::Identity();
  const double eps_a = -1e-4;
  const Mat3 D = Vec3(-m.nu_i * eps_a, eps_a, -m.nu_i * eps_a).asDiagonal();
  for (const double e : {0.75, 0.85, 0.95}) {
    // Act
    const Mat3 rate = simhypo_rate(m, s, e, D);
    // Assert: radial stress held (eq 10), q_dot / |eps_a_dot| = E_i (eq 11)
    EXPECT_NEAR(rate(0, 0), 0.0, 1e-9 * m.E_i * std::abs(eps_a)) << "e = " << e;
    EXPECT_NEAR(rate(0, 0) - rate(1, 1), m.E_i * std::abs(eps_a), 1e-9 * m.E_i * std::abs(eps_a));
  }
}

TEST(SimhypoSand, ShearModulusAtTheCalibrationPressureIsEiOverTwoOnePlusNu) {
  // Arrange
  const SimhypoSand model(example_sand());
  const std::vector<double> internal = {0.85, 0.0};
  // Act
  const ElasticModuli k = model.moduli(-100e3 * Mat3::Identity(), internal);
  // Assert: G = f_s tr(sigma) / 2 = E_i / (2 (1 + nu_i)) at sigma_c (eq 11); K positive
  EXPECT_NEAR(k.shear, 40e6 / 2.6, 1e-6);
  EXPECT_GT(k.bulk, 0.0);
}

// ---------------------------------------------------------------------------------------------
// integrate: eq 32, tangent, zero increment, objectivity, apex

TEST(SimhypoSand, VoidRatioFollowsEq32) {
  // Arrange: isotropic compression increments, tr(d_eps) = -1e-3 each, one sub-step each
  const SimhypoSand model(example_sand());
  Mat3 stress = -100e3 * Mat3::Identity();
  std::vector<double> internal = {0.85, 0.0};
  const Mat3 d_strain = -1e-3 / 3.0 * Mat3::Identity();
  // Act
  for (int k = 0; k < 100; ++k) model.integrate(d_strain, stress, internal);
  // Assert: 1 + e_{n+1} = (1 + e_n)(1 + tr(d_eps)) (eq 32), stress compressed
  EXPECT_NEAR(internal[0], 1.85 * std::pow(1.0 - 1e-3, 100) - 1.0, 1e-12);
  EXPECT_LT(mean_stress(stress), -100e3);
}

TEST(SimhypoSand, TangentMatchesFiniteDifferenceOfIntegrate) {
  // Arrange: a state well inside the surface, a small increment in a general direction
  const SimhypoSand model(example_sand());
  const Mat3 stress = general_stress();
  const std::vector<double> internal = {0.85, 0.0};
  Mat3 d_strain;
  d_strain << -4e-7, 1e-7, 2e-7, 1e-7, -7e-7, -1.5e-7, 2e-7, -1.5e-7, 3e-7;
  ASSERT_LT(failure_function(model.parameters(), stress, 0.85), 0.0);
  // Act
  const Mat6 analytic = model.tangent(d_strain, stress, internal);
  const Mat6 numeric = finite_difference_tangent(model, d_strain, stress, internal, 1e-4);
  // Assert
  EXPECT_LT((analytic - numeric).norm(), 1e-5 * analytic.norm()) << "analytic\n"
                                                                 << analytic << "\nnumeric\n"
                                                                 << numeric;
}

TEST(SimhypoSand, TangentTimesIncrementIsTheRate) {
  // Arrange: eq 12 is homogeneous of degree one in the stretching
  const SimhypoSand model(example_sand());
  const Mat3 stress = general_stress();
  const std::vector<double> internal = {0.85, 0.0};
  Mat3 D;
  D << -4e-3, 1e-3, 0.0, 1e-3, -7e-3, 0.0, 0.0, 0.0, 3e-3;
  // Act
  const Vec6 from_tangent = model.tangent(D, stress, internal) * strain_to_voigt(D);
  const Vec6 rate = stress_to_voigt(model.objective_rate(D, stress, internal));
  // Assert
  EXPECT_LT((from_tangent - rate).norm(), 1e-12 * rate.norm());
}

TEST(SimhypoSand, ZeroStrainIncrementLeavesTheStateUnchanged) {
  // Arrange
  const SimhypoSand model(example_sand());
  const Mat3 start = general_stress();
  Mat3 stress = start;
  std::vector<double> internal = {0.85, 0.0};
  // Act
  model.integrate(Mat3::Zero(), stress, internal);
  // Assert
  EXPECT_EQ(stress, start);
  EXPECT_EQ(internal[0], 0.85);
  EXPECT_EQ(internal[1], 0.0);
}

TEST(SimhypoSand, RigidRotationLeavesInvariantsUnchanged) {
  // Arrange: 1000 spin increments of 1e-3 rad about an oblique axis, zero stretching
  const SimhypoSand model(example_sand());
  Mat3 stress = general_stress();
  std::vector<double> internal = {0.85, 0.0};
  const Vec3 axis = Vec3(1.0, 2.0, 3.0).normalized() * 1e-3;
  Mat3 d_spin;
  d_spin << 0.0, -axis(2), axis(1), axis(2), 0.0, -axis(0), -axis(1), axis(0), 0.0;
  const double p0 = mean_stress(stress), q0 = von_mises(stress), lode0 = lode_angle(stress);
  // Act
  for (int k = 0; k < 1000; ++k) update_stress(model, Mat3::Zero(), d_spin, stress, internal);
  // Assert
  EXPECT_NEAR(mean_stress(stress), p0, 1e-10 * std::abs(p0));
  EXPECT_NEAR(von_mises(stress), q0, 1e-10 * q0);
  EXPECT_NEAR(lode_angle(stress), lode0, 1e-10);
  EXPECT_GT(norm(stress - general_stress()), 1e-3 * norm(stress));  // it did rotate
  EXPECT_EQ(internal[1], 0.0);
}

TEST(SimhypoSand, TensileMeanStressReturnsToTheApexAndIsCounted) {
  // Arrange
  const SimhypoSand model(example_sand());
  Mat3 stress = 5e3 * Mat3::Identity();
  std::vector<double> internal = {0.85, 0.0};
  const Mat3 d_strain = Vec3(1e-4, -2e-4, 0.0).asDiagonal();
  // Act
  const Mat3 rate = model.objective_rate(d_strain, stress, internal);
  model.integrate(d_strain, stress, internal);
  // Assert: finite, compressive (or at the apex), counted
  EXPECT_TRUE(rate.allFinite());
  EXPECT_TRUE(stress.allFinite());
  EXPECT_GE(effective_pressure(stress), model.parameters().p_min * (1.0 - 1e-12));
  EXPECT_GE(internal[1], 1.0);
}

// ---------------------------------------------------------------------------------------------
// Stress corrections (eqs 36-38)

// Drucker-Prager cone |s| = k |p|: Method C has the closed form alpha_c = k |p| / |s|.
double cone(const Mat3& s) {
  return norm(deviator(s)) / (0.5 * std::abs(mean_stress(s))) - 1.0;
}

TEST(StressCorrection, MethodCMatchesTheClosedFormOnADruckerPragerCone) {
  // Arrange: |s| / |p| = 0.8 against a cone of 0.5
  Mat3 stress = general_stress();
  const Mat3 s0 = deviator(stress);
  stress = mean_stress(stress) * Mat3::Identity() +
           s0 * (0.8 * std::abs(mean_stress(stress)) / norm(s0));
  const double p = mean_stress(stress);
  // Act
  const double alpha = scale_deviator_to_surface(cone, stress, 1e-10);
  // Assert
  EXPECT_NEAR(alpha, 0.5 / 0.8, 1e-9);
  EXPECT_NEAR(mean_stress(stress), p, 1e-9 * std::abs(p));
  EXPECT_NEAR(cone(stress), 0.0, 1e-10);
}

TEST(StressCorrection, GradientMatchesTheConeNormal) {
  // Arrange: d/dsigma of |s|/(k|p|) = s/(|s| k|p|) + |s|/(k p^2) * sign(p) I/3 ... at p < 0:
  // f = |s| / (-k p) - 1, df = s:ds/(|s| (-k p)) + |s| dp / (k p^2), dp = tr(ds)/3
  const Mat3 stress = general_stress();
  const Mat3 s = deviator(stress);
  const double p = mean_stress(stress), k = 0.5;
  const Mat3 expected = s / (norm(s) * (-k * p)) + norm(s) / (k * p * p) / 3.0 * Mat3::Identity();
  // Act
  const Mat3 gradient = failure_gradient(cone, stress);
  // Assert
  EXPECT_LT(norm(gradient - expected), 1e-7 * norm(expected));
}

TEST(StressCorrection, EveryMethodBringsTheModelBackWithinTolerance) {
  for (const CorrectionMethod method :
       {CorrectionMethod::A, CorrectionMethod::B, CorrectionMethod::C}) {
    // Arrange: triaxial compression above the critical ratio at the critical void ratio
    SimhypoSandParameters m = example_sand();
    m.correction = method;
    const SimhypoSand model(m);
    const double p = 150e3;
    const double e = critical_void_ratio(m, p);
    Mat3 stress = triaxial_compression(p, 1.2 * critical_ratio_m(m.phi_c) * p);
    std::vector<double> internal = {e, 0.0};
    const Mat3 axial_rate = Vec3(0.0, -1.0, 0.0).asDiagonal() * 1e5;
    ASSERT_GT(failure_function(m, stress, e), m.correction_tolerance);
    // Act
    const bool acted = model.correct_with_rate(stress, internal, axial_rate);
    // Assert
    EXPECT_TRUE(acted);
    EXPECT_LE(std::abs(failure_function(m, stress, e)), m.correction_tolerance)
        << correction_method_name(method);
    EXPECT_EQ(internal[1], 1.0);
  }
}

TEST(StressCorrection, MethodCKeepsMeanStressAndLodeAngleOfTheModel) {
  // Arrange: a general state pushed outside the surface of a loose sample
  const SimhypoSand model(example_sand());
  const Mat3 s0 = general_stress();
  Mat3 stress = mean_stress(s0) * Mat3::Identity() + 3.0 * deviator(s0);
  const double e = 0.95;
  std::vector<double> internal = {e, 0.0};
  const double p = mean_stress(stress), lode = lode_angle(stress);
  ASSERT_GT(failure_function(model.parameters(), stress, e), 1e-3);
  // Act
  model.correct(stress, internal);
  // Assert: eq 38 keeps I1 and the direction of the deviator
  EXPECT_NEAR(mean_stress(stress), p, 1e-12 * std::abs(p));
  EXPECT_NEAR(lode_angle(stress), lode, 1e-12);
  EXPECT_LE(std::abs(failure_function(model.parameters(), stress, e)), 1e-3);
  EXPECT_EQ(internal[1], 1.0);
}

TEST(StressCorrection, StateInsideTheSurfaceIsLeftAlone) {
  // Arrange
  const SimhypoSand model(example_sand());
  const Mat3 start = triaxial_compression(100e3, 50e3);
  Mat3 stress = start;
  std::vector<double> internal = {0.85, 0.0};
  // Act
  model.correct(stress, internal);
  // Assert
  EXPECT_EQ(stress, start);
  EXPECT_EQ(internal[1], 0.0);
}

// ---------------------------------------------------------------------------------------------
// Input

std::map<std::string, ParameterValue> example_values() {
  return builtin_models().find("simhypo-sand").example;
}

std::string input_error_message(std::map<std::string, ParameterValue> values) {
  try {
    make_model("simhypo-sand", std::move(values), "material.sand");
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(SimhypoSandInput, RegistryExampleBuildsWithVoidRatioAndCounter) {
  // Arrange / Act
  const auto model = make_model("simhypo-sand", example_values(), "material.sand");
  const auto variables = model->internal_variables();
  // Assert
  EXPECT_EQ(model->name(), "simhypo-sand");
  ASSERT_EQ(variables.size(), 2u);
  EXPECT_EQ(variables[0].name, "void_ratio");
  EXPECT_EQ(variables[0].initial, std::get<double>(example_values().at("e0")));
  EXPECT_EQ(variables[1].name, "corrections");
  EXPECT_EQ(variables[1].initial, 0.0);
}

TEST(SimhypoSandInput, FrictionAngleOutOfRangeIsRefusedWithKeyAndRange) {
  auto values = example_values();
  values["phi_c"] = 95.0;
  const std::string message = input_error_message(values);
  EXPECT_NE(message.find("material.sand.phi_c = 95"), std::string::npos) << message;
  EXPECT_NE(message.find("(0, 90)"), std::string::npos) << message;
  EXPECT_NE(message.find("deg"), std::string::npos) << message;
}

TEST(SimhypoSandInput, PoissonRatioOfOneHalfIsRefusedWithKeyAndRange) {
  auto values = example_values();
  values["nu_i"] = 0.5;
  const std::string message = input_error_message(values);
  EXPECT_NE(message.find("material.sand.nu_i = 0.5"), std::string::npos) << message;
  EXPECT_NE(message.find("[0, 0.5)"), std::string::npos) << message;
}

TEST(SimhypoSandInput, NegativeVoidRatioIsRefusedWithKeyAndRange) {
  auto values = example_values();
  values["e0"] = -0.1;
  const std::string message = input_error_message(values);
  EXPECT_NE(message.find("material.sand.e0 = -0.1"), std::string::npos) << message;
  EXPECT_NE(message.find("> 0"), std::string::npos) << message;
}

TEST(SimhypoSandInput, UnknownCorrectionMethodIsRefusedWithTheChoices) {
  auto values = example_values();
  values["correction"] = std::string("D");
  const std::string message = input_error_message(values);
  EXPECT_NE(message.find("material.sand.correction"), std::string::npos) << message;
  EXPECT_NE(message.find("A, B, C, none"), std::string::npos) << message;
}

TEST(SimhypoSandInput, CorrectionDefaultsToMethodCWithTolerance1em3) {
  std::map<std::string, ParameterValue> resolved;
  make_model("simhypo-sand", example_values(), "material.sand", &resolved);
  EXPECT_EQ(std::get<std::string>(resolved.at("correction")), "C");
  EXPECT_EQ(std::get<double>(resolved.at("correction_tolerance")), 1e-3);
}

}  // namespace
}  // namespace duet::constitutive
