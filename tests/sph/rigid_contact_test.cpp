// Tests of the frictional rigid-body contact (sph/rigid_contact.hpp, simhypo-sand eqs 39-40):
// the closed-form forces of one particle, and an elastic block on a frictional plane under a
// tilted gravity run through the driver: it slides with a = g (sin t - mu cos t) when
// tan t > mu, stays put when tan t < mu, and the plane carries the weight's normal part.
#include "sph/rigid_contact.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include "benchmarks/driver.hpp"
#include "common/h5_writer.hpp"
#include "common/input_error.hpp"
#include "common/scene_loader.hpp"
#include "sph/method.hpp"

namespace duet::sph {
namespace {

constexpr double kGravity = 9.81;    // m/s^2
constexpr double kDensity = 2000.0;  // kg/m^3
constexpr double kWidth = 0.2;       // m, block
constexpr double kHeight = 0.1;      // m, block
constexpr double kSpacing = 0.01;    // m: 20 x 10 = 200 particles

// ---------------------------------------------------------------- one particle, closed form

TEST(ContactForce, IntrusionGivesTwoMassOverDtSquaredTimesDepthAlongTheNormal) {
  // Arrange
  const double m = 0.2, dt = 1e-4, d = 3e-5;
  const Vec2 n = Vec2(0.6, 0.8);
  // Act
  const ContactForce f = contact_force(m, dt, d, n, Vec2::Zero(), 0.5);
  // Assert: eq 39, F_n = 2 m d / dt^2 n = 1200 n N/m
  EXPECT_NEAR(f.normal.x(), 2.0 * m * d / (dt * dt) * 0.6, 1e-9);
  EXPECT_NEAR(f.normal.y(), 2.0 * m * d / (dt * dt) * 0.8, 1e-9);
  EXPECT_EQ(f.tangential, Vec2::Zero());
  EXPECT_FALSE(f.sliding);
}

TEST(ContactForce, StickingTangentialDisplacementGivesTwoMassOverDtSquaredAgainstIt) {
  // Arrange: |F_t| = 2 m du / dt^2 = 400 N/m below mu |F_n| = 0.5 * 1200 N/m
  const double m = 0.2, dt = 1e-4, d = 3e-5, du = 1e-5;
  const Vec2 tau(0.8, -0.6);
  // Act
  const ContactForce f = contact_force(m, dt, d, Vec2(0.6, 0.8), du * tau, 0.5);
  // Assert: eq 40 first case, opposing the displacement
  EXPECT_NEAR(f.tangential.x(), -2.0 * m * du / (dt * dt) * 0.8, 1e-9);
  EXPECT_NEAR(f.tangential.y(), 2.0 * m * du / (dt * dt) * 0.6, 1e-9);
  EXPECT_FALSE(f.sliding);
}

TEST(ContactForce, TangentialForceBeyondMuTimesNormalIsCappedThere) {
  // Arrange: the sticking force would be 4000 N/m, the cap is 0.5 * 1200 = 600 N/m
  const double m = 0.2, dt = 1e-4, d = 3e-5, du = 1e-4, mu = 0.5;
  const Vec2 tau(0.8, -0.6);
  // Act
  const ContactForce f = contact_force(m, dt, d, Vec2(0.6, 0.8), du * tau, mu);
  // Assert: eq 40 second case, mu |F_n| tau against the displacement
  const double cap = mu * 2.0 * m * d / (dt * dt);
  EXPECT_NEAR(f.tangential.norm(), cap, 1e-9);
  EXPECT_NEAR(f.tangential.dot(tau), -cap, 1e-9);
  EXPECT_TRUE(f.sliding);
}

TEST(RigidContact, ParticleInsideTheHalfSpacingLayerIsPushedOutAndTheBodyFeelsTheReaction) {
  // Arrange: a square body [0, 1]^2, a particle 0.2 dp above its top (0.3 dp into the layer)
  const double dp = 0.01, dt = 1e-4;
  RigidContact contact;
  contact.bodies.push_back({"plate", {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {}, 0.4});
  std::vector<WallGeometry> bodies{outward_geometry(contact.bodies[0])};
  Particles p;
  p.resize(1);
  p.position[0] = Vec2(0.5, 1.0 + 0.2 * dp);
  p.mass[0] = 0.2;
  initialise_contact(contact, p.position, dp, 1);
  std::vector<Vec2> a(1, Vec2::Zero());
  // Act
  apply_contact(contact, bodies, p, dt, a);
  // Assert: intrusion dp/2 - 0.2 dp = 0.3 dp, a = 2 d / dt^2 upwards; reaction = -m a
  const double expected = 2.0 * 0.3 * dp / (dt * dt);
  EXPECT_NEAR(a[0].x(), 0.0, 1e-9);
  EXPECT_NEAR(a[0].y(), expected, 1e-6 * expected);
  EXPECT_NEAR(contact.reaction[0].y(), -0.2 * expected, 1e-6 * expected);
  EXPECT_EQ(contact.contacts, 1);
}

TEST(RigidContact, ParticleOutsideTheLayerFeelsNothing) {
  // Arrange: 0.6 dp above the top, beyond the dp/2 contact surface
  const double dp = 0.01;
  RigidContact contact;
  contact.bodies.push_back({"plate", {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {}, 0.4});
  std::vector<WallGeometry> bodies{outward_geometry(contact.bodies[0])};
  Particles p;
  p.resize(1);
  p.position[0] = Vec2(0.5, 1.0 + 0.6 * dp);
  p.mass[0] = 0.2;
  initialise_contact(contact, p.position, dp, 1);
  std::vector<Vec2> a(1, Vec2::Zero());
  // Act
  apply_contact(contact, bodies, p, 1e-4, a);
  // Assert
  EXPECT_EQ(a[0], Vec2::Zero());
  EXPECT_EQ(contact.reaction[0], Vec2::Zero());
}

/// One particle of mass 0.2 kg/m released at rest on the contact surface (dp/2 above a plane
/// y = 0) under g = 9.81 (sin t, -cos t), stepped with leapfrog (v += dt a, x += dt v) as the
/// solver does, the plane moving along x at `plane_speed`; returns the particle's displacement
/// along x after `steps` steps of dt.
double single_particle_slide(double tilt_degrees, double mu, int steps, double dt,
                             double plane_speed = 0.0) {
  const double t = tilt_degrees * std::numbers::pi / 180.0;
  const Vec2 g(kGravity * std::sin(t), -kGravity * std::cos(t));
  const double dp = 0.01;
  RigidContact contact;
  WallVelocity velocity;
  if (plane_speed != 0.0) {
    velocity = [plane_speed](double, const Vec2&) { return Vec2(plane_speed, 0.0); };
  }
  contact.bodies.push_back({"plane", {{-1, -0.1}, {1, -0.1}, {1, 0}, {-1, 0}}, velocity, mu});
  std::vector<WallGeometry> bodies{outward_geometry(contact.bodies[0])};
  Particles p;
  p.resize(1);
  p.position[0] = Vec2(0.0, 0.5 * dp);
  p.mass[0] = 0.2;
  initialise_contact(contact, p.position, dp, 1);
  std::vector<Vec2> a(1);
  for (int k = 0; k < steps; ++k) {
    a[0] = g;
    move_bodies(contact, bodies, k * dt, k > 0 ? dt : 0.0, false);
    apply_contact(contact, bodies, p, dt, a);
    p.velocity[0] += dt * a[0];
    p.position[0] += dt * p.velocity[0];
  }
  return p.position[0].x();
}

TEST(RigidContact, SingleParticleOnAPlaneSticksBelowTheFrictionAngle) {
  // Arrange / Act: tan 30 deg = 0.577 < mu = 0.8, 0.2 s
  const double moved = single_particle_slide(30.0, 0.8, 2000, 1e-4);
  // Assert: it would slide g sin t T^2 / 2 = 0.098 m without friction
  std::printf("single particle, sticking: moved %.3e m\n", moved);
  EXPECT_LT(std::abs(moved), 1e-9);
}

TEST(RigidContact, SingleParticleOnAPlaneSlidesWithGravityMinusCoulombFriction) {
  // Arrange: tan 30 deg > mu = 0.3
  const double t = 30.0 * std::numbers::pi / 180.0, mu = 0.3, dt = 1e-4;
  const int steps = 2000;
  // Act
  const double moved = single_particle_slide(30.0, mu, steps, dt);
  // Assert: x = a T^2 / 2, a = g (sin t - mu cos t)
  const double expected =
      0.5 * kGravity * (std::sin(t) - mu * std::cos(t)) * std::pow(steps * dt, 2);
  std::printf("single particle, sliding: moved %.5f m, closed form %.5f m\n", moved, expected);
  EXPECT_NEAR(moved, expected, 0.01 * expected);
}

TEST(RigidContact, MovingPlaneDragsAParticleAlongAtMuGUntilItMatchesTheSpeed) {
  // Arrange: a horizontal plane that moves at V = 0.05 m/s from t = 0, mu = 0.5
  const double speed = 0.05, mu = 0.5, dt = 1e-4;
  const int steps = 2000;
  // Act
  const double moved = single_particle_slide(0.0, mu, steps, dt, speed);
  // Assert: friction accelerates it at mu g for t_1 = V / (mu g) = 0.0102 s, then it rides
  // along: x(T) = V T - V^2 / (2 mu g)
  const double expected = speed * steps * dt - speed * speed / (2.0 * mu * kGravity);
  std::printf("single particle on a moving plane: moved %.6f m, closed form %.6f m\n", moved,
              expected);
  EXPECT_NEAR(moved, expected, 0.01 * expected);
}

TEST(RigidContact, OutlineNormalsPointOutOfTheBodySoThePenetrationCheckSeesParticlesInside) {
  // Arrange: a counter-clockwise and a clockwise square [0, 1]^2
  const FrictionalBodySpec ccw{"ccw", {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {}, 0.4};
  const FrictionalBodySpec cw{"cw", {{0, 0}, {0, 1}, {1, 1}, {1, 0}}, {}, 0.4};
  for (const FrictionalBodySpec& body : {ccw, cw}) {
    // Act
    const WallGeometry g = outward_geometry(body);
    // Assert: 0.01 m inside the top is behind the outline (the solver's check, walls.hpp), 0.01 m
    // above it is not
    EXPECT_TRUE(behind_wall(g, Vec2(0.5, 0.99), 0.03)) << body.name;
    EXPECT_FALSE(behind_wall(g, Vec2(0.5, 1.01), 0.03)) << body.name;
  }
}

// ------------------------------------------------------------- through the driver

/// An elastic block (linear elastic, E = 1 MPa) resting on a frictional plane (a static rigid
/// body, top at y = 0), gravity tilted by `tilt` degrees: g = 9.81 (sin t, -cos t). The block
/// first settles on the plane under that gravity (gravity loading, 0.1 s with a damping of
/// 200 / s, about twice the fundamental frequency), so the run starts at rest in equilibrium:
/// started from zero stress instead, the normal force swings between 0 and 2 M g cos t and the
/// block slips while it is low.
std::string block_scene(double tilt_degrees, double mu) {
  const double t = tilt_degrees * std::numbers::pi / 180.0;
  char text[2048];
  std::snprintf(text, sizeof text, R"(
name = "friction-block"
spacing = %g
gravity = [%.12g, %.12g]
[time]
end_time = 0.3
output_interval = 0.01
[initial_stress]
kind = "gravity-loading"
damping = 200.0
time = 0.1
[material.block]
model = "linear-elastic"
density = %g
E = 1.0e6
nu = 0.3
[body.block]
material = "block"
shape = "rectangle"
min = [0.0, 0.0]
max = [%g, %g]
[rigid_body.plane]
vertices = [[-0.3, -0.1], [0.8, -0.1], [0.8, 0.0], [-0.3, 0.0]]
surface = "friction"
friction = %g
[measure.normal]
kind = "reaction"
target = "plane"
component = "y"
at = "series"
[sph]
integrator = "leapfrog"
cfl = 0.2
sound_speed = 30.0
)",
                kSpacing, kGravity * std::sin(t), -kGravity * std::cos(t), kDensity, kWidth,
                kHeight, mu);
  return text;
}

struct BlockRun {
  RunSummary summary;
  std::string h5;
};

BlockRun run_block(double tilt_degrees, double mu, const std::string& tag) {
  const Scene scene = load_scene_from_string(block_scene(tilt_degrees, mu), "friction-block.toml");
  MethodRegistry methods;
  register_sph(methods);
  const auto dir = (std::filesystem::temp_directory_path() /
                    ("duet-sph-friction-" + tag + "-" + std::to_string(::getpid())))
                       .string();
  std::filesystem::remove_all(dir);
  BlockRun run{run_scene(scene, methods.find("sph"), RunOptions{dir, false}), dir + "/run.h5"};
  return run;
}

/// The number after "key": in metrics.json (-1 when absent).
long metrics_count(const std::string& dir, const std::string& key) {
  std::ifstream in(dir + "/metrics.json");
  std::stringstream text;
  text << in.rdbuf();
  const std::string metrics = text.str();
  const auto at = metrics.find("\"" + key + "\":");
  if (at == std::string::npos) return -1;
  return std::stol(metrics.substr(at + key.size() + 3));
}

/// Mean x of the particles in frame k.
double mean_x(const Frame& f) {
  double s = 0.0;
  for (const Vec2& x : f.position) s += x.x();
  return s / static_cast<double>(f.position.size());
}

/// Time average of the series `name` over t >= from.
double series_mean(const std::string& h5, const std::string& name, double from) {
  const auto time = read_series(h5, "time");
  const auto value = read_series(h5, name);
  double s = 0.0;
  int n = 0;
  for (std::size_t k = 0; k < time.size(); ++k) {
    if (time[k] < from) continue;
    s += value[k];
    ++n;
  }
  return s / n;
}

TEST(RigidContactBlock, SlidesWithGravityMinusCoulombFrictionWhenTiltExceedsFrictionAngle) {
  // Arrange: t = 30 deg, tan t = 0.577 > mu = 0.3
  const double tilt = 30.0, mu = 0.3;
  const double t = tilt * std::numbers::pi / 180.0;
  const double a = kGravity * (std::sin(t) - mu * std::cos(t));  // 2.356 m/s^2
  // Act
  const BlockRun run = run_block(tilt, mu, "slide");
  // Assert: the block's mean velocity over the last frame interval (exact at the midpoint for a
  // constant acceleration) against a t from rest
  ASSERT_TRUE(run.summary.completed()) << run.summary.failure_reason;
  const std::size_t n = count_frames(run.h5);
  const Frame f0 = read_frame(run.h5, n - 2);
  const Frame f1 = read_frame(run.h5, n - 1);
  const double v = (mean_x(f1) - mean_x(f0)) / (f1.time - f0.time);
  const double v_exact = a * 0.5 * (f0.time + f1.time);
  const double weight_normal = kDensity * kWidth * kHeight * kGravity * std::cos(t);
  const double normal = -series_mean(run.h5, "normal", 0.1);
  std::printf(
      "slide: v = %.5f m/s, closed form %.5f (%.2f %%); normal reaction %.2f N/m, "
      "M g cos t = %.2f (%.2f %%), %ld steps\n",
      v, v_exact, 100.0 * (v / v_exact - 1.0), normal, weight_normal,
      100.0 * (normal / weight_normal - 1.0), run.summary.steps);
  EXPECT_NEAR(v, v_exact, 0.03 * v_exact);
  EXPECT_NEAR(normal, weight_normal, 0.03 * weight_normal);
  EXPECT_EQ(metrics_count(run.summary.out_dir, "penetrations_max"), 0);
}

TEST(RigidContactBlock, StaysPutWhenTiltIsBelowFrictionAngle) {
  // Arrange: t = 30 deg, tan t = 0.577 < mu = 0.8
  const double tilt = 30.0, mu = 0.8;
  const double t = tilt * std::numbers::pi / 180.0;
  // Act
  const BlockRun run = run_block(tilt, mu, "stick");
  // Assert: the block settled on the plane under this gravity (initial_stress gravity-loading,
  // which zeroes the displacements), so at rest its mean displacement stays below dp / 1000,
  // where without friction it would slide g sin t T^2 / 2 = 0.22 m in 0.3 s (and a stick force
  // from one step's du_t alone, sph/rigid_contact.hpp, lets it creep 8.9e-4 m)
  ASSERT_TRUE(run.summary.completed()) << run.summary.failure_reason;
  const std::size_t n = count_frames(run.h5);
  const double moved = mean_x(read_frame(run.h5, n - 1)) - mean_x(read_frame(run.h5, 0));
  const double weight_normal = kDensity * kWidth * kHeight * kGravity * std::cos(t);
  const double normal = -series_mean(run.h5, "normal", 0.1);
  std::printf(
      "stick: mean displacement %.3e m; normal reaction %.2f N/m, M g cos t = %.2f (%.2f %%)\n",
      moved, normal, weight_normal, 100.0 * (normal / weight_normal - 1.0));
  EXPECT_LT(std::abs(moved), 1e-3 * kSpacing);
  EXPECT_NEAR(normal, weight_normal, 0.03 * weight_normal);
  EXPECT_EQ(metrics_count(run.summary.out_dir, "penetrations_max"), 0);
}

TEST(RigidContactBlock, FrictionalBodyWithTheVerletIntegratorIsRefused) {
  // Arrange: the same scene with the default three-level Verlet scheme
  const Scene scene = load_scene_from_string(block_scene(30.0, 0.3), "friction-block.toml",
                                             {"sph.integrator=verlet"});
  MethodRegistry methods;
  register_sph(methods);
  // Act / Assert
  EXPECT_THROW(methods.find("sph").make(scene), InputError);
}

}  // namespace
}  // namespace duet::sph
