// Tests of the stiffness stabilisation of nodal integration (spfem/stiffness_stabilisation.hpp):
// zero for affine deformations and rigid rotations (patch test, objectivity), the force is
// -dW/dx (central differences), momentum and angular momentum are conserved, and a mode that the
// node-based smoothing cannot see (checkerboard on a lattice) costs energy (the scene key:
// tests/common/scene_loader_test.cpp).
#include "spfem/stiffness_stabilisation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "spfem/smoothing.hpp"
#include "tests/spfem/delaunay_mesh.hpp"

namespace duet::spfem {
namespace {

using testing::delaunay_mesh;

constexpr double kDp = 0.1;  // m

/// A jittered 8 x 6 lattice (+-0.2 dp), so no triangle is special.
std::vector<Vec2> jittered_points(unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> jitter(-0.2 * kDp, 0.2 * kDp);
  std::vector<Vec2> x;
  for (int j = 0; j < 6; ++j) {
    for (int i = 0; i < 8; ++i) {
      x.emplace_back((i + 0.5) * kDp + jitter(random), (j + 0.5) * kDp + jitter(random));
    }
  }
  return x;
}

/// Per-node P-wave moduli that differ from node to node (Pa), so Q_k of the full derivative
/// does not vanish.
std::vector<double> varying_moduli(std::size_t n, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> m(5e6, 2e7);
  std::vector<double> out(n);
  for (double& v : out) v = m(random);
  return out;
}

/// `reference` moved by a random displacement of up to `size` dp per component, then rotated by
/// `angle` (rad) about the origin.
std::vector<Vec2> perturbed(const std::vector<Vec2>& reference, double size, double angle,
                            unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> d(-size * kDp, size * kDp);
  const Mat2 r = Eigen::Rotation2Dd(angle).toRotationMatrix();
  std::vector<Vec2> x;
  for (const Vec2& p : reference) x.push_back(r * (p + Vec2(d(random), d(random))));
  return x;
}

struct Problem {
  std::vector<Vec2> reference;
  AlphaMesh mesh;
  NodeTriangles rows;
  std::vector<double> modulus;
  double s = 1.0;
};

Problem jittered_problem(unsigned seed) {
  Problem p;
  p.reference = jittered_points(seed);
  p.mesh = delaunay_mesh(p.reference);
  build_node_triangles(p.mesh.triangles, p.reference.size(), p.rows);
  p.modulus = varying_moduli(p.reference.size(), seed + 1);
  return p;
}

double energy(const Problem& p, const std::vector<Vec2>& x) {
  StiffnessStabilisationScratch scratch;
  return stiffness_stabilisation_energy(p.mesh.triangles, p.rows, p.reference, x, p.modulus, p.s,
                                        scratch);
}

std::vector<Vec2> forces(const Problem& p, const std::vector<Vec2>& x, double* w = nullptr) {
  StiffnessStabilisationScratch scratch;
  std::vector<Vec2> f;
  const double e = stiffness_stabilisation_forces(p.mesh.triangles, p.rows, p.reference, x,
                                                  p.modulus, p.s, scratch, f);
  if (w != nullptr) *w = e;
  return f;
}

double largest(const std::vector<Vec2>& f) {
  double m = 0.0;
  for (const Vec2& v : f) m = std::max(m, v.norm());
  return m;
}

TEST(StiffnessStabilisation, VanishesForAffineDeformationsAndLargeRigidRotations) {
  // Arrange: stretch and shear, then a rigid rotation of 1.2 rad and a translation
  const Problem p = jittered_problem(7);
  const Mat2 stretch = (Mat2() << 1.3, 0.4, -0.1, 0.8).finished();
  const Mat2 rotation = Eigen::Rotation2Dd(1.2).toRotationMatrix();
  const Vec2 shift(0.7, -2.1);
  std::vector<Vec2> affine, rigid;
  for (const Vec2& x : p.reference) {
    affine.push_back(rotation * stretch * x + shift);
    rigid.push_back(rotation * x + shift);
  }
  // The scale of a force that a non-affine field of O(1) strain would give: s M dp
  const double scale = p.s * 2e7 * kDp;
  const double energy_scale = p.s * 2e7 * kDp * kDp * static_cast<double>(p.reference.size());
  for (const std::vector<Vec2>* x : {&affine, &rigid}) {
    // Act
    double w = 0.0;
    const std::vector<Vec2> f = forces(p, *x, &w);
    // Assert: F_e = Fbar_k everywhere
    std::printf("max |f| / (s M dp) = %.2e, W / (s M n dp^2) = %.2e\n", largest(f) / scale,
                w / energy_scale);
    EXPECT_LT(largest(f), 1e-12 * scale);
    EXPECT_LT(std::abs(w), 1e-24 * energy_scale);
  }
}

TEST(StiffnessStabilisation, ForceIsMinusTheGradientOfTheEnergyByCentralDifferences) {
  // Arrange: a non-affine deformation of a jittered mesh, rotated by 0.6 rad, moduli varying by
  // node
  const Problem p = jittered_problem(11);
  const std::vector<Vec2> x = perturbed(p.reference, 0.15, 0.6, 12);
  // Act
  double w = 0.0;
  const std::vector<Vec2> f = forces(p, x, &w);
  // Assert: W is quadratic in x, so a central difference is exact up to rounding
  ASSERT_GT(w, 0.0);
  EXPECT_NEAR(w, energy(p, x), 1e-14 * w);
  const double h = 1e-6 * kDp;
  double worst = 0.0;
  for (std::size_t a = 0; a < x.size(); ++a) {
    for (int c = 0; c < 2; ++c) {
      std::vector<Vec2> plus = x, minus = x;
      plus[a][c] += h;
      minus[a][c] -= h;
      const double gradient = (energy(p, plus) - energy(p, minus)) / (2.0 * h);
      worst = std::max(worst, std::abs(-gradient - f[a][c]));
    }
  }
  std::printf("max |f + dW/dx| / max |f| = %.2e (max |f| %.3e N/m)\n", worst / largest(f),
              largest(f));
  EXPECT_LT(worst, 1e-6 * largest(f));
}

TEST(StiffnessStabilisation, ForcesSumToZeroAndExertNoTorque) {
  // Arrange: a non-affine, rotated deformation (momentum is conserved for any x)
  const Problem p = jittered_problem(21);
  const std::vector<Vec2> x = perturbed(p.reference, 0.2, -0.9, 22);
  // Act
  const std::vector<Vec2> f = forces(p, x);
  // Assert: sum f = 0 (sum_a G_a^e = 0) and sum x x f = 0 (W does not change under a rotation of
  // x, which holds because Fbar_k is differentiated too)
  Vec2 total = Vec2::Zero();
  double torque = 0.0, size = 0.0, moment_size = 0.0;
  for (std::size_t a = 0; a < x.size(); ++a) {
    total += f[a];
    torque += x[a].x() * f[a].y() - x[a].y() * f[a].x();
    size += f[a].norm();
    moment_size += x[a].norm() * f[a].norm();
  }
  std::printf("|sum f| / sum |f| = %.2e, |torque| / sum |x||f| = %.2e\n", total.norm() / size,
              std::abs(torque) / moment_size);
  ASSERT_GT(size, 0.0);
  EXPECT_LT(total.norm(), 1e-12 * size);
  EXPECT_LT(std::abs(torque), 1e-12 * moment_size);
}

TEST(StiffnessStabilisation, CheckerboardModeThatSmoothingCannotSeeCostsEnergy) {
  // Arrange: a 10 x 8 lattice split along one diagonal direction throughout, and the
  // checkerboard displacement u = eps dp (-1)^(i+j) (1, 1). Around an interior node the patch of
  // triangles is centrally symmetric and so is u, so the smoothed gradient
  // (1 / A_k) sum_e (A_e / 3) grad u_e = boundary integral of u n is zero: nodal integration
  // sees no strain there.
  const int nx = 10, ny = 8;
  const auto id = [&](int i, int j) { return static_cast<std::int32_t>(j * nx + i); };
  Problem p;
  AlphaMesh& mesh = p.mesh;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) p.reference.emplace_back((i + 0.5) * kDp, (j + 0.5) * kDp);
  }
  for (int j = 0; j + 1 < ny; ++j) {
    for (int i = 0; i + 1 < nx; ++i) {
      mesh.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      mesh.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  mesh.n_delaunay = mesh.triangles.size();
  build_node_triangles(mesh.triangles, p.reference.size(), p.rows);
  p.modulus.assign(p.reference.size(), 1e7);
  const double eps = 1e-3;
  std::vector<Vec2> x, mode;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const double sign = (i + j) % 2 == 0 ? 1.0 : -1.0;
      mode.push_back(sign * Vec2(1.0, 1.0));
      x.push_back(p.reference[static_cast<std::size_t>(id(i, j))] + eps * kDp * mode.back());
    }
  }
  SmoothingCells cells;
  build_smoothing_cells(mesh, p.reference, cells);
  std::vector<Mat2> smoothed;
  smoothed_velocity_gradients(cells, mode, smoothed);
  // Act
  const double w = energy(p, x);
  // Assert: invisible to the smoothing at every interior node, but W > 0. Every triangle has
  // |F_e - I| = |eps (1, 1) (x) (-+2, +-2)| = 4 eps, so with Fbar_k = I at every node W would be
  // 1/2 s M (4 eps)^2 area = 8 s M eps^2 area; at the boundary nodes Fbar_k is the minimiser of
  // sum_e A0_e |F_e - F|^2, which only lowers it.
  double interior = 0.0;
  for (int j = 1; j + 1 < ny; ++j) {
    for (int i = 1; i + 1 < nx; ++i) {
      interior = std::max(interior, smoothed[static_cast<std::size_t>(id(i, j))].norm());
    }
  }
  const double area = (nx - 1) * (ny - 1) * kDp * kDp;
  const double full = 8.0 * p.s * 1e7 * eps * eps * area;
  std::printf("max interior |smoothed grad u| = %.2e /m, W / (8 s M eps^2 area) = %.3f\n", interior,
              w / full);
  EXPECT_LT(interior, 1e-12);
  EXPECT_GT(w, 0.5 * full);
  EXPECT_LE(w, full * (1.0 + 1e-12));
}

}  // namespace
}  // namespace duet::spfem
