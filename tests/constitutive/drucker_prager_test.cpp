// Unit tests of constitutive/drucker_prager.cpp: one test per regime of the return mapping
// (elastic, cone, tension cut-off, corner, apex), the consistent tangent against finite
// differences, integrate_with_tangent against integrate and tangent in each regime, the continuum
// rate (Bui 2008 eqs 8-9), objectivity, and parameter refusal.
// Closed forms used here are derived in constitutive/docs/drucker_prager.md.

#include "constitutive/drucker_prager.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "common/input_error.hpp"
#include "constitutive/objective.hpp"
#include "tests/constitutive/refusal.hpp"
#include "tests/constitutive/same_return.hpp"

namespace duet::constitutive {
namespace {

constexpr double E = 20e6;  // Pa
constexpr double nu = 0.3;
constexpr double phi = 30.0;  // deg
constexpr double psi = 10.0;  // deg
constexpr double c = 10e3;    // Pa

std::map<std::string, ParameterValue> soil() {
  return {{"E", E}, {"nu", nu}, {"phi", phi}, {"psi", psi}, {"c", c}};
}

DruckerPrager make(std::map<std::string, ParameterValue> values = soil()) {
  auto model = make_model("drucker-prager", std::move(values), "material.sand");
  return dynamic_cast<const DruckerPrager&>(*model);
}

std::vector<double> initial_internal(const Model& model) {
  std::vector<double> internal;
  for (const auto& v : model.internal_variables()) internal.push_back(v.initial);
  return internal;
}

double relative_surface_error(const DruckerPrager& model, const Mat3& stress) {
  return std::abs(model.cone().yield_function(stress)) / model.stress_scale(stress);
}

double relative_difference(const Mat6& a, const Mat6& b) {
  return (a - b).norm() / b.norm();
}

Mat3 diagonal(double xx, double yy, double zz) {
  return Vec3(xx, yy, zz).asDiagonal();
}

/// A general compressive state (all six components) inside the cone of soil().
Mat3 general_stress() {
  Mat3 s;
  s << -120e3, 15e3, -8e3, 15e3, -90e3, 5e3, -8e3, 5e3, -100e3;
  return s;
}

/// A strain increment with shear that pushes general_stress() well past the cone.
Mat3 shearing_increment() {
  Mat3 d;
  d << 2e-3, 3e-3, -1e-3, 3e-3, -4e-3, 0.5e-3, -1e-3, 0.5e-3, 1e-3;
  return d;
}

TEST(DruckerPragerCone, ApexLiesAtCohesionTimesCotPhi) {
  // Arrange
  const auto cone = DruckerPragerCone::from_coulomb(phi, psi, c);
  // Act
  const double apex = cone.apex_mean_stress();
  // Assert: the cone and Mohr-Coulomb share the apex p = c cot(phi).
  EXPECT_NEAR(apex, c / std::tan(phi * std::numbers::pi / 180.0), 1e-9 * apex);
  EXPECT_NEAR(cone.yield_function(apex * Mat3::Identity()), 0.0, 1e-9 * c);
}

TEST(DruckerPragerCone, YieldFunctionIsNegativeUnderIsotropicCompression) {
  const auto cone = DruckerPragerCone::from_coulomb(phi, psi, c);
  EXPECT_LT(cone.yield_function(-100e3 * Mat3::Identity()), 0.0);
  EXPECT_LT(cone.yield_function(Mat3::Zero()), 0.0);  // cohesive: the origin is inside
}

TEST(DruckerPragerCone, PlaneStrainAssociatedFitReducesToMohrCoulombFactor) {
  // With psi = phi, 1 - 3 alpha^2 = 9 / (cos^2 phi (9 + 12 tan^2 phi)) (docs, "plane strain"),
  // which is what makes the plane-strain peak equal Mohr-Coulomb.
  const auto cone = DruckerPragerCone::from_coulomb(phi, phi, c);
  const double t = std::tan(phi * std::numbers::pi / 180.0);
  const double cos_phi = std::cos(phi * std::numbers::pi / 180.0);
  EXPECT_NEAR(std::sqrt(1.0 - 3.0 * cone.alpha_phi * cone.alpha_phi),
              3.0 / (cos_phi * std::sqrt(9.0 + 12.0 * t * t)), 1e-14);
  EXPECT_DOUBLE_EQ(cone.alpha_phi, cone.alpha_psi);
}

TEST(DruckerPrager, ElasticIncrementInsideConeIsHooke) {
  // Arrange
  const auto model = make();
  auto internal = initial_internal(model);
  Mat3 stress = -100e3 * Mat3::Identity();
  const Mat3 d_strain = diagonal(-1e-4, 0.5e-4, 0.0);
  // Act
  model.integrate(d_strain, stress, internal);
  // Assert
  const ElasticParameters elastic{E, nu};
  const Mat3 expected = -100e3 * Mat3::Identity() + elastic_increment(elastic, d_strain);
  EXPECT_LT((stress - expected).norm(), 1e-12 * expected.norm());
  EXPECT_EQ(internal[drucker_prager_plastic_strain], 0.0);
}

TEST(DruckerPrager, ZeroStrainIncrementLeavesStressUnchanged) {
  // Arrange: one state inside, one on the cone (after a plastic step).
  const auto model = make();
  auto internal = initial_internal(model);
  Mat3 on_surface = general_stress();
  model.integrate(shearing_increment(), on_surface, internal);
  const Mat3 inside = general_stress();
  const auto internal_before = internal;
  // Act
  Mat3 a = inside, b = on_surface;
  model.integrate(Mat3::Zero(), a, internal);
  model.integrate(Mat3::Zero(), b, internal);
  // Assert
  EXPECT_EQ(a, inside);
  EXPECT_EQ(b, on_surface);
  EXPECT_EQ(internal, internal_before);
}

TEST(DruckerPrager, SmoothReturnLandsOnConeAndKeepsLodeAngle) {
  // Arrange
  const auto model = make();
  const ElasticParameters elastic{E, nu};
  const Mat3 trial = general_stress() + elastic_increment(elastic, shearing_increment());
  ASSERT_GT(model.cone().yield_function(trial), 0.0);
  // Act
  const auto result = model.return_mapping(trial);
  // Assert
  EXPECT_EQ(result.regime, DruckerPragerRegime::cone);
  EXPECT_LT(relative_surface_error(model, result.stress), 1e-10);
  EXPECT_NEAR(lode_angle(result.stress), lode_angle(trial), 1e-12);  // radial in the deviator
}

TEST(DruckerPrager, PlasticStrainFollowsNonAssociatedFlowDirection) {
  // Arrange
  const auto model = make();
  auto internal = initial_internal(model);
  const ElasticParameters elastic{E, nu};
  Mat3 stress = general_stress();
  const Mat3 trial = stress + elastic_increment(elastic, shearing_increment());
  // Act
  model.integrate(shearing_increment(), stress, internal);
  // Assert: d eps_p = C^-1 (trial - sigma) is parallel to dg/dsigma = alpha_psi I + s/(2 sqrt J2)
  // (Bui 2008 eqs 4, 7): tr(d eps_p) / |dev(d eps_p)| = 3 sqrt(2) alpha_psi.
  const Mat3 d_stress = trial - stress;
  const Mat3 d_plastic = deviator(d_stress) / (2.0 * elastic.shear_modulus()) +
                         mean_stress(d_stress) / (3.0 * elastic.bulk_modulus()) * identity3();
  const double dilatancy_ratio = d_plastic.trace() / norm(deviator(d_plastic));
  EXPECT_NEAR(dilatancy_ratio, 3.0 * std::sqrt(2.0) * model.cone().alpha_psi, 1e-9);
  // The deviatoric plastic strain is parallel to the returned deviator.
  const Mat3 n_plastic = deviator(d_plastic) / norm(deviator(d_plastic));
  const Mat3 n_stress = deviator(stress) / norm(deviator(stress));
  EXPECT_LT(norm(n_plastic - n_stress), 1e-9);
  EXPECT_NEAR(internal[drucker_prager_plastic_strain],
              std::sqrt(2.0 / 3.0 * contract(d_plastic, d_plastic)), 1e-15);
  EXPECT_EQ(internal[drucker_prager_corrections], 0.0);
}

TEST(DruckerPrager, TensileTrialReturnsToApex) {
  // Arrange: isotropic extension beyond the apex c cot(phi) = 17.3 kPa, plus a little shear.
  const auto model = make();
  auto internal = initial_internal(model);
  Mat3 stress = Mat3::Zero();
  Mat3 d_strain = 1e-3 * Mat3::Identity();
  d_strain(0, 1) = d_strain(1, 0) = 1e-5;
  // Act
  model.integrate(d_strain, stress, internal);
  // Assert: isotropic, on the apex, f = 0 there; counted as a correction.
  const double apex = model.cone().apex_mean_stress();
  EXPECT_LT(norm(deviator(stress)), 1e-12 * apex);
  EXPECT_NEAR(mean_stress(stress), apex, 1e-12 * apex);
  EXPECT_LT(relative_surface_error(model, stress), 1e-10);
  EXPECT_EQ(internal[drucker_prager_corrections], 1.0);
  EXPECT_GT(internal[drucker_prager_plastic_strain], 0.0);
}

TEST(DruckerPrager, TensileTrialWithLargeShearReturnsToConeNotApex) {
  // Arrange: p_trial beyond the apex, but sqrt(J2) large enough that the dilatant return
  // (dp = -3 K alpha_psi dl) lands on the cone below the apex (docs, "regions").
  const auto model = make();
  const double apex = model.cone().apex_mean_stress();
  Mat3 trial = (apex + 1e3) * Mat3::Identity();
  trial(0, 1) = trial(1, 0) = 400e3;
  // Act
  const auto result = model.return_mapping(trial);
  // Assert
  EXPECT_EQ(result.regime, DruckerPragerRegime::cone);
  EXPECT_LT(mean_stress(result.stress), apex);
  EXPECT_LT(relative_surface_error(model, result.stress), 1e-10);
}

TEST(DruckerPrager, TrialPastCutoffWithSmallShearReturnsToCutoffKeepingDeviator) {
  // Arrange: cut-off at 5 kPa, below the apex 17.3 kPa.
  auto values = soil();
  values["tension_cutoff"] = 5e3;
  const auto model = make(values);
  Mat3 trial = 8e3 * Mat3::Identity();
  trial(0, 1) = trial(1, 0) = 2e3;
  // Act
  const auto result = model.return_mapping(trial);
  // Assert
  EXPECT_EQ(result.regime, DruckerPragerRegime::cutoff);
  EXPECT_NEAR(mean_stress(result.stress), 5e3, 1e-12 * 5e3);
  EXPECT_LT(norm(deviator(result.stress) - deviator(trial)), 1e-12 * norm(trial));
  EXPECT_LT(model.cone().yield_function(result.stress), 0.0);
}

TEST(DruckerPrager, TrialPastCutoffWithLargeShearReturnsToCorner) {
  // Arrange
  auto values = soil();
  values["tension_cutoff"] = 5e3;
  const auto model = make(values);
  Mat3 trial = 15e3 * Mat3::Identity();
  trial(0, 1) = trial(1, 0) = 10e3;
  // Act
  const auto result = model.return_mapping(trial);
  // Assert: on both the cut-off and the cone, deviator direction kept.
  EXPECT_EQ(result.regime, DruckerPragerRegime::corner);
  EXPECT_NEAR(mean_stress(result.stress), 5e3, 1e-12 * 5e3);
  EXPECT_LT(relative_surface_error(model, result.stress), 1e-10);
  EXPECT_NEAR(lode_angle(result.stress), lode_angle(trial), 1e-12);
}

TEST(DruckerPrager, ConsistentTangentEqualsFiniteDifferenceOnSmoothReturn) {
  // Arrange
  const auto model = make();
  const auto internal = initial_internal(model);
  const Mat3 stress = general_stress();
  const Mat3 d_strain = shearing_increment();
  ASSERT_EQ(model.return_mapping(stress + elastic_increment({E, nu}, d_strain)).regime,
            DruckerPragerRegime::cone);
  // Act
  const Mat6 analytic = model.tangent(d_strain, stress, internal);
  const Mat6 numeric = finite_difference_tangent(model, d_strain, stress, internal);
  // Assert
  EXPECT_LT(relative_difference(analytic, numeric), 1e-6);
  // Non-associated flow: the consistent tangent is not symmetric.
  EXPECT_GT((analytic - analytic.transpose()).norm(), 1e-3 * analytic.norm());
}

TEST(DruckerPrager, ConsistentTangentEqualsFiniteDifferenceOnCutoffAndCorner) {
  // Arrange
  auto values = soil();
  values["tension_cutoff"] = 5e3;
  const auto model = make(values);
  const auto internal = initial_internal(model);
  Mat3 stress = 2e3 * Mat3::Identity();
  stress(0, 1) = stress(1, 0) = 1e3;
  Mat3 small_shear = 1e-3 * Mat3::Identity();
  small_shear(0, 2) = small_shear(2, 0) = 1e-4;
  Mat3 large_shear = small_shear;
  large_shear(0, 2) = large_shear(2, 0) = 2e-3;
  // Act / Assert
  for (const Mat3& d_strain : {small_shear, large_shear}) {
    const Mat6 analytic = model.tangent(d_strain, stress, internal);
    const Mat6 numeric = finite_difference_tangent(model, d_strain, stress, internal);
    EXPECT_LT(relative_difference(analytic, numeric), 1e-6);
  }
  EXPECT_EQ(model.return_mapping(stress + elastic_increment({E, nu}, small_shear)).regime,
            DruckerPragerRegime::cutoff);
  EXPECT_EQ(model.return_mapping(stress + elastic_increment({E, nu}, large_shear)).regime,
            DruckerPragerRegime::corner);
}

TEST(DruckerPrager, TangentAtApexIsZeroLikeItsFiniteDifference) {
  // Arrange
  const auto model = make();
  const auto internal = initial_internal(model);
  const Mat3 d_strain = 1e-3 * Mat3::Identity();
  // Act
  const Mat6 analytic = model.tangent(d_strain, Mat3::Zero(), internal);
  const Mat6 numeric = finite_difference_tangent(model, d_strain, Mat3::Zero(), internal);
  // Assert: the stress is pinned at the apex, so d sigma / d eps = 0.
  EXPECT_EQ(analytic.norm(), 0.0);
  EXPECT_LT(numeric.norm(), 1e-6 * elastic_stiffness({E, nu}).norm());
}

TEST(DruckerPrager, IntegrateWithTangentMatchesSeparateCallsWhenElastic) {
  const auto model = make();
  const Mat3 stress = -100e3 * Mat3::Identity();
  const Mat3 d_strain = diagonal(-1e-4, 0.5e-4, 0.0);
  ASSERT_EQ(model.return_mapping(stress + elastic_increment({E, nu}, d_strain)).regime,
            DruckerPragerRegime::elastic);
  expect_integrate_with_tangent_matches(model, d_strain, stress, initial_internal(model));
}

TEST(DruckerPrager, IntegrateWithTangentMatchesSeparateCallsOnCone) {
  const auto model = make();
  const Mat3 stress = general_stress();
  ASSERT_EQ(model.return_mapping(stress + elastic_increment({E, nu}, shearing_increment())).regime,
            DruckerPragerRegime::cone);
  expect_integrate_with_tangent_matches(model, shearing_increment(), stress,
                                        initial_internal(model));
}

TEST(DruckerPrager, IntegrateWithTangentMatchesSeparateCallsOnCutoffAndCorner) {
  // The set-up of ConsistentTangentEqualsFiniteDifferenceOnCutoffAndCorner.
  auto values = soil();
  values["tension_cutoff"] = 5e3;
  const auto model = make(values);
  Mat3 stress = 2e3 * Mat3::Identity();
  stress(0, 1) = stress(1, 0) = 1e3;
  Mat3 small_shear = 1e-3 * Mat3::Identity();
  small_shear(0, 2) = small_shear(2, 0) = 1e-4;
  Mat3 large_shear = small_shear;
  large_shear(0, 2) = large_shear(2, 0) = 2e-3;
  ASSERT_EQ(model.return_mapping(stress + elastic_increment({E, nu}, small_shear)).regime,
            DruckerPragerRegime::cutoff);
  ASSERT_EQ(model.return_mapping(stress + elastic_increment({E, nu}, large_shear)).regime,
            DruckerPragerRegime::corner);
  expect_integrate_with_tangent_matches(model, small_shear, stress, initial_internal(model));
  expect_integrate_with_tangent_matches(model, large_shear, stress, initial_internal(model));
}

TEST(DruckerPrager, IntegrateWithTangentMatchesSeparateCallsAtApex) {
  // The set-up of TensileTrialReturnsToApex: isotropic extension past c cot(phi), a little shear.
  const auto model = make();
  Mat3 d_strain = 1e-3 * Mat3::Identity();
  d_strain(0, 1) = d_strain(1, 0) = 1e-5;
  const DruckerPragerReturn r = model.return_mapping(elastic_increment({E, nu}, d_strain));
  ASSERT_EQ(r.regime, DruckerPragerRegime::corner);
  ASSERT_LT(norm(deviator(r.stress)), 1e-12 * model.cone().apex_mean_stress());  // the apex
  expect_integrate_with_tangent_matches(model, d_strain, Mat3::Zero(), initial_internal(model));
}

TEST(DruckerPrager, IsotropicTensileTrialReturnsExactlyToApex) {
  // Arrange: a trial with no deviator at all (the flow direction of the cone is undefined).
  const auto model = make();
  auto internal = initial_internal(model);
  Mat3 stress = Mat3::Zero();
  // Act
  model.integrate(1e-3 * Mat3::Identity(), stress, internal);
  // Assert
  const double apex = model.cone().apex_mean_stress();
  EXPECT_TRUE(stress.allFinite());
  EXPECT_NEAR(stress(0, 0), apex, 1e-12 * apex);
  EXPECT_EQ(norm(deviator(stress)), 0.0);
  EXPECT_EQ(internal[drucker_prager_corrections], 1.0);
}

TEST(DruckerPrager, TangentIsElasticStiffnessInElasticRegime) {
  const auto model = make();
  const auto internal = initial_internal(model);
  const Mat6 analytic = model.tangent(diagonal(-1e-5, 0.0, 0.0), general_stress(), internal);
  EXPECT_LT(relative_difference(analytic, elastic_stiffness({E, nu})), 1e-14);
}

TEST(DruckerPrager, ContinuumRateKeepsLoadedStateOnCone) {
  // Arrange: a state on the cone, loaded by the shearing stretching.
  const auto model = make();
  auto internal = initial_internal(model);
  Mat3 stress = general_stress();
  model.integrate(shearing_increment(), stress, internal);
  // Act
  const Mat3 rate = model.objective_rate(shearing_increment(), stress, internal);
  // Assert: consistency f_dot = alpha I1_dot + s : sigma_dot / (2 sqrt J2) = 0 (Bui 2008 eq 9).
  const Mat3 s = deviator(stress);
  const double rho = std::sqrt(j2(stress));
  const double f_dot = model.cone().alpha_phi * rate.trace() + contract(s, rate) / (2.0 * rho);
  EXPECT_LT(std::abs(f_dot), 1e-10 * norm(rate));
  EXPECT_GT(norm(rate - elastic_increment({E, nu}, shearing_increment())), 0.1 * norm(rate));
}

TEST(DruckerPrager, ContinuumRateIsSmallIncrementLimitOfReturnMapping) {
  // Arrange
  const auto model = make();
  auto internal = initial_internal(model);
  Mat3 stress = general_stress();
  model.integrate(shearing_increment(), stress, internal);
  const double h = 1e-6;
  // Act
  const Mat3 rate = model.objective_rate(shearing_increment(), stress, internal);
  Mat3 stepped = stress;
  model.integrate(h * shearing_increment(), stepped, internal);
  // Assert: the consistent return differs from the rate by O(h).
  EXPECT_LT(norm((stepped - stress) / h - rate), 1e-4 * norm(rate));
}

TEST(DruckerPrager, ContinuumRateIsElasticWhenUnloading) {
  const auto model = make();
  auto internal = initial_internal(model);
  Mat3 stress = general_stress();
  model.integrate(shearing_increment(), stress, internal);
  const Mat3 unloading = -shearing_increment();
  const Mat3 rate = model.objective_rate(unloading, stress, internal);
  EXPECT_LT(norm(rate - elastic_increment({E, nu}, unloading)), 1e-12 * norm(rate));
}

TEST(DruckerPrager, ContinuumRateAtApexUnderExtensionIsZero) {
  const auto model = make();
  const auto internal = initial_internal(model);
  const Mat3 apex = model.cone().apex_mean_stress() * Mat3::Identity();
  Mat3 stretching = 1.0 * Mat3::Identity();
  stretching(0, 1) = stretching(1, 0) = 0.1;
  const Mat3 rate = model.objective_rate(stretching, apex, internal);
  EXPECT_LT(norm(rate), 1e-10 * E);
}

TEST(DruckerPrager, RigidRotationLeavesInvariantsUnchanged) {
  // Arrange: a state on the cone, rotated 1000 times by 1e-3 rad with zero stretching.
  const auto model = make();
  auto internal = initial_internal(model);
  Mat3 stress = general_stress();
  model.integrate(shearing_increment(), stress, internal);
  const double p0 = mean_stress(stress), j2_0 = j2(stress), j3_0 = j3(stress);
  const Vec3 axis = Vec3(1.0, 2.0, 3.0).normalized();
  Mat3 d_spin;
  d_spin << 0.0, -axis(2), axis(1), axis(2), 0.0, -axis(0), -axis(1), axis(0), 0.0;
  d_spin *= 1e-3;
  // Act
  for (int step = 0; step < 1000; ++step) {
    update_stress(model, Mat3::Zero(), d_spin, stress, internal);
  }
  // Assert
  EXPECT_NEAR(mean_stress(stress), p0, 1e-10 * std::abs(p0));
  EXPECT_NEAR(j2(stress), j2_0, 1e-10 * j2_0);
  EXPECT_NEAR(j3(stress), j3_0, 1e-10 * std::abs(j3_0));
  EXPECT_LT(relative_surface_error(model, stress), 1e-10);
}

TEST(DruckerPrager, ModuliAreElastic) {
  const auto model = make();
  const auto moduli = model.moduli(Mat3::Zero(), {});
  EXPECT_DOUBLE_EQ(moduli.bulk, E / (3.0 * (1.0 - 2.0 * nu)));
  EXPECT_DOUBLE_EQ(moduli.shear, E / (2.0 * (1.0 + nu)));
}

TEST(DruckerPrager, InternalVariablesAreNamedForTheirMeaning) {
  const auto names = make().internal_variables();
  ASSERT_EQ(names.size(), 2u);
  EXPECT_EQ(names[drucker_prager_plastic_strain].name, "plastic_strain");
  EXPECT_EQ(names[drucker_prager_corrections].name, "corrections");
}

TEST(DruckerPrager, CorrectReturnsDriftedStateToCone) {
  const auto model = make();
  auto internal = initial_internal(model);
  Mat3 stress = general_stress();
  stress(0, 1) = stress(1, 0) = 200e3;  // outside
  model.correct(stress, internal);
  EXPECT_LT(relative_surface_error(model, stress), 1e-10);
  EXPECT_GT(internal[drucker_prager_plastic_strain], 0.0);
}

void expect_refused(std::map<std::string, ParameterValue> values,
                    const std::vector<std::string>& fragments) {
  expect_model_refused("drucker-prager", std::move(values), "material.sand", fragments);
}

TEST(DruckerPragerParameters, DilatancyAboveFrictionIsRefused) {
  auto values = soil();
  values["psi"] = 35.0;
  expect_refused(values, {"material.sand.psi = 35", "[0, 30]", "deg"});
}

TEST(DruckerPragerParameters, IncompressiblePoissonRatioIsRefused) {
  auto values = soil();
  values["nu"] = 0.5;
  expect_refused(values, {"material.sand.nu = 0.5", "[0, 0.5)"});
}

TEST(DruckerPragerParameters, FrictionAngleOfNinetyIsRefused) {
  auto values = soil();
  values["phi"] = 90.0;
  expect_refused(values, {"material.sand.phi = 90", "[0, 90)", "deg"});
}

TEST(DruckerPragerParameters, NegativeCohesionIsRefused) {
  auto values = soil();
  values["c"] = -1.0;
  expect_refused(values, {"material.sand.c = -1", ">= 0", "Pa"});
}

TEST(DruckerPragerParameters, CutoffAboveApexIsRefused) {
  auto values = soil();
  values["tension_cutoff"] = 20e3;  // apex is 17.32 kPa
  expect_refused(values, {"material.sand.tension_cutoff = 20000", "[0, 17320.5", "Pa"});
}

TEST(DruckerPragerParameters, MissingCohesionIsRefused) {
  auto values = soil();
  values.erase("c");
  expect_refused(values, {"material.sand.c: missing", "Pa"});
}

TEST(DruckerPragerParameters, UnknownKeyIsRefused) {
  auto values = soil();
  values["cohesion"] = 1.0;
  expect_refused(values, {"material.sand.cohesion: unknown parameter", "tension_cutoff"});
}

TEST(DruckerPragerParameters, RegistryExampleIsBuiAluminiumBars) {
  // Arrange
  const auto& info = builtin_models().find("drucker-prager");
  std::map<std::string, ParameterValue> resolved;
  // Act
  const auto model = make_model("drucker-prager", info.example, "material.bars", &resolved);
  // Assert: cohesionless, so the cut-off defaults to the apex at p = 0.
  EXPECT_EQ(std::get<double>(resolved.at("phi")), 19.8);
  EXPECT_EQ(std::get<double>(resolved.at("tension_cutoff")), 0.0);
  EXPECT_EQ(model->name(), "drucker-prager");
}

}  // namespace
}  // namespace duet::constitutive
