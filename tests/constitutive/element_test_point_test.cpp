// The element-test driver (constitutive/element_test.cpp) against linear-elastic closed forms
// (Hooke's law, isotropic): constrained modulus M = E(1-nu)/((1+nu)(1-2nu)), K0 = nu/(1-nu),
// Young's modulus and Poisson's ratio in triaxial, G = E/(2(1+nu)) in simple shear.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/input_error.hpp"
#include "constitutive/element_test.hpp"
#include "constitutive/linear_elastic.hpp"

namespace duet::constitutive {
namespace {

constexpr double E = 1e7;
constexpr double nu = 0.3;
constexpr double start = -100e3;

LinearElastic elastic() {
  return LinearElastic(ElasticParameters{E, nu});
}

ElementTest make_test(ElementTestKind kind, double strain, int increments) {
  ElementTest t;
  t.kind = kind;
  t.initial_stress = start;
  t.strain = strain;
  t.increments = increments;
  return t;
}

/// Linear elastic with a tangent of the wrong sign: Newton on it cannot make progress, so the
/// driver must fall back to its finite-difference Jacobian.
class WrongTangentElastic final : public Model {
 public:
  std::string_view name() const override { return "wrong-tangent"; }
  void integrate(const Mat3& d, Mat3& s, std::span<double> i) const override {
    inner_.integrate(d, s, i);
  }
  Mat3 objective_rate(const Mat3& d, const Mat3& s, std::span<const double> i) const override {
    return inner_.objective_rate(d, s, i);
  }
  Mat6 tangent(const Mat3& d, const Mat3& s, std::span<const double> i) const override {
    return -inner_.tangent(d, s, i);
  }
  ElasticModuli moduli(const Mat3& s, std::span<const double> i) const override {
    return inner_.moduli(s, i);
  }

 private:
  LinearElastic inner_ = elastic();
};

/// Axial strain raises every normal stress alike: sigma_xx cannot be held in triaxial.
class IsotropicResponse final : public Model {
 public:
  std::string_view name() const override { return "isotropic-response"; }
  void integrate(const Mat3& d, Mat3& s, std::span<double>) const override {
    s += E * d(1, 1) * Mat3::Identity();
  }
  Mat3 objective_rate(const Mat3& d, const Mat3&, std::span<const double>) const override {
    return E * d(1, 1) * Mat3::Identity();
  }
  ElasticModuli moduli(const Mat3&, std::span<const double>) const override { return {E, E}; }
};

/// Hypoelastic: stiffness proportional to the mean stress, tangent from finite differences
/// (the Model default), so triaxial needs several Newton iterations per increment.
class PressureDependentElastic final : public Model {
 public:
  std::string_view name() const override { return "pressure-dependent"; }
  void integrate(const Mat3& d, Mat3& s, std::span<double>) const override {
    const Mat3 trial = s + scale(s) * elastic_increment(ElasticParameters{E, nu}, d);
    s += 0.5 * (scale(s) + scale(trial)) * elastic_increment(ElasticParameters{E, nu}, d);
  }
  Mat3 objective_rate(const Mat3& d, const Mat3& s, std::span<const double>) const override {
    return scale(s) * elastic_increment(ElasticParameters{E, nu}, d);
  }
  ElasticModuli moduli(const Mat3&, std::span<const double>) const override { return {E, E}; }

 private:
  static double scale(const Mat3& s) { return std::abs(mean_stress(s)) / std::abs(start); }
};

/// Linear elastic that gives a non-finite stress for strain increments above 0.6e-3 in any
/// component: the driver must cut such increments and still finish every requested row.
class SmallStepsOnlyElastic final : public Model {
 public:
  std::string_view name() const override { return "small-steps-only"; }
  void integrate(const Mat3& d, Mat3& s, std::span<double> i) const override {
    if (d.cwiseAbs().maxCoeff() > 0.6e-3) {
      s.setConstant(std::numeric_limits<double>::quiet_NaN());
      return;
    }
    inner_.integrate(d, s, i);
  }
  Mat3 objective_rate(const Mat3& d, const Mat3& s, std::span<const double> i) const override {
    return inner_.objective_rate(d, s, i);
  }
  ElasticModuli moduli(const Mat3& s, std::span<const double> i) const override {
    return inner_.moduli(s, i);
  }

 private:
  LinearElastic inner_ = elastic();
};

TEST(ElementTestOedometer, LateralToAxialStressIncrementIsNuOverOneMinusNu) {
  const auto rows = run_element_test(elastic(), make_test(ElementTestKind::oedometer, -0.01, 10));

  const double d_axial = rows.back().axial_stress - rows.front().axial_stress;
  const double d_lateral = rows.back().lateral_stress - rows.front().lateral_stress;
  EXPECT_NEAR(d_lateral / d_axial, nu / (1.0 - nu), 1e-12);
  EXPECT_NEAR(rows.back().out_of_plane_stress, rows.back().lateral_stress, 1e-6);
}

TEST(ElementTestOedometer, AxialStressIncrementIsConstrainedModulusTimesStrain) {
  const auto rows = run_element_test(elastic(), make_test(ElementTestKind::oedometer, -0.01, 10));

  const double constrained = E * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
  EXPECT_NEAR(rows.back().axial_stress - start, constrained * -0.01, 1e-9 * constrained * 0.01);
  EXPECT_DOUBLE_EQ(rows.back().axial_strain, -0.01);
  EXPECT_DOUBLE_EQ(rows.back().lateral_strain, 0.0);
  EXPECT_DOUBLE_EQ(rows.back().volumetric_strain, -0.01);
}

TEST(ElementTestOedometer, UnloadingReturnsElasticStressToStart) {
  ElementTest test = make_test(ElementTestKind::oedometer, -0.01, 10);
  test.unload_to = 0.0;

  const auto rows = run_element_test(elastic(), test);

  EXPECT_NEAR(rows.back().axial_strain, 0.0, 1e-15);
  EXPECT_NEAR(rows.back().axial_stress, start, 1e-9 * std::abs(start));
  EXPECT_NEAR(rows.back().lateral_stress, start, 1e-9 * std::abs(start));
}

TEST(ElementTestOedometer, RowsAreIncrementsPlusStartPlusUnloading) {
  ElementTest test = make_test(ElementTestKind::oedometer, -0.01, 10);
  test.unload_to = -0.005;  // half the loading path at the loading step: 5 more rows

  const auto rows = run_element_test(elastic(), test);

  EXPECT_EQ(unloading_increments(test), 5);
  EXPECT_EQ(rows.size(), 10u + 1u + 5u);
  EXPECT_DOUBLE_EQ(rows[10].axial_strain, -0.01);
  EXPECT_NEAR(rows.back().axial_strain, -0.005, 1e-15);
}

TEST(ElementTestTriaxial, RowsAreIncrementsPlusStart) {
  const auto rows = run_element_test(elastic(), make_test(ElementTestKind::triaxial, -0.01, 7));

  EXPECT_EQ(rows.size(), 8u);
  EXPECT_DOUBLE_EQ(rows.front().axial_stress, start);
  EXPECT_DOUBLE_EQ(rows.front().q, 0.0);
}

TEST(ElementTestTriaxial, AxialStressIncrementIsYoungsModulusTimesAxialStrain) {
  const auto rows = run_element_test(elastic(), make_test(ElementTestKind::triaxial, -0.01, 10));

  EXPECT_NEAR(rows.back().axial_stress - start, E * -0.01, 1e-9 * E * 0.01);
  EXPECT_NEAR(rows.back().q, E * 0.01, 1e-9 * E * 0.01);
}

TEST(ElementTestTriaxial, LateralStrainIsMinusNuTimesAxialStrain) {
  const auto rows = run_element_test(elastic(), make_test(ElementTestKind::triaxial, -0.01, 10));

  EXPECT_NEAR(rows.back().lateral_strain, -nu * -0.01, 1e-12);
  EXPECT_NEAR(rows.back().volumetric_strain, (1.0 - 2.0 * nu) * -0.01, 1e-12);
}

TEST(ElementTestTriaxial, LateralStressStaysAtInitialStress) {
  const auto rows = run_element_test(elastic(), make_test(ElementTestKind::triaxial, -0.01, 10));

  for (const auto& row : rows) {
    EXPECT_NEAR(row.lateral_stress, start, 1e-9 * std::abs(start));
    EXPECT_NEAR(row.out_of_plane_stress, start, 1e-9 * std::abs(start));
  }
}

TEST(ElementTestTriaxial, WrongTangentFallsBackToFiniteDifferencesAndConverges) {
  const auto rows =
      run_element_test(WrongTangentElastic(), make_test(ElementTestKind::triaxial, -0.01, 10));

  EXPECT_NEAR(rows.back().axial_stress - start, E * -0.01, 1e-6 * E * 0.01);
  EXPECT_NEAR(rows.back().lateral_stress, start, 1e-9 * std::abs(start));
}

TEST(ElementTestTriaxial, NonlinearModelHoldsLateralStressToTolerance) {
  const auto rows =
      run_element_test(PressureDependentElastic(), make_test(ElementTestKind::triaxial, -0.05, 20));

  for (const auto& row : rows) {
    // the driver's tolerance is relative to the stress norm |sigma|
    const double stress_norm = std::hypot(row.axial_stress, row.lateral_stress, row.lateral_stress);
    EXPECT_NEAR(row.lateral_stress, start, element_test_tolerance * stress_norm);
  }
  EXPECT_LT(rows.back().axial_stress, start);  // compression stiffens the sample
}

TEST(ElementTestTriaxial, IncrementThatFailsIsCutAndTheTestCompletes) {
  const auto rows =
      run_element_test(SmallStepsOnlyElastic(), make_test(ElementTestKind::triaxial, -0.01, 10));

  ASSERT_EQ(rows.size(), 11u);  // rows stay at the requested increments, cuts are internal
  EXPECT_NEAR(rows.back().axial_stress - start, E * -0.01, 1e-9 * E * 0.01);
  EXPECT_NEAR(rows.back().lateral_stress, start, element_test_tolerance * 3.0 * std::abs(start));
  // Finite-difference tangent here, so Newton stops at the driver's tolerance, not at round-off:
  // a held-stress residual of 1e-9 |sigma| (|sigma| < 3e5 Pa) is a lateral strain error below
  // 1e-9 * 3e5 / E per increment, 20 half increments.
  EXPECT_NEAR(rows.back().lateral_strain, -nu * -0.01, 20 * element_test_tolerance * 3e5 / E);
}

TEST(ElementTestTriaxial, UnreachableHeldStressIsReportedNotSilent) {
  try {
    run_element_test(IsotropicResponse(), make_test(ElementTestKind::triaxial, -0.01, 10));
    FAIL() << "expected ElementTestFailure";
  } catch (const ElementTestFailure& failure) {
    EXPECT_EQ(failure.rows().size(), 1u);  // only the start was reached
    EXPECT_NE(std::string(failure.what()).find("increment 1 of 10"), std::string::npos);
  }
}

TEST(ElementTestSimpleShear, ShearStressIsShearModulusTimesGamma) {
  const auto rows = run_element_test(elastic(), make_test(ElementTestKind::simple_shear, 0.02, 10));

  const double G = E / (2.0 * (1.0 + nu));
  EXPECT_NEAR(rows.back().shear_stress, G * 0.02, 1e-9 * G * 0.02);
  EXPECT_DOUBLE_EQ(rows.back().shear_strain, 0.02);
}

TEST(ElementTestSimpleShear, VerticalStressStaysAtInitialStress) {
  const auto rows = run_element_test(elastic(), make_test(ElementTestKind::simple_shear, 0.02, 10));

  for (const auto& row : rows) {
    EXPECT_NEAR(row.axial_stress, start, 1e-9 * std::abs(start));
    EXPECT_NEAR(row.axial_strain, 0.0, 1e-15);  // elastic: shear does not dilate
  }
}

TEST(ElementTestRows, ModelWithoutVoidRatioWritesNanAndZeroCorrections) {
  const auto rows = run_element_test(elastic(), make_test(ElementTestKind::oedometer, -0.01, 2));

  EXPECT_TRUE(std::isnan(rows.back().void_ratio));
  EXPECT_EQ(rows.back().corrections, 0.0);
}

TEST(ElementTestInput, ZeroIncrementsIsRefusedNamingTheKey) {
  try {
    run_element_test(elastic(), make_test(ElementTestKind::oedometer, -0.01, 0));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("element.increments = 0"), std::string::npos);
  }
}

TEST(ElementTestInput, UnloadingOutsideOedometerIsRefused) {
  ElementTest test = make_test(ElementTestKind::triaxial, -0.01, 10);
  test.unload_to = 0.0;

  EXPECT_THROW(run_element_test(elastic(), test), InputError);
}

TEST(ElementTestInput, UnloadToBeyondTheLoadingStrainIsRefused) {
  ElementTest test = make_test(ElementTestKind::oedometer, -0.01, 10);
  test.unload_to = -0.02;

  EXPECT_THROW(run_element_test(elastic(), test), InputError);
}

TEST(ElementTestInput, UnknownTestNameSuggestsTheClosest) {
  try {
    parse_element_test_kind("simple_shear");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("simple-shear"), std::string::npos);
  }
}

}  // namespace
}  // namespace duet::constitutive
