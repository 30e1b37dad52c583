// The SPH step's working set (sph/README.md, step 2): walls moved, ghost candidates chosen, the
// pair loop's inputs copied in working order (soil sorted by cell, ghosts, dummies), and the
// Verlet list rebuilt when something has moved half the skin.
#include <algorithm>
#include <stdexcept>
#include <string>

#include "common/solver.hpp"
#include "sph/pair_terms.hpp"
#include "sph/sph_solver.hpp"

namespace duet::sph {

using detail::artificial_stress_term;
using detail::in_plane;
using detail::kParallelMin;
using detail::mirror;
using detail::ring_weight;

void SphSolver::update_walls(double time, double dt) {
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
    const WallVelocity& velocity = setup_.walls[static_cast<std::size_t>(dummy_wall_[d])].velocity;
    if (!velocity) continue;
    dummy_position_[d] += dt * dummy_velocity_[d];
    dummy_velocity_[d] = settling_ ? Vec2::Zero() : velocity(time, dummy_position_[d]);
  }
}

void SphSolver::select_ghosts(const Particles& particles) {
  // Candidates: every soil particle that can come within reach (2h, Peng 2015 section 4.2 with
  // k = 2) in front of a free-slip segment, and project onto it, before the next build. Neither
  // it nor the wall moves more than skin / 2 until then, so a margin of one skin suffices.
  const double reach = kernel_.support_radius();
  ghost_source_.clear();
  ghost_wall_.clear();
  ghost_segment_.clear();
  ghost_plane_.clear();
  // A candidate of a wall that is not a symmetry plane, near a plane, also has its ghost mirrored
  // across that plane: the corner's image, where the soil by both sees the ghost of its own
  // mirror image (without it a particle in the corner of the cavity wall and the plane y = 0
  // lacks the diagonal quarter of its support, is pushed into the corner and is overtaken by
  // the wall: the SPH cavity at dp 0.5 expanded four times slower failed so at a/a0 1.97).
  const auto add = [&](std::size_t i, std::size_t w, std::uint32_t segment) {
    ghost_source_.push_back(static_cast<std::uint32_t>(i));
    ghost_wall_.push_back(static_cast<std::uint32_t>(w));
    ghost_segment_.push_back(segment);
    ghost_plane_.push_back(-1);
    if (setup_.walls[w].symmetry) return;
    for (std::size_t p = 0; p < setup_.walls.size(); ++p) {
      const WallGeometry& plane = geometry_[p];
      if (!setup_.walls[p].symmetry || plane.points.size() != 2) continue;
      // the ghost lies within the candidate's distance of the wall, beyond it: near the plane
      // when the particle is within twice the reach of it
      const double d = (particles.position[i] - plane.points[0]).dot(plane.normals[0]);
      if (std::abs(d) >= 2.0 * (reach + skin_)) continue;
      ghost_source_.push_back(static_cast<std::uint32_t>(i));
      ghost_wall_.push_back(static_cast<std::uint32_t>(w));
      ghost_segment_.push_back(segment);
      ghost_plane_.push_back(static_cast<std::int32_t>(p));
    }
  };
  for (std::size_t w = 0; w < setup_.walls.size(); ++w) {
    if (setup_.walls[w].condition != WallCondition::free_slip) continue;
    const WallGeometry& g = geometry_[w];
    for (std::size_t s = 0; s + 1 < g.points.size(); ++s) {
      const Vec2 a = g.points[s];
      const Vec2 t = g.points[s + 1] - a;
      const double length = t.norm();
      for (std::size_t i = 0; i < particles.size(); ++i) {
        const Vec2 x = particles.position[i];
        const double d = (x - a).dot(g.normals[s]);
        const double along = (x - a).dot(t) / length;
        if (d < -skin_ || d >= reach + skin_ || along < -skin_ || along > length + skin_) continue;
        add(i, w, static_cast<std::uint32_t>(s));
      }
      // The wedge beyond the vertex that starts segment s (mirror_at_vertex): candidates within
      // reach of the vertex
      if (segment_before(g, s) < 0) continue;
      for (std::size_t i = 0; i < particles.size(); ++i) {
        if ((particles.position[i] - a).norm() >= reach + skin_) continue;
        add(i, w, static_cast<std::uint32_t>(s) | kVertexGhost);
      }
    }
  }
}

double SphSolver::gather(const Particles& particles) {
  // Copies what the pair loop reads into work_, in working order, and returns the largest
  // squared displacement of any working entry since the last neighbour build.
  const std::size_t n = particles.size();
  const std::size_t n_ghost = ghost_source_.size();
  const double b = setup_.options.artificial_stress;
  const double reach = kernel_.support_radius();
  const bool reference = !rebuild_;
  // The velocity pass's gradient factors stay valid only if no working position changes
  // (bitwise: the pair loop must compute what it would have computed itself).
  const bool cached = gradient_cached_;
  const auto same = [this](std::size_t k, const Vec2& x) {
    return work_[k].x == x.x() && work_[k].y == x.y();
  };
  bool unchanged = true;
  double moved2 = 0.0;
  std::size_t active = 0;
  // Axisymmetric (Garcia-Senz et al. 2009): the pair sums run over the ring masses m and ring
  // volumes m / rho, the stress (and eq 29's R) over rho^2 2 pi |r| (sph/README.md,
  // "Axisymmetric")
  const bool ring = setup_.axisymmetric;
#pragma omp parallel for schedule(static) reduction(max : moved2) reduction(&& : unchanged) \
    if (n >= kParallelMin)
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = order_[k];
    const Vec2 x = particles.position[i];
    if (cached) unchanged = unchanged && same(k, x);
    const Vec2 v = particles.velocity[i];
    const double rho = particles.density[i];
    const Mat3& s = particles.stress[i];
    const double ring_over = ring ? 1.0 / ring_weight(x.x()) : 1.0;
    const double inv_rho2 = ring ? ring_over / (rho * rho) : 1.0 / (rho * rho);
    const double m = particles.mass[i];
    work_[k] = {x.x(),
                x.y(),
                v.x(),
                v.y(),
                m,
                rho,
                m / rho,
                s(0, 0) * inv_rho2,
                s(1, 1) * inv_rho2,
                s(0, 1) * inv_rho2};
    if (b > 0.0) {
      const Mat2 r = artificial_stress_term(in_plane(s), rho, b) * ring_over;
      work_r_[k] = {r(0, 0), r(1, 1), r(0, 1)};
    }
    if (reference) moved2 = std::max(moved2, (x - work_reference_[k]).squaredNorm());
  }
  for (std::size_t g = 0; g < n_ghost; ++g) {  // a few hundred: serial
    // Ghost: the mirrored state of its soil particle (Peng 2015 section 4.2); a candidate out of
    // reach carries no mass, so it adds nothing to any sum.
    const std::size_t src = ghost_source_[g];
    const WallGeometry& wall = geometry_[ghost_wall_[g]];
    const bool at_vertex = (ghost_segment_[g] & kVertexGhost) != 0;
    const std::size_t segment = ghost_segment_[g] & ~kVertexGhost;
    Vec2 x, v;
    Vec2 normal = wall.normals[segment];
    bool acts = at_vertex ? mirror_at_vertex(wall, segment, particles.position[src],
                                             particles.velocity[src], reach, x, v, normal)
                          : mirror_particle(wall, segment, particles.position[src],
                                            particles.velocity[src], reach, x, v);
    Mat2 s = mirror(in_plane(particles.stress[src]), normal);
    if (ghost_plane_[g] >= 0) {
      // the corner's image: the ghost mirrored across the symmetry plane, where it acts when the
      // ghost lies within reach in front of the plane (select_ghosts)
      const WallGeometry& plane = geometry_[static_cast<std::size_t>(ghost_plane_[g])];
      const Vec2 n_p = plane.normals[0];
      const double d = (x - plane.points[0]).dot(n_p);
      acts = acts && d >= 0.0 && d < reach;
      x -= 2.0 * d * n_p;
      v = mirror(v, n_p);
      s = mirror(s, n_p);
    }
    active += acts ? 1 : 0;
    if (cached) unchanged = unchanged && same(n + g, x);
    const double rho = particles.density[src];
    // Axisymmetric: the ring of the ghost's own radius |x| with its soil particle's plane mass
    // (an image across the axis, at -r, is its particle's very ring)
    const double ring_over = ring ? 1.0 / ring_weight(x.x()) : 1.0;
    const double inv_rho2 = ring ? ring_over / (rho * rho) : 1.0 / (rho * rho);
    const double m_src =
        ring ? particles.mass[src] * ring_weight(x.x()) / ring_weight(particles.position[src].x())
             : particles.mass[src];
    const double m = acts ? m_src : 0.0;
    work_[n + g] = {x.x(),
                    x.y(),
                    v.x(),
                    v.y(),
                    m,
                    rho,
                    m / rho,
                    s(0, 0) * inv_rho2,
                    s(1, 1) * inv_rho2,
                    s(0, 1) * inv_rho2};
    if (b > 0.0) {
      const Mat2 r = artificial_stress_term(s, rho, b) * ring_over;
      work_r_[n + g] = {r(0, 0), r(1, 1), r(0, 1)};
    }
    boundary_position_[n_dummy_ + g] = x;
    if (reference) moved2 = std::max(moved2, (x - work_reference_[n + g]).squaredNorm());
  }
  for (std::size_t d = 0; d < n_dummy_; ++d) {
    // Dummy: mass, density and stress depend on the soil particle it interacts with (pair loop).
    const std::size_t k = n + n_ghost + d;
    const Vec2 x = dummy_position_[d];
    if (cached) unchanged = unchanged && same(k, x);
    work_[k] = {x.x(), x.y(), dummy_velocity_[d].x(), dummy_velocity_[d].y(), 0, 0, 0, 0, 0, 0};
    boundary_position_[d] = x;
    if (reference) moved2 = std::max(moved2, (x - work_reference_[k]).squaredNorm());
  }
  for (std::size_t w = 0; w < geometry_.size() && reference; ++w) {
    for (std::size_t p = 0; p < geometry_[w].points.size(); ++p) {
      moved2 = std::max(moved2, (geometry_[w].points[p] - wall_reference_[w][p]).squaredNorm());
    }
  }
  n_active_ghosts_ = active;
  gradient_cached_ = cached && unchanged;
  return moved2;
}

void SphSolver::rebuild_neighbours(const Particles& particles) {
  const std::size_t n = particles.size();
  select_ghosts(particles);
  const std::size_t n_ghost = ghost_source_.size();
  const std::size_t n_work = n + n_ghost + n_dummy_;
  gradient_cached_ = false;  // a new working order and new rows
  work_.resize(n_work);
  work_r_.resize(setup_.options.artificial_stress > 0.0 ? n_work : 0);
  work_wall_.resize(n_work);
  boundary_position_.resize(n_dummy_ + n_ghost);
  for (std::size_t k = 0; k < n; ++k) work_wall_[k] = -1;
  for (std::size_t g = 0; g < n_ghost; ++g) {
    work_wall_[n + g] = static_cast<std::int32_t>(ghost_wall_[g]);
  }
  for (std::size_t d = 0; d < n_dummy_; ++d) work_wall_[n + n_ghost + d] = dummy_wall_[d];

  // The working order: soil particles sorted by cell (ghosts and dummies follow, unsorted: they
  // lie along the walls anyway).
  const double cell = kernel_.support_radius() + skin_;
  all_position_.resize(n);
  std::copy(particles.position.begin(), particles.position.end(), all_position_.begin());
  try {
    cells_.build(all_position_, cell);
  } catch (const std::domain_error& e) {
    throw NumericalFailure(std::string("neighbour search: ") + e.what());
  }
  const auto sorted = cells_.sorted();
  std::copy(sorted.begin(), sorted.end(), order_.begin());
  rebuild_ = true;
  gather(particles);

  // Rows over the working positions: soil and ghosts first, dummies last.
  all_position_.resize(n_work);
  for (std::size_t k = 0; k < n_work; ++k) all_position_[k] = Vec2(work_[k].x, work_[k].y);
  cells_.build(all_position_, cell);
  neighbours_.build(cells_, all_position_, n, cell, n + n_ghost);
  counters_.neighbours_max = std::max(counters_.neighbours_max, neighbours_.max_count());
  neighbours_.drop_lower_pairs(n);  // each soil pair once: the pair loop serves both ends
  gradient_factor_.resize(n * neighbours_.stride());  // grows only with the rows
  work_reference_.assign(all_position_.begin(), all_position_.end());
  for (std::size_t w = 0; w < geometry_.size(); ++w) wall_reference_[w] = geometry_[w].points;
  rebuild_ = false;
  ++counters_.neighbour_builds;
}

}  // namespace duet::sph
