// Unit tests of constitutive/tresca.cpp: one test per regime of the return mapping (elastic, main
// plane, right edge, left edge) with their closed forms (constitutive/docs/tresca.md), the
// consistent tangent against finite differences, integrate_with_tangent against integrate and
// tangent in each regime, the continuum rate, objectivity under rigid rotation, the internal
// variables and parameter refusal.

#include "constitutive/tresca.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/input_error.hpp"
#include "constitutive/objective.hpp"
#include "tests/constitutive/refusal.hpp"
#include "tests/constitutive/same_return.hpp"

namespace duet::constitutive {
namespace {

constexpr double E = 10e6;  // Pa
constexpr double nu = 0.3;
constexpr double cu = 50e3;  // Pa

std::map<std::string, ParameterValue> clay() {
  return {{"E", E}, {"nu", nu}, {"cu", cu}};
}

Tresca make(std::map<std::string, ParameterValue> values = clay()) {
  auto model = make_model("tresca", std::move(values), "material.clay");
  return dynamic_cast<const Tresca&>(*model);
}

std::vector<double> initial_internal(const Model& model) {
  std::vector<double> internal;
  for (const auto& v : model.internal_variables()) internal.push_back(v.initial);
  return internal;
}

double relative_difference(const Mat6& a, const Mat6& b) {
  return (a - b).norm() / b.norm();
}

/// A rotation that mixes all three axes, so principal frames are not the coordinate axes.
Mat3 rotation() {
  return Eigen::AngleAxisd(0.7, Vec3(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
}

/// A strain increment with all six components.
Mat3 general_increment() {
  Mat3 d;
  d << 2e-4, 3e-4, -1e-4, 3e-4, -4e-4, 0.5e-4, -1e-4, 0.5e-4, 1e-4;
  return d;
}

/// The start stress whose elastic trial under general_increment() has the given principal
/// values in the frame rotation(): trial = R diag(values) R^T.
Mat3 start_for_trial(const Vec3& principal_trial) {
  const Mat3 R = rotation();
  return R * principal_trial.asDiagonal() * R.transpose() -
         elastic_increment({E, nu}, general_increment());
}

Vec3 principal(const Mat3& s) {
  return spectral_decomposition(s).values;
}

TEST(TrescaSurface, MainPlaneIsTwiceTheUndrainedStrength) {
  const FacetedSurface s = tresca_surface(cu);
  EXPECT_DOUBLE_EQ(s.main.value(Vec3(cu, 0.0, -cu)), 0.0);
  EXPECT_FALSE(s.apex.has_value());
}

TEST(Tresca, ElasticIncrementInsideSurfaceIsHooke) {
  // Arrange
  const Tresca model = make();
  auto internal = initial_internal(model);
  Mat3 stress = -100e3 * Mat3::Identity();
  const Mat3 d = 0.1 * general_increment();  // sigma1 - sigma3 well below 2 c_u
  // Act
  model.integrate(d, stress, internal);
  // Assert
  EXPECT_LT((stress - (-100e3 * Mat3::Identity() + elastic_increment({E, nu}, d))).norm(), 1e-9);
  EXPECT_EQ(internal[tresca_corrections], 0.0);
}

TEST(Tresca, ZeroStrainIncrementLeavesStressUnchanged) {
  // Arrange: a state on the surface (after a plastic step) and one inside.
  const Tresca model = make();
  auto internal = initial_internal(model);
  Mat3 on_surface = start_for_trial(Vec3(0.0, -100e3, -200e3));
  model.integrate(general_increment(), on_surface, internal);
  const Mat3 before = on_surface;
  const double corrections = internal[tresca_corrections];
  // Act
  model.integrate(Mat3::Zero(), on_surface, internal);
  // Assert
  EXPECT_EQ(on_surface, before);
  EXPECT_EQ(internal[tresca_corrections], corrections);
}

TEST(Tresca, MainPlaneReturnLandsOnSurfaceWithClosedForm) {
  // Arrange: trial principal stresses (0, -100, -200) kPa: f_trial = 100 kPa.
  const Tresca model = make();
  auto internal = initial_internal(model);
  Mat3 stress = start_for_trial(Vec3(0.0, -100e3, -200e3));
  // Act
  model.integrate(general_increment(), stress, internal);
  // Assert: Box 8.1: sigma1,3 = (s1 + s3)/2 +- c_u, sigma2 unchanged, frame unchanged.
  const Vec3 s = principal(stress);
  EXPECT_NEAR(s(0) - s(2), 2.0 * cu, 1e-10 * 2.0 * cu);
  EXPECT_NEAR(s(0), -50e3, 1e-10 * 200e3);
  EXPECT_NEAR(s(1), -100e3, 1e-10 * 200e3);
  EXPECT_NEAR(s(2), -150e3, 1e-10 * 200e3);
  const Mat3 R = rotation();
  EXPECT_LT((stress - R * s.asDiagonal() * R.transpose()).norm(), 1e-10 * 200e3);
  // Plastic strain d_gamma (e1e1 - e3e3): equivalent sqrt(4/3) d_gamma, d_gamma = f/(4G).
  const double G = E / (2.0 * (1.0 + nu));
  EXPECT_NEAR(internal[tresca_plastic_strain], std::sqrt(4.0 / 3.0) * 100e3 / (4.0 * G), 1e-15);
  EXPECT_EQ(internal[tresca_corrections], 1.0);
}

TEST(Tresca, RightEdgeReturnLandsOnBothPlanes) {
  // Arrange: sigma2 near sigma3.
  const Tresca model = make();
  auto internal = initial_internal(model);
  const Vec3 trial(0.0, -190e3, -200e3);
  Mat3 stress = start_for_trial(trial);
  // Act
  const StressReturn r =
      model.return_mapping(stress + elastic_increment({E, nu}, general_increment()));
  model.integrate(general_increment(), stress, internal);
  // Assert: sigma1 - sigma3 = sigma1 - sigma2 = 2 c_u; p kept (isochoric flow).
  EXPECT_EQ(r.principal.regime, PrincipalRegime::right_edge);
  const Vec3 s = principal(stress);
  const double scale = 200e3;
  EXPECT_NEAR(s(0) - s(2), 2.0 * cu, 1e-10 * scale);
  EXPECT_NEAR(s(0) - s(1), 2.0 * cu, 1e-10 * scale);
  EXPECT_NEAR(s.sum(), trial.sum(), 1e-10 * scale);
  EXPECT_NEAR(s(0), trial.sum() / 3.0 + 4.0 * cu / 3.0, 1e-10 * scale);
}

TEST(Tresca, LeftEdgeReturnLandsOnBothPlanes) {
  const Tresca model = make();
  auto internal = initial_internal(model);
  const Vec3 trial(0.0, -10e3, -200e3);
  Mat3 stress = start_for_trial(trial);
  const StressReturn r =
      model.return_mapping(stress + elastic_increment({E, nu}, general_increment()));
  model.integrate(general_increment(), stress, internal);
  EXPECT_EQ(r.principal.regime, PrincipalRegime::left_edge);
  const Vec3 s = principal(stress);
  const double scale = 200e3;
  EXPECT_NEAR(s(0) - s(2), 2.0 * cu, 1e-10 * scale);
  EXPECT_NEAR(s(1) - s(2), 2.0 * cu, 1e-10 * scale);
  EXPECT_NEAR(s(2), trial.sum() / 3.0 - 4.0 * cu / 3.0, 1e-10 * scale);
}

TEST(Tresca, ConsistentTangentEqualsFiniteDifferenceOnMainPlaneAndEdges) {
  // Trial principal values distinct in each case, so the finite difference is smooth.
  const Tresca model = make();
  const auto internal = initial_internal(model);
  const Vec3 trials[] = {Vec3(0.0, -100e3, -200e3), Vec3(0.0, -190e3, -200e3),
                         Vec3(0.0, -10e3, -200e3)};
  const PrincipalRegime regimes[] = {PrincipalRegime::main_plane, PrincipalRegime::right_edge,
                                     PrincipalRegime::left_edge};
  for (int k = 0; k < 3; ++k) {
    const Mat3 stress = start_for_trial(trials[k]);
    ASSERT_EQ(model.return_mapping(stress + elastic_increment({E, nu}, general_increment()))
                  .principal.regime,
              regimes[k]);
    // Act
    const Mat6 analytic = model.tangent(general_increment(), stress, internal);
    const Mat6 numeric = finite_difference_tangent(model, general_increment(), stress, internal);
    // Assert
    EXPECT_LT(relative_difference(analytic, numeric), 1e-6) << principal_regime_name(regimes[k]);
  }
}

TEST(Tresca, TangentIsElasticStiffnessInElasticRegime) {
  const Tresca model = make();
  const auto internal = initial_internal(model);
  const Mat6 C = elastic_stiffness({E, nu});
  EXPECT_EQ(model.tangent(0.1 * general_increment(), -100e3 * Mat3::Identity(), internal), C);
}

TEST(Tresca, IntegrateWithTangentMatchesSeparateCallsWhenElastic) {
  const Tresca model = make();
  const Mat3 stress = -100e3 * Mat3::Identity();
  const Mat3 d = 0.1 * general_increment();
  ASSERT_EQ(model.return_mapping(stress + elastic_increment({E, nu}, d)).principal.regime,
            PrincipalRegime::elastic);
  expect_integrate_with_tangent_matches(model, d, stress, initial_internal(model));
}

TEST(Tresca, IntegrateWithTangentMatchesSeparateCallsOnMainPlane) {
  const Tresca model = make();
  const Mat3 stress = start_for_trial(Vec3(0.0, -100e3, -200e3));
  ASSERT_EQ(model.return_mapping(stress + elastic_increment({E, nu}, general_increment()))
                .principal.regime,
            PrincipalRegime::main_plane);
  expect_integrate_with_tangent_matches(model, general_increment(), stress,
                                        initial_internal(model));
}

TEST(Tresca, IntegrateWithTangentMatchesSeparateCallsOnRightEdge) {
  const Tresca model = make();
  const Mat3 stress = start_for_trial(Vec3(0.0, -190e3, -200e3));
  ASSERT_EQ(model.return_mapping(stress + elastic_increment({E, nu}, general_increment()))
                .principal.regime,
            PrincipalRegime::right_edge);
  expect_integrate_with_tangent_matches(model, general_increment(), stress,
                                        initial_internal(model));
}

TEST(Tresca, IntegrateWithTangentMatchesSeparateCallsOnLeftEdge) {
  const Tresca model = make();
  const Mat3 stress = start_for_trial(Vec3(0.0, -10e3, -200e3));
  ASSERT_EQ(model.return_mapping(stress + elastic_increment({E, nu}, general_increment()))
                .principal.regime,
            PrincipalRegime::left_edge);
  expect_integrate_with_tangent_matches(model, general_increment(), stress,
                                        initial_internal(model));
}

TEST(Tresca, ContinuumRateIsSmallIncrementLimitOfReturnMapping) {
  // Arrange: on the main plane, then a further loading stretching.
  const Tresca model = make();
  auto internal = initial_internal(model);
  Mat3 stress = start_for_trial(Vec3(0.0, -100e3, -200e3));
  model.integrate(general_increment(), stress, internal);
  // A stretching rate (1/s) that widens sigma1 - sigma3 in the principal frame, plus shear.
  Mat3 D = rotation() * Vec3(1.0, 0.3, -1.0).asDiagonal() * rotation().transpose();
  D(0, 1) += 0.2;
  D(1, 0) += 0.2;
  // Act
  const Mat3 rate = model.objective_rate(D, stress, internal);
  // Step: small enough that the second-order rotation of the eigenvectors, (E |D| dt)^2 / gap,
  // stays below 1e-7 of the rate; large enough that round-off (1e-16 sigma / dt) does too.
  const double dt = 1e-10;
  Mat3 stepped = stress;
  model.integrate(D * dt, stepped, internal);
  // Assert: the rate keeps sigma1 - sigma3 and is the limit of the return mapping.
  EXPECT_LT((rate - (stepped - stress) / dt).norm(), 1e-6 * rate.norm());
  EXPECT_GT((rate - elastic_increment({E, nu}, D)).norm(), 0.1 * rate.norm());  // plastic
}

TEST(Tresca, ContinuumRateOnEdgeIsSmallIncrementLimitOfReturnMapping) {
  // Arrange: on the left edge (sigma1 = sigma2), loaded by a stretching that splits them.
  const Tresca model = make();
  auto internal = initial_internal(model);
  Mat3 stress = start_for_trial(Vec3(0.0, -10e3, -200e3));
  model.integrate(general_increment(), stress, internal);
  Mat3 D;
  D << 1.0, 0.3, 0.2, 0.3, -2.0, 0.1, 0.2, 0.1, 0.5;
  // Act
  const Mat3 rate = model.objective_rate(D, stress, internal);
  const double dt = 1e-10;
  Mat3 stepped = stress;
  model.integrate(D * dt, stepped, internal);
  // Assert
  EXPECT_LT((rate - (stepped - stress) / dt).norm(), 1e-5 * rate.norm());
}

TEST(Tresca, ContinuumRateIsElasticWhenUnloading) {
  const Tresca model = make();
  auto internal = initial_internal(model);
  Mat3 stress = start_for_trial(Vec3(0.0, -100e3, -200e3));
  model.integrate(general_increment(), stress, internal);
  const Mat3 unloading = -general_increment();
  const Mat3 rate = model.objective_rate(unloading, stress, internal);
  EXPECT_LT((rate - elastic_increment({E, nu}, unloading)).norm(), 1e-12 * rate.norm());
}

TEST(Tresca, RigidRotationLeavesInvariantsUnchanged) {
  // Arrange: a state on the surface (J3 != 0), rotated 1000 times by 1e-3 rad, zero stretching.
  const Tresca model = make();
  auto internal = initial_internal(model);
  Mat3 stress = start_for_trial(Vec3(0.0, -120e3, -200e3));
  model.integrate(general_increment(), stress, internal);
  const double p0 = mean_stress(stress), j2_0 = j2(stress), j3_0 = j3(stress);
  const Vec3 axis = Vec3(1.0, 2.0, 3.0).normalized();
  Mat3 spin;  // skew(axis) * angle
  spin << 0.0, -axis(2), axis(1), axis(2), 0.0, -axis(0), -axis(1), axis(0), 0.0;
  spin *= 1e-3;
  // Act
  for (int step = 0; step < 1000; ++step) {
    update_stress(model, Mat3::Zero(), spin, stress, internal);
  }
  // Assert
  EXPECT_NEAR(mean_stress(stress), p0, 1e-10 * std::abs(p0));
  EXPECT_NEAR(j2(stress), j2_0, 1e-10 * j2_0);
  EXPECT_NEAR(j3(stress), j3_0, 1e-10 * std::abs(j3_0));
  EXPECT_EQ(internal[tresca_corrections], 1.0);  // rotation alone never yields
}

TEST(Tresca, CorrectReturnsDriftedStateToSurface) {
  const Tresca model = make();
  auto internal = initial_internal(model);
  Mat3 stress = -100e3 * Mat3::Identity();
  stress(0, 1) = stress(1, 0) = 80e3;  // sigma1 - sigma3 = 160 kPa > 2 c_u
  model.correct(stress, internal);
  EXPECT_NEAR(model.yield_function(stress), 0.0, 1e-10 * 200e3);
  EXPECT_GT(internal[tresca_plastic_strain], 0.0);
}

TEST(Tresca, ModuliAreElastic) {
  const Tresca model = make();
  const ElasticModuli m = model.moduli(Mat3::Zero(), initial_internal(model));
  EXPECT_DOUBLE_EQ(m.bulk, E / (3.0 * (1.0 - 2.0 * nu)));
  EXPECT_DOUBLE_EQ(m.shear, E / (2.0 * (1.0 + nu)));
}

TEST(Tresca, InternalVariablesAreNamedForTheirMeaning) {
  const auto variables = make().internal_variables();
  ASSERT_EQ(variables.size(), 2u);
  EXPECT_EQ(variables[tresca_plastic_strain].name, "plastic_strain");
  EXPECT_EQ(variables[tresca_corrections].name, "corrections");
}

void expect_refused(std::map<std::string, ParameterValue> values,
                    const std::vector<std::string>& fragments) {
  expect_model_refused("tresca", std::move(values), "material.clay", fragments);
}

TEST(TrescaParameters, ZeroUndrainedStrengthIsRefused) {
  auto values = clay();
  values["cu"] = 0.0;
  expect_refused(values, {"material.clay.cu = 0", "> 0", "Pa"});
}

TEST(TrescaParameters, IncompressiblePoissonRatioIsRefused) {
  auto values = clay();
  values["nu"] = 0.5;
  expect_refused(values, {"material.clay.nu = 0.5", "[0, 0.5)"});
}

TEST(TrescaParameters, NegativeYoungsModulusIsRefused) {
  auto values = clay();
  values["E"] = -1.0;
  expect_refused(values, {"material.clay.E = -1", "> 0", "Pa"});
}

TEST(TrescaParameters, MissingUndrainedStrengthIsRefused) {
  auto values = clay();
  values.erase("cu");
  expect_refused(values, {"material.clay.cu: missing", "Pa"});
}

TEST(TrescaParameters, UnknownKeyIsRefused) {
  auto values = clay();
  values["c"] = 1.0;
  expect_refused(values, {"material.clay.c: unknown parameter"});
}

TEST(TrescaParameters, RegistryExampleHasZhangFootingRigidity) {
  // Zhang 2018 (papers/004, fig 12a): I_r = G / c_u = 33.4; the example gives E/c_u = 100.
  const ModelInfo& info = builtin_models().find("tresca");
  const double E_example = std::get<double>(info.example.at("E"));
  const double nu_example = std::get<double>(info.example.at("nu"));
  const double cu_example = std::get<double>(info.example.at("cu"));
  const double rigidity = E_example / (2.0 * (1.0 + nu_example)) / cu_example;
  EXPECT_NEAR(rigidity, 33.4, 0.5);
  EXPECT_NO_THROW(make_model("tresca", info.example, "material.clay"));
}

}  // namespace
}  // namespace duet::constitutive
