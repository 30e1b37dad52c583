// Tests of the SPH step (sph/sph_solver.hpp): rest states, rigid translation, momentum balance,
// wall reactions, and the closed-form settlement of an elastic column under its own weight.
#include "sph/sph_solver.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "common/solver.hpp"
#include "constitutive/registry.hpp"

namespace duet::sph {
namespace {

constexpr double kDensity = 2000.0;  // kg/m^3
constexpr double kYoung = 1.0e6;     // Pa
constexpr double kPoisson = 0.3;

std::unique_ptr<constitutive::Model> elastic() {
  return constitutive::make_model("linear-elastic", {{"E", kYoung}, {"nu", kPoisson}},
                                  "material.test");
}

/// Oedometric (constrained) modulus M = E (1 - nu) / ((1 + nu)(1 - 2 nu)).
double constrained_modulus() {
  return kYoung * (1.0 - kPoisson) / ((1.0 + kPoisson) * (1.0 - 2.0 * kPoisson));
}

/// A block of nx by ny particles on a square lattice of spacing dp, lower left corner at origin.
Particles block(int nx, int ny, double dp, const Vec2& origin = Vec2::Zero()) {
  Particles p;
  p.resize(static_cast<std::size_t>(nx * ny));
  std::size_t k = 0;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i, ++k) {
      p.position[k] = origin + Vec2((i + 0.5) * dp, (j + 0.5) * dp);
      p.volume[k] = dp * dp;
      p.density[k] = kDensity;
      p.mass[k] = kDensity * dp * dp;
      p.material[k] = 0;
      p.body[k] = 0;
    }
  }
  return p;
}

SphSetup setup(double dp, SphIntegrator integrator = SphIntegrator::verlet) {
  SphSetup s;
  s.spacing = dp;
  s.options.integrator = integrator;
  s.options.sound_speed = 30.0;  // above the P-wave speed sqrt(M / rho) = 25.9 m/s
  s.options.cfl = 0.1;
  s.models.push_back(elastic());
  return s;
}

/// Column of width w and height hgt in a box: no-slip floor, free-slip sides.
void add_box(SphSetup& s, double w, double hgt) {
  s.walls.push_back({"floor", {Vec2(0, 0), Vec2(w, 0)}, WallCondition::no_slip, {}});
  s.walls.push_back({"left", {Vec2(0, 0), Vec2(0, 2 * hgt)}, WallCondition::free_slip, {}});
  s.walls.push_back({"right", {Vec2(w, 0), Vec2(w, 2 * hgt)}, WallCondition::free_slip, {}});
}

/// A block (as `block`) under a uniform pressure of 10 kPa.
Particles pressed_block(int nx, int ny, double dp, const Vec2& origin = Vec2::Zero()) {
  Particles p = block(nx, ny, dp, origin);
  for (Mat3& stress : p.stress) stress = -1.0e4 * Mat3::Identity();
  return p;
}

/// A symmetry plane from a to b (a free-slip wall to SPH, its ghosts the other half).
WallSpec symmetry_plane(const Vec2& a, const Vec2& b) {
  WallSpec plane{"plane", {a, b}, WallCondition::free_slip, {}};
  plane.symmetry = true;
  return plane;
}

double run(SphSolver& solver, Particles& p, int steps) {
  double t = 0.0;
  for (int k = 0; k < steps; ++k) t += solver.step(p, t);
  return t;
}

TEST(SphSolver, FreeBlockTranslatingRigidlyKeepsZeroStress) {
  // Arrange: no gravity, no walls, uniform velocity
  const double dp = 0.01;
  Particles p = block(12, 8, dp);
  const Vec2 v(1.5, -0.5);
  for (auto& vi : p.velocity) vi = v;
  const std::vector<Vec2> x0 = p.position;
  for (const SphIntegrator integrator : {SphIntegrator::verlet, SphIntegrator::leapfrog}) {
    Particles q = p;
    SphSolver solver(setup(dp, integrator));
    solver.initialise(q);
    // Act
    const double t = run(solver, q, 200);
    // Assert
    double stress = 0.0, drift = 0.0;
    for (std::size_t i = 0; i < q.size(); ++i) {
      stress = std::max(stress, q.stress[i].cwiseAbs().maxCoeff());
      drift = std::max(drift, (q.position[i] - x0[i] - v * t).norm());
    }
    EXPECT_EQ(stress, 0.0);
    EXPECT_LT(drift, 1e-12);
  }
}

TEST(SphSolver, PairForcesConserveMomentumWithoutWalls) {
  // Arrange: random stresses (tension included, artificial stress on), random velocities, no
  // gravity: every pair term of eq 30 is antisymmetric, so sum_i m_i a_i = 0.
  const double dp = 0.01;
  Particles p = block(15, 10, dp);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.velocity[i] = Vec2(u(rng), u(rng));
    p.position[i] += 0.2 * dp * Vec2(u(rng), u(rng));
    Mat3 s = Mat3::Zero();
    s(0, 0) = 1e4 * u(rng);
    s(1, 1) = 1e4 * u(rng);
    s(0, 1) = s(1, 0) = 1e4 * u(rng);
    p.stress[i] = s;
  }
  SphSetup s = setup(dp);
  s.options.artificial_stress = 0.3;
  SphSolver solver(std::move(s));
  solver.initialise(p);
  // Act
  solver.step(p, 0.0);
  // Assert
  Vec2 total = Vec2::Zero();
  double scale = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    total += p.mass[i] * solver.accelerations()[i];
    scale += p.mass[i] * solver.accelerations()[i].norm();
  }
  EXPECT_LT(total.norm(), 1e-12 * scale);
  EXPECT_GT(scale, 0.0);
}

TEST(SphSolver, AUniformStressIsInEquilibriumInTheCornerOfAWallAndASymmetryPlane) {
  // Arrange: a quarter of a block under a uniform pressure of 10 kPa, held by a free-slip wall
  // x = 0 and a symmetry plane y = 0 (the corner of the cavity wall and its symmetry planes), no
  // gravity. The corner particles need the ghosts of the plane's images across the wall (the
  // corner's images) for a whole support; without them they are pushed into the corner.
  const double dp = 0.01;
  Particles p = pressed_block(12, 12, dp);
  SphSetup s = setup(dp);
  s.walls.push_back({"wall", {Vec2(0, 0), Vec2(0, 0.3)}, WallCondition::free_slip, {}});
  s.walls.push_back(symmetry_plane(Vec2(0, 0), Vec2(0.3, 0)));
  SphSolver solver(std::move(s));
  solver.initialise(p);
  // Act
  solver.step(p, 0.0);
  // Assert: within 3 dp of the corner (far from the free edges) every particle is at rest,
  // against the scale p / (rho dp) = 500 m/s^2 of one missing neighbour's push
  const double scale = 1.0e4 / (kDensity * dp);
  int checked = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.position[i].x() > 3 * dp || p.position[i].y() > 3 * dp) continue;
    EXPECT_LT(solver.accelerations()[i].norm(), 1e-9 * scale)
        << "particle at (" << p.position[i].x() << ", " << p.position[i].y() << ")";
    ++checked;
  }
  EXPECT_EQ(checked, 9);
}

TEST(SphSolver, AWallCutByASymmetryPlaneCarriesHalfTheWholeBodysThrust) {
  // Arrange: a block 0.12 m wide and 0.24 m high under a uniform pressure of 10 kPa against a
  // free-slip wall x = 0, whole (y from -0.12 to 0.12) and halved by a symmetry plane y = 0
  const double dp = 0.01;
  const auto wall_thrust = [dp](bool half) {
    Particles p = half ? pressed_block(12, 12, dp) : pressed_block(12, 24, dp, Vec2(0.0, -0.12));
    SphSetup s = setup(dp);
    s.walls.push_back(
        {"wall", {Vec2(0, half ? 0.0 : -0.3), Vec2(0, 0.3)}, WallCondition::free_slip, {}});
    if (half) s.walls.push_back(symmetry_plane(Vec2(0, 0), Vec2(0.3, 0)));
    SphSolver solver(std::move(s));
    solver.initialise(p);
    solver.step(p, 0.0);
    return solver.wall_forces()[0];
  };
  // Act
  const Vec2 whole = wall_thrust(false);
  const Vec2 half = wall_thrust(true);
  // Assert: the soil pushes the wall towards -x; the half carries half of it, the corner's
  // images of the ghosts included (without them the half carried less)
  // (the y parts differ: the ghosts of the free top row pull along the wall, and in the whole
  // block the bottom row's cancel them)
  ASSERT_LT(whole.x(), -0.5 * 1.0e4 * 0.24);
  EXPECT_NEAR(half.x(), 0.5 * whole.x(), 1e-9 * std::abs(whole.x()));
}

TEST(SphSolver, AParticleEndingAStepBeyondASymmetryPlaneBecomesItsMirrorImage) {
  // Arrange: a stress-free block on a symmetry plane y = 0; its corner particle set 1 mm beyond
  // the plane, moving away from it at 1 m/s, with a shear stress
  const double dp = 0.01;
  Particles p = block(6, 6, dp);
  p.position[0] = Vec2(0.5 * dp, -0.001);
  p.velocity[0] = Vec2(0.2, -1.0);
  p.stress[0](0, 1) = p.stress[0](1, 0) = 100.0;
  SphSetup s = setup(dp);
  s.walls.push_back(symmetry_plane(Vec2(-0.3, 0), Vec2(0.3, 0)));
  SphSolver solver(std::move(s));
  solver.initialise(p);
  // Act
  const double dt = solver.step(p, 0.0);
  // Assert: in front of the plane, moving towards +y, the shear stress of its image (-100 Pa,
  // changed by one step's rate at most), counted once
  EXPECT_GT(p.position[0].y(), 0.001);
  EXPECT_LT(p.position[0].y(), 0.001 + 1.5 * dt);
  EXPECT_GT(p.velocity[0].y(), 0.5);
  EXPECT_NEAR(p.velocity[0].x(), 0.2, 0.1);
  EXPECT_LT(p.stress[0](0, 1), -50.0);
  EXPECT_EQ(p.stress[0](0, 1), p.stress[0](1, 0));
  EXPECT_EQ(solver.counters().symmetry_reflections, 1);
}

TEST(SphSolver, GeostaticColumnStaysAtRest) {
  // Arrange: elastic column 0.1 m wide, 0.2 m high, geostatic stress with K0 = nu / (1 - nu)
  const double dp = 0.005, w = 0.1, hgt = 0.2, g = 9.81;
  const double k0 = kPoisson / (1.0 - kPoisson);
  for (const SphIntegrator integrator : {SphIntegrator::verlet, SphIntegrator::leapfrog}) {
    Particles p = block(20, 40, dp);
    for (std::size_t i = 0; i < p.size(); ++i) {
      const double sv = -kDensity * g * (hgt - p.position[i].y());
      p.stress[i].diagonal() << k0 * sv, sv, k0 * sv;
    }
    SphSetup s = setup(dp, integrator);
    s.gravity = Vec2(0, -g);
    add_box(s, w, hgt);
    SphSolver solver(std::move(s));
    solver.initialise(p);
    // Act: 3000 steps, about two P-wave periods 4 H / c of the column
    const double t = run(solver, p, 3000);
    // Assert: the largest displacement stays below the elastic settlement scale of the column
    // under its own weight, rho g H^2 / (2 M) = 2.9e-4 m, and speeds below 1% of sqrt(g H).
    double u_max = 0.0, v_max = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      u_max = std::max(u_max, p.displacement[i].norm());
      v_max = std::max(v_max, p.velocity[i].norm());
    }
    const double settlement = kDensity * g * hgt * hgt / (2.0 * constrained_modulus());
    std::printf("integrator %d: t = %.4f s, u_max = %.3e m (scale %.3e), v_max = %.3e m/s\n",
                static_cast<int>(integrator), t, u_max, settlement, v_max);
    EXPECT_LT(u_max, settlement);
    EXPECT_LT(v_max, 0.01 * std::sqrt(g * hgt));
    EXPECT_EQ(solver.counters().penetrations_max, 0);
  }
}

TEST(SphSolver, FloorCarriesTheWeightOfAColumnAtRest) {
  // Arrange
  const double dp = 0.005, w = 0.1, hgt = 0.2, g = 9.81;
  const double k0 = kPoisson / (1.0 - kPoisson);
  Particles p = block(20, 40, dp);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double sv = -kDensity * g * (hgt - p.position[i].y());
    p.stress[i].diagonal() << k0 * sv, sv, k0 * sv;
  }
  SphSetup s = setup(dp);
  s.gravity = Vec2(0, -g);
  add_box(s, w, hgt);
  SphSolver solver(std::move(s));
  solver.initialise(p);
  // Act
  run(solver, p, 1000);
  // Assert: floor reaction = weight rho g w H (N/m), side walls carry no vertical load
  const double weight = kDensity * g * w * hgt;
  const auto& f = solver.wall_forces();
  std::printf("floor %.3f N/m (weight %.3f), left %.3f %.3f, right %.3f %.3f\n", f[0].y(), weight,
              f[1].x(), f[1].y(), f[2].x(), f[2].y());
  EXPECT_NEAR(-f[0].y(), weight, 0.02 * weight);
  EXPECT_NEAR(f[1].y(), 0.0, 0.02 * weight);
  EXPECT_NEAR(f[2].y(), 0.0, 0.02 * weight);
}

TEST(SphSolver, FreeSlipWallsCarryTheAtRestLateralThrust) {
  // Arrange: as above; ghost particles of the free-slip side walls must carry the horizontal
  // thrust K0 rho g H^2 / 2 of the geostatic stress and no shear.
  const double dp = 0.005, w = 0.1, hgt = 0.2, g = 9.81;
  const double k0 = kPoisson / (1.0 - kPoisson);
  Particles p = block(20, 40, dp);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double sv = -kDensity * g * (hgt - p.position[i].y());
    p.stress[i].diagonal() << k0 * sv, sv, k0 * sv;
  }
  SphSetup s = setup(dp);
  s.gravity = Vec2(0, -g);
  add_box(s, w, hgt);
  SphSolver solver(std::move(s));
  solver.initialise(p);
  // Act
  run(solver, p, 1000);
  // Assert
  const double thrust = k0 * kDensity * g * hgt * hgt / 2.0;
  const auto& f = solver.wall_forces();
  EXPECT_NEAR(-f[1].x(), thrust, 0.02 * thrust);
  EXPECT_NEAR(f[2].x(), thrust, 0.02 * thrust);
}

TEST(SphSolver, GravityLoadingWithDampingReachesTheGeostaticStress) {
  // Arrange: stress-free column in a box; Peng 2015 section 5.3 gravity loading with damping
  const double dp = 0.005, w = 0.05, hgt = 0.1, g = 9.81;
  Particles p = block(10, 20, dp);
  SphSetup s = setup(dp, SphIntegrator::leapfrog);
  s.gravity = Vec2(0, -g);
  add_box(s, w, hgt);
  SphSolver solver(std::move(s));
  solver.initialise(p);
  const double period = 4.0 * hgt / std::sqrt(constrained_modulus() / kDensity);
  // Act: damping 1/s of the order of the lowest frequency, for four periods
  solver.settle(p, 4.0 * period, 2.0 * std::numbers::pi / period);
  // Assert: vertical stress of the particles at mid-height (away from floor and surface) equals
  // -rho g (H - y); horizontal over vertical equals nu / (1 - nu); everything at rest.
  double worst_v = 0.0, worst_k0 = 0.0, v_max = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    v_max = std::max(v_max, p.velocity[i].norm());
    const double y = p.position[i].y();
    if (y < 0.3 * hgt || y > 0.7 * hgt) continue;
    const double sv = -kDensity * g * (hgt - y);
    worst_v = std::max(worst_v, std::abs(p.stress[i](1, 1) / sv - 1.0));
    worst_k0 = std::max(
        worst_k0, std::abs(p.stress[i](0, 0) / p.stress[i](1, 1) - kPoisson / (1.0 - kPoisson)));
  }
  std::printf("worst sigma_v error %.3f, worst K0 error %.3f\n", worst_v, worst_k0);
  EXPECT_LT(worst_v, 0.05);
  EXPECT_LT(worst_k0, 0.05);
  EXPECT_EQ(v_max, 0.0);
  EXPECT_EQ(p.displacement[0].norm(), 0.0);
}

TEST(SphSolver, ElasticColumnSettlesToTheConstrainedCompressionSolution) {
  // Arrange: stress-free column, gravity switched on; free-slip sides make it one-dimensional, so
  // the static top settlement is rho g H^2 / (2 M). The column oscillates about it and the
  // artificial viscosity damps it; average the top displacement over the last wave period.
  const double dp = 0.005, w = 0.05, hgt = 0.1, g = 9.81;
  Particles p = block(10, 20, dp);
  SphSetup s = setup(dp, SphIntegrator::leapfrog);
  s.gravity = Vec2(0, -g);
  add_box(s, w, hgt);
  SphSolver solver(std::move(s));
  solver.initialise(p);
  const double c = std::sqrt(constrained_modulus() / kDensity);
  const double period = 4.0 * hgt / c;
  // Act
  double t = 0.0, sum = 0.0, weight = 0.0;
  while (t < 8.0 * period) {
    const double dt = solver.step(p, t);
    t += dt;
    if (t > 7.0 * period) {
      double top = 0.0;
      int n_top = 0;
      for (std::size_t i = 0; i < p.size(); ++i) {
        if (p.position[i].y() - p.displacement[i].y() > hgt - dp) {
          top += p.displacement[i].y();
          ++n_top;
        }
      }
      sum += dt * top / n_top;
      weight += dt;
    }
  }
  const double settlement = -sum / weight;
  // Assert
  const double exact = kDensity * g * hgt * hgt / (2.0 * constrained_modulus());
  std::printf("settlement %.4e m, closed form %.4e m\n", settlement, exact);
  EXPECT_NEAR(settlement, exact, 0.1 * exact);
}

TEST(SphSolver, LeapfrogKeepsAnUndampedElasticVibrationBounded) {
  // Arrange: the column above with no artificial viscosity at all. Gravity switched on at rest
  // makes the top swing between 0 and twice the static settlement rho g H^2 / (2 M) for ever.
  // The stress must answer the velocities that moved the particles (velocity_gradient_pass.cpp):
  // answering the previous step's velocities grows every mode by (omega dt)^2 per step, and the
  // shortest modes, (omega dt)^2 ~ (2 cfl)^2 = 0.04, blow up within a few periods.
  const double dp = 0.005, w = 0.05, hgt = 0.1, g = 9.81;
  Particles p = block(10, 20, dp);
  SphSetup s = setup(dp, SphIntegrator::leapfrog);
  s.options.alpha = 0.0;
  s.options.beta = 0.0;
  s.gravity = Vec2(0, -g);
  add_box(s, w, hgt);
  SphSolver solver(std::move(s));
  solver.initialise(p);
  const double c = std::sqrt(constrained_modulus() / kDensity);
  const double period = 4.0 * hgt / c;
  // Act: the largest top settlement in the first and in the eighth period
  double t = 0.0, first = 0.0, last = 0.0;
  while (t < 8.0 * period) {
    t += solver.step(p, t);
    double top = 0.0;
    int n_top = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.position[i].y() - p.displacement[i].y() > hgt - dp) {
        top -= p.displacement[i].y();
        ++n_top;
      }
    }
    top /= n_top;
    if (t < period) first = std::max(first, top);
    if (t > 7.0 * period) last = std::max(last, top);
  }
  // Assert: still swinging to about twice the static settlement, no growth
  const double exact = kDensity * g * hgt * hgt / (2.0 * constrained_modulus());
  std::printf("largest settlement: first period %.4e m, eighth %.4e m, static %.4e m\n", first,
              last, exact);
  EXPECT_NEAR(first, 2.0 * exact, 0.2 * exact);
  EXPECT_LT(last, 1.1 * first);
  EXPECT_GT(last, 0.8 * first);
}

}  // namespace
}  // namespace duet::sph
