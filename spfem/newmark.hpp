#pragma once
// The time integrator of one implicit increment: quasi-static (no inertia) or Newmark's average
// acceleration, beta = 1/4, gamma = 1/2 (Newmark 1959; Hughes 2000 sec. 9.1: unconditionally
// stable, no numerical damping). Over [t_n, t_n+1] with dt = t_n+1 - t_n and the increment's
// displacement u:
//   a_n+1 = c (u - dt v_n) - a_n,  c = 1 / (beta dt^2) = 4 / dt^2
//   v_n+1 = v_n + dt / 2 (a_n + a_n+1)
// The inertia M a_n+1 joins the residual and c M the tangent's diagonal.

#include <cstddef>
#include <vector>

#include "common/particles.hpp"
#include "common/tensor.hpp"

namespace duet::spfem {

struct NewmarkIncrement {
  bool inertia = false;  // false: quasi-static
  double dt = 0.0;       // s
  double c_mass = 0.0;   // 1 / (beta dt^2); 0 when quasi-static
  const Particles* particles = nullptr;
  const std::vector<Vec2>* acceleration = nullptr;  // a_n per node

  NewmarkIncrement(bool with_inertia, double t0, double t1, const Particles& p,
                   const std::vector<Vec2>& a_n)
      : inertia(with_inertia),
        dt(t1 - t0),
        c_mass(with_inertia ? 4.0 / ((t1 - t0) * (t1 - t0)) : 0.0),
        particles(&p),
        acceleration(&a_n) {}

  /// a_n+1 of node i for the increment's displacement ui.
  Vec2 acceleration_at_end(std::size_t i, const Vec2& ui) const {
    return c_mass * (ui - dt * particles->velocity[i]) - (*acceleration)[i];
  }

  /// The inertia force M a_n+1 of node i (zero when quasi-static).
  Vec2 inertia_force(std::size_t i, const Vec2& ui) const {
    if (!inertia) return Vec2::Zero();
    return particles->mass[i] *
           (c_mass * (ui - dt * particles->velocity[i]) - (*acceleration)[i]).eval();
  }

  /// Newton's start at constant acceleration: dt v_n + dt^2 / 2 a_n.
  Vec2 constant_acceleration_guess(std::size_t i) const {
    return dt * particles->velocity[i] + 0.5 * dt * dt * (*acceleration)[i];
  }

  /// c M, the inertia's contribution to the tangent's diagonal (empty when quasi-static).
  std::vector<double> mass_diagonal() const {
    std::vector<double> d;
    if (!inertia) return d;
    d.resize(particles->size());
    for (std::size_t i = 0; i < d.size(); ++i) d[i] = c_mass * particles->mass[i];
    return d;
  }
};

}  // namespace duet::spfem
