// Tests of the SPH step's axisymmetric formulation (sph/README.md, "Axisymmetric"; Garcia-Senz
// et al. 2009): the r-z plane's SPH over the ring masses with the stress over rho^2 2 pi r, the
// hoop force -sigma_tt G_r / (rho r) and hoop rate v_r G_r / r, with the axis held by a symmetry
// plane whose ghosts mirror the soil.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "common/solver.hpp"
#include "constitutive/registry.hpp"
#include "sph/sph_solver.hpp"

namespace duet::sph {
namespace {

constexpr double kDensity = 2000.0;  // kg/m^3
constexpr double kSpacing = 0.1;     // m
constexpr int kColumns = 14;         // r from 0 to 1.4 m
constexpr int kRows = 14;            // z from 0 to 1.4 m

/// nx by ny particles on a square lattice of spacing dp from the axis (x = r >= 0), each the
/// ring it sweeps (axisymmetric) or a plane particle per metre (plane strain).
Particles lattice(bool ring, int columns = kColumns, int rows = kRows, double dp = kSpacing) {
  Particles p;
  p.resize(static_cast<std::size_t>(columns * rows));
  std::size_t k = 0;
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < columns; ++i, ++k) {
      p.position[k] = Vec2((i + 0.5) * dp, (j + 0.5) * dp);
      const double area = dp * dp;
      const double volume = ring ? 2.0 * std::numbers::pi * p.position[k].x() * area : area;
      p.volume[k] = volume;
      p.density[k] = kDensity;
      p.mass[k] = kDensity * volume;
      p.material[k] = 0;
      p.body[k] = 0;
    }
  }
  return p;
}

/// The axis x = 0 as a symmetry plane (a free-slip wall to SPH, its ghosts the mirror image).
SphSetup setup_on_axis(bool ring) {
  SphSetup s;
  s.spacing = kSpacing;
  s.axisymmetric = ring;
  s.options.sound_speed = 50.0;
  s.options.cfl = 0.1;
  s.models.push_back(
      constitutive::make_model("linear-elastic", {{"E", 1.0e6}, {"nu", 0.3}}, "material.test"));
  WallSpec axis{"axis", {Vec2(0.0, -1.0), Vec2(0.0, 3.0)}, WallCondition::free_slip, {}};
  axis.symmetry = true;
  s.walls.push_back(axis);
  return s;
}

/// Interior: the whole kernel support (2h) inside the lattice or its mirror image across the
/// axis, i.e. at least 2h from the top, bottom and outer edges (the axis side has the ghosts).
bool interior(const Vec2& x, double two_h) {
  const double r_max = kColumns * kSpacing, z_max = kRows * kSpacing;
  return x.x() < r_max - two_h && x.y() > two_h && x.y() < z_max - two_h;
}

TEST(SphAxisymmetric, LinearVelocityFieldGivesThePlaneGradientAndHoopRateAwayFromTheAxis) {
  // Arrange: v = (a r, b z), expanding (no pair approaches: no artificial viscosity), no stress;
  // the same lattice and velocities as plane particles per metre
  const double a = 0.01, b = 0.02;  // 1/s
  Particles rings = lattice(true);
  Particles plane = lattice(false);
  for (Particles* p : {&rings, &plane}) {
    for (std::size_t i = 0; i < p->size(); ++i) {
      p->velocity[i] = Vec2(a * p->position[i].x(), b * p->position[i].y());
    }
  }
  SphSolver ring_solver(setup_on_axis(true));
  SphSolver plane_solver(setup_on_axis(false));
  ring_solver.initialise(rings);
  plane_solver.initialise(plane);
  // Act: one Verlet step, whose stress update takes the gradient at the initial state
  ring_solver.step(rings, 0.0);
  plane_solver.step(plane, 0.0);
  // Assert: at particles whose support lies in the lattice (2h from its edges and from the axis),
  // the ring-weighted gradient (1 / eta_i) sum_j m_j (v_j - v_i) (x) grad W_ij is plane SPH's
  // (the weights' extra term r_j / r_i - 1 sums a third moment of the lattice, zero), and the
  // hoop rate v_r G_r / r is a times the same lattice sum G_r = sum_j A_j (r_j - r_i) d_r W_ij
  // as d v_r / dr's: both within 2 % of the field's (the cubic spline's lattice sum at h/dp =
  // sqrt(2) is 1.016, as in plane strain)
  const double two_h = ring_solver.kernel().support_radius();
  const Particles start = lattice(true);
  int checked = 0;
  for (std::size_t i = 0; i < rings.size(); ++i) {
    if (!interior(start.position[i], two_h) || start.position[i].x() < two_h) continue;
    const Mat3 l = ring_solver.full_velocity_gradient(i);
    const Mat3 l_plane = plane_solver.full_velocity_gradient(i);
    EXPECT_NEAR(l(0, 0), l_plane(0, 0), 1e-12 * b) << i;
    EXPECT_NEAR(l(1, 1), l_plane(1, 1), 1e-12 * b) << i;
    EXPECT_NEAR(l(0, 1), l_plane(0, 1), 1e-12 * b) << i;
    EXPECT_NEAR(l(1, 0), l_plane(1, 0), 1e-12 * b) << i;
    EXPECT_NEAR(l(2, 2), l(0, 0), 1e-12 * a) << i;
    EXPECT_NEAR(l(0, 0), a, 0.02 * a) << i;
    EXPECT_NEAR(l(1, 1), b, 0.02 * b) << i;
    EXPECT_NEAR(l(2, 2), a, 0.02 * a) << i;
    EXPECT_EQ(l_plane(2, 2), 0.0) << i;
    ++checked;
  }
  EXPECT_GT(checked, 30);
}

TEST(SphAxisymmetric, UniformHydrostaticStressGivesZeroAccelerationAtInteriorParticles) {
  // Arrange: sigma = -p I (the hoop stress included), at rest, no gravity
  const double p = 1.0e4;  // Pa
  Particles rings = lattice(true);
  for (Mat3& s : rings.stress) s = -p * Mat3::Identity();
  SphSolver solver(setup_on_axis(true));
  solver.initialise(rings);
  // Act
  solver.step(rings, 0.0);
  // Assert: the pair sums' (sigma_rr, sigma_rz) G_r / (rho r) and the hoop force
  // -sigma_tt G_r / (rho r) cancel, G_r being the same lattice sum, also beside the axis (its
  // images at |r|); the r-z plane's divergence of a uniform stress is zero
  const double two_h = solver.kernel().support_radius();
  const Particles start = lattice(true);
  int checked = 0, beside_axis = 0;
  for (std::size_t i = 0; i < rings.size(); ++i) {
    if (!interior(start.position[i], two_h)) continue;
    EXPECT_LT(solver.accelerations()[i].norm(), 1e-9 * p / (kDensity * kSpacing)) << i;
    ++checked;
    beside_axis += start.position[i].x() < kSpacing ? 1 : 0;
  }
  EXPECT_GT(checked, 40);
  EXPECT_GT(beside_axis, 4);
}

TEST(SphAxisymmetric, UniformStressWithAnotherHoopStressAcceleratesByTheCylindricalTerms) {
  // Arrange: uniform sigma_rr = sigma_zz = -p, sigma_rz = tau, sigma_tt = -q: the plane
  // divergence vanishes, the cylindrical one is ((q - p) / r, tau / r)
  const double p = 1.0e4, q = 6.0e3, tau = 2.0e3;  // Pa
  Particles rings = lattice(true);
  for (Mat3& s : rings.stress) {
    s = Mat3::Zero();
    s(0, 0) = s(1, 1) = -p;
    s(2, 2) = -q;
    s(0, 1) = s(1, 0) = tau;
  }
  SphSolver solver(setup_on_axis(true));
  solver.initialise(rings);
  // Act
  solver.step(rings, 0.0);
  // Assert: rho a = ((sigma_rr - sigma_tt) / r, sigma_rz / r) at particles whose support lies in
  // the lattice (away from the axis: the axis's mirror image reverses sigma_rz, which is not
  // uniform there), within 2 %: the pair sums and the hoop force see e_r as the lattice sum
  // G_r = 1.016 (as the gradient of the previous test)
  const double two_h = solver.kernel().support_radius();
  const Particles start = lattice(true);
  int checked = 0;
  for (std::size_t i = 0; i < rings.size(); ++i) {
    const Vec2 x = start.position[i];
    if (!interior(x, two_h) || x.x() < two_h) continue;
    const Vec2 expected((q - p) / (kDensity * x.x()), tau / (kDensity * x.x()));
    EXPECT_LT((solver.accelerations()[i] - expected).norm(), 0.02 * expected.norm()) << i;
    ++checked;
  }
  EXPECT_GT(checked, 20);
}

TEST(SphAxisymmetric, ElasticCylinderCompressedAxiallyCarriesYoungsModulusTimesStrainTimesArea) {
  // Arrange: a linear-elastic cylinder r <= R = 1 m, H = 1 m tall (nu 0.3) on a free-slip floor,
  // held on the axis by its symmetry plane, its free-slip top wall pressed down at a speed that
  // rises smoothly to V over T and stays (quasi-static: the P wave crosses H in 0.04 s); the
  // lateral surface is free, so the stress is uniaxial (simple compression): F = E eps pi R^2
  const double dp = 0.1, radius = 1.0, height = 1.0;
  const double young = 1.0e6, speed = 0.01, ramp = 0.2, end = 1.0;
  Particles rings = lattice(true, static_cast<int>(std::lround(radius / dp)),
                            static_cast<int>(std::lround(height / dp)), dp);
  SphSetup s;
  s.spacing = dp;
  s.axisymmetric = true;
  s.options.sound_speed = 40.0;  // above the P-wave speed sqrt(M / rho) = 26 m/s
  s.options.cfl = 0.1;
  s.models.push_back(
      constitutive::make_model("linear-elastic", {{"E", young}, {"nu", 0.3}}, "material.test"));
  WallSpec axis{"axis", {Vec2(0.0, -0.5), Vec2(0.0, 1.5)}, WallCondition::free_slip, {}};
  axis.symmetry = true;
  s.walls.push_back(axis);
  s.walls.push_back({"floor", {Vec2(-0.5, 0.0), Vec2(1.5, 0.0)}, WallCondition::free_slip, {}});
  const auto top_speed = [=](double t) {
    return t < ramp ? 0.5 * speed * (1.0 - std::cos(std::numbers::pi * t / ramp)) : speed;
  };
  s.walls.push_back({"top",
                     {Vec2(-0.5, height), Vec2(1.5, height)},
                     WallCondition::free_slip,
                     [=](double t, const Vec2&) { return Vec2(0.0, -top_speed(t)); }});
  SphSolver solver(std::move(s));
  solver.initialise(rings);
  // Act: to eps = 0.9 % (the wall's travel V (t - T / 2) over H), the force averaged over the
  // last 0.2 s (what is left of the oscillation)
  double t = 0.0, force = 0.0, weight = 0.0;
  while (t < end) {
    const double dt = solver.step(rings, t);
    t += dt;
    if (t > end - 0.2) {
      force += dt * solver.wall_forces()[2].y();
      weight += dt;
    }
  }
  force /= weight;
  // Assert: the top wall's reaction, of the whole circumference, against the closed form at the
  // mean strain of the window (the wall's travel, V (t - T / 2), over H)
  const double strain = speed * (end - 0.1 - 0.5 * ramp) / height;
  const double expected = young * strain * std::numbers::pi * radius * radius;
  RecordProperty("force_over_closed_form", std::to_string(force / expected));
  EXPECT_NEAR(force, expected, 0.05 * expected);
}

TEST(SphAxisymmetric, ParticleOnTheAxisFailsCleanly) {
  // Arrange: one ring's particle moved onto the axis
  Particles rings = lattice(true);
  rings.position[0].x() = 0.0;
  SphSolver solver(setup_on_axis(true));
  solver.initialise(rings);
  // Act, Assert
  EXPECT_THROW(solver.step(rings, 0.0), NumericalFailure);
}

}  // namespace
}  // namespace duet::sph
