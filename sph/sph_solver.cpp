#include "sph/sph_solver.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>

#include "common/input_error.hpp"
#include "common/solver.hpp"
#include "common/suggest.hpp"
#include "constitutive/objective.hpp"

namespace duet::sph {

namespace {

// The three-level Verlet scheme decouples its even and odd steps and amplifies dissipative terms
// (the artificial viscosity); the usual cure (Monaghan 1989, as in the Verlet SPH codes Peng 2015
// follows) is a forward Euler step from n every so many steps. Peng 2015 does not state its
// interval; 40 is the customary value.
constexpr long kVerletEulerInterval = 40;

Mat2 in_plane(const Mat3& s) {
  return s.topLeftCorner<2, 2>();
}

/// Peng 2015 eq 29: R^{mn} = -b sigma^{mn} / rho^2 where sigma^{mn} > 0, else 0.
Mat2 artificial_stress_term(const Mat2& sigma, double rho, double b) {
  Mat2 r = Mat2::Zero();
  for (int m = 0; m < 2; ++m) {
    for (int n = 0; n < 2; ++n) {
      if (sigma(m, n) > 0.0) r(m, n) = -b * sigma(m, n) / (rho * rho);
    }
  }
  return r;
}

/// Mirror image R s R of an in-plane tensor across a line with unit normal n, R = I - 2 n n^T.
Mat2 mirror(const Mat2& s, const Vec2& n) {
  const Mat2 r = Mat2::Identity() - 2.0 * n * n.transpose();
  return r * s * r;
}

Mat3 embed(const Mat2& a) {
  Mat3 b = Mat3::Zero();
  b.topLeftCorner<2, 2>() = a;
  return b;
}

}  // namespace

SphSolver::SphSolver(SphSetup setup)
    : setup_(std::move(setup)),
      kernel_(setup_.options.kernel, setup_.options.h_over_dp * setup_.spacing),
      h_(setup_.options.h_over_dp * setup_.spacing) {
  const duet::SphOptions& o = setup_.options;
  if (!(setup_.spacing > 0.0)) throw InputError("sph: particle spacing must be > 0 m");
  if (o.dummy_layers < 1) throw InputError("sph.dummy_layers must be >= 1");
  // Peng 2015 eq 28: f_ij = W_ij / W(dp), n = W(0) / W(dp)
  w_dp_ = kernel_.value(setup_.spacing);
  exponent_n_ = kernel_.value(0.0) / w_dp_;
}

void SphSolver::initialise(Particles& particles) {
  const std::size_t n = particles.size();
  const double dp = setup_.spacing;
  const int n_threads = omp_get_max_threads();

  n_internal_.clear();
  void_ratio_slot_.clear();
  for (const auto& model : setup_.models) {
    const auto vars = model->internal_variables();
    n_internal_.push_back(vars.size());
    int slot = -1;
    for (std::size_t k = 0; k < vars.size(); ++k) {
      if (vars[k].name == "void_ratio") slot = static_cast<int>(k);
    }
    void_ratio_slot_.push_back(slot);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const int m = particles.material[i];
    if (m < 0 || static_cast<std::size_t>(m) >= setup_.models.size()) {
      throw std::invalid_argument("sph: particle without a material model");
    }
    if (n_internal_[static_cast<std::size_t>(m)] > particles.internal.width) {
      throw std::invalid_argument("sph: internal variable block narrower than the model needs");
    }
  }

  // Walls: orient each segment towards the soil, then lay the dummy particles behind it.
  geometry_.clear();
  boundary_position_.clear();
  boundary_velocity_.clear();
  boundary_wall_.clear();
  for (std::size_t w = 0; w < setup_.walls.size(); ++w) {
    const WallSpec& wall = setup_.walls[w];
    geometry_.push_back(orient_wall(wall, particles.position, kernel_.support_radius()));
    if (wall.condition != WallCondition::no_slip) continue;
    for (const Vec2& x : dummy_particles(geometry_.back(), dp, setup_.options.dummy_layers)) {
      boundary_position_.push_back(x);
      boundary_velocity_.push_back(Vec2::Zero());
      boundary_wall_.push_back(static_cast<std::int32_t>(w));
    }
  }
  n_dummy_ = boundary_position_.size();
  dummy_reference_ = boundary_position_;
  counters_ = SphCounters{};
  counters_.dummy_particles = n_dummy_;

  // Reserve for the worst case of ghosts (every soil particle mirrored by every free-slip wall
  // segment) so that a step never reallocates.
  std::size_t free_slip_segments = 0;
  for (const auto& wall : setup_.walls) {
    if (wall.condition == WallCondition::free_slip) free_slip_segments += wall.polyline.size() - 1;
  }
  const std::size_t capacity = n_dummy_ + n * free_slip_segments;
  boundary_position_.reserve(capacity);
  boundary_velocity_.reserve(capacity);
  boundary_wall_.reserve(capacity);
  ghost_source_.reserve(n * free_slip_segments);
  ghost_normal_.reserve(n * free_slip_segments);
  all_position_.reserve(n + capacity);

  acceleration_.assign(n, Vec2::Zero());
  external_force_.assign(n, Vec2::Zero());
  velocity_gradient_.assign(n, Mat2::Zero());
  density_rate_.assign(n, 0.0);
  stress_over_rho2_.assign(n, Mat2::Zero());
  artificial_r_.assign(n, Mat2::Zero());
  wall_force_.assign(setup_.walls.size(), Vec2::Zero());
  wall_force_scratch_.assign(static_cast<std::size_t>(n_threads) * setup_.walls.size(),
                             Vec2::Zero());
  velocity_old_ = particles.velocity;
  stress_old_ = particles.stress;
  strain_old_ = particles.strain;
  density_old_ = particles.density;
  void_ratio_old_.assign(n, 0.0);
  scratch_velocity_.resize(n);
  scratch_stress_.resize(n);
  scratch_strain_.resize(n);
  scratch_density_.resize(n);
  first_step_ = true;
  previous_dt_ = 0.0;
  timers_.reset();
}

void SphSolver::update_boundary(const Particles& particles, double time, double dt) {
  // Moving walls follow their prescribed velocity over the last step (dummies move with them),
  // then take the velocity of the coming step.
  for (std::size_t w = 0; w < setup_.walls.size(); ++w) {
    WallGeometry& g = geometry_[w];
    const WallVelocity& velocity = setup_.walls[w].velocity;
    if (!velocity) continue;
    for (std::size_t k = 0; k < g.points.size(); ++k) {
      g.points[k] += dt * g.point_velocity[k];
      // Walls stay put while the soil settles under gravity loading.
      g.point_velocity[k] = settling_ ? Vec2::Zero() : velocity(time, g.points[k]);
    }
    update_normals(g);
  }
  for (std::size_t d = 0; d < n_dummy_; ++d) {
    const WallVelocity& velocity =
        setup_.walls[static_cast<std::size_t>(boundary_wall_[d])].velocity;
    if (!velocity) continue;
    boundary_position_[d] += dt * boundary_velocity_[d];
    boundary_velocity_[d] = settling_ ? Vec2::Zero() : velocity(time, boundary_position_[d]);
  }
  // Ghosts are rebuilt from the current soil state (Peng 2015 section 4.2, reach kh with k = 2).
  boundary_position_.resize(n_dummy_);
  boundary_velocity_.resize(n_dummy_);
  boundary_wall_.resize(n_dummy_);
  ghost_source_.clear();
  ghost_normal_.clear();
  for (std::size_t w = 0; w < setup_.walls.size(); ++w) {
    if (setup_.walls[w].condition != WallCondition::free_slip) continue;
    append_ghost_particles(geometry_[w], static_cast<std::int32_t>(w), particles.position,
                           particles.velocity, kernel_.support_radius(), boundary_position_,
                           boundary_velocity_, boundary_wall_, ghost_source_, ghost_normal_);
  }
  counters_.ghost_particles_max = std::max(counters_.ghost_particles_max, ghost_source_.size());
}

void SphSolver::find_neighbours(const Particles& particles) {
  const std::size_t n = particles.size();
  all_position_.resize(n + boundary_position_.size());
  std::copy(particles.position.begin(), particles.position.end(), all_position_.begin());
  std::copy(boundary_position_.begin(), boundary_position_.end(), all_position_.begin() + n);
  try {
    cells_.build(all_position_, kernel_.support_radius());
  } catch (const std::domain_error& e) {
    throw NumericalFailure(std::string("neighbour search: ") + e.what());
  }
  neighbours_.build(cells_, all_position_, n, kernel_.support_radius());
  counters_.neighbours_max = std::max(counters_.neighbours_max, neighbours_.max_count());
}

void SphSolver::pair_loop(const Particles& particles) {
  const duet::SphOptions& o = setup_.options;
  const std::size_t n = particles.size();
  const std::size_t n_walls = setup_.walls.size();
  const double h = h_;
  const double cs = o.sound_speed;
  const double b = o.artificial_stress;
  const double dummy_volume = setup_.spacing * setup_.spacing;
  const bool sigma_max = o.wall_stress == SphWallStress::sigma_max;

#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    const double rho = particles.density[i];
    const Mat2 s = in_plane(particles.stress[i]);
    stress_over_rho2_[i] = s / (rho * rho);
    artificial_r_[i] = b > 0.0 ? artificial_stress_term(s, rho, b) : Mat2::Zero();
  }
  std::fill(wall_force_scratch_.begin(), wall_force_scratch_.end(), Vec2::Zero());

  // Gather per soil particle i, visited in cell order: each thread writes only row i and its
  // own wall-force slots, so the loop is free of races without atomics.
  const auto sorted = cells_.sorted();
#pragma omp parallel
  {
    Vec2* wall_force = wall_force_scratch_.data() + omp_get_thread_num() * n_walls;
#pragma omp for schedule(dynamic, 64)
    for (std::size_t k = 0; k < sorted.size(); ++k) {
      const std::size_t i = sorted[k];
      if (i >= n) continue;
      const auto row = neighbours_.of(i);
      const Vec2 xi = particles.position[i];
      const Vec2 vi = particles.velocity[i];
      const double rho_i = particles.density[i];
      const double m_i = particles.mass[i];
      const Mat2 si = in_plane(particles.stress[i]);

      // Peng 2015 eq 31: dummy-particle stress with diagonal = min over the soil neighbours
      // (and i itself), off-diagonal = that of particle i. Bui 2008: the stress of i.
      Mat2 s_dummy = si;
      bool sees_dummy = false;
      for (const std::uint32_t j : row) sees_dummy = sees_dummy || (j >= n && j < n + n_dummy_);
      if (sigma_max && sees_dummy) {
        for (const std::uint32_t j : row) {
          if (j >= n) continue;
          const Mat3& sj = particles.stress[j];
          s_dummy(0, 0) = std::min(s_dummy(0, 0), sj(0, 0));
          s_dummy(1, 1) = std::min(s_dummy(1, 1), sj(1, 1));
        }
      }
      const Mat2 dummy_over_rho2 = s_dummy / (rho_i * rho_i);
      const Mat2 dummy_r = b > 0.0 ? artificial_stress_term(s_dummy, rho_i, b) : Mat2::Zero();

      Vec2 a = Vec2::Zero();
      Mat2 grad_v = Mat2::Zero();
      double rho_rate = 0.0;
      for (const std::uint32_t j : row) {
        Vec2 xj, vj;
        Mat2 term_j, r_j;
        double m_j, rho_j;
        int wall = -1;
        if (j < n) {
          xj = particles.position[j];
          vj = particles.velocity[j];
          m_j = particles.mass[j];
          rho_j = particles.density[j];
          term_j = stress_over_rho2_[j];
          r_j = artificial_r_[j];
        } else {
          const std::size_t bj = j - n;
          xj = boundary_position_[bj];
          vj = boundary_velocity_[bj];
          wall = boundary_wall_[bj];
          if (bj < n_dummy_) {
            // Dummy particle: density and volume of the interacting soil particle's lattice.
            rho_j = rho_i;
            m_j = rho_i * dummy_volume;
            term_j = dummy_over_rho2;
            r_j = dummy_r;
          } else {
            // Ghost: the mirrored state of its soil particle (Peng 2015 section 4.2).
            const std::size_t g = bj - n_dummy_;
            const auto src = static_cast<std::size_t>(ghost_source_[g]);
            rho_j = particles.density[src];
            m_j = particles.mass[src];
            const Mat2 sj = mirror(in_plane(particles.stress[src]), ghost_normal_[g]);
            term_j = sj / (rho_j * rho_j);
            r_j = b > 0.0 ? artificial_stress_term(sj, rho_j, b) : Mat2::Zero();
          }
        }
        const Vec2 r_ij = xi - xj;
        const double r = r_ij.norm();
        const Vec2 grad = kernel_.gradient(r_ij, r);
        const Vec2 v_ij = vi - vj;

        // Peng 2015 eqs 26-27: artificial viscosity on approaching pairs
        double pi_ij = 0.0;
        const double vr = v_ij.dot(r_ij);
        if (vr < 0.0) {
          const double phi = h * vr / (r * r + 0.01 * h * h);
          pi_ij = (-o.alpha * cs * phi + o.beta * phi * phi) / (0.5 * (rho_i + rho_j));
        }
        // Peng 2015 eq 30: sigma_i/rho_i^2 + sigma_j/rho_j^2 - Pi_ij I + S_ij
        Mat2 term = stress_over_rho2_[i] + term_j;
        term.diagonal().array() -= pi_ij;
        if (b > 0.0) {
          // Peng 2015 eq 28: S_ij = f_ij^n (R_i + R_j), f_ij = W_ij / W(dp)
          const double f = kernel_.value(r) / w_dp_;
          term += std::pow(f, exponent_n_) * (artificial_r_[i] + r_j);
        }
        const Vec2 a_ij = m_j * (term * grad);
        a += a_ij;
        if (wall >= 0) wall_force[wall] -= m_i * a_ij;  // reaction: force of i on the wall

        const double volume_j = m_j / rho_j;
        // Peng 2015 eq 21: grad v_i = sum_j (v_j - v_i) (x) grad_i W_ij m_j / rho_j
        grad_v -= v_ij * grad.transpose() * volume_j;
        // simhypo-sand eq 24: d rho_i / dt = sum_j m_j (v_i - v_j) . grad_i W_ij
        rho_rate += m_j * v_ij.dot(grad);
      }
      acceleration_[i] = a + setup_.gravity + external_force_[i] / m_i;  // eq 30: + g
      velocity_gradient_[i] = grad_v;
      density_rate_[i] = rho_rate;
    }
  }
  for (std::size_t w = 0; w < n_walls; ++w) {
    Vec2 f = Vec2::Zero();
    for (std::size_t t = 0; t * n_walls < wall_force_scratch_.size(); ++t) {
      f += wall_force_scratch_[t * n_walls + w];
    }
    wall_force_[w] = f;
  }
}

double SphSolver::time_step() const {
  double a_max = 0.0;
  for (const Vec2& a : acceleration_) a_max = std::max(a_max, a.norm());
  // Peng 2015 eq 36: dt_1 = min_i sqrt(h / |a_i|); eq 37: dt = chi min(dt_1, h / c_s)
  const double dt_1 = a_max > 0.0 ? std::sqrt(h_ / a_max) : std::numeric_limits<double>::max();
  return setup_.options.cfl * std::min(dt_1, h_ / setup_.options.sound_speed);
}

void SphSolver::advance(Particles& particles, double dt) {
  const std::size_t n = particles.size();
  const bool verlet = setup_.options.integrator == SphIntegrator::verlet;
  const bool continuity = setup_.options.continuity;
  // Eqs 32-35 step over 2 dt from n - 1; with a variable dt the interval is dt_{n-1} + dt_n, and
  // the first step is a forward Euler step from n.
  const bool euler = first_step_ || counters_.steps % kVerletEulerInterval == 0;
  const double span = euler ? dt : previous_dt_ + dt;
  long bad = -1;

#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    const auto m = static_cast<std::size_t>(particles.material[i]);
    const constitutive::Model& model = *setup_.models[m];
    const std::span<double> internal(particles.internal.of(i), n_internal_[m]);
    const Mat3 l = embed(velocity_gradient_[i]);
    const Mat3 d = sym(l);   // Peng 2015 eq 22
    const Mat3 w = skew(l);  // Peng 2015 eq 23
    // Gravity loading only: velocity damping -c v (Peng 2015 section 5.3).
    const Vec2 a = acceleration_[i] - damping_ * particles.velocity[i];
    if (verlet) {
      const Vec2 v_n = particles.velocity[i];
      const Vec2 v_base = euler ? v_n : velocity_old_[i];
      const Mat3 s_base = euler ? particles.stress[i] : stress_old_[i];
      const Mat3 e_base = euler ? particles.strain[i] : strain_old_[i];
      scratch_velocity_[i] = v_base + span * a;      // eq 32
      const Vec2 dx = dt * v_n + 0.5 * dt * dt * a;  // eq 33
      particles.position[i] += dx;
      particles.displacement[i] += dx;
      const Mat3 rate = constitutive::stress_rate(model, d, w, particles.stress[i], internal);
      scratch_stress_[i] = s_base + span * rate;  // eq 34
      scratch_strain_[i] = e_base + span * d;     // eq 35
      const int e_slot = void_ratio_slot_[m];
      if (e_slot >= 0) {
        // simhypo-sand eq 32: e^{n+1} = e^{n-1} + 2 dt (1 + e^n) tr(eps_dot^n)
        const double e_n = internal[static_cast<std::size_t>(e_slot)];
        const double e_base = euler ? e_n : void_ratio_old_[i];
        void_ratio_old_[i] = e_n;
        internal[static_cast<std::size_t>(e_slot)] = e_base + span * (1.0 + e_n) * d.trace();
      }
      model.correct(scratch_stress_[i], internal);
      if (continuity) {
        scratch_density_[i] =
            (euler ? particles.density[i] : density_old_[i]) + span * density_rate_[i];
      }
    } else {
      // Leapfrog: kick, drift; stress by the incremental objective update of the library.
      particles.velocity[i] += dt * a;
      const Vec2 dx = dt * particles.velocity[i];
      particles.position[i] += dx;
      particles.displacement[i] += dx;
      constitutive::update_stress(model, d * dt, w * dt, particles.stress[i], internal);
      model.correct(particles.stress[i], internal);
      particles.strain[i] += d * dt;
      if (continuity) particles.density[i] += dt * density_rate_[i];
    }
    if (continuity) particles.volume[i] = particles.mass[i] / particles.density[i];
  }
  if (verlet) {
    // n - 1 <- n, n <- n + 1 (swap keeps every buffer: no allocation)
    std::swap(velocity_old_, particles.velocity);
    std::swap(particles.velocity, scratch_velocity_);
    std::swap(stress_old_, particles.stress);
    std::swap(particles.stress, scratch_stress_);
    std::swap(strain_old_, particles.strain);
    std::swap(particles.strain, scratch_strain_);
    if (continuity) {
      std::swap(density_old_, particles.density);
      std::swap(particles.density, scratch_density_);
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!particles.stress[i].allFinite() || !particles.position[i].allFinite() ||
        !particles.velocity[i].allFinite()) {
      bad = static_cast<long>(i);
      break;
    }
  }
  if (bad >= 0) throw NumericalFailure("non-finite particle state after the SPH update", bad);
  first_step_ = false;
  previous_dt_ = dt;
}

long SphSolver::count_penetrations(const Particles& particles) const {
  const double depth = setup_.options.dummy_layers * setup_.spacing;
  long count = 0;
  const std::size_t n = particles.size();
#pragma omp parallel for schedule(static) reduction(+ : count)
  for (std::size_t i = 0; i < n; ++i) {
    for (const WallGeometry& g : geometry_) {
      if (behind_wall(g, particles.position[i], depth)) {
        ++count;
        break;
      }
    }
  }
  return count;
}

double SphSolver::step(Particles& particles, double time) {
  {
    ScopedTimer t(timers_, Phase::other);
    update_boundary(particles, time, counters_.steps > 0 ? previous_dt_ : 0.0);
  }
  {
    ScopedTimer t(timers_, Phase::neighbours);
    find_neighbours(particles);
  }
  {
    ScopedTimer t(timers_, Phase::forces);
    pair_loop(particles);
  }
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (!acceleration_[i].allFinite()) {
      throw NumericalFailure("non-finite acceleration", static_cast<long>(i));
    }
  }
  const double dt = time_step();
  {
    ScopedTimer t(timers_, Phase::constitutive);
    advance(particles, dt);
  }
  ScopedTimer checks(timers_, Phase::other);
  double v_max = 0.0;
  long fastest = -1;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const double v = particles.velocity[i].norm();
    if (v > v_max) {
      v_max = v;
      fastest = static_cast<long>(i);
    }
  }
  if (v_max > setup_.options.sound_speed) {
    // Runaway kinetic energy: a particle faster than the sound speed breaks eq 37's time step.
    throw NumericalFailure("runaway kinetic energy: particle speed " + std::to_string(v_max) +
                               " m/s exceeds the sound speed",
                           fastest);
  }
  const long penetrations = count_penetrations(particles);
  counters_.penetrations_last_step = penetrations;
  counters_.penetrations_max = std::max(counters_.penetrations_max, penetrations);
  counters_.penetrations_total += penetrations;
  counters_.dt_min = counters_.steps == 0 ? dt : std::min(counters_.dt_min, dt);
  counters_.dt_max = std::max(counters_.dt_max, dt);
  ++counters_.steps;
  return dt;
}

void SphSolver::settle(Particles& particles, double duration, double damping) {
  damping_ = damping;
  settling_ = true;
  double t = -duration;
  while (t < 0.0) t += step(particles, t);
  damping_ = 0.0;
  settling_ = false;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    particles.velocity[i] = Vec2::Zero();
    particles.displacement[i] = Vec2::Zero();
    particles.strain[i] = Mat3::Zero();
  }
  first_step_ = true;
}

}  // namespace duet::sph
