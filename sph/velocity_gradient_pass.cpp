// The leapfrog's second pair pass (sph/README.md, step 5): the velocity gradient (Peng 2015 eq 21)
// and the density rate (simhypo-sand eq 24) of the velocity field that has just moved the
// particles. Evaluating them with the velocities of the force pass instead (one step old) makes
// the stress answer the motion half a step late: for an elastic oscillator that update has
// |lambda|^2 = 1 + (omega dt)^2 per step, an energy pump that only the artificial viscosity
// holds back, and a deposit never comes to rest. With the new velocities the kick-drift-stress
// cycle is symplectic (|lambda| = 1).
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "sph/dummy_velocity.hpp"
#include "sph/pair_terms.hpp"
#include "sph/sph_solver.hpp"

namespace duet::sph {

using detail::kParallelMin;
using detail::PairSum;
using detail::plane_area;

void SphSolver::velocity_gradient_pass(const Particles& particles) {
  {
    ScopedTimer t(timers_, Phase::neighbours);
    // The drift has moved everything: refresh the working copy (ghosts mirror the new state;
    // dummies and walls keep the positions of the step's start, their velocities are the step's)
    // and rebuild the lists if the drift took something past half the skin.
    const double moved2 = gather(particles);
    if (4.0 * moved2 >= skin_ * skin_) rebuild_neighbours(particles);
  }
  ScopedTimer t(timers_, Phase::forces);
  const std::size_t n = particles.size();
  const double support2 = kernel_.support_radius() * kernel_.support_radius();
  const double tiny = std::numeric_limits<double>::min();
  const double dummy_volume = setup_.spacing * setup_.spacing;
  const PairData* work = work_.data();
  const std::int32_t* work_wall = work_wall_.data();
  const bool extrapolated = setup_.options.dummy_velocity == SphDummyVelocity::extrapolated;
  const bool parallel = n >= kParallelMin;
  const bool ring = setup_.axisymmetric;
  const std::size_t stride = neighbours_.stride();
  double* factor = gradient_factor_.data();
  int team = 1;

  // Pair (i, j): grad_i W_ij (gx, gy) and v_i - v_j (vx, vy); false when j lies in the skin.
  // The gradient factor f (grad_i W_ij = f r_ij) goes to the pair's slot `cached` for the next
  // step's pair loop, which sees these same positions (SphSolver::gradient_factor_).
  struct Pair {
    double gx, gy, vx, vy;
  };
  const auto pair_terms = [&](const PairData& pi, const PairData& pj, double& cached, Pair& p) {
    const double dx = pi.x - pj.x, dy = pi.y - pj.y;
    const double r2 = dx * dx + dy * dy;
    if (r2 >= support2) return false;
    const double r = std::sqrt(r2);
    const double f = kernel_.gradient_factor(r, 1.0 / std::max(r, tiny));
    cached = f;
    p = {f * dx, f * dy, pi.vx - pj.vx, pi.vy - pj.vy};
    return true;
  };
  // Peng 2015 eq 21 and simhypo eq 24, the same at both ends (PairSum::add_rates).
  const auto add = [](PairSum& s, const Pair& p, double m, double volume) {
    s.add_rates(p.gx, p.gy, p.vx, p.vy, m, volume);
  };

  // Soil pairs once each, shares scattered into the thread's own buffer (as in pair_loop);
  // ghosts and dummies act on their row's particle only.
#pragma omp parallel if (parallel)
  {
    const auto t_id = static_cast<std::size_t>(omp_get_thread_num());
#pragma omp single nowait
    team = omp_get_num_threads();
    PairSum* sum = pair_sum_.data() + t_id * n;
    std::fill(sum, sum + n, PairSum{});
#pragma omp for schedule(static, 256)  // reproducible shares, as in the force pass
    for (std::size_t k = 0; k < n; ++k) {
      const PairData& pi = work[k];
      PairSum s;
      Pair p;
      const auto early = neighbours_.early(k);
      const auto late = neighbours_.late(k);
      double* row_factor = factor + k * stride;  // early part, then late part, as in the row
      double* late_factor = row_factor + early.size();
      for (std::size_t e = 0; e < early.size(); ++e) {
        const std::uint32_t j = early[e];
        const PairData& pj = work[j];
        if (!pair_terms(pi, pj, row_factor[e], p)) continue;
        add(s, p, pj.m, pj.vol);
        if (ring) s.add_ring(p.gx, std::abs(pj.x) - pi.x, plane_area(pj));  // as in pair_loop
        if (j < n) {
          add(sum[j], p, pi.m, pi.vol);
          if (ring) sum[j].add_ring(p.gx, pj.x - pi.x, plane_area(pi));
        }
      }
      // Dummy particles: mass rho_i dp^2, volume dp^2, the wall's velocity or the extrapolated
      // one (Morris 1997 / Bui 2008, as in pair_loop).
      const double m_dummy = pi.rho * dummy_volume;
      // Axisymmetric: the dummy is the ring of its own radius (as in pair_loop)
      const auto add_dummy = [&](const PairData& pj) {
        if (!ring) {
          add(s, p, m_dummy, dummy_volume);
          return;
        }
        const double w_d = detail::ring_weight(pj.x);
        add(s, p, w_d * m_dummy, w_d * dummy_volume);
        s.add_ring(p.gx, std::abs(pj.x) - pi.x, dummy_volume);
      };
      if (!extrapolated) {
        for (std::size_t e = 0; e < late.size(); ++e) {
          if (pair_terms(pi, work[late[e]], late_factor[e], p)) add_dummy(work[late[e]]);
        }
      } else {
        WallLine line;  // pi's nearest segment of the dummy's wall
        for (std::size_t e = 0; e < late.size(); ++e) {
          PairData pj = work[late[e]];
          extrapolate_dummy_velocity(pi, work_wall[late[e]], line, pj);
          if (pair_terms(pi, pj, late_factor[e], p)) add_dummy(pj);
        }
      }
      sum[k] += s;
    }
  }
  const auto n_team = static_cast<std::size_t>(team);
#pragma omp parallel for schedule(static) if (parallel)
  for (std::size_t k = 0; k < n; ++k) {
    PairSum s = pair_sum_[k];
    for (std::size_t t_id = 1; t_id < n_team; ++t_id) s += pair_sum_[t_id * n + k];
    set_rates(order_[k], work[k], s);
  }
  // Nothing moves before the next step's gather, which clears this if anything did.
  gradient_cached_ = true;
}

}  // namespace duet::sph
