// Tests of the boundary layer of the node-based smoothing (spfem/smoothing.hpp, layer_depth > 0):
// the particles are cell-centred, so the mesh through them lies dp/2 inside the material; each
// surface edge owns a strip of depth dp/2 outside it with its triangle's gradient. Checked: the
// linear patch test, the cell areas of a rectangle lattice (closed form, corner wedges included),
// the force a uniform stress transmits across a cut (sigma n times the true body's edge length) and
// virtual power.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <utility>
#include <vector>

#include "spfem/smoothing.hpp"
#include "tests/spfem/delaunay_mesh.hpp"

namespace duet::spfem {
namespace {

using testing::delaunay_mesh;
using testing::Lattice;
using testing::signed_area;

// A lattice jittered by up to 0.2 dp (a mesh with no ties and no regular surface).
std::vector<Vec2> jittered(const Lattice& lattice, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  std::vector<Vec2> x = lattice.points();
  for (Vec2& p : x) p += lattice.dp * Vec2(u(random), u(random));
  return x;
}

const Mat2 kGeneralGradient = (Mat2() << 0.7, -1.3, 0.45, -0.2).finished();

TEST(SmoothingLayer, LinearVelocityStaysExactAtEveryNode) {
  // Arrange: irregular mesh, v = v0 + G (x - x_c) about the body's centre x_c (the rounding of
  // sum_l v_l b_kl grows with |v| / (|G| dp)), layer of depth dp/2
  const Lattice lattice;
  const std::vector<Vec2> x = jittered(lattice, 7);
  const AlphaMesh mesh = delaunay_mesh(x);
  SmoothingCells cells;
  build_smoothing_cells(mesh, x, cells, 0.5 * lattice.dp);
  const Vec2 centre(0.5 * lattice.width(), 0.5 * lattice.height());
  std::vector<Vec2> v(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    v[i] = Vec2(0.03, -0.08) + kGeneralGradient * (x[i] - centre);
  }
  // Act
  std::vector<Mat2> l;
  smoothed_velocity_gradients(cells, v, l);
  // Assert: every cell (surface ones with their strips) integrates exact element gradients
  double worst = 0.0;
  for (const Mat2& l_k : l) {
    worst = std::max(worst, (l_k - kGeneralGradient).norm() / kGeneralGradient.norm());
  }
  std::printf("patch test with the layer: relative error %.2e\n", worst);
  EXPECT_LT(worst, 1e-12);
}

TEST(SmoothingLayer, CellAreasSumToTheBodyArea) {
  // Arrange: mesh (W - dp)(H - dp), perimeter 2 (W - dp) + 2 (H - dp), strips dp/2 deep, four
  // right-angled corners with a dp/2 x dp/2 wedge each
  const Lattice lattice;
  const std::vector<Vec2> x = lattice.points();
  const AlphaMesh mesh = delaunay_mesh(x);
  SmoothingCells cells;
  // Act
  build_smoothing_cells(mesh, x, cells, 0.5 * lattice.dp);
  // Assert: (W - dp)(H - dp) + (2 (W - dp) + 2 (H - dp)) dp / 2 + 4 (dp / 2)^2 = W H
  double sum = 0.0;
  for (const double a_k : cells.area) sum += a_k;
  const double body = lattice.width() * lattice.height();
  std::printf("cell areas %.12f, W H = %.12f\n", sum, body);
  EXPECT_NEAR(sum, body, 1e-12 * body);
}

// Resultant of the internal forces of a uniform stress on the nodes on one side of a straight cut
// through the lattice: the force the other part transmits across the cut.
Vec2 resultant_beyond(const std::vector<Vec2>& x, const std::vector<Vec2>& force, int axis,
                      double cut) {
  Vec2 sum = Vec2::Zero();
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (x[i][axis] > cut) sum += force[i];
  }
  return sum;
}

TEST(SmoothingLayer, UniformStressTransmitsSigmaNTimesTheTrueEdgeLengthsAcrossCuts) {
  // Arrange: general plane-strain stress on every node
  const Lattice lattice;
  const std::vector<Vec2> x = lattice.points();
  const AlphaMesh mesh = delaunay_mesh(x);
  SmoothingCells cells;
  build_smoothing_cells(mesh, x, cells, 0.5 * lattice.dp);
  Mat3 sigma;
  sigma << -3.0e5, 1.2e5, 0.0, 1.2e5, -1.0e5, 0.0, 0.0, 0.0, -1.5e5;  // Pa
  const Mat2 s = sigma.topLeftCorner<2, 2>();
  // Act
  std::vector<Vec2> force;
  internal_forces(cells, std::vector<Mat3>(x.size(), sigma), force);
  // Assert: the right part (cut x = W/2 between columns) holds sigma n_x H with the body's true
  // height H (the mesh alone gives H - dp), the top part (cut y = H/2) sigma n_y W
  const Vec2 right = resultant_beyond(x, force, 0, 0.5 * lattice.width());
  const Vec2 top = resultant_beyond(x, force, 1, 0.5 * lattice.height());
  const Vec2 right_expected = s * Vec2(1.0, 0.0) * lattice.height();
  const Vec2 top_expected = s * Vec2(0.0, 1.0) * lattice.width();
  std::printf(
      "right part %.6g %.6g (expected %.6g %.6g); top part %.6g %.6g (expected %.6g %.6g)\n",
      right.x(), right.y(), right_expected.x(), right_expected.y(), top.x(), top.y(),
      top_expected.x(), top_expected.y());
  const double scale = sigma.norm() * lattice.width();
  EXPECT_LT((right - right_expected).norm(), 1e-12 * scale);
  EXPECT_LT((top - top_expected).norm(), 1e-12 * scale);
}

TEST(SmoothingLayer, InternalPowerEqualsStressPowerWithTheLayer) {
  // Arrange: arbitrary nodal velocities and stresses on an irregular mesh
  const Lattice lattice;
  const std::vector<Vec2> x = jittered(lattice, 9);
  const AlphaMesh mesh = delaunay_mesh(x);
  SmoothingCells cells;
  build_smoothing_cells(mesh, x, cells, 0.5 * lattice.dp);
  std::mt19937 random(10);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec2> v(x.size());
  std::vector<Mat3> stress(x.size(), Mat3::Zero());
  for (std::size_t k = 0; k < x.size(); ++k) {
    v[k] = Vec2(u(random), u(random));
    stress[k](0, 0) = 1.0e5 * u(random);
    stress[k](1, 1) = 1.0e5 * u(random);
    stress[k](0, 1) = stress[k](1, 0) = 1.0e5 * u(random);
  }
  // Act
  std::vector<Vec2> force;
  internal_forces(cells, stress, force);
  std::vector<Mat2> l;
  smoothed_velocity_gradients(cells, v, l);
  // Assert: sum_l F_l . v_l == sum_k A_k sigma_k : L_k
  double internal_power = 0.0;
  double stress_power = 0.0;
  double scale = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    internal_power += force[k].dot(v[k]);
    const Mat2 s = stress[k].topLeftCorner<2, 2>();
    stress_power += cells.area[k] * (s.array() * l[k].array()).sum();
    scale += cells.area[k] * (s.array() * l[k].array()).abs().sum();
  }
  EXPECT_NEAR(internal_power, stress_power, 1e-12 * scale);
}

TEST(SmoothingLayer, RefillAtMovedPointsMatchesAFreshBuildOnTheSameTriangles) {
  // Arrange: cells of a mesh at x, then the same triangles at moved points x'
  const Lattice lattice;
  const std::vector<Vec2> x = jittered(lattice, 11);
  const AlphaMesh mesh = delaunay_mesh(x);
  std::vector<Vec2> moved = x;
  for (Vec2& p : moved) p += 0.1 * lattice.dp * Vec2(std::sin(7.0 * p.y()), std::cos(5.0 * p.x()));
  SmoothingCells refilled;
  build_smoothing_cells(mesh, x, refilled, 0.5 * lattice.dp);
  SmoothingCells fresh;
  build_smoothing_cells(mesh, moved, fresh, 0.5 * lattice.dp);
  // Act
  refill_smoothing_cells(mesh, moved, refilled, 0.5 * lattice.dp);
  // Assert: same rows, same areas and gradients (bit for bit: the same arithmetic)
  ASSERT_EQ(refilled.column, fresh.column);
  EXPECT_EQ(refilled.transpose, fresh.transpose);
  EXPECT_EQ(refilled.area, fresh.area);
  for (std::size_t e = 0; e < fresh.gradient.size(); ++e) {
    EXPECT_EQ(refilled.gradient[e], fresh.gradient[e]) << "entry " << e;
  }
}

}  // namespace
}  // namespace duet::spfem
