#include "sph/rigid_contact.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "sph/pair_terms.hpp"

namespace duet::sph {

using detail::kParallelMin;

ContactForce contact_force(double mass, double dt, double intrusion, const Vec2& normal,
                           const Vec2& tangential_displacement, double mu) {
  const double stiffness = 2.0 * mass / (dt * dt);
  ContactForce f;
  f.normal = stiffness * intrusion * normal;                // simhypo eq 39: F_n = 2 m / dt^2 d n
  const Vec2 stick = -stiffness * tangential_displacement;  // eq 40: 2 m / dt^2 du_t, against du_t
  const double cap = mu * f.normal.norm();                  // eq 40: |F_t| <= mu |F_n|
  const double magnitude = stick.norm();
  if (magnitude <= cap) {
    f.tangential = stick;
  } else {
    f.tangential = cap / magnitude * stick;  // eq 40 otherwise: mu |F_n| tau
    f.sliding = true;
  }
  return f;
}

ContactPoint nearest_outline_point(const WallGeometry& body, std::span<const Vec2> step_shift,
                                   const Vec2& x) {
  double best = std::numeric_limits<double>::infinity();
  std::size_t best_segment = 0;
  double best_u = 0.0;
  Vec2 best_point = x;
  bool inside = false;
  for (std::size_t s = 0; s + 1 < body.points.size(); ++s) {
    const Vec2 a = body.points[s];
    const Vec2 b = body.points[s + 1];
    const Vec2 t = b - a;
    const double u = std::clamp((x - a).dot(t) / t.squaredNorm(), 0.0, 1.0);
    const Vec2 p = a + u * t;
    const double r2 = (x - p).squaredNorm();
    if (r2 < best) {
      best = r2;
      best_segment = s;
      best_u = u;
      best_point = p;
    }
    // Crossing number: a ray from x towards +x crosses the edge.
    if ((a.y() > x.y()) != (b.y() > x.y())) {
      const double cross_x = a.x() + (x.y() - a.y()) / (b.y() - a.y()) * (b.x() - a.x());
      if (x.x() < cross_x) inside = !inside;
    }
  }
  ContactPoint c;
  const double r = std::sqrt(best);
  c.distance = inside ? -r : r;
  if (r > 1e-12 * (1.0 + x.norm())) {
    c.normal = (inside ? Vec2(best_point - x) : Vec2(x - best_point)) / r;
  } else {
    c.normal = body.normals[best_segment];
  }
  const std::size_t s = best_segment;
  c.velocity = (1.0 - best_u) * body.point_velocity[s] + best_u * body.point_velocity[s + 1];
  c.step_displacement = (1.0 - best_u) * step_shift[s] + best_u * step_shift[s + 1];
  return c;
}

WallGeometry outward_geometry(const FrictionalBodySpec& body) {
  if (body.outline.size() < 3) {
    throw std::invalid_argument("rigid body " + body.name + ": an outline needs three points");
  }
  WallGeometry g;
  g.points = body.outline;
  g.points.push_back(body.outline.front());
  double area2 = 0.0;  // twice the signed area: positive when counter-clockwise
  for (std::size_t k = 0; k + 1 < g.points.size(); ++k) {
    area2 += g.points[k].x() * g.points[k + 1].y() - g.points[k + 1].x() * g.points[k].y();
  }
  // The left normal of a counter-clockwise outline points into the body: the soil side is right.
  g.side.assign(g.points.size() - 1, area2 > 0.0 ? -1 : 1);
  g.normals.assign(g.points.size() - 1, Vec2::Zero());
  g.point_velocity.assign(g.points.size(), Vec2::Zero());
  update_normals(g);
  return g;
}

namespace {

void update_box(RigidContact& contact, std::size_t b, const WallGeometry& g) {
  Vec2 lo = g.points.front(), hi = g.points.front();
  for (const Vec2& p : g.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  contact.box_min[b] = lo - Vec2::Constant(contact.offset);
  contact.box_max[b] = hi + Vec2::Constant(contact.offset);
}

}  // namespace

void initialise_contact(RigidContact& contact, std::span<const Vec2> position, double spacing,
                        int n_threads) {
  const std::size_t n_bodies = contact.bodies.size();
  contact.offset = 0.5 * spacing;
  contact.step_shift.clear();
  contact.box_min.assign(n_bodies, Vec2::Zero());
  contact.box_max.assign(n_bodies, Vec2::Zero());
  for (std::size_t b = 0; b < n_bodies; ++b) {
    const WallGeometry g = outward_geometry(contact.bodies[b]);
    contact.step_shift.emplace_back(g.points.size(), Vec2::Zero());
    update_box(contact, b, g);
  }
  contact.previous_position.assign(position.begin(), position.end());
  contact.tangential.assign(position.size(), Vec2::Zero());
  contact.body_of.assign(position.size(), -1);
  contact.reaction_scratch.assign(static_cast<std::size_t>(n_threads) * n_bodies, Vec2::Zero());
  contact.reaction.assign(n_bodies, Vec2::Zero());
  contact.contacts = 0;
}

void move_bodies(RigidContact& contact, std::span<WallGeometry> bodies, double time,
                 double dt_previous, bool settling) {
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const WallVelocity& velocity = contact.bodies[b].velocity;
    if (!velocity) continue;
    WallGeometry& g = bodies[b];
    for (std::size_t k = 0; k < g.points.size(); ++k) {
      const Vec2 shift = dt_previous * g.point_velocity[k];
      g.points[k] += shift;
      contact.step_shift[b][k] = shift;
      // Bodies stay put while the soil settles under gravity loading.
      g.point_velocity[k] = settling ? Vec2::Zero() : velocity(time, g.points[k]);
    }
    update_normals(g);
    update_box(contact, b, g);
  }
}

void apply_contact(RigidContact& contact, std::span<const WallGeometry> bodies,
                   const Particles& particles, double dt, std::span<Vec2> acceleration) {
  const std::size_t n = particles.size();
  const std::size_t n_bodies = bodies.size();
  const double offset = contact.offset;
  std::fill(contact.reaction_scratch.begin(), contact.reaction_scratch.end(), Vec2::Zero());
  long contacts = 0;

  // Gather per soil particle: each thread writes its own particles' state and its own reaction
  // slots, so the loop is free of races without atomics.
#pragma omp parallel if (n >= kParallelMin) reduction(+ : contacts)
  {
    Vec2* reaction = contact.reaction_scratch.data() + omp_get_thread_num() * n_bodies;
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2 x = particles.position[i];
      const Vec2 moved = x - contact.previous_position[i];
      contact.previous_position[i] = x;
      // The body whose outline is nearest (deepest intrusion), among those intruded.
      int best = -1;
      ContactPoint at;
      for (std::size_t b = 0; b < n_bodies; ++b) {
        if ((x.array() < contact.box_min[b].array()).any() ||
            (x.array() > contact.box_max[b].array()).any()) {
          continue;
        }
        const ContactPoint c = nearest_outline_point(bodies[b], contact.step_shift[b], x);
        if (c.distance < offset && (best < 0 || c.distance < at.distance)) {
          best = static_cast<int>(b);
          at = c;
        }
      }
      if (best != contact.body_of[i]) contact.tangential[i] = Vec2::Zero();
      contact.body_of[i] = best;
      if (best < 0) continue;
      // du_t: the step's displacement relative to the moving body, added to the accumulated
      // one, both in the current tangent plane.
      const Vec2 n_out = at.normal;
      Vec2 du_t = contact.tangential[i] + (moved - at.step_displacement);
      du_t -= du_t.dot(n_out) * n_out;
      const double intrusion = offset - at.distance;  // surface dp/2 off the outline
      const double m = particles.mass[i];
      const auto b = static_cast<std::size_t>(best);
      const ContactForce f =
          contact_force(m, dt, intrusion, n_out, du_t, contact.bodies[b].friction);
      // Sliding: the contact point follows the particle so that the stick force equals the cap.
      contact.tangential[i] = f.sliding ? Vec2(-f.tangential * (dt * dt / (2.0 * m))) : du_t;
      const Vec2 force = f.normal + f.tangential;
      acceleration[i] += force / m;
      reaction[b] -= force;  // reaction on the body
      ++contacts;
    }
  }
  for (std::size_t b = 0; b < n_bodies; ++b) {
    Vec2 f = Vec2::Zero();
    for (std::size_t t = 0; t * n_bodies < contact.reaction_scratch.size(); ++t) {
      f += contact.reaction_scratch[t * n_bodies + b];
    }
    contact.reaction[b] = f;
  }
  contact.contacts = contacts;
}

}  // namespace duet::sph
