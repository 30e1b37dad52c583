#pragma once
// Frictional contact between soil particles and rigid bodies with prescribed motion (simhypo-sand
// 2024, eqs 39-40, after Wang et al.): a penalty force that pushes an intruding
// particle back out within one step, F_n = 2 m / dt^2 d n (eq 39), and a Coulomb friction force
// F_t = 2 m / dt^2 du_t (sticking) capped at mu |F_n| (sliding, eq 40).
//
// Where the contact surface sits: the particles of a body resting on a wall sit dp/2 off it (the
// lattice is cell-centred, and the first row of dummy particles sits dp/2 behind a wall), so the
// contact surface is the body's outline offset by dp/2 towards the soil; a particle at distance
// s from the outline (negative inside the body) intrudes by d = dp/2 - s when that is positive.
// The soil's own penetration check still counts particles behind the outline itself.
//
// du_t: the relative tangential displacement of the particle and the body (eq 40) is accumulated
// over the steps while the particle stays in contact (each step adds its displacement over the
// step relative to the moving body) and, when the cap holds, shortened so that 2 m / dt^2 |du_t|
// = mu |F_n| (the contact point slides with the particle). With du_t the increment of one step
// alone, the stick force is a damper of rate 2 / dt that reverses the particle's tangential
// velocity every step, and it creeps at about dt |g_t| / 2 instead of sticking (sph/README.md).
// A particle that leaves the contact (no intrusion) or changes body starts afresh, du_t = 0.
//
// The penalty stiffness 2 m / dt^2 puts the contact at omega dt = sqrt(2): stable with the
// leapfrog update (x += dt v^{n+1}), unstable with the three-level Verlet scheme of Peng 2015
// eqs 32-35 (its velocity leap over 2 dt amplifies any spring with omega dt above about 0.1), so
// sph/method.cpp accepts frictional bodies with sph.integrator = "leapfrog" only.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "common/particles.hpp"
#include "common/tensor.hpp"
#include "sph/walls.hpp"

namespace duet::sph {

/// A rigid body with a frictional surface, as the solver sees it.
struct FrictionalBodySpec {
  std::string name;
  std::vector<Vec2> outline;  // m; a simple polygon, not repeating its first point
  WallVelocity velocity;      // empty: fixed
  double friction = 0.0;      // Coulomb coefficient mu (-)
};

/// Eqs 39-40 for one particle: normal and tangential force (N/m) on the particle.
struct ContactForce {
  Vec2 normal = Vec2::Zero();
  Vec2 tangential = Vec2::Zero();
  bool sliding = false;  // the friction force is capped at mu |F_n|
};

/// Contact force on a particle of mass m (kg/m) intruding by `intrusion` (m, >= 0) along the
/// outward unit normal n of the surface, with the relative tangential displacement du_t (m,
/// perpendicular to n) over a step of dt (s), Coulomb coefficient mu. The friction force opposes
/// du_t.
ContactForce contact_force(double mass, double dt, double intrusion, const Vec2& normal,
                           const Vec2& tangential_displacement, double mu);

/// Where a point stands relative to a body's outline.
struct ContactPoint {
  double distance = 0.0;                  // signed distance from the outline, m (negative inside)
  Vec2 normal = Vec2::UnitY();            // outward unit normal at the nearest outline point
  Vec2 velocity = Vec2::Zero();           // body velocity at the nearest outline point, m/s
  Vec2 step_displacement = Vec2::Zero();  // body displacement there over the last step, m
};

/// The nearest point of the closed outline `body` (WallGeometry with the first point repeated)
/// to x, and the signed distance (inside by the crossing-number test). `step_shift` holds each
/// outline point's displacement over the last step.
ContactPoint nearest_outline_point(const WallGeometry& body, std::span<const Vec2> step_shift,
                                   const Vec2& x);

/// The outline as a closed polyline with the normals pointing out of the body (the soil side),
/// for the solver's penetration check.
WallGeometry outward_geometry(const FrictionalBodySpec& body);

/// The contact's state: sized once by initialise_contact, so a step allocates nothing.
struct RigidContact {
  std::vector<FrictionalBodySpec> bodies;
  double offset = 0.0;                        // m, dp / 2: contact surface off the outline
  std::vector<std::vector<Vec2>> step_shift;  // per body, per outline point: last step's motion
  std::vector<Vec2> box_min, box_max;         // per body: bounding box grown by dp/2
  std::vector<Vec2> previous_position;        // per soil particle, at the last contact evaluation
  std::vector<Vec2> tangential;               // per soil particle: accumulated du_t (m), 0 if free
  std::vector<std::int32_t> body_of;          // per soil particle: body in contact, or -1
  std::vector<Vec2> reaction_scratch;         // per thread, per body
  std::vector<Vec2> reaction;                 // per body: force of the soil on the body (N/m)
  long contacts = 0;                          // particles in contact in the last step
};

/// Sizes the state for `n` soil particles at `position` and `n_threads` OpenMP threads.
void initialise_contact(RigidContact& contact, std::span<const Vec2> position, double spacing,
                        int n_threads);

/// Moves every body by its prescribed velocity over the last step (dt_previous), then takes the
/// velocity at `time` (zero while settling), as the solver moves its walls.
void move_bodies(RigidContact& contact, std::span<WallGeometry> bodies, double time,
                 double dt_previous, bool settling);

/// Adds eqs 39-40's contact force / m to `acceleration` of every soil particle near a body, for
/// a step of dt, and sums the reaction on each body (minus the force on the soil). Gathers per
/// particle; per-thread reaction slots, no atomics.
void apply_contact(RigidContact& contact, std::span<const WallGeometry> bodies,
                   const Particles& particles, double dt, std::span<Vec2> acceleration);

}  // namespace duet::sph
