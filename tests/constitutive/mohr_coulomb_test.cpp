// Unit tests of constitutive/mohr_coulomb.cpp: one test per regime of the return mapping
// (elastic, main plane, right edge, left edge, apex), the consistent tangent against finite
// differences, integrate_with_tangent against integrate and tangent in each regime, triaxial
// compression strength against the Mohr-Coulomb closed form, the continuum rate, objectivity under
// rigid rotation and parameter refusal (constitutive/docs/mohr_coulomb.md).

#include "constitutive/mohr_coulomb.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "common/input_error.hpp"
#include "constitutive/element_test.hpp"
#include "constitutive/objective.hpp"
#include "constitutive/tresca.hpp"
#include "tests/constitutive/refusal.hpp"
#include "tests/constitutive/same_return.hpp"

namespace duet::constitutive {
namespace {

constexpr double E = 20e6;  // Pa
constexpr double nu = 0.3;
constexpr double phi = 30.0;  // deg
constexpr double psi = 10.0;  // deg
constexpr double c = 10e3;    // Pa
constexpr double degree = std::numbers::pi / 180.0;

std::map<std::string, ParameterValue> soil() {
  return {{"E", E}, {"nu", nu}, {"phi", phi}, {"psi", psi}, {"c", c}};
}

MohrCoulomb make(std::map<std::string, ParameterValue> values = soil()) {
  auto model = make_model("mohr-coulomb", std::move(values), "material.sand");
  return dynamic_cast<const MohrCoulomb&>(*model);
}

std::vector<double> initial_internal(const Model& model) {
  std::vector<double> internal;
  for (const auto& v : model.internal_variables()) internal.push_back(v.initial);
  return internal;
}

double relative_difference(const Mat6& a, const Mat6& b) {
  return (a - b).norm() / b.norm();
}

Mat3 rotation() {
  return Eigen::AngleAxisd(0.7, Vec3(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
}

Mat3 general_increment() {
  Mat3 d;
  d << 2e-4, 3e-4, -1e-4, 3e-4, -4e-4, 0.5e-4, -1e-4, 0.5e-4, 1e-4;
  return d;
}

/// Start stress whose elastic trial under general_increment() is R diag(principal_trial) R^T.
Mat3 start_for_trial(const Vec3& principal_trial) {
  const Mat3 R = rotation();
  return R * principal_trial.asDiagonal() * R.transpose() -
         elastic_increment({E, nu}, general_increment());
}

Vec3 principal(const Mat3& s) {
  return spectral_decomposition(s).values;
}

double apex() {
  return c / std::tan(phi * degree);  // c cot(phi) = 17.32 kPa
}

// Trial principal stresses (Pa) that select each regime for soil().
const Vec3 main_plane_trial(-50e3, -100e3, -300e3);
const Vec3 right_edge_trial(-50e3, -295e3, -300e3);
const Vec3 left_edge_trial(-40e3, -60e3, -300e3);
const Vec3 apex_trial(120e3, 100e3, 90e3);

PrincipalRegime regime_of(const MohrCoulomb& model, const Mat3& start) {
  return model.return_mapping(start + elastic_increment({E, nu}, general_increment()))
      .principal.regime;
}

TEST(MohrCoulombSurface, ApexIsCohesionTimesCotPhi) {
  const FacetedSurface s = mohr_coulomb_surface(phi, psi, c);
  ASSERT_TRUE(s.apex.has_value());
  EXPECT_NEAR(*s.apex, apex(), 1e-9 * apex());
  EXPECT_NEAR(s.main.value(Vec3::Constant(*s.apex)), 0.0, 1e-9 * c);
  EXPECT_FALSE(mohr_coulomb_surface(0.0, 0.0, c).apex.has_value());
}

TEST(MohrCoulomb, ElasticIncrementInsideSurfaceIsHooke) {
  const MohrCoulomb model = make();
  auto internal = initial_internal(model);
  Mat3 stress = -100e3 * Mat3::Identity();
  const Mat3 d = 0.1 * general_increment();
  model.integrate(d, stress, internal);
  EXPECT_LT((stress - (-100e3 * Mat3::Identity() + elastic_increment({E, nu}, d))).norm(), 1e-9);
  EXPECT_EQ(internal[mohr_coulomb_corrections], 0.0);
}

TEST(MohrCoulomb, ZeroStrainIncrementLeavesStressUnchanged) {
  const MohrCoulomb model = make();
  auto internal = initial_internal(model);
  Mat3 stress = start_for_trial(main_plane_trial);
  model.integrate(general_increment(), stress, internal);
  const Mat3 before = stress;
  model.integrate(Mat3::Zero(), stress, internal);
  EXPECT_EQ(stress, before);
  EXPECT_EQ(internal[mohr_coulomb_corrections], 1.0);
}

TEST(MohrCoulomb, MainPlaneReturnLandsOnSurfaceAlongNonAssociatedFlow) {
  // Arrange
  const MohrCoulomb model = make();
  auto internal = initial_internal(model);
  Mat3 stress = start_for_trial(main_plane_trial);
  ASSERT_EQ(regime_of(model, stress), PrincipalRegime::main_plane);
  // Act
  model.integrate(general_increment(), stress, internal);
  // Assert: on the plane; and the intermediate stress moved by (4G/3 - 2K) sin(psi) d_gamma
  // (Box 8.4), d_gamma = f_trial / (4G (1 + sin phi sin psi / 3) + 4 K sin phi sin psi).
  const double K = E / (3.0 * (1.0 - 2.0 * nu)), G = E / (2.0 * (1.0 + nu));
  const double sp = std::sin(phi * degree), ss = std::sin(psi * degree);
  const Vec3& t = main_plane_trial;
  const double f_trial = t(0) - t(2) + (t(0) + t(2)) * sp - 2.0 * c * std::cos(phi * degree);
  const double d_gamma = f_trial / (4.0 * G * (1.0 + sp * ss / 3.0) + 4.0 * K * sp * ss);
  const Vec3 s = principal(stress);
  EXPECT_NEAR(model.yield_function(stress), 0.0, 1e-10 * 300e3);
  EXPECT_NEAR(s(1), t(1) + (4.0 * G / 3.0 - 2.0 * K) * ss * d_gamma, 1e-10 * 300e3);
  EXPECT_NEAR(s(0), t(0) - (2.0 * G * (1.0 + ss / 3.0) + 2.0 * K * ss) * d_gamma, 1e-10 * 300e3);
}

TEST(MohrCoulomb, RightEdgeReturnLandsOnBothPlanes) {
  const MohrCoulomb model = make();
  auto internal = initial_internal(model);
  Mat3 stress = start_for_trial(right_edge_trial);
  ASSERT_EQ(regime_of(model, stress), PrincipalRegime::right_edge);
  model.integrate(general_increment(), stress, internal);
  const Vec3 s = principal(stress);
  EXPECT_NEAR(model.yield_function(stress), 0.0, 1e-10 * 300e3);
  EXPECT_NEAR(s(1) - s(2), 0.0, 1e-10 * 300e3);  // second plane: sigma2 = sigma3
}

TEST(MohrCoulomb, LeftEdgeReturnLandsOnBothPlanes) {
  const MohrCoulomb model = make();
  auto internal = initial_internal(model);
  Mat3 stress = start_for_trial(left_edge_trial);
  ASSERT_EQ(regime_of(model, stress), PrincipalRegime::left_edge);
  model.integrate(general_increment(), stress, internal);
  const Vec3 s = principal(stress);
  EXPECT_NEAR(model.yield_function(stress), 0.0, 1e-10 * 300e3);
  EXPECT_NEAR(s(0) - s(1), 0.0, 1e-10 * 300e3);  // second plane: sigma1 = sigma2
}

TEST(MohrCoulomb, TensileTrialReturnsToApex) {
  const MohrCoulomb model = make();
  auto internal = initial_internal(model);
  Mat3 stress = start_for_trial(apex_trial);
  ASSERT_EQ(regime_of(model, stress), PrincipalRegime::apex);
  model.integrate(general_increment(), stress, internal);
  EXPECT_LT((stress - apex() * Mat3::Identity()).norm(), 1e-10 * apex());
  EXPECT_NEAR(model.yield_function(stress), 0.0, 1e-10 * apex());
  EXPECT_EQ(internal[mohr_coulomb_corrections], 1.0);
}

TEST(MohrCoulomb, CohesionlessSoilReturnsTensionToZeroStress) {
  // phi 30, psi 0, c 0 (the registry example): any tensile state returns to the apex, 0.
  const MohrCoulomb model = make({{"E", E}, {"nu", nu}, {"phi", 30.0}, {"psi", 0.0}, {"c", 0.0}});
  auto internal = initial_internal(model);
  Mat3 stress = Mat3::Zero();
  model.integrate(general_increment().cwiseAbs(), stress, internal);
  EXPECT_LT(stress.norm(), 1e-20);
}

TEST(MohrCoulomb, ConsistentTangentEqualsFiniteDifferenceOnMainPlaneAndEdges) {
  const MohrCoulomb model = make();
  const auto internal = initial_internal(model);
  for (const Vec3& trial : {main_plane_trial, right_edge_trial, left_edge_trial}) {
    const Mat3 stress = start_for_trial(trial);
    const Mat6 analytic = model.tangent(general_increment(), stress, internal);
    const Mat6 numeric = finite_difference_tangent(model, general_increment(), stress, internal);
    EXPECT_LT(relative_difference(analytic, numeric), 1e-6)
        << principal_regime_name(regime_of(model, stress));
  }
}

TEST(MohrCoulomb, TangentAtApexIsZeroLikeItsFiniteDifference) {
  const MohrCoulomb model = make();
  const auto internal = initial_internal(model);
  const Mat3 stress = start_for_trial(apex_trial);
  EXPECT_EQ(model.tangent(general_increment(), stress, internal), Mat6::Zero());
  EXPECT_LT(finite_difference_tangent(model, general_increment(), stress, internal).norm(),
            1e-9 * E);
}

TEST(MohrCoulomb, IntegrateWithTangentMatchesSeparateCallsWhenElastic) {
  const MohrCoulomb model = make();
  const Mat3 stress = -100e3 * Mat3::Identity();
  const Mat3 d = 0.1 * general_increment();
  ASSERT_EQ(model.return_mapping(stress + elastic_increment({E, nu}, d)).principal.regime,
            PrincipalRegime::elastic);
  expect_integrate_with_tangent_matches(model, d, stress, initial_internal(model));
}

TEST(MohrCoulomb, IntegrateWithTangentMatchesSeparateCallsOnMainPlane) {
  const MohrCoulomb model = make();
  const Mat3 stress = start_for_trial(main_plane_trial);
  ASSERT_EQ(regime_of(model, stress), PrincipalRegime::main_plane);
  expect_integrate_with_tangent_matches(model, general_increment(), stress,
                                        initial_internal(model));
}

TEST(MohrCoulomb, IntegrateWithTangentMatchesSeparateCallsOnRightEdge) {
  const MohrCoulomb model = make();
  const Mat3 stress = start_for_trial(right_edge_trial);
  ASSERT_EQ(regime_of(model, stress), PrincipalRegime::right_edge);
  expect_integrate_with_tangent_matches(model, general_increment(), stress,
                                        initial_internal(model));
}

TEST(MohrCoulomb, IntegrateWithTangentMatchesSeparateCallsOnLeftEdge) {
  const MohrCoulomb model = make();
  const Mat3 stress = start_for_trial(left_edge_trial);
  ASSERT_EQ(regime_of(model, stress), PrincipalRegime::left_edge);
  expect_integrate_with_tangent_matches(model, general_increment(), stress,
                                        initial_internal(model));
}

TEST(MohrCoulomb, IntegrateWithTangentMatchesSeparateCallsAtApex) {
  const MohrCoulomb model = make();
  const Mat3 stress = start_for_trial(apex_trial);
  ASSERT_EQ(regime_of(model, stress), PrincipalRegime::apex);
  expect_integrate_with_tangent_matches(model, general_increment(), stress,
                                        initial_internal(model));
}

TEST(MohrCoulomb, TriaxialCompressionStrengthEqualsMohrCoulombClosedForm) {
  // Arrange: drained triaxial (sigma_xx = sigma_zz = -100 kPa held, axial y compressed 5 %).
  const MohrCoulomb model = make();
  ElementTest test;
  test.kind = ElementTestKind::triaxial;
  test.initial_stress = -100e3;
  test.strain = -0.05;
  test.increments = 200;
  // Act
  const std::vector<ElementRow> rows = run_element_test(model, test);
  // Assert: with compression negative the axial stress is the most compressive (sigma3 of the
  // code, sigma1 of the compression-positive textbook formula) and the confining stress the
  // least: axial = confining (1 + sin phi)/(1 - sin phi) - 2 c cos phi / (1 - sin phi).
  const double sp = std::sin(phi * degree);
  const double confining = test.initial_stress;
  const double expected = confining * (1.0 + sp) / (1.0 - sp) -
                          2.0 * c * std::cos(phi * degree) / (1.0 - sp);  // -334.6 kPa
  EXPECT_NEAR(rows.back().axial_stress, expected, 1e-10 * std::abs(expected));
  EXPECT_NEAR(rows.back().lateral_stress, confining, 1e-9 * std::abs(confining));
}

TEST(MohrCoulomb, WithoutFrictionEqualsTresca) {
  // phi = psi = 0: Mohr-Coulomb is the Tresca prism with c_u = c.
  const MohrCoulomb mc = make({{"E", E}, {"nu", nu}, {"phi", 0.0}, {"psi", 0.0}, {"c", 50e3}});
  const Tresca tresca({E, nu}, 50e3);
  auto internal = initial_internal(mc);
  for (const Vec3& trial : {Vec3(0.0, -100e3, -200e3), Vec3(0.0, -190e3, -200e3)}) {
    Mat3 a = start_for_trial(trial), b = a;
    mc.integrate(general_increment(), a, internal);
    tresca.integrate(general_increment(), b, internal);
    EXPECT_LT((a - b).norm(), 1e-10 * 200e3);
  }
}

TEST(MohrCoulomb, ContinuumRateIsSmallIncrementLimitOfReturnMapping) {
  const MohrCoulomb model = make();
  for (const Vec3& trial : {main_plane_trial, left_edge_trial}) {
    auto internal = initial_internal(model);
    Mat3 stress = start_for_trial(trial);
    model.integrate(general_increment(), stress, internal);
    Mat3 D;
    D << 1.0, 0.3, 0.2, 0.3, -2.0, 0.1, 0.2, 0.1, 0.5;
    const Mat3 rate = model.objective_rate(D, stress, internal);
    const double dt = 1e-10;  // see the Tresca test: second order and round-off below 1e-7
    Mat3 stepped = stress;
    model.integrate(D * dt, stepped, internal);
    EXPECT_LT((rate - (stepped - stress) / dt).norm(), 1e-5 * rate.norm());
  }
}

TEST(MohrCoulomb, ContinuumRateIsElasticWhenUnloading) {
  const MohrCoulomb model = make();
  auto internal = initial_internal(model);
  Mat3 stress = start_for_trial(main_plane_trial);
  model.integrate(general_increment(), stress, internal);
  const Mat3 unloading = -general_increment();
  const Mat3 rate = model.objective_rate(unloading, stress, internal);
  EXPECT_LT((rate - elastic_increment({E, nu}, unloading)).norm(), 1e-12 * rate.norm());
}

TEST(MohrCoulomb, ContinuumRateAtApexUnderExtensionIsZero) {
  const MohrCoulomb model = make();
  const auto internal = initial_internal(model);
  Mat3 stretching = Mat3::Identity();
  stretching(0, 1) = stretching(1, 0) = 0.1;
  const Mat3 rate = model.objective_rate(stretching, apex() * Mat3::Identity(), internal);
  EXPECT_LT(rate.norm(), 1e-10 * E);
}

TEST(MohrCoulomb, RigidRotationLeavesInvariantsUnchanged) {
  const MohrCoulomb model = make();
  auto internal = initial_internal(model);
  Mat3 stress = start_for_trial(main_plane_trial);
  model.integrate(general_increment(), stress, internal);
  const double p0 = mean_stress(stress), j2_0 = j2(stress), j3_0 = j3(stress);
  const Vec3 axis = Vec3(1.0, 2.0, 3.0).normalized();
  Mat3 spin;
  spin << 0.0, -axis(2), axis(1), axis(2), 0.0, -axis(0), -axis(1), axis(0), 0.0;
  spin *= 1e-3;
  for (int step = 0; step < 1000; ++step) {
    update_stress(model, Mat3::Zero(), spin, stress, internal);
  }
  EXPECT_NEAR(mean_stress(stress), p0, 1e-10 * std::abs(p0));
  EXPECT_NEAR(j2(stress), j2_0, 1e-10 * j2_0);
  EXPECT_NEAR(j3(stress), j3_0, 1e-10 * std::abs(j3_0));
  EXPECT_EQ(internal[mohr_coulomb_corrections], 1.0);
}

TEST(MohrCoulomb, ModuliAreElastic) {
  const MohrCoulomb model = make();
  const ElasticModuli m = model.moduli(Mat3::Zero(), initial_internal(model));
  EXPECT_DOUBLE_EQ(m.bulk, E / (3.0 * (1.0 - 2.0 * nu)));
  EXPECT_DOUBLE_EQ(m.shear, E / (2.0 * (1.0 + nu)));
}

TEST(MohrCoulomb, InternalVariablesAreNamedForTheirMeaning) {
  const auto variables = make().internal_variables();
  ASSERT_EQ(variables.size(), 2u);
  EXPECT_EQ(variables[mohr_coulomb_plastic_strain].name, "plastic_strain");
  EXPECT_EQ(variables[mohr_coulomb_corrections].name, "corrections");
}

void expect_refused(std::map<std::string, ParameterValue> values,
                    const std::vector<std::string>& fragments) {
  expect_model_refused("mohr-coulomb", std::move(values), "material.sand", fragments);
}

TEST(MohrCoulombParameters, DilatancyAboveFrictionIsRefused) {
  auto values = soil();
  values["psi"] = 35.0;
  expect_refused(values, {"material.sand.psi = 35", "[0, 30]", "deg"});
}

TEST(MohrCoulombParameters, FrictionAngleOfNinetyIsRefused) {
  auto values = soil();
  values["phi"] = 90.0;
  expect_refused(values, {"material.sand.phi = 90", "[0, 90)", "deg"});
}

TEST(MohrCoulombParameters, NegativeCohesionIsRefused) {
  auto values = soil();
  values["c"] = -1.0;
  expect_refused(values, {"material.sand.c = -1", ">= 0", "Pa"});
}

TEST(MohrCoulombParameters, NoStrengthAtAllIsRefused) {
  auto values = soil();
  values["phi"] = 0.0;
  values["psi"] = 0.0;
  values["c"] = 0.0;
  expect_refused(values, {"material.sand.c = 0", "> 0", "Pa"});
}

TEST(MohrCoulombParameters, UnknownKeyIsRefused) {
  auto values = soil();
  values["cu"] = 1.0;
  expect_refused(values, {"material.sand.cu: unknown parameter"});
}

TEST(MohrCoulombParameters, RegistryExampleIsCohesionlessSand) {
  const ModelInfo& info = builtin_models().find("mohr-coulomb");
  EXPECT_EQ(std::get<double>(info.example.at("phi")), 30.0);
  EXPECT_EQ(std::get<double>(info.example.at("c")), 0.0);
  EXPECT_NO_THROW(make_model("mohr-coulomb", info.example, "material.sand"));
}

}  // namespace
}  // namespace duet::constitutive
