#include "sph/sph_solver.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <span>
#include <stdexcept>

#include "common/input_error.hpp"
#include "common/solver.hpp"
#include "common/suggest.hpp"
#include "constitutive/objective.hpp"
#include "constitutive/scene_models.hpp"
#include "sph/dummy_velocity.hpp"
#include "sph/pair_terms.hpp"

namespace duet::sph {

using detail::artificial_stress_term;
using detail::ForcePair;
using detail::kParallelMin;
using detail::mirror;
using detail::PairSum;
using detail::plane_area;

namespace {

// The three-level Verlet scheme decouples its even and odd steps and amplifies dissipative terms
// (the artificial viscosity); the usual cure (Monaghan 1989, as in the Verlet SPH codes Peng 2015
// follows) is a forward Euler step from n every so many steps. Peng 2015 does not state its
// interval; 40 is the customary value.
constexpr long kVerletEulerInterval = 40;

// Verlet-list skin as a fraction of the kernel support 2h: neighbour rows hold every pair closer
// than 2h + skin and stay valid until some particle (soil, ghost, dummy) or wall point has moved
// skin / 2 since the last build (then no pair can have closed from beyond 2h + skin to within
// 2h). Not tuned: collapse-bui at dp = 2 mm, CFL 0.3 rebuilds every 52 steps on average (1092
// builds in 56,569 steps), and the skipped skin pairs cost little (README, step 3).
constexpr double kSkinFraction = 0.1;

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
  if (setup_.axisymmetric && o.wall_stress == SphWallStress::sigma_max) {
    // eq 31's minimum would compare stresses over different rings' weights (pair_terms.hpp)
    throw InputError(
        "sph.wall_stress = \"sigma-max\" with formulation = \"axisymmetric\": not implemented; "
        "use \"bui\"");
  }
  // Peng 2015 eq 28: f_ij = W_ij / W(dp), n = W(0) / W(dp)
  w_dp_ = kernel_.value(setup_.spacing);
  exponent_n_ = kernel_.value(0.0) / w_dp_;
  skin_ = kSkinFraction * kernel_.support_radius();
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
  dummy_position_.clear();
  dummy_velocity_.clear();
  dummy_wall_.clear();
  for (const WallSpec& wall : setup_.walls) {
    geometry_.push_back(orient_wall(wall, particles.position, kernel_.support_radius()));
  }
  for (std::size_t w = 0; w < setup_.walls.size(); ++w) {
    if (setup_.walls[w].condition != WallCondition::no_slip) continue;
    std::vector<Vec2> dummies = dummy_particles(geometry_[w], dp, setup_.options.dummy_layers);
    // and their images across each symmetry plane: the other half of a body the plane cuts
    // (sph/walls.hpp). They move with this wall, as its own do: such a body moves along the plane.
    for (std::size_t s = 0; s < setup_.walls.size(); ++s) {
      if (!setup_.walls[s].symmetry) continue;
      const std::vector<Vec2> images =
          mirror_dummies_across(geometry_[s], dummies, kernel_.support_radius(), dp);
      dummies.insert(dummies.end(), images.begin(), images.end());
    }
    for (const Vec2& x : dummies) {
      dummy_position_.push_back(x);
      dummy_velocity_.push_back(Vec2::Zero());
      dummy_wall_.push_back(static_cast<std::int32_t>(w));
    }
  }
  // Frictional rigid bodies (simhypo eqs 39-40, sph/rigid_contact.hpp): their outlines follow
  // the walls in geometry_ (so the penetration check counts them), with no dummies or ghosts.
  contact_.bodies = setup_.frictional_bodies;
  for (const FrictionalBodySpec& b : contact_.bodies) geometry_.push_back(outward_geometry(b));
  initialise_contact(contact_, particles.position, dp, n_threads);
  wall_reference_.clear();
  for (const WallGeometry& g : geometry_) wall_reference_.push_back(g.points);
  n_dummy_ = dummy_position_.size();
  counters_ = SphCounters{};
  counters_.dummy_particles = n_dummy_;

  // Reserve for the worst case of ghost candidates (every soil particle mirrored by every
  // free-slip wall segment) so that a step never reallocates.
  std::size_t free_slip_segments = 0;
  std::size_t planes = 0;
  for (const auto& wall : setup_.walls) {
    if (wall.condition == WallCondition::free_slip) free_slip_segments += wall.polyline.size() - 1;
    if (wall.symmetry) ++planes;
  }
  // each segment's and each vertex's candidates, and their corner images (select_ghosts)
  const std::size_t max_ghosts = 2 * n * free_slip_segments * (1 + planes);
  const std::size_t max_working = n + max_ghosts + n_dummy_;
  ghost_source_.reserve(max_ghosts);
  ghost_wall_.reserve(max_ghosts);
  ghost_segment_.reserve(max_ghosts);
  ghost_plane_.reserve(max_ghosts);
  boundary_position_.reserve(n_dummy_ + max_ghosts);
  work_.reserve(max_working);
  work_r_.reserve(max_working);
  work_wall_.reserve(max_working);
  work_reference_.reserve(max_working);
  all_position_.reserve(max_working);
  order_.resize(n);
  for (std::size_t i = 0; i < n; ++i) order_[i] = static_cast<std::uint32_t>(i);
  rebuild_ = true;
  gradient_cached_ = false;

  acceleration_.assign(n, Vec2::Zero());
  external_force_.assign(n, Vec2::Zero());
  velocity_gradient_.assign(n, Mat2::Zero());
  hoop_rate_.assign(setup_.axisymmetric ? n : 0, 0.0);
  density_rate_.assign(n, 0.0);
  wall_force_.assign(setup_.walls.size(), Vec2::Zero());
  wall_force_scratch_.assign(static_cast<std::size_t>(n_threads) * setup_.walls.size(),
                             Vec2::Zero());
  pair_sum_.resize(static_cast<std::size_t>(n_threads) * n);
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

void SphSolver::use_models(std::vector<std::unique_ptr<constitutive::Model>> models) {
  constitutive::replace_models(setup_.models, std::move(models), "sph");
}

/// What every row of the force pass reads, resolved once per step.
struct SphSolver::ForcePass {
  detail::ForcePairTerms terms;  // the per-pair terms, eqs 26-30
  std::size_t n;                 // soil particles
  std::size_t n_walls;
  double b;             // artificial stress coefficient, eq 29 (0 = off)
  double dummy_volume;  // dp^2
  Vec2 gravity;
  bool sigma_max;     // dummies carry eq 31's stress, else that of the soil particle (Bui 2008)
  bool extrapolated;  // dummies move with Morris 1997 / Bui 2008's velocity, else the wall's
  // The leapfrog takes eq 21's velocity gradient and eq 24's density rate from its second pass
  // (velocity_gradient_pass.cpp, at the new positions and velocities), which overwrites them
  // before anything reads them: only Verlet needs them here.
  bool rates;
  bool parallel;
  // The kernel gradient factors of the leapfrog's velocity pass, when it ran at these very
  // positions with this neighbour list (gradient_cached_), row k at k * stride; else null. The
  // artificial stress needs W_ij and r as well, so with b > 0 everything is computed here.
  const double* cached_factor;
  std::size_t stride;
  // By driver index: the particles' stress (the axisymmetric hoop force reads the hoop stress).
  const Mat3* stress;
  bool ring;  // axisymmetric
};

void SphSolver::pair_loop(const Particles& particles) {
  const duet::SphOptions& o = setup_.options;
  const double b = o.artificial_stress;
  const ForcePass pass{
      .terms = detail::ForcePairTerms(kernel_, o, h_, w_dp_, exponent_n_, setup_.axisymmetric),
      .n = particles.size(),
      .n_walls = setup_.walls.size(),
      .b = b,
      .dummy_volume = setup_.spacing * setup_.spacing,
      .gravity = setup_.gravity,
      .sigma_max = o.wall_stress == SphWallStress::sigma_max,
      .extrapolated = o.dummy_velocity == SphDummyVelocity::extrapolated,
      .rates = o.integrator != SphIntegrator::leapfrog,
      .parallel = particles.size() >= kParallelMin,
      .cached_factor = gradient_cached_ && b == 0.0 ? gradient_factor_.data() : nullptr,
      .stride = neighbours_.stride(),
      .stress = particles.stress.data(),
      .ring = setup_.axisymmetric,
  };
  std::fill(wall_force_scratch_.begin(), wall_force_scratch_.end(), Vec2::Zero());
  const int team = soil_pair_pass(pass);
  const double a_max2 = particle_pass(pass, static_cast<std::size_t>(team));
  // Each wall's force: the threads' slots summed in thread order.
  for (std::size_t w = 0; w < pass.n_walls; ++w) {
    Vec2 f = Vec2::Zero();
    for (std::size_t t = 0; t * pass.n_walls < wall_force_scratch_.size(); ++t) {
      f += wall_force_scratch_[t * pass.n_walls + w];
    }
    wall_force_[w] = f;
  }
  if (!std::isfinite(a_max2)) {
    for (std::size_t i = 0; i < pass.n; ++i) {
      if (!acceleration_[i].allFinite()) {
        throw NumericalFailure("non-finite acceleration", static_cast<long>(i));
      }
    }
  }
  acceleration_max_ = std::sqrt(a_max2);
}

int SphSolver::soil_pair_pass(const ForcePass& pass) {
  const std::size_t n = pass.n;
  int team = 1;
  // Each soil pair sits in one row (NeighbourLists::drop_lower_pairs) and is evaluated once; its
  // shares go to both ends in the thread's own buffer (a scatter into thread-private memory: no
  // races, no atomics), summed in pass 2. Peng 2015 eq 31 needs, for the dummies, the smallest
  // normal stresses among each particle's soil neighbours: gathered the same way.
#pragma omp parallel if (pass.parallel)
  {
    const auto t = static_cast<std::size_t>(omp_get_thread_num());
#pragma omp single nowait
    team = omp_get_num_threads();
    PairSum* sum = pair_sum_.data() + t * n;
    std::fill(sum, sum + n, PairSum{});
    Vec2* wall_force = wall_force_scratch_.data() + t * pass.n_walls;
    // Static chunks: each row's shares land in the same thread's buffer every run, so the sums
    // of pass 2 (over the buffers in thread order) are bitwise reproducible; dynamic scheduling
    // made two-thread runs differ at round-off from run to run.
#pragma omp for schedule(static, 256)
    for (std::size_t k = 0; k < n; ++k) soil_pair_row(k, pass, sum, wall_force);
  }
  return team;
}

void SphSolver::soil_pair_row(std::size_t k, const ForcePass& pass, PairSum* sum,
                              Vec2* wall_force) const {
  const PairData* work = work_.data();
  const PairData& pi = work[k];
  const bool artificial_stress = pass.b > 0.0;
  const SymR r_i = artificial_stress ? work_r_[k] : SymR{0.0, 0.0, 0.0};
  PairSum s;
  ForcePair p;
  const auto early = neighbours_.early(k);
  const double* row_factor =
      pass.cached_factor != nullptr ? pass.cached_factor + k * pass.stride : nullptr;
  for (std::size_t e = 0; e < early.size(); ++e) {
    const std::uint32_t j = early[e];
    const PairData& pj = work[j];
    const SymR& r_j = artificial_stress ? work_r_[j] : r_i;
    const double* cached = row_factor != nullptr ? row_factor + e : nullptr;
    if (!pass.terms.evaluate(pi, pj, pj.rho, pj.sxx, pj.syy, pj.sxy, r_i, r_j, cached, p)) {
      continue;
    }
    s.add_force(p, pj.m, pj.vol, 1.0, pass.rates);
    if (pass.ring) s.add_ring(p.gx, std::abs(pj.x) - pi.x, plane_area(pj));
    if (j < pass.n) {
      PairSum& sj = sum[j];
      sj.add_force(p, pi.m, pi.vol, -1.0, pass.rates);
      if (pass.ring) sj.add_ring(p.gx, pj.x - pi.x, plane_area(pi));
      if (pass.sigma_max) {
        s.take_min_normal_stress(pj);
        sj.take_min_normal_stress(pi);
      }
    } else {
      // A ghost acts on i alone; minus its force is the reaction on its free-slip wall.
      wall_force[work_wall_[j]] -= pi.m * pj.m * p.bracket_times_gradient();
    }
  }
  sum[k] += s;
}

double SphSolver::particle_pass(const ForcePass& pass, std::size_t n_team) {
  const std::size_t n = pass.n;
  double a_max2 = 0.0;
#pragma omp parallel if (pass.parallel)
  {
    Vec2* wall_force = wall_force_scratch_.data() + omp_get_thread_num() * pass.n_walls;
#pragma omp for schedule(static, 256) reduction(max : a_max2) nowait  // wall_force: as pass 1
    for (std::size_t k = 0; k < n; ++k) {
      // The threads' shares in thread order, then the dummies: they need eq 31's minimum over
      // all soil neighbours, complete only now.
      PairSum s = pair_sum_[k];
      for (std::size_t t = 1; t < n_team; ++t) s += pair_sum_[t * n + k];
      if (!neighbours_.late(k).empty()) dummy_pairs(k, pass, s, wall_force);
      const std::size_t i = order_[k];
      // Peng 2015 eq 30: + g, and the scene's load
      Vec2 a = Vec2(s.ax, s.ay) + pass.gravity + external_force_[i] / work_[k].m;
      const PairData& pk = work_[k];
      if (pass.ring) {
        // Axisymmetric: the hoop stress's force on the ring, -sigma_tt / (rho r) radially
        // (Garcia-Senz et al. 2009: the 2 pi P / eta term of the radial momentum equation, the
        // hoop stress -P there). The pair sums over ring masses with the stress over
        // rho^2 2 pi r are (1 / eta) div(2 pi r sigma), which holds (sigma_rr, sigma_rz) / (rho r)
        // besides the r-z plane's divergence; so that a uniform stress sigma_rr = sigma_tt is in
        // equilibrium exactly, the hoop force takes the pair sums' own radial direction
        // G_r = sum_j A_j (|r_j| - r_i) d_r W_ij (1 to the kernel's lattice sum inside the body,
        // less by the axis, whose images stand at |r|) for the unit vector e_r.
        a.x() -= pass.stress[i](2, 2) * s.ring_r / (pk.rho * pk.x);
      }
      acceleration_[i] = a;
      if (pass.rates) set_rates(i, pk, s);
      const double a2 = a.squaredNorm();
      a_max2 = std::max(a_max2, std::isfinite(a2) ? a2 : std::numeric_limits<double>::infinity());
    }
  }
  return a_max2;
}

void SphSolver::dummy_pairs(std::size_t k, const ForcePass& pass, PairSum& s,
                            Vec2* wall_force) const {
  // Dummy particles: density of i, volume dp^2 of its lattice, and stress sigma_max (Peng 2015
  // eq 31: diagonal = the smallest normal stresses among i and its soil neighbours, off-diagonal
  // = that of i) or, with Bui 2008, the stress of i; velocity the wall's or, with
  // sph.dummy_velocity = "extrapolated", Morris 1997 / Bui 2008's.
  const PairData& pi = work_[k];
  const double rho_i = pi.rho;
  const double inv_rho2 = 1.0 / (rho_i * rho_i);
  const double min_xx = std::min(s.min_xx, pi.sxx * rho_i * rho_i);
  const double min_yy = std::min(s.min_yy, pi.syy * rho_i * rho_i);
  const double dxx = pass.sigma_max ? min_xx * inv_rho2 : pi.sxx;  // stress / rho^2
  const double dyy = pass.sigma_max ? min_yy * inv_rho2 : pi.syy;
  const SymR r_i = pass.b > 0.0 ? work_r_[k] : SymR{0.0, 0.0, 0.0};
  SymR r_dummy{0.0, 0.0, 0.0};
  if (pass.b > 0.0) {
    // Peng 2015 eq 29 of the dummy's stress
    Mat2 s_dummy;
    s_dummy << dxx * rho_i * rho_i, pi.sxy * rho_i * rho_i, pi.sxy * rho_i * rho_i,
        dyy * rho_i * rho_i;
    const Mat2 r = artificial_stress_term(s_dummy, rho_i, pass.b);
    r_dummy = {r(0, 0), r(1, 1), r(0, 1)};
  }
  const double m_dummy = rho_i * pass.dummy_volume;
  // Axisymmetric: pi's stress and R are over rho^2 2 pi r_i; a dummy's over its own ring's
  const double w_i = pass.ring ? detail::ring_weight(pi.x) : 1.0;
  // The late part of row k follows its early part in the cache, as in the row.
  const double* late_factor = pass.cached_factor != nullptr ? pass.cached_factor + k * pass.stride +
                                                                  neighbours_.early(k).size()
                                                            : nullptr;
  const auto dummy = [&](const PairData& pj, std::int32_t wall, std::size_t e) {
    ForcePair p;
    const double* cached = late_factor != nullptr ? late_factor + e : nullptr;
    if (!pass.ring) {
      if (!pass.terms.evaluate(pi, pj, rho_i, dxx, dyy, pi.sxy, r_i, r_dummy, cached, p)) return;
      s.add_force(p, m_dummy, pass.dummy_volume, 1.0, pass.rates);
      // minus the dummy's force on i is the reaction on its wall
      wall_force[wall] -= pi.m * m_dummy * p.bracket_times_gradient();
      return;
    }
    // Axisymmetric: the dummy is the ring of its own radius (its images beyond the axis too)
    const double w_d = detail::ring_weight(pj.x);
    const double scale = w_i / w_d;
    const SymR r_d{r_dummy.xx * scale, r_dummy.yy * scale, r_dummy.xy * scale};
    if (!pass.terms.evaluate(pi, pj, rho_i, dxx * scale, dyy * scale, pi.sxy * scale, r_i, r_d,
                             cached, p)) {
      return;
    }
    s.add_force(p, w_d * m_dummy, w_d * pass.dummy_volume, 1.0, pass.rates);
    s.add_ring(p.gx, std::abs(pj.x) - pi.x, pass.dummy_volume);
    wall_force[wall] -= pi.m * (w_d * m_dummy) * p.bracket_times_gradient();
  };
  const auto late = neighbours_.late(k);
  if (!pass.extrapolated) {
    for (std::size_t e = 0; e < late.size(); ++e) dummy(work_[late[e]], work_wall_[late[e]], e);
  } else {
    WallLine line;  // pi's nearest segment of the dummy's wall
    for (std::size_t e = 0; e < late.size(); ++e) {
      const std::uint32_t j = late[e];
      PairData pj = work_[j];
      extrapolate_dummy_velocity(pi, work_wall_[j], line, pj);
      dummy(pj, work_wall_[j], e);
    }
  }
}

void SphSolver::extrapolate_dummy_velocity(const PairData& pi, int wall, WallLine& line,
                                           PairData& pj) const {
  // Morris 1997 / Bui 2008 (sph/dummy_velocity.hpp): v_B = v_w - (d_B / d_A)(v_A - v_w), the
  // dummy's own velocity being its wall's. The nearest segment is found once per wall and soil
  // particle (rows keep a wall's dummies together, so usually once per particle).
  const Vec2 x_a(pi.x, pi.y);
  if (line.wall != wall) {
    line = nearest_wall_line(geometry_[static_cast<std::size_t>(wall)], wall, x_a);
  }
  const Vec2 v = extrapolated_dummy_velocity(Vec2(pi.vx, pi.vy), Vec2(pj.vx, pj.vy), line.distance,
                                             distance_behind(line, Vec2(pj.x, pj.y)));
  pj.vx = v.x();
  pj.vy = v.y();
}

double SphSolver::time_step() const {
  // Peng 2015 eq 36: dt_1 = min_i sqrt(h / |a_i|); eq 37: dt = chi min(dt_1, h / c_s)
  const double dt_1 = acceleration_max_ > 0.0 ? std::sqrt(h_ / acceleration_max_)
                                              : std::numeric_limits<double>::max();
  return setup_.options.cfl * std::min(dt_1, h_ / setup_.options.sound_speed);
}

void SphSolver::kick_drift(Particles& particles, double dt) {
  const std::size_t n = particles.size();
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (std::size_t i = 0; i < n; ++i) {
    // Gravity loading only: velocity damping -c v (Peng 2015 section 5.3).
    const Vec2 a = acceleration_[i] - damping_ * particles.velocity[i];
    particles.velocity[i] += dt * a;
    const Vec2 dx = dt * particles.velocity[i];
    particles.position[i] += dx;
    particles.displacement[i] += dx;
  }
}

void SphSolver::advance(Particles& particles, double dt) {
  const std::size_t n = particles.size();
  const bool verlet = setup_.options.integrator == SphIntegrator::verlet;
  const bool continuity = setup_.options.continuity;
  // Eqs 32-35 step over 2 dt from n - 1; with a variable dt the interval is dt_{n-1} + dt_n, and
  // the first step is a forward Euler step from n.
  const bool euler = first_step_ || counters_.steps % kVerletEulerInterval == 0;
  const double span = euler ? dt : previous_dt_ + dt;
  std::size_t bad = n;  // first particle with a non-finite state
  double v_max2 = 0.0;
  long penetrations = 0;
  const double depth = setup_.options.dummy_layers * setup_.spacing;

#pragma omp parallel for schedule(dynamic, 128) reduction(min : bad) reduction(max : v_max2) \
    reduction(+ : penetrations) if (n >= kParallelMin)
  for (std::size_t i = 0; i < n; ++i) {
    const auto m = static_cast<std::size_t>(particles.material[i]);
    const constitutive::Model& model = *setup_.models[m];
    const std::span<double> internal(particles.internal.of(i), n_internal_[m]);
    const Mat3 l = full_velocity_gradient(i);
    const Mat3 d = sym(l);   // Peng 2015 eq 22
    const Mat3 w = skew(l);  // Peng 2015 eq 23
    const Vec2* v_new = &particles.velocity[i];
    const Mat3* s_new = &particles.stress[i];
    if (verlet) {
      // Gravity loading only: velocity damping -c v (Peng 2015 section 5.3).
      const Vec2 a = acceleration_[i] - damping_ * particles.velocity[i];
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
        particles.volume[i] = particles.mass[i] / scratch_density_[i];
      }
      v_new = &scratch_velocity_[i];
      s_new = &scratch_stress_[i];
    } else {
      // Leapfrog, after kick_drift and velocity_gradient_pass: the stress by the incremental
      // objective update of the library, over the velocity gradient of the new velocities.
      constitutive::update_stress(model, d * dt, w * dt, particles.stress[i], internal);
      model.correct(particles.stress[i], internal);
      particles.strain[i] += d * dt;
      if (continuity) {
        particles.density[i] += dt * density_rate_[i];
        particles.volume[i] = particles.mass[i] / particles.density[i];
      }
    }
    if (!s_new->allFinite() || !particles.position[i].allFinite() || !v_new->allFinite()) {
      bad = std::min(bad, i);
    }
    v_max2 = std::max(v_max2, v_new->squaredNorm());
    // Particles behind a wall, within its dummy layers (counted, reported in diagnostics).
    for (const WallGeometry& g : geometry_) {
      if (behind_wall(g, particles.position[i], depth)) {
        ++penetrations;
        break;
      }
    }
  }
  penetrations_ = penetrations;
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
  if (bad < n) {
    throw NumericalFailure("non-finite particle state after the SPH update",
                           static_cast<long>(bad));
  }
  if (v_max2 > setup_.options.sound_speed * setup_.options.sound_speed) {
    // Runaway kinetic energy: a particle faster than the sound speed breaks eq 37's time step.
    long fastest = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (particles.velocity[i].squaredNorm() == v_max2) fastest = static_cast<long>(i);
    }
    throw NumericalFailure("runaway kinetic energy: particle speed " +
                               std::to_string(std::sqrt(v_max2)) + " m/s exceeds the sound speed",
                           fastest);
  }
  first_step_ = false;
  previous_dt_ = dt;
}

void SphSolver::set_rates(std::size_t i, const PairData& p, const PairSum& s) {
  Mat2 l;
  l << s.lxx, s.lxy, s.lyx, s.lyy;
  if (!setup_.axisymmetric) {
    velocity_gradient_[i] = l;
    density_rate_[i] = s.rho_rate;
    return;
  }
  // Axisymmetric: the sums over ring volumes and masses, over the particle's ring weight (eq 21
  // as (1 / eta_i) sum_j m_j (v_j - v_i) (x) grad W_ij, the gradient the pair forces do work
  // on; eq 24 as the rate of eta = 2 pi r rho). The hoop rate of stretching v_r / r, with the
  // radial direction G_r of the hoop force (its power's conjugate): the ring's circumference
  // grows at 2 pi v_r (Garcia-Senz et al. 2009: the v_r / r term of the continuity equation).
  // The ring's stretching takes rho v_r / r off the density besides the plane's.
  const double w = detail::ring_weight(p.x);
  velocity_gradient_[i] = l / w;
  const double hoop = p.vx * s.ring_r / p.x;
  hoop_rate_[i] = hoop;
  density_rate_[i] = s.rho_rate / w - p.rho * hoop;
}

Mat3 SphSolver::full_velocity_gradient(std::size_t i) const {
  Mat3 l = embed(velocity_gradient_[i]);
  // Axisymmetric: the out-of-plane slot is the hoop direction, its rate of stretching v_r / r
  if (!hoop_rate_.empty()) l(2, 2) = hoop_rate_[i];
  return l;
}

void SphSolver::check_off_axis(const Particles& particles) const {
  if (!setup_.axisymmetric) return;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (!(particles.position[i].x() > 0.0)) {
      throw NumericalFailure(
          "a particle reached the axis (r = " + std::to_string(particles.position[i].x()) +
              " m <= 0): its ring has no radius",
          static_cast<long>(i));
    }
  }
}

double SphSolver::step(Particles& particles, double time) {
  {
    ScopedTimer t(timers_, Phase::neighbours);
    update_walls(time, counters_.steps > 0 ? previous_dt_ : 0.0);
    // Verlet list: rebuild (and re-sort the working order) once anything has moved skin / 2.
    const double moved2 = rebuild_ ? 0.0 : gather(particles);
    if (rebuild_ || 4.0 * moved2 >= skin_ * skin_) rebuild_neighbours(particles);
  }
  {
    ScopedTimer t(timers_, Phase::forces);
    pair_loop(particles);
  }
  const double dt = time_step();
  if (!contact_.bodies.empty()) {
    // Frictional rigid bodies (simhypo eqs 39-40): the penalty force 2 m / dt^2 needs this
    // step's dt, and stays out of eq 36's time step.
    ScopedTimer t(timers_, Phase::forces);
    const std::span<WallGeometry> bodies(geometry_.data() + setup_.walls.size(),
                                         contact_.bodies.size());
    move_bodies(contact_, bodies, time, counters_.steps > 0 ? previous_dt_ : 0.0, settling_);
    apply_contact(contact_, bodies, particles, dt, acceleration_);
  }
  if (setup_.options.integrator == SphIntegrator::leapfrog) {
    {
      ScopedTimer t(timers_, Phase::integration);
      kick_drift(particles, dt);
    }
    velocity_gradient_pass(particles);
  }
  {
    ScopedTimer t(timers_, Phase::constitutive);
    advance(particles, dt);
    // Axisymmetric: the axis's symmetry plane holds the rings off r = 0; a particle that reached
    // it fails here rather than becoming its mirror image (a ring through the axis)
    check_off_axis(particles);
    reflect_across_symmetry_planes(particles);
  }
  counters_.penetrations_last_step = penetrations_;
  counters_.penetrations_max = std::max(counters_.penetrations_max, penetrations_);
  counters_.penetrations_total += penetrations_;
  counters_.ghost_particles_max = std::max(counters_.ghost_particles_max, n_active_ghosts_);
  counters_.dt_min = counters_.steps == 0 ? dt : std::min(counters_.dt_min, dt);
  counters_.dt_max = std::max(counters_.dt_max, dt);
  ++counters_.steps;
  return dt;
}

void SphSolver::reflect_across_symmetry_planes(Particles& particles) {
  // A symmetry plane holds the soil by its ghosts alone, whose pair force vanishes as a particle
  // nears its own image (the kernel's gradient is zero at zero distance), so nothing stops a
  // particle pushed onto the plane from passing it: the SPH cavity at dp 0.5 failed so at a/a0
  // 1.79 when expanded four times slower (its particle 4, by the wall's foot). Beyond the plane
  // such a particle stands for its mirror image, the same material point of the symmetric body:
  // it becomes that image, and carries on.
  const std::size_t n = particles.size();
  const bool verlet = setup_.options.integrator == SphIntegrator::verlet;
  long reflected = 0;
  for (std::size_t w = 0; w < setup_.walls.size(); ++w) {
    if (!setup_.walls[w].symmetry) continue;
    const WallGeometry& plane = geometry_[w];
    if (plane.points.size() != 2) continue;  // a plane is one straight segment
    const Vec2 nv = plane.normals[0];
    const auto reflect_velocity = [&](Vec2& v) { v = mirror(v, nv); };
    const auto reflect_tensor = [&](Mat3& t) { t = mirror(t, nv); };
#pragma omp parallel for schedule(static) reduction(+ : reflected) if (n >= kParallelMin)
    for (std::size_t i = 0; i < n; ++i) {
      bool inside = false;
      const double d = signed_distance(plane, 0, particles.position[i], &inside);
      if (!(inside && d < 0.0)) continue;
      const Vec2 shift = -2.0 * d * nv;
      particles.position[i] += shift;
      particles.displacement[i] += shift;
      reflect_velocity(particles.velocity[i]);
      reflect_tensor(particles.stress[i]);
      reflect_tensor(particles.strain[i]);
      if (verlet) {
        reflect_velocity(velocity_old_[i]);
        reflect_tensor(stress_old_[i]);
        reflect_tensor(strain_old_[i]);
      }
      ++reflected;
    }
  }
  counters_.symmetry_reflections += reflected;
}

void SphSolver::settle(Particles& particles, double duration, double damping) {
  damping_ = damping;
  settling_ = true;
  double t = -duration;
  while (t < 0.0) t += step(particles, t);
  damping_ = 0.0;
  settling_ = false;
  particles.start_from_rest();
  first_step_ = true;
  gradient_cached_ = false;
}

}  // namespace duet::sph

namespace duet::sph {

void SphSolver::save_state(StateBag& state) const {
  for (std::size_t w = 0; w < geometry_.size(); ++w) {
    const std::string key = "solver.geometry." + std::to_string(w);
    put(state, key + ".points", geometry_[w].points);
    put(state, key + ".normals", geometry_[w].normals);
    put(state, key + ".point_velocity", geometry_[w].point_velocity);
  }
  put(state, "solver.dummy_position", dummy_position_);
  put(state, "solver.dummy_velocity", dummy_velocity_);
  put(state, "solver.acceleration", acceleration_);
  put_matrices(state, "solver.velocity_gradient", velocity_gradient_);
  put(state, "solver.density_rate", density_rate_);
  if (setup_.axisymmetric) put(state, "solver.hoop_rate", hoop_rate_);
  put(state, "solver.wall_force", wall_force_);
  put(state, "solver.velocity_old", velocity_old_);
  put_matrices(state, "solver.stress_old", stress_old_);
  put_matrices(state, "solver.strain_old", strain_old_);
  put(state, "solver.density_old", density_old_);
  put(state, "solver.void_ratio_old", void_ratio_old_);
  const SphCounters& c = counters_;
  put(state, "solver.scalars",
      std::vector<double>{
          first_step_ ? 1.0 : 0.0, previous_dt_, double(penetrations_), double(c.steps),
          double(c.penetrations_last_step), double(c.penetrations_max),
          double(c.penetrations_total), double(c.ghost_particles_max), double(c.neighbours_max),
          double(c.neighbour_builds), c.dt_min, c.dt_max, double(c.symmetry_reflections)});
  const RigidContact& k = contact_;
  for (std::size_t b = 0; b < k.step_shift.size(); ++b) {
    put(state, "solver.contact.step_shift." + std::to_string(b), k.step_shift[b]);
  }
  put(state, "solver.contact.box_min", k.box_min);
  put(state, "solver.contact.box_max", k.box_max);
  put(state, "solver.contact.previous_position", k.previous_position);
  put(state, "solver.contact.tangential", k.tangential);
  put_integers(state, "solver.contact.body_of", k.body_of);
  put(state, "solver.contact.reaction", k.reaction);
  put(state, "solver.contact.contacts", static_cast<double>(k.contacts));
}

void SphSolver::restore_state(const StateBag& state) {
  // Each array as long as the one initialise sized: the same scene, the same particles.
  const auto same_size = [](const std::string& key, std::size_t had, std::size_t read) {
    if (had != read) throw_bad_entry(key, "is not of this scene's size");
  };
  const auto vectors = [&](const std::string& key, std::vector<Vec2>& out) {
    const std::size_t had = out.size();
    get(state, key, out);
    same_size(key, had, out.size());
  };
  for (std::size_t w = 0; w < geometry_.size(); ++w) {
    const std::string key = "solver.geometry." + std::to_string(w);
    vectors(key + ".points", geometry_[w].points);
    vectors(key + ".normals", geometry_[w].normals);
    vectors(key + ".point_velocity", geometry_[w].point_velocity);
  }
  vectors("solver.dummy_position", dummy_position_);
  vectors("solver.dummy_velocity", dummy_velocity_);
  vectors("solver.acceleration", acceleration_);
  get_matrices(state, "solver.velocity_gradient", velocity_gradient_);
  get(state, "solver.density_rate", density_rate_);
  if (setup_.axisymmetric) get(state, "solver.hoop_rate", hoop_rate_);
  vectors("solver.wall_force", wall_force_);
  vectors("solver.velocity_old", velocity_old_);
  get_matrices(state, "solver.stress_old", stress_old_);
  get_matrices(state, "solver.strain_old", strain_old_);
  get(state, "solver.density_old", density_old_);
  get(state, "solver.void_ratio_old", void_ratio_old_);
  const std::vector<double>& v = entry(state, "solver.scalars");
  // 12 before the symmetry planes' reflection count was kept
  if (v.size() != 12 && v.size() != 13) throw_bad_entry("solver.scalars", "has another size");
  first_step_ = v[0] != 0.0;
  previous_dt_ = v[1];
  penetrations_ = static_cast<long>(v[2]);
  SphCounters& c = counters_;
  c.steps = static_cast<long>(v[3]);
  c.penetrations_last_step = static_cast<long>(v[4]);
  c.penetrations_max = static_cast<long>(v[5]);
  c.penetrations_total = static_cast<long>(v[6]);
  c.ghost_particles_max = static_cast<std::size_t>(v[7]);
  c.neighbours_max = static_cast<std::size_t>(v[8]);
  c.neighbour_builds = static_cast<long>(v[9]);
  c.dt_min = v[10];
  c.dt_max = v[11];
  c.symmetry_reflections = v.size() > 12 ? static_cast<long>(v[12]) : 0;
  RigidContact& k = contact_;
  for (std::size_t b = 0; b < k.step_shift.size(); ++b) {
    vectors("solver.contact.step_shift." + std::to_string(b), k.step_shift[b]);
  }
  vectors("solver.contact.box_min", k.box_min);
  vectors("solver.contact.box_max", k.box_max);
  vectors("solver.contact.previous_position", k.previous_position);
  vectors("solver.contact.tangential", k.tangential);
  const std::size_t bodies_of = k.body_of.size();
  get_integers(state, "solver.contact.body_of", k.body_of);
  same_size("solver.contact.body_of", bodies_of, k.body_of.size());
  vectors("solver.contact.reaction", k.reaction);
  k.contacts = static_cast<long>(scalar(state, "solver.contact.contacts"));
}

}  // namespace duet::sph
