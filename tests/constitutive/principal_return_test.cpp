// Unit tests of constitutive/principal_return.cpp: the spectral decomposition, the one- and
// two-vector returns of perfect plasticity (de Souza Neto 2008 Boxes 8.1-8.2, 8.4-8.5), the
// regime selection, the derivative of isotropic tensor functions (Box A.2) against closed forms,
// and the continuum rate. The faceted surfaces are built here from their formulas so the
// machinery is tested apart from the models.

#include "constitutive/principal_return.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace duet::constitutive {
namespace {

constexpr double K = 10e6;   // Pa
constexpr double G = 4e6;    // Pa
constexpr double cu = 50e3;  // Pa

Mat3 elasticity() {
  return principal_elasticity(K, G);
}

/// Tresca: f = sigma1 - sigma3 - 2 c_u, associated.
FacetedSurface tresca(double strength = cu) {
  FacetedSurface s;
  s.main.normal = Vec3(1, 0, -1);
  s.right.normal = Vec3(1, -1, 0);
  s.left.normal = Vec3(0, 1, -1);
  for (PrincipalPlane* p : {&s.main, &s.right, &s.left}) {
    p->flow = p->normal;
    p->level = 2.0 * strength;
  }
  return s;
}

/// Mohr-Coulomb: f = (sigma1 - sigma3) + (sigma1 + sigma3) sin(phi) - 2 c cos(phi), flow with psi.
FacetedSurface mohr_coulomb(double phi_deg, double psi_deg, double c) {
  const double sp = std::sin(phi_deg * std::numbers::pi / 180.0);
  const double ss = std::sin(psi_deg * std::numbers::pi / 180.0);
  const double level = 2.0 * c * std::cos(phi_deg * std::numbers::pi / 180.0);
  FacetedSurface s;
  s.main = {Vec3(1 + sp, 0, -(1 - sp)), Vec3(1 + ss, 0, -(1 - ss)), level};
  s.right = {Vec3(1 + sp, -(1 - sp), 0), Vec3(1 + ss, -(1 - ss), 0), level};
  s.left = {Vec3(0, 1 + sp, -(1 - sp)), Vec3(0, 1 + ss, -(1 - ss)), level};
  s.apex = c / std::tan(phi_deg * std::numbers::pi / 180.0);
  return s;
}

Mat3 general_symmetric() {
  Mat3 s;
  s << -120e3, 15e3, -8e3, 15e3, -90e3, 5e3, -8e3, 5e3, -100e3;
  return s;
}

/// Largest value of the six Mohr-Coulomb-type plane functions over all orderings, i.e. the
/// yield function without assuming the sorted order.
double surface_value(const FacetedSurface& s, const Vec3& sigma) {
  Vec3 sorted = sigma;
  std::sort(sorted.data(), sorted.data() + 3, std::greater<>());
  return s.main.value(sorted);
}

TEST(SpectralDecomposition, ValuesDescendAndReassembleTheTensor) {
  // Arrange
  const Mat3 s = general_symmetric();
  // Act
  const SpectralDecomposition d = spectral_decomposition(s);
  // Assert
  EXPECT_GE(d.values(0), d.values(1));
  EXPECT_GE(d.values(1), d.values(2));
  EXPECT_LT((assemble_from_principal(d.values, d.directions) - s).norm(), 1e-10 * s.norm());
  EXPECT_LT((d.directions.transpose() * d.directions - Mat3::Identity()).norm(), 1e-14);
  EXPECT_NEAR(d.values.sum(), s.trace(), 1e-10 * s.norm());
}

TEST(PrincipalElasticity, IsHookeOnPrincipalStrains) {
  const Vec3 strain(1e-3, -2e-3, 0.5e-3);
  const Vec3 hooke = (K - 2.0 / 3.0 * G) * strain.sum() * Vec3::Ones() + 2.0 * G * strain;
  EXPECT_LT((elasticity() * strain - hooke).norm(), 1e-9 * hooke.norm());
}

TEST(PrincipalReturn, InsideTrialIsElastic) {
  const Vec3 trial(-50e3, -70e3, -120e3);  // sigma1 - sigma3 = 70 kPa < 100 kPa
  const PrincipalReturn r = principal_return(trial, tresca(), elasticity(), 1e-6);
  EXPECT_EQ(r.regime, PrincipalRegime::elastic);
  EXPECT_EQ(r.stress, trial);
  EXPECT_EQ(r.jacobian, Mat3::Identity());
}

TEST(PrincipalReturn, OneVectorReturnToTrescaMainPlaneHasClosedForm) {
  // Arrange: intermediate stress in the middle, so the return stays in the sextant.
  const Vec3 trial(0.0, -100e3, -200e3);
  // Act
  const PrincipalReturn r = principal_return(trial, tresca(), elasticity(), 1e-6);
  // Assert: Box 8.1 with H = 0: d_gamma = f_trial / 4G, sigma1,3 -/+ 2G d_gamma, sigma2 kept.
  ASSERT_EQ(r.regime, PrincipalRegime::main_plane);
  const double f_trial = 200e3 - 2.0 * cu;
  EXPECT_NEAR(r.multipliers(0), f_trial / (4.0 * G), 1e-15);
  EXPECT_NEAR(r.stress(0), -50e3, 1e-9);
  EXPECT_NEAR(r.stress(1), -100e3, 1e-9);
  EXPECT_NEAR(r.stress(2), -150e3, 1e-9);
}

TEST(PrincipalReturn, TrescaTrialNearSigma3ReturnsToRightEdge) {
  // Arrange: sigma2 close to sigma3; the one-vector return would lift sigma3 above sigma2.
  const Vec3 trial(0.0, -190e3, -200e3);
  // Act
  const PrincipalReturn r = principal_return(trial, tresca(), elasticity(), 1e-6);
  // Assert: both planes active, sigma2 = sigma3, mean stress kept (isochoric flow), and the
  // closed form sigma1 = p + 4 c_u / 3, sigma2 = sigma3 = p - 2 c_u / 3.
  ASSERT_EQ(r.regime, PrincipalRegime::right_edge);
  const double p = trial.sum() / 3.0;
  EXPECT_NEAR(r.stress(0), p + 4.0 * cu / 3.0, 1e-9);
  EXPECT_EQ(r.stress(1), r.stress(2));
  EXPECT_NEAR(r.stress(2), p - 2.0 * cu / 3.0, 1e-9);
  EXPECT_GT(r.multipliers.minCoeff(), 0.0);
}

TEST(PrincipalReturn, TrescaTrialNearSigma1ReturnsToLeftEdge) {
  const Vec3 trial(0.0, -10e3, -200e3);
  const PrincipalReturn r = principal_return(trial, tresca(), elasticity(), 1e-6);
  ASSERT_EQ(r.regime, PrincipalRegime::left_edge);
  const double p = trial.sum() / 3.0;
  EXPECT_EQ(r.stress(0), r.stress(1));
  EXPECT_NEAR(r.stress(0), p + 2.0 * cu / 3.0, 1e-9);
  EXPECT_NEAR(r.stress(2), p - 4.0 * cu / 3.0, 1e-9);
  EXPECT_GT(r.multipliers.minCoeff(), 0.0);
}

TEST(PrincipalReturn, MohrCoulombTrialBeyondApexReturnsToApex) {
  // Arrange: phi 30, c 10 kPa: apex at c cot(phi) = 17.32 kPa; a tensile trial well past it.
  const FacetedSurface mc = mohr_coulomb(30.0, 10.0, 10e3);
  const Vec3 trial(120e3, 100e3, 90e3);
  // Act
  const PrincipalReturn r = principal_return(trial, mc, elasticity(), 1e-6);
  // Assert
  ASSERT_EQ(r.regime, PrincipalRegime::apex);
  EXPECT_LT((r.stress - Vec3::Constant(*mc.apex)).norm(), 1e-10 * *mc.apex);
  EXPECT_EQ(r.jacobian, Mat3::Zero());
}

TEST(PrincipalReturn, RandomTrialsLandOnSurfaceSortedWithPositiveMultipliers) {
  // Arrange: many trials around the Mohr-Coulomb cone (non-associated) and the Tresca prism.
  const FacetedSurface surfaces[] = {mohr_coulomb(30.0, 10.0, 10e3), mohr_coulomb(35.0, 0.0, 5e3),
                                     tresca()};
  std::mt19937 generator(42);
  std::uniform_real_distribution<double> uniform(-400e3, 100e3);
  int counts[5] = {0, 0, 0, 0, 0};
  for (const FacetedSurface& surface : surfaces) {
    for (int k = 0; k < 3000; ++k) {
      Vec3 trial(uniform(generator), uniform(generator), uniform(generator));
      std::sort(trial.data(), trial.data() + 3, std::greater<>());
      // Act
      const PrincipalReturn r = principal_return(trial, surface, elasticity(), 1e-6);
      ++counts[static_cast<int>(r.regime)];
      // Assert: admissible everywhere, on the surface when plastic, sorted, dissipative.
      const double scale = trial.cwiseAbs().maxCoeff() + surface.main.level;
      EXPECT_LE(surface_value(surface, r.stress), 1e-10 * scale);
      if (r.regime != PrincipalRegime::elastic) {
        EXPECT_NEAR(surface.main.value(r.stress), 0.0, 1e-10 * scale);
      }
      EXPECT_GE(r.stress(0) + 1e-10 * scale, r.stress(1));
      EXPECT_GE(r.stress(1) + 1e-10 * scale, r.stress(2));
      EXPECT_GE(r.multipliers.minCoeff(), 0.0);
    }
  }
  // Every regime was visited.
  for (int regime = 0; regime < 5; ++regime) EXPECT_GT(counts[regime], 0) << regime;
}

TEST(PrincipalReturn, JacobianEqualsFiniteDifferenceInEveryRegime) {
  const FacetedSurface mc = mohr_coulomb(30.0, 10.0, 10e3);
  const Vec3 trials[] = {Vec3(-50e3, -100e3, -300e3),  // main plane
                         Vec3(-50e3, -295e3, -300e3),  // right edge
                         Vec3(-40e3, -60e3, -300e3),   // left edge
                         Vec3(120e3, 100e3, 90e3)};    // apex
  const PrincipalRegime expected[] = {PrincipalRegime::main_plane, PrincipalRegime::right_edge,
                                      PrincipalRegime::left_edge, PrincipalRegime::apex};
  for (int k = 0; k < 4; ++k) {
    const PrincipalReturn r = principal_return(trials[k], mc, elasticity(), 1e-6);
    ASSERT_EQ(r.regime, expected[k]);
    Mat3 fd;
    const double h = 1.0;  // Pa; the map is affine within a regime
    for (int b = 0; b < 3; ++b) {
      const Vec3 plus = trials[k] + h * Vec3::Unit(b), minus = trials[k] - h * Vec3::Unit(b);
      fd.col(b) = (principal_return(plus, mc, elasticity(), 1e-6).stress -
                   principal_return(minus, mc, elasticity(), 1e-6).stress) /
                  (2.0 * h);
    }
    EXPECT_LT((r.jacobian - fd).norm(), 1e-8) << principal_regime_name(r.regime);
  }
}

TEST(IsotropicFunctionTangent, IdentityMapGivesIdentity) {
  const SpectralDecomposition d = spectral_decomposition(general_symmetric());
  const Mat6 T = isotropic_function_tangent(d, d.values, Mat3::Identity());
  EXPECT_LT((T - Mat6::Identity()).norm(), 1e-12);
}

TEST(IsotropicFunctionTangent, SquareOfTensorMatchesProductRule) {
  // Arrange: Y = X^2 has y_a = x_a^2, dy_a/dx_b = 2 x_a delta_ab; closed form dY = X dX + dX X.
  const Mat3 X = general_symmetric() / 1e5;
  const SpectralDecomposition d = spectral_decomposition(X);
  const Vec3 y = d.values.cwiseProduct(d.values);
  const Mat3 J = (2.0 * d.values).asDiagonal();
  // Act
  const Mat6 T = isotropic_function_tangent(d, y, J);
  // Assert
  for (int j = 0; j < 6; ++j) {
    const Mat3 dX = voigt_to_stress(Vec6::Unit(j));
    const Vec6 expected = stress_to_voigt(X * dX + dX * X);
    EXPECT_LT((T.col(j) - expected).norm(), 1e-12 * expected.norm() + 1e-14) << j;
  }
}

TEST(IsotropicFunctionTangent, RepeatedEigenvaluesUseTheLimit) {
  // Y = X^2 at X with a double eigenvalue: the limit (J_aa - J_ab) = 2 x gives the product rule.
  const Mat3 X = Vec3(2.0, 2.0, -1.0).asDiagonal();
  const SpectralDecomposition d = spectral_decomposition(X);
  const Mat6 T =
      isotropic_function_tangent(d, d.values.cwiseProduct(d.values), (2.0 * d.values).asDiagonal());
  const Mat3 dX = voigt_to_stress(Vec6::Unit(3));  // xy shear inside the double eigenspace
  EXPECT_LT((T.col(3) - stress_to_voigt(X * dX + dX * X)).norm(), 1e-12);
}

TEST(ContinuumRate, InsideTheSurfaceIsTheElasticRate) {
  const Mat3 stress = Vec3(-80e3, -100e3, -120e3).asDiagonal();
  Mat3 rate;
  rate << 1e3, 2e3, 0, 2e3, -1e3, 0, 0, 0, 0;
  EXPECT_EQ(continuum_rate(stress, rate, tresca(), elasticity(), 1e-6), rate);
}

TEST(ContinuumRate, LoadingOnMainPlaneIsTangentToIt) {
  // Arrange: on the Tresca main plane with distinct principal stresses, loaded outward.
  const Mat3 stress = Vec3(-50e3, -100e3, -150e3).asDiagonal();
  Mat3 elastic_rate;
  elastic_rate << 4e3, 1e3, 0.5e3, 1e3, 0.0, 0.0, 0.5e3, 0.0, -4e3;
  // Act
  const Mat3 rate = continuum_rate(stress, elastic_rate, tresca(), elasticity(), 1e-6);
  // Assert: d(sigma1 - sigma3)/dt = rate_11 - rate_33 = 0; sigma2 and shears elastic.
  EXPECT_NEAR(rate(0, 0) - rate(2, 2), 0.0, 1e-9 * elastic_rate.norm());
  EXPECT_NEAR(rate(1, 1), elastic_rate(1, 1), 1e-9 * elastic_rate.norm());
  EXPECT_NEAR(rate(0, 1), elastic_rate(0, 1), 1e-9 * elastic_rate.norm());
}

TEST(ContinuumRate, AtMohrCoulombApexUnderExtensionIsZero) {
  const FacetedSurface mc = mohr_coulomb(30.0, 10.0, 10e3);
  const Mat3 apex = *mc.apex * Mat3::Identity();
  Mat3 elastic_rate = 1e3 * Mat3::Identity();
  elastic_rate(0, 1) = elastic_rate(1, 0) = 100.0;
  EXPECT_LT(continuum_rate(apex, elastic_rate, mc, elasticity(), 1e-6).norm(), 1e-9 * 1e3);
}

}  // namespace
}  // namespace duet::constitutive
