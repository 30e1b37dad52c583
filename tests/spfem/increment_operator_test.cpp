// Tests of the implicit SPFEM operator (spfem/increment_operator.hpp): the assembled tangent
// against a central-difference Jacobian of the assembled internal force, on an irregular cloud
// with a non-trivial stress and a finite displacement (so the spin and the geometric terms are
// exercised), for elasticity, Tresca on its surface and on an edge, and non-associated
// Drucker-Prager (../shared/notes/implicit-spfem.md: "the test that decides"); and the same for an
// axisymmetric cloud (x = r: ring volumes, hoop strain and hoop force).
#include "spfem/increment_operator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "constitutive/registry.hpp"
#include "tests/spfem/straight_wall.hpp"

namespace duet::spfem {
namespace {

using testing::straight_wall;

constexpr double kSpacing = 1.0;  // m
constexpr int kNx = 6;
constexpr int kNy = 5;

/// Nodes at the cell centres of a kNx x kNy lattice, each jittered by up to 0.2 dp.
Particles cloud(const constitutive::Model& model, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> jitter(-0.2, 0.2);
  Particles p;
  p.resize(static_cast<std::size_t>(kNx * kNy));
  const std::vector<constitutive::InternalVariable> variables = model.internal_variables();
  p.internal.width = variables.size();
  p.internal.values.assign(p.size() * p.internal.width, 0.0);
  std::size_t k = 0;
  for (int j = 0; j < kNy; ++j) {
    for (int i = 0; i < kNx; ++i, ++k) {
      p.position[k] = kSpacing * Vec2(i + 0.5 + jitter(random), j + 0.5 + jitter(random));
      p.volume[k] = kSpacing * kSpacing;
      p.density[k] = 1000.0;
      p.mass[k] = 1000.0 * kSpacing * kSpacing;
      p.material[k] = 0;
      for (std::size_t v = 0; v < variables.size(); ++v) {
        p.internal.values[k * p.internal.width + v] = variables[v].initial;
      }
    }
  }
  return p;
}

struct Case {
  std::unique_ptr<constitutive::Model> model;
  Particles start;
  std::vector<Vec2> u;
};

/// The increment's displacement: a uniform gradient `g` plus a random part of size `noise` dp.
std::vector<Vec2> displacement(const Particles& p, const Mat2& g, double noise, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  std::vector<Vec2> u(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    u[i] = g * p.position[i] + noise * kSpacing * Vec2(d(random), d(random));
  }
  return u;
}

/// Relative Frobenius distance between the assembled tangent and the central-difference Jacobian
/// of F_int, every dof free.
double tangent_error(Case& c, bool boundary_layer, double stiffness_stabilisation = 0.0,
                     std::vector<NodeBoundary> walls = {}, double increment_stabilisation = 0.0,
                     bool axisymmetric = false) {
  std::vector<std::unique_ptr<constitutive::Model>> models;
  models.push_back(std::move(c.model));
  duet::SpfemOptions options;
  options.boundary_layer = boundary_layer;
  options.stiffness_stabilisation = stiffness_stabilisation;
  NodalDiscretisation discretisation(options, kSpacing, std::move(walls), axisymmetric);
  discretisation.initialise(c.start.position);
  discretisation.place_boundaries(0.0, false);
  discretisation.update(c.start.position);
  const std::size_t n = c.start.size();
  const DofMap dofs = eliminate(n, {}, std::vector<std::uint8_t>(n, 0));
  IncrementOperator op(discretisation, models, c.start,
                       std::vector<Vec2>(2 * discretisation.wall_strips().edges.size()), nullptr,
                       increment_stabilisation);
  EXPECT_TRUE(op.evaluate(c.u));
  op.assemble_tangent(dofs);
  const Eigen::MatrixXd k = Eigen::MatrixXd(op.tangent());
  Eigen::MatrixXd fd(2 * n, 2 * n);
  const double h = 1e-6 * kSpacing;
  for (std::size_t j = 0; j < 2 * n; ++j) {
    std::vector<Vec2> plus = c.u;
    std::vector<Vec2> minus = c.u;
    plus[j / 2][int(j % 2)] += h;
    minus[j / 2][int(j % 2)] -= h;
    op.evaluate(plus);
    const std::vector<Vec2> f_plus = op.internal_force();
    op.evaluate(minus);
    const std::vector<Vec2>& f_minus = op.internal_force();
    for (std::size_t i = 0; i < n; ++i) {
      for (int a = 0; a < 2; ++a) {
        fd(Eigen::Index(2 * i + a), Eigen::Index(j)) = (f_plus[i][a] - f_minus[i][a]) / (2.0 * h);
      }
    }
  }
  // Free dofs are ordered node by node, x then y (no constraint): the same order as fd.
  return (k - fd).norm() / fd.norm();
}

Case elastic_case() {
  Case c;
  c.model = constitutive::make_model("linear-elastic", {{"E", 100.0}, {"nu", 0.3}}, "test");
  c.start = cloud(*c.model, 3);
  std::mt19937 random(5);
  std::uniform_real_distribution<double> s(-15.0, 15.0);  // |sigma| / G about 0.4
  for (Mat3& sigma : c.start.stress) {
    sigma.setZero();
    sigma(0, 0) = s(random);
    sigma(1, 1) = s(random);
    sigma(2, 2) = s(random);
    sigma(0, 1) = sigma(1, 0) = s(random);
  }
  const Mat2 g = (Mat2() << 0.01, 0.03, -0.02, 0.005).finished();  // a rotation of 0.025 rad
  c.u = displacement(c.start, g, 2e-3, 11);
  return c;
}

TEST(IncrementOperator, ElasticTangentMatchesFiniteDifferenceJacobian) {
  Case c = elastic_case();
  const double error = tangent_error(c, false);
  std::printf("elastic, no layer: %.2e\n", error);
  EXPECT_LT(error, 1e-6);
}

TEST(IncrementOperator, ElasticTangentMatchesFiniteDifferenceJacobianWithBoundaryLayer) {
  Case c = elastic_case();
  const double error = tangent_error(c, true);
  std::printf("elastic, boundary layer: %.2e\n", error);
  EXPECT_LT(error, 1e-6);
}

TEST(IncrementOperator, StiffnessStabilisationHessianMatchesFiniteDifferenceJacobian) {
  // The stabilisation's energy W is quadratic in the positions: its Hessian is exact
  Case c = elastic_case();
  const double error = tangent_error(c, true, 0.5);
  std::printf("elastic, layer, stiffness stabilisation 0.5: %.2e\n", error);
  EXPECT_LT(error, 1e-6);
}

TEST(IncrementOperator, IncrementStabilisationHessianMatchesFiniteDifferenceJacobian) {
  // Both energies at once: the total one on the initial positions, the increment's on x_n
  Case c = elastic_case();
  for (Vec2& x : c.start.displacement) x = Vec2(0.03, -0.02);  // x_n differs from the initial
  const double error = tangent_error(c, true, 0.5, {}, 2.0);
  std::printf("elastic, layer, stiffness 0.5 and increment stabilisation 2: %.2e\n", error);
  EXPECT_LT(error, 1e-6);
}

TEST(IncrementOperator, IncrementStabilisationResistsOnlyTheIncrementsHourglassPart) {
  // Anchored to the increment's start, the energy vanishes for an affine increment however the
  // body got there (so it holds no stress from earlier increments), and it resists a
  // non-affine one: the work of its force over the increment is 2 W > 0.
  Case c = elastic_case();
  for (Vec2& x : c.start.displacement) x = Vec2(0.03, -0.02);
  std::vector<std::unique_ptr<constitutive::Model>> models;
  models.push_back(std::move(c.model));
  duet::SpfemOptions options;
  NodalDiscretisation discretisation(options, kSpacing, {});
  discretisation.initialise(c.start.position);
  discretisation.place_boundaries(0.0, false);
  discretisation.update(c.start.position);
  const auto force_work = [&](double s, const std::vector<Vec2>& u) {
    // both built before either evaluates: an evaluation refills the discretisation's cells
    IncrementOperator op(discretisation, models, c.start, {}, nullptr, s);
    IncrementOperator plain(discretisation, models, c.start, {}, nullptr, 0.0);
    EXPECT_TRUE(op.evaluate(u));
    const std::vector<Vec2> f = op.internal_force();
    EXPECT_TRUE(plain.evaluate(u));
    double work = 0.0;
    double largest = 0.0;
    for (std::size_t i = 0; i < u.size(); ++i) {
      const Vec2 extra = f[i] - plain.internal_force()[i];
      work += extra.dot(u[i]);
      largest = std::max(largest, extra.norm());
    }
    std::printf("increment stabilisation 2: work %.3e, largest force %.3e\n", work, largest);
    return std::pair{work, largest};
  };
  const Mat2 g = (Mat2() << 0.01, 0.03, -0.02, 0.005).finished();
  const std::vector<Vec2> affine = displacement(c.start, g, 0.0, 11);
  EXPECT_LT(force_work(2.0, affine).second, 1e-10);  // forces of order 0.1 N/m when rough
  const std::vector<Vec2> rough = displacement(c.start, g, 2e-3, 11);
  const auto [work, largest] = force_work(2.0, rough);
  EXPECT_GT(work, 0.0);
  EXPECT_GT(largest, 1e-3);
}

/// The cloud's first column and row onto the lattice, dp / 2 from walls along x = 0 and y = 0.
void against_walls(Case& c) {
  for (std::size_t i = 0; i < c.start.size(); ++i) {
    if (i % kNx == 0) c.start.position[i].x() = 0.5 * kSpacing;
    if (i < std::size_t(kNx)) c.start.position[i].y() = 0.5 * kSpacing;
  }
}

TEST(IncrementOperator, TangentWithWallStripsMatchesFiniteDifferenceJacobian) {
  // A no-slip wall along x = 0 and a free-slip one along y = 0 (the cloud's first column and
  // row lie within reach of them): their wall strips enter the rows of the nodes at the walls
  Case c = elastic_case();
  against_walls(c);
  const double error = tangent_error(
      c, true, 0.0,
      {straight_wall("clamp", Vec2(0.0, -1.0), Vec2(0.0, 6.0), NodeCondition::bonded),
       straight_wall("floor", Vec2(-1.0, 0.0), Vec2(7.0, 0.0), NodeCondition::smooth)});
  std::printf("elastic, layer, wall strips: %.2e\n", error);
  EXPECT_LT(error, 1e-6);
}

TEST(IncrementOperator, TrescaOnItsSurfaceTangentMatchesFiniteDifferenceJacobian) {
  // Arrange: every node at yield in simple shear (sigma_xy = c_u, sigma_xx = sigma_yy = sigma_zz
  // = -p), loaded further in shear: the return is onto the smooth surface
  Case c;
  c.model = constitutive::make_model("tresca", {{"E", 100.0}, {"nu", 0.45}, {"cu", 2.0}}, "test");
  c.start = cloud(*c.model, 4);
  for (Mat3& sigma : c.start.stress) {
    sigma = -5.0 * Mat3::Identity();
    sigma(0, 1) = sigma(1, 0) = 2.0;
  }
  const Mat2 g = (Mat2() << 0.0, 0.02, 0.0, 0.0).finished();
  c.u = displacement(c.start, g, 1e-3, 12);
  const double error = tangent_error(c, true);
  std::printf("tresca surface: %.2e\n", error);
  EXPECT_LT(error, 1e-6);
}

TEST(IncrementOperator, TrescaOnAnEdgeTangentMatchesFiniteDifferenceJacobian) {
  // Arrange: sigma_xx = sigma_zz = c_u, sigma_yy = -c_u (two principal stresses equal, at yield),
  // compressed further along y: the return is onto the edge where two planes of Tresca meet
  Case c;
  c.model = constitutive::make_model("tresca", {{"E", 100.0}, {"nu", 0.45}, {"cu", 2.0}}, "test");
  c.start = cloud(*c.model, 6);
  for (Mat3& sigma : c.start.stress) sigma = Vec3(2.0, -2.0, 2.0).asDiagonal();
  const Mat2 g = (Mat2() << 0.0, 0.0, 0.0, -0.03).finished();
  c.u = displacement(c.start, g, 1e-3, 13);
  const double error = tangent_error(c, true);
  std::printf("tresca edge: %.2e\n", error);
  EXPECT_LT(error, 1e-6);
}

TEST(IncrementOperator, NonAssociatedDruckerPragerTangentMatchesFiniteDifferenceJacobian) {
  // Arrange: phi = 30, psi = 5 (non-associated), isotropic compression plus shear, sheared on
  Case c;
  c.model = constitutive::make_model(
      "drucker-prager", {{"E", 100.0}, {"nu", 0.3}, {"phi", 30.0}, {"psi", 5.0}, {"c", 0.5}},
      "test");
  c.start = cloud(*c.model, 8);
  for (Mat3& sigma : c.start.stress) {
    sigma = -3.0 * Mat3::Identity();
    sigma(0, 1) = sigma(1, 0) = 1.5;
  }
  const Mat2 g = (Mat2() << 0.0, 0.04, 0.0, 0.0).finished();
  c.u = displacement(c.start, g, 1e-3, 14);
  const double error = tangent_error(c, true);
  std::printf("drucker-prager: %.2e\n", error);
  EXPECT_LT(error, 1e-6);
}

// Axisymmetric (x = r about x = 0): the cloud moved out by `shift` so that r runs from about
// `shift` + 0.3 dp to 6 dp across it (the rings, the hoop strain u_r / r and the hoop force
// change from node to node), the increment's displacement taken anew on the moved cloud.
void move_off_axis(Case& c, double shift, const Mat2& g, double noise, unsigned seed) {
  for (Vec2& x : c.start.position) x.x() += shift;
  c.u = displacement(c.start, g, noise, seed);
}

TEST(IncrementOperator, AxisymmetricElasticTangentMatchesFiniteDifferenceJacobian) {
  // Arrange: elastic_case's stresses (sigma_tt included) on a cloud at r >= 0.5 m
  Case c = elastic_case();
  move_off_axis(c, 0.2, (Mat2() << 0.01, 0.03, -0.02, 0.005).finished(), 2e-3, 11);
  // Act
  const double error = tangent_error(c, false, 0.0, {}, 0.0, true);
  // Assert
  std::printf("axisymmetric elastic, no layer: %.2e\n", error);
  EXPECT_LT(error, 1e-6);
}

TEST(IncrementOperator, AxisymmetricElasticTangentMatchesFiniteDifferenceJacobianWithLayer) {
  // Arrange: as above, with the boundary layer (its rows' dA_k/dx by differences)
  Case c = elastic_case();
  move_off_axis(c, 0.2, (Mat2() << 0.01, 0.03, -0.02, 0.005).finished(), 2e-3, 11);
  // Act
  const double error = tangent_error(c, true, 0.0, {}, 0.0, true);
  // Assert
  std::printf("axisymmetric elastic, boundary layer: %.2e\n", error);
  EXPECT_LT(error, 1e-6);
}

TEST(IncrementOperator, AxisymmetricStabilisationHessiansMatchFiniteDifferenceJacobian) {
  // Arrange: both stabilisation energies, their moduli weighed by the rings
  Case c = elastic_case();
  move_off_axis(c, 0.2, (Mat2() << 0.01, 0.03, -0.02, 0.005).finished(), 2e-3, 11);
  for (Vec2& x : c.start.displacement) x = Vec2(0.03, -0.02);
  // Act
  const double error = tangent_error(c, true, 0.5, {}, 2.0, true);
  // Assert
  std::printf("axisymmetric elastic, layer, both stabilisations: %.2e\n", error);
  EXPECT_LT(error, 1e-6);
}

TEST(IncrementOperator, AxisymmetricTangentOnTheAxisWallMatchesFiniteDifferenceJacobian) {
  // Arrange: the cloud's first column at r = dp / 2 against a symmetry wall on the axis x = 0
  // and its first row on a no-slip base y = 0 (wall strips in the rows at both); the nodes at
  // the axis move radially too, so their hoop strain u_r / r is the cloud's largest
  Case c = elastic_case();
  against_walls(c);
  c.u = displacement(c.start, (Mat2() << 0.01, 0.03, -0.02, 0.005).finished(), 2e-3, 11);
  // Act
  const double error = tangent_error(
      c, true, 0.0,
      {straight_wall("axis", Vec2(0.0, -1.0), Vec2(0.0, 6.0), NodeCondition::symmetry),
       straight_wall("base", Vec2(-1.0, 0.0), Vec2(7.0, 0.0), NodeCondition::bonded)},
      0.0, true);
  // Assert
  std::printf("axisymmetric elastic, layer, axis and base wall strips: %.2e\n", error);
  EXPECT_LT(error, 1e-6);
}

TEST(IncrementOperator, AxisymmetricTrescaOnItsSurfaceTangentMatchesFiniteDifferenceJacobian) {
  // Arrange: every node at yield in r-z shear (sigma_rz = c_u, sigma_rr = sigma_zz = sigma_tt =
  // -p) on a cloud at r >= 0.5 m, sheared further and stretched radially (hoop strain u_r / r)
  Case c;
  c.model = constitutive::make_model("tresca", {{"E", 100.0}, {"nu", 0.45}, {"cu", 2.0}}, "test");
  c.start = cloud(*c.model, 4);
  for (Mat3& sigma : c.start.stress) {
    sigma = -5.0 * Mat3::Identity();
    sigma(0, 1) = sigma(1, 0) = 2.0;
  }
  move_off_axis(c, 0.2, (Mat2() << 0.005, 0.02, 0.0, 0.0).finished(), 1e-3, 12);
  // Act
  const double error = tangent_error(c, true, 0.0, {}, 0.0, true);
  // Assert
  std::printf("axisymmetric tresca surface: %.2e\n", error);
  EXPECT_LT(error, 1e-6);
}

TEST(IncrementOperator, AxisymmetricTrescaYieldingInHoopTangentMatchesFiniteDifferenceJacobian) {
  // Arrange: sigma_tt - sigma_rr = 2 c_u at yield (the cavity's state), expanded radially: the
  // hoop row of D_k carries the return
  Case c;
  c.model = constitutive::make_model("tresca", {{"E", 100.0}, {"nu", 0.45}, {"cu", 2.0}}, "test");
  c.start = cloud(*c.model, 6);
  for (Mat3& sigma : c.start.stress) sigma = Vec3(-4.0, -2.0, 0.0).asDiagonal();
  move_off_axis(c, 0.2, (Mat2() << 0.01, 0.0, 0.0, 0.0).finished(), 1e-3, 13);
  for (std::size_t i = 0; i < c.u.size(); ++i) c.u[i].x() += 0.01 * kSpacing;  // u_r / r > 0
  // Act
  const double error = tangent_error(c, true, 0.0, {}, 0.0, true);
  // Assert
  std::printf("axisymmetric tresca, hoop yield: %.2e\n", error);
  EXPECT_LT(error, 1e-6);
}

TEST(IncrementOperator, AxisymmetricTrescaOnAnEdgeTangentMatchesFiniteDifferenceJacobian) {
  // Arrange: sigma_rr = sigma_tt = c_u, sigma_zz = -c_u (the radial and hoop stresses equal, at
  // yield: triaxial compression about the axis), stretched equally in r and theta (u_r = 0.005 r)
  // and compressed along z: the return is onto the edge where two planes of Tresca meet, with
  // the hoop stress one of its two equal principal stresses
  Case c;
  c.model = constitutive::make_model("tresca", {{"E", 100.0}, {"nu", 0.45}, {"cu", 2.0}}, "test");
  c.start = cloud(*c.model, 6);
  for (Mat3& sigma : c.start.stress) sigma = Vec3(2.0, -2.0, 2.0).asDiagonal();
  move_off_axis(c, 0.2, (Mat2() << 0.005, 0.0, 0.0, -0.03).finished(), 1e-3, 13);
  // Act
  const double error = tangent_error(c, true, 0.0, {}, 0.0, true);
  // Assert
  std::printf("axisymmetric tresca edge: %.2e\n", error);
  EXPECT_LT(error, 1e-6);
}

}  // namespace
}  // namespace duet::spfem
