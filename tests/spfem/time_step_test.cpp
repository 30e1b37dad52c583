// Tests of the explicit SPFEM time step (ExplicitSolver::time_step): the Gershgorin bound on the
// highest frequency of the assembled smoothed system. On a lattice the step is below the true
// central-difference limit 2 / omega_max (found here by power iteration on the same operator) and
// within a factor of it; a surface node held by an alpha-shape sliver, whose cell is tiny but whose
// mass is a full particle's, no longer cuts the step.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <utility>
#include <vector>

#include "constitutive/registry.hpp"
#include "spfem/explicit_solver.hpp"
#include "spfem/smoothing.hpp"

namespace duet::spfem {
namespace {

constexpr double kDensity = 2000.0;  // kg/m^3
constexpr double kYoung = 1.0e6;     // Pa
constexpr double kPoisson = 0.3;
constexpr double kSpacing = 0.01;  // m

void add_node(Particles& p, std::size_t k, const Vec2& x) {
  p.position[k] = x;
  p.volume[k] = kSpacing * kSpacing;
  p.density[k] = kDensity;
  p.mass[k] = kDensity * kSpacing * kSpacing;
  p.material[k] = 0;
  p.body[k] = 0;
}

/// nx by ny nodes at the cell centres of a square lattice, plus `extra` nodes at `extra_at`.
Particles block(int nx, int ny, const std::vector<Vec2>& extra_at = {}) {
  Particles p;
  p.resize(static_cast<std::size_t>(nx * ny) + extra_at.size());
  std::size_t k = 0;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i, ++k)
      add_node(p, k, Vec2((i + 0.5) * kSpacing, (j + 0.5) * kSpacing));
  }
  for (const Vec2& x : extra_at) add_node(p, k++, x);
  return p;
}

EspfemSetup setup(double safety) {
  EspfemSetup s;
  s.spacing = kSpacing;
  s.options.time_step_safety = safety;
  s.options.time_step = SpfemTimeStep::gershgorin;
  s.options.remesh = Remesh::angle;
  s.models.push_back(constitutive::make_model("linear-elastic", {{"E", kYoung}, {"nu", kPoisson}},
                                              "material.test"));
  return s;
}

/// Largest eigenvalue of M^-1 K for the smoothed plane-strain linear elastic stiffness of `cells`
/// (K u = F_int of the stress of the smoothed strain of u), by power iteration.
double omega_max_squared(const SmoothingCells& cells, const std::vector<double>& mass) {
  const double lambda = kYoung * kPoisson / ((1.0 + kPoisson) * (1.0 - 2.0 * kPoisson));
  const double shear = kYoung / (2.0 * (1.0 + kPoisson));
  const std::size_t n = mass.size();
  std::vector<Vec2> u(n), f(n);
  std::vector<Mat2> gradient;
  std::vector<Mat3> stress(n);
  for (std::size_t i = 0; i < n; ++i) u[i] = Vec2(std::sin(1.0 + 3.7 * i), std::cos(2.0 * i));
  double rayleigh = 0.0;
  for (int iteration = 0; iteration < 3000; ++iteration) {
    smoothed_velocity_gradients(cells, u, gradient);
    for (std::size_t k = 0; k < n; ++k) {
      const Mat2 eps = 0.5 * (gradient[k] + gradient[k].transpose());
      stress[k] = Mat3::Zero();
      stress[k].topLeftCorner<2, 2>() = lambda * eps.trace() * Mat2::Identity() + 2.0 * shear * eps;
    }
    internal_forces(cells, stress, f);
    double ku = 0.0, mu = 0.0, norm = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      ku += u[i].dot(f[i]);
      mu += mass[i] * u[i].squaredNorm();
    }
    rayleigh = ku / mu;  // u^T K u / u^T M u, rises to omega_max^2
    for (std::size_t i = 0; i < n; ++i) {
      u[i] = f[i] / mass[i];
      norm = std::max(norm, u[i].norm());
    }
    for (Vec2& ui : u) ui /= norm;
  }
  return rayleigh;
}

TEST(TimeStep, LatticeStepIsBelowTheCentralDifferenceLimitAndWithinAFactorTwoOfIt) {
  // Arrange: a free 12 x 8 lattice block at rest, safety 1 (the bound's own limit)
  Particles p = block(12, 8);
  ExplicitSolver solver(setup(1.0));
  solver.initialise(p);
  // Act
  const double dt = solver.step(p, 0.0);
  const double limit = 2.0 / std::sqrt(omega_max_squared(solver.cells(), p.mass));
  // Assert: stable (dt below 2 / omega_max) without being needlessly small
  const double c =
      std::sqrt(kYoung * (1.0 - kPoisson) / ((1.0 + kPoisson) * (1.0 - 2.0 * kPoisson)) / kDensity);
  std::printf("dt %.6e s, 2/omega_max %.6e s, ratio %.4f, dp/c %.6e s\n", dt, limit, dt / limit,
              kSpacing / c);
  EXPECT_LE(dt, limit);
  EXPECT_GT(dt, 0.5 * limit);
}

// duet check's estimate of a run's steps takes the rule's step on a lattice as this fraction of
// dp / c; an interior-dominated block's step is within 5 % of it.
TEST(TimeStep, GershgorinStepOnALatticeIsItsStatedFractionOfDpOverC) {
  Particles p = block(12, 8);
  ExplicitSolver solver(setup(1.0));
  solver.initialise(p);
  const double dt = solver.step(p, 0.0);
  const double c =
      std::sqrt(kYoung * (1.0 - kPoisson) / ((1.0 + kPoisson) * (1.0 - 2.0 * kPoisson)) / kDensity);
  EXPECT_NEAR(dt / (kSpacing / c), lattice_step_over_dp_per_c(SpfemTimeStep::gershgorin), 0.035);
}

TEST(TimeStep, SurfaceNodeHeldByASliverDoesNotCutTheStep) {
  // Arrange: the same block, and once more with a node 0.25 dp above the middle of a top surface
  // edge (outside the circumcircles of the lattice squares, so the top row stays). It is held by
  // one triangle only, thinner than the layer depth dp/2 (2 A_e = dp^2 / 4 < dp/2 x dp), so it
  // gets no strip: its cell is A_e / 3 = dp^2 / 24, while it carries a full particle mass.
  Particles plain = block(12, 8);
  const Vec2 above(6.0 * kSpacing, 7.75 * kSpacing);
  Particles with_sliver = block(12, 8, {above});
  ExplicitSolver plain_solver(setup(1.0));
  ExplicitSolver sliver_solver(setup(1.0));
  plain_solver.initialise(plain);
  sliver_solver.initialise(with_sliver);
  // Act
  const double dt_plain = plain_solver.step(plain, 0.0);
  const double dt_sliver = sliver_solver.step(with_sliver, 0.0);
  // Assert: the node is in the mesh with a small cell, the step stays within 30 % of the plain one
  // (sqrt(A_k) / c would have cut it by sqrt(24) = 4.9) and below the true limit
  const SmoothingCells& cells = sliver_solver.cells();
  const double cell = cells.area.back();
  const double limit = 2.0 / std::sqrt(omega_max_squared(cells, with_sliver.mass));
  std::printf("sliver node cell %.4f dp^2; dt %.6e s (plain %.6e s), 2/omega_max %.6e s\n",
              cell / (kSpacing * kSpacing), dt_sliver, dt_plain, limit);
  ASSERT_GT(cell, 0.0);
  EXPECT_LT(cell, 0.05 * kSpacing * kSpacing);
  EXPECT_GT(dt_sliver, 0.7 * dt_plain);
  EXPECT_LE(dt_sliver, limit);
}

/// Largest in-plane |sigma_dot|_2 / (|v| |b|) of `model` at `stress` over the rates D = sym(v (x)
/// b) of unit in-plane v and b (1-degree sweep), the quantity the Gershgorin block bound needs.
double largest_rate(const constitutive::Model& model, const Mat3& stress) {
  const std::vector<double> internal(model.internal_variables().size(), 0.0);
  double largest = 0.0;
  for (int i = 0; i < 360; ++i) {
    const double a = i * std::numbers::pi / 180.0;
    const Vec3 v(std::cos(a), std::sin(a), 0.0);
    for (int j = 0; j < 180; ++j) {
      const double c = j * std::numbers::pi / 180.0;
      const Vec3 b(std::cos(c), std::sin(c), 0.0);
      const Mat3 d = 0.5 * (v * b.transpose() + b * v.transpose());
      const Mat2 rate = model.objective_rate(d, stress, internal).topLeftCorner<2, 2>();
      const Eigen::Vector2d eigen = Eigen::SelfAdjointEigenSolver<Mat2>(rate).eigenvalues();
      largest = std::max({largest, std::abs(eigen(0)), std::abs(eigen(1))});
    }
  }
  return largest;
}

std::unique_ptr<constitutive::Model> collapse_sand() {
  // Peng 2015 Table 1, sand collapse
  return constitutive::make_model("hypoplastic",
                                  {{"c1", -55.6}, {"c2", -171.2}, {"c3", -540.9}, {"c4", -170.9}},
                                  "material.sand");
}

TEST(TimeStep, HypoplasticTangentBoundIsTheIsotropicClosedForm) {
  // Arrange: isotropic eta = -p I, where every term of the bound is attained by v = b
  const auto sand = collapse_sand();
  const double p = 1000.0;  // Pa
  // Act
  const constitutive::ElasticModuli e = sand->moduli(-p * Mat3::Identity(), {});
  // Assert: (3 |c1| + |c2| + |c3| / 3 + |c4|) p (Peng 2015 eq 15 at eta = -p I) and the sweep
  const double closed_form = (3.0 * 55.6 + 171.2 + 540.9 / 3.0 + 170.9) * p;
  EXPECT_NEAR(e.tangent_bound, closed_form, 1e-9 * closed_form);
  EXPECT_NEAR(largest_rate(*sand, -p * Mat3::Identity()), closed_form, 1e-6 * closed_form);
}

TEST(TimeStep, HypoplasticTangentBoundCoversTheRateAlongEveryInPlaneDirection) {
  // Arrange: K0 = 0.5, and two sheared states (tension positive, Pa)
  const auto sand = collapse_sand();
  std::vector<Mat3> stresses(3);
  stresses[0] << -500, 0, 0, 0, -1000, 0, 0, 0, -500;
  stresses[1] << -600, 250, 0, 250, -1000, 0, 0, 0, -700;
  stresses[2] << -200, 300, 0, 300, -1500, 0, 0, 0, -500;
  for (const Mat3& stress : stresses) {
    // Act
    const constitutive::ElasticModuli e = sand->moduli(stress, {});
    const double largest = largest_rate(*sand, stress);
    const double isotropic = std::abs(e.bulk - 2.0 * e.shear / 3.0) + 2.0 * e.shear;
    std::printf("bound %.5e, largest rate %.5e, |lambda| + 2G %.5e (x%.3f short)\n",
                e.tangent_bound, largest, isotropic, largest / isotropic);
    // Assert: a bound (the sweep is a lower estimate of the supremum), within 1 % of it, and the
    // isotropic projection of L alone falls short of the N term's share (by 2.1-3.4 here)
    EXPECT_GE(e.tangent_bound, largest);
    EXPECT_LT(e.tangent_bound, 1.01 * largest);
    EXPECT_GT(largest, 2.0 * isotropic);
  }
}

/// The 12 x 8 block of hypoplastic sand at -p I, compressed uniformly at `rate` (1/s) about its
/// centre; returns the first step's dt and whether the stress-increment limit set it.
std::pair<double, long> compressed_sand_step(double rate, double limit) {
  const double p = 1000.0;  // Pa
  Particles particles = block(12, 8);
  particles.internal.width = 1;
  particles.internal.values.assign(particles.size(), 0.0);
  const Vec2 centre(6.0 * kSpacing, 4.0 * kSpacing);
  for (std::size_t k = 0; k < particles.size(); ++k) {
    particles.stress[k] = -p * Mat3::Identity();
    particles.velocity[k] = -rate * (particles.position[k] - centre);
  }
  EspfemSetup s = setup(0.5);
  s.models.front() = collapse_sand();
  s.options.stress_increment_limit = limit;
  ExplicitSolver solver(std::move(s));
  solver.initialise(particles);
  const double dt = solver.step(particles, 0.0);
  return {dt, solver.counters().stress_limited_steps};
}

TEST(TimeStep, StressIncrementLimitBoundsTheStiffeningOfAFastCompressedNodeOnly) {
  // Arrange: a linear velocity field, so every node has D = -rate I (in plane, patch test), at
  // -p I where M = 689.2 p (HypoplasticTangentBoundIsTheIsotropicClosedForm) and |sigma| = sqrt(3)
  // p
  const double rate = 100.0;  // 1/s: a grain landing on the pile at 1 m/s over a spacing
  const double limit = 0.5;
  // Act
  const auto [dt_fast, limited_fast] = compressed_sand_step(rate, limit);
  const auto [dt_slow, limited_slow] = compressed_sand_step(1e-3 * rate, limit);
  const auto [dt_pulled, limited_pulled] = compressed_sand_step(-rate, limit);
  // Assert: dt = limit |sigma| / (M |D|) = 0.5 sqrt(3) / (689.2 sqrt(2) 100) while it is below
  // the Gershgorin step; a slow compression keeps that step, and so does a fast extension (the
  // stress falls: sigma : D < 0)
  const double m_over_sigma = (3.0 * 55.6 + 171.2 + 540.9 / 3.0 + 170.9) / std::sqrt(3.0);
  const double expected = limit / (m_over_sigma * std::sqrt(2.0) * rate);
  std::printf("dt %.6e s (closed form %.6e s), slow compression dt %.6e s\n", dt_fast, expected,
              dt_slow);
  EXPECT_NEAR(dt_fast, expected, 1e-9 * expected);
  EXPECT_EQ(limited_fast, 1);
  EXPECT_EQ(limited_slow, 0);
  EXPECT_GT(dt_slow, 10.0 * dt_fast);
  EXPECT_EQ(limited_pulled, 0);
  EXPECT_GT(dt_pulled, 10.0 * dt_fast);
}

}  // namespace
}  // namespace duet::spfem
