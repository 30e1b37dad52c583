#include "spfem/implicit_solver.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "common/geometry.hpp"
#include "common/input_error.hpp"
#include "common/solver.hpp"
#include "spfem/increment_operator.hpp"
#include "spfem/newton_increment.hpp"

namespace duet::spfem {

namespace {

std::string format_residuals(const std::vector<double>& r) {
  std::ostringstream out;
  out.precision(3);
  const std::size_t first = r.size() > 6 ? r.size() - 6 : 0;
  for (std::size_t i = first; i < r.size(); ++i) out << (i > first ? ", " : "") << r[i];
  return out.str();
}

// The increment rules shared by the load steps (step) and the gravity loading (settle). A failed
// increment may be halved while half of it stays above the floor nominal / 2^max_step_cuts:
// without the floor the halvings of successive increments compound (each grows back only after
// easy convergence) and a run can creep on with vanishing increments that converge trivially
// while its time stands still.
bool may_halve(const duet::SpfemImplicitOptions& o, double size, double nominal) {
  return o.adaptive && 0.5 * size >= nominal * std::ldexp(1.0, -o.max_step_cuts) * (1.0 - 1e-9);
}

// The next increment after one of `size` converged in `iterations`: grown by 1.5 after easy
// convergence, never beyond nominal; the nominal one when not adaptive.
double next_increment(const duet::SpfemImplicitOptions& o, double size, double nominal,
                      int iterations) {
  if (!o.adaptive) return nominal;
  return iterations <= o.easy_iterations ? std::min(nominal, 1.5 * size) : size;
}

// Why a failed increment of `size` is not halved again, for the failure message.
std::string why_not_halved(const duet::SpfemImplicitOptions& o, double size, double nominal,
                           int cuts) {
  std::ostringstream why;
  if (!o.adaptive) {
    why << "spfem.implicit.adaptive = false: increments are never cut";
  } else {
    why << "after " << cuts << (cuts == 1 ? " cut" : " cuts") << " of this increment, " << size
        << " s is the smallest increment allowed (nominal " << nominal << " s / 2^"
        << o.max_step_cuts << ", spfem.implicit.max_step_cuts"
        << (cuts == 0 ? "; earlier increments' cuts brought it there" : "") << ")";
  }
  return why.str();
}

}  // namespace

ImplicitSolver::ImplicitSolver(IspfemSetup setup)
    : setup_(std::move(setup)),
      discretisation_(setup_.options, setup_.spacing, setup_.boundaries, setup_.axisymmetric) {
  const duet::SpfemImplicitOptions& o = setup_.implicit;
  if (!(o.tolerance > 0.0)) throw InputError("spfem.implicit.tolerance must be > 0");
  if (!(o.displacement_tolerance > 0.0)) {
    throw InputError("spfem.implicit.displacement_tolerance must be > 0");
  }
  if (o.max_iterations < 1) throw InputError("spfem.implicit.max_iterations must be >= 1");
  if (o.load_steps < 1) throw InputError("spfem.implicit.load_steps must be >= 1");
  if (!(o.increment >= 0.0)) throw InputError("spfem.implicit.increment must be >= 0 s");
  if (!(o.increment_stabilisation >= 0.0)) {
    throw InputError("spfem.implicit.increment_stabilisation must be >= 0");
  }
}

void ImplicitSolver::initialise(Particles& particles) {
#if defined(__GLIBC__)
  // UMFPACK allocates its numeric workspace (tens of MB) at every factorisation and frees it
  // after; above glibc's mmap threshold each is a fresh mapping whose pages fault in zeroed.
  // Kept in the heap, a factorisation is a fifth faster (benchmarks/RESULTS.md). Process-wide;
  // the memory stays with the process until it ends.
  mallopt(M_MMAP_THRESHOLD, 256 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
  const std::size_t n = particles.size();
  for (std::size_t i = 0; i < n; ++i) {
    const int m = particles.material[i];
    if (m < 0 || static_cast<std::size_t>(m) >= setup_.models.size()) {
      throw std::invalid_argument("ispfem: particle without a material model");
    }
    if (setup_.models[std::size_t(m)]->internal_variables().size() > particles.internal.width) {
      throw std::invalid_argument("ispfem: internal variable block narrower than the model needs");
    }
  }
  discretisation_.initialise(particles.position);
  released_.assign(n, 0);
  held_by_.assign(n, 0);
  held_initialised_ = false;
  previous_u_.assign(n, Vec2::Zero());
  acceleration_.assign(n, Vec2::Zero());
  dynamic_started_ = false;
  previous_increment_ = 0.0;
  increment_ = 0.0;
  external_force_.assign(n, Vec2::Zero());
  boundary_force_.assign(setup_.boundaries.size(), Vec2::Zero());
  load_peak_.assign(setup_.boundaries.size(), 0.0);
  counters_ = NewtonCounters{};
  timers_.reset();
}

std::vector<NodeConstraint> ImplicitSolver::find_constraints(const std::vector<Vec2>& x, double t0,
                                                             double t1, bool crossed_only) const {
  // The touch of node_contact.hpp, as the explicit solver finds it: within dp/2 of a segment on
  // the soil side (the lattice puts the first row of nodes there), or crossed by less than dp.
  // A wall keeps a node it held at the last increment's end while within dp: held at exactly
  // dp/2, a node moved along one chord's normal can leave the next chord's reach by round-off
  // (the cavity's polar lattice: its first ring lost the wall at every other increment).
  const double reach = 0.5 * setup_.spacing * (1.0 + 1e-6);
  const double held_reach = setup_.spacing;
  const double depth = setup_.spacing;
  const std::vector<NodeBoundary>& boundaries = discretisation_.boundaries();
  const std::vector<BoundaryGeometry>& geometry = discretisation_.geometry();
  std::vector<NodeConstraint> out;
  std::vector<NodeContact> found;
  for (std::size_t i = 0; i < x.size(); ++i) {
    for (std::size_t b = 0; b < boundaries.size(); ++b) {
      const NodeBoundary& boundary = boundaries[b];
      if (released_[i] != 0 && boundary.condition != NodeCondition::bonded) continue;
      found.clear();
      const bool held = !boundary.rigid_body && (held_by_[i] & (std::uint64_t{1} << (b % 64)));
      const double r = held ? held_reach : reach;
      // with a wall's convex vertex: the cavity at dp 0.25 failed at a/a0 1.24 without it
      find_node_contacts(geometry[b], boundary.rigid_body, std::int32_t(i), std::int32_t(b), x[i],
                         r, depth, found);
      for (const NodeContact& c : found) {
        if (crossed_only && !(c.distance < 0.0)) continue;
        NodeConstraint k;
        k.node = c.node;
        k.boundary = c.boundary;
        k.kind = constraint_kind(boundary.condition);
        k.normal = c.normal;
        k.increment =
            settling_ ? Vec2(Vec2::Zero()) : boundary_displacement(boundary, t0, t1, c.point);
        out.push_back(k);
      }
    }
  }
  return out;
}

std::string ImplicitSolver::wall_crossing(const std::vector<Vec2>& x, const std::vector<Vec2>& u,
                                          double t0, double t1) {
  std::string out;
  discretisation_.place_boundaries(t1, settling_);
  const std::vector<NodeBoundary>& boundaries = discretisation_.boundaries();
  for (std::size_t b = 0; b < boundaries.size() && out.empty(); ++b) {
    const NodeBoundary& wall = boundaries[b];
    if (wall.rigid_body) continue;
    const Vec2 motion = wall.radial || settling_
                            ? Vec2(Vec2::Zero())
                            : boundary_displacement(wall, t0, t1, wall.polyline.front());
    const std::int64_t i = first_node_crossing(discretisation_.geometry()[b], motion, x, u);
    if (i >= 0) {
      const Vec2 to = x[std::size_t(i)] + u[std::size_t(i)];
      std::ostringstream why;
      why << "node " << i << " crossed wall '" << wall.name << "' (x = " << to.x()
          << " m, y = " << to.y() << " m)";
      out = why.str();
    }
  }
  discretisation_.place_boundaries(t0, settling_);
  return out;
}

ImplicitSolver::SqueezedTriangle ImplicitSolver::most_squeezed_triangle(
    const std::vector<Vec2>& x, const std::vector<Vec2>& u) const {
  // Slivers of the alpha shape's surface (area far below a lattice triangle's dp^2 / 2) turn
  // over under any motion of their nodes: only triangles of a fair size count
  constexpr double kFairTriangle = 0.25;  // twice the area, in dp^2: a quarter of a lattice one's
  const double dp = setup_.spacing;
  const auto twice_area = [](const Vec2& p, const Vec2& q) {
    return p.x() * q.y() - p.y() * q.x();
  };
  SqueezedTriangle worst;
  for (const Triangle& t : discretisation_.mesh().triangles) {
    const auto [a, b, c] = t;
    const double before = twice_area(x[b] - x[a], x[c] - x[a]);
    const double after = twice_area(x[b] + u[b] - x[a] - u[a], x[c] + u[c] - x[a] - u[a]);
    if (before > kFairTriangle * dp * dp && after < worst.ratio * before) {
      worst.ratio = after / before;
      worst.triangle = t;
      worst.at = x[a];
    }
  }
  return worst;
}

std::string ImplicitSolver::SqueezedTriangle::describe(double floor) const {
  std::ostringstream why;
  why.precision(3);
  why << "the converged increment " << (ratio <= 0.0 ? "turns" : "squeezes")
      << " the triangle of nodes " << triangle[0] << ", " << triangle[1] << ", " << triangle[2]
      << " (near x = " << at.x() << " m, y = " << at.y() << " m) "
      << (ratio <= 0.0 ? "inside out" : "to a fraction of its area") << " (area ratio " << ratio
      << ", below spfem.implicit.min_area_ratio = " << floor
      << "): a snap-through, refused with spfem.implicit.snap = \"refuse\"";
  return why.str();
}

ImplicitSolver::Attempt ImplicitSolver::solve_increment(Particles& particles, double t0, double t1,
                                                        bool may_cut) {
  const duet::SpfemImplicitOptions& o = setup_.implicit;
  const std::size_t n = particles.size();
  Attempt attempt;
  {
    ScopedTimer t(timers_, Phase::mesh);
    // Mesh, wall strips and smoothing cells on the configuration at the increment's start
    discretisation_.place_boundaries(t0, settling_);
    discretisation_.update(particles.position);
  }
  const SmoothingCells& cells = discretisation_.cells();
  std::vector<std::uint8_t> held(n, 0);  // in no triangle: no stiffness, no unknowns (DofMap)
  for (std::size_t i = 0; i < n; ++i) held[i] = cells.area[i] > 0.0 ? 0 : 1;
  std::vector<NodeConstraint> constraints = start_contacts(particles, t0, t1);
  const double external_norm = update_external_force(particles, t1);

  const Models* models_now = models_at_ ? models_at_(t1) : nullptr;
  IncrementOperator op(discretisation_, models_now ? *models_now : setup_.models, particles,
                       wall_strip_increments(t0, t1), &timers_, o.increment_stabilisation);
  const NewmarkIncrement integrator(o.newmark && !settling_, t0, t1, particles, acceleration_);
  if (integrator.inertia && !dynamic_started_) {
    // the first step from rest under the loads alone (a body released from a settled state
    // has a = 0: settle() marks it started)
    for (std::size_t i = 0; i < n; ++i) {
      acceleration_[i] = particles.mass[i] > 0.0 ? Vec2(external_force_[i] / particles.mass[i])
                                                 : Vec2(Vec2::Zero());
    }
    dynamic_started_ = true;
  }
  const std::vector<double> mass_diagonal = integrator.mass_diagonal();

  for (int pass = 0; pass < o.active_set_passes; ++pass) {
    const DofMap dofs = eliminate(n, constraints, held);
    refuse_if_unheld(dofs, held, integrator.inertia, t0);
    std::vector<Vec2> u = initial_guess(dofs, integrator, t1 - t0);
    IncrementResidual residual(op, dofs, external_force_, external_norm, held, integrator);
    NewtonOutcome newton =
        newton_solve(op, dofs, residual, mass_diagonal, o, particles.position, timers_, u);
    counters_.iterations += newton.iterations;
    counters_.factorisations += newton.factorisations;
    counters_.line_search_halvings += newton.line_search_halvings;
    attempt.converged = newton.converged;
    attempt.why = std::move(newton.why);
    attempt.residuals = std::move(newton.residuals);
    if (!attempt.converged) return attempt;
    attempt.displacement = u;

    // Active set: release tensile contacts, attach nodes that crossed a boundary.
    std::vector<NodeConstraint> kept = release_pulling_contacts(particles, op, constraints);
    const bool released = kept.size() != constraints.size();
    const bool attached = attach_crossing_nodes(particles, u, held, t0, t1, kept);
    if (!(released || attached)) break;
    if (pass + 1 == o.active_set_passes) break;  // keep the last solution
    ++counters_.active_set_passes;
    constraints = std::move(kept);
  }

  if (std::string why = refusal(particles, attempt.displacement, t0, t1); !why.empty()) {
    attempt.converged = false;
    attempt.why = std::move(why);
    return attempt;
  }
  std::vector<Vec2> force = reactions(op, integrator, attempt.displacement, constraints);
  if (std::string why = load_drop(force, t1, may_cut); !why.empty()) {
    ++counters_.load_drop_cuts;
    attempt.converged = false;
    attempt.why = std::move(why);
    return attempt;
  }
  commit(particles, op, integrator, attempt.displacement, constraints, std::move(force), t1);
  return attempt;
}

double ImplicitSolver::driven_load(std::size_t boundary, const Vec2& force, double t) const {
  const NodeBoundary& b = setup_.boundaries[boundary];
  if (b.radial) {
    return schedule_value(b.radial_velocity, t).x() != 0.0 ? force.norm() : std::nan("");
  }
  const Vec2 v = schedule_value(b.velocity, t);
  return v != Vec2::Zero() ? -force.dot(v.normalized()) : std::nan("");
}

std::string ImplicitSolver::load_drop(const std::vector<Vec2>& force, double t1, bool may_cut) {
  const duet::SpfemImplicitOptions& o = setup_.implicit;
  // A perfectly plastic or elastic soil's load on a boundary driven into it does not fall; a
  // quasi-static increment that lets it fall has followed a soft mode of nodal integration
  // through a snap (benchmarks/run_warnings.hpp warns of the same in the output). Dynamics and
  // gravity loading are left alone.
  if (!(o.load_drop > 0.0) || !setup_.monotonic || o.newmark || settling_) return "";
  std::vector<std::pair<std::size_t, double>> dropped;  // boundary, its load at t1
  for (std::size_t b = 0; b < force.size(); ++b) {
    const double load = driven_load(b, force[b], t1);
    if (std::isnan(load) || !(load_peak_[b] > 0.0)) continue;
    if (load < (1.0 - o.load_drop) * load_peak_[b]) dropped.emplace_back(b, load);
  }
  if (dropped.empty()) return "";
  if (!may_cut) {  // kept: the path goes on from the lower load
    for (const auto& [b, load] : dropped) load_peak_[b] = load;
    counters_.load_drops_accepted += long(dropped.size());
    return "";
  }
  const auto [b, load] = dropped.front();
  std::ostringstream why;
  why << "the load on " << setup_.boundaries[b].name << " fell to " << load << " from its peak "
      << load_peak_[b] << ", more than spfem.implicit.load_drop = " << o.load_drop
      << " below it, though no material can soften";
  return why.str();
}

std::vector<NodeConstraint> ImplicitSolver::start_contacts(const Particles& particles, double t0,
                                                           double t1) {
  // A released node is let go until it no longer touches any boundary
  const std::size_t n = particles.size();
  std::vector<std::uint8_t> released_before = released_;
  std::fill(released_.begin(), released_.end(), 0);
  std::vector<NodeConstraint> all = find_constraints(particles.position, t0, t1, false);
  std::vector<std::uint8_t> touching(n, 0);
  for (const NodeConstraint& c : all) touching[std::size_t(c.node)] = 1;
  for (std::size_t i = 0; i < n; ++i) released_[i] = released_before[i] && touching[i];
  std::vector<NodeConstraint> constraints;
  for (const NodeConstraint& c : all) {
    const NodeBoundary& b = discretisation_.boundaries()[std::size_t(c.boundary)];
    const bool bonded = b.condition == NodeCondition::bonded;
    // A rigid body keeps the nodes it held at the last increment's end (or at the start of the
    // run) while they stay within reach; it takes new ones only when they cross it
    // (attach_crossing_nodes): by proximity alone, the column of nodes dp/2 beside a footing's
    // side is seized as soon as the footing's base passes them and dragged down with it.
    if (b.rigid_body && held_initialised_ &&
        !(held_by_[std::size_t(c.node)] & (std::uint64_t{1} << (c.boundary % 64)))) {
      continue;
    }
    if (bonded || released_[std::size_t(c.node)] == 0) constraints.push_back(c);
  }
  return constraints;
}

double ImplicitSolver::update_external_force(const Particles& particles, double t1) {
  // F_ext at the end of the increment: the scene's loads and gravity
  if (loads_) {
    loads_(t1, external_force_);
  } else {
    std::fill(external_force_.begin(), external_force_.end(), Vec2::Zero());
  }
  for (std::size_t i = 0; i < particles.size(); ++i) {
    external_force_[i] += gravity_factor_ * particles.mass[i] * setup_.gravity;
  }
  double external_norm = 0.0;
  for (const Vec2& f : external_force_) external_norm += f.squaredNorm();
  return std::sqrt(external_norm);
}

std::vector<Vec2> ImplicitSolver::wall_strip_increments(double t0, double t1) const {
  // The wall strips' wall points move with their walls over the increment
  const WallStrips& strips = discretisation_.wall_strips();
  std::vector<Vec2> wall_increment(2 * strips.edges.size(), Vec2::Zero());
  for (std::size_t e = 0; e < strips.edges.size() && !settling_; ++e) {
    const WallEdge& edge = strips.edges[e];
    if (edge.free_slip) continue;
    const NodeBoundary& b = discretisation_.boundaries()[std::size_t(edge.boundary)];
    wall_increment[2 * e] = boundary_displacement(b, t0, t1, edge.a_wall);
    wall_increment[2 * e + 1] = boundary_displacement(b, t0, t1, edge.b_wall);
  }
  return wall_increment;
}

void ImplicitSolver::refuse_if_unheld(const DofMap& dofs, const std::vector<std::uint8_t>& held,
                                      bool inertia, double t0) {
  long n_constrained = 0;
  for (std::size_t i = 0; i < held.size(); ++i) n_constrained += dofs.constrained[i] && !held[i];
  counters_.constrained_nodes_max = std::max(counters_.constrained_nodes_max, n_constrained);
  if (n_constrained == 0 && !inertia) {
    std::ostringstream why;
    why << "ispfem: no wall or rigid body holds any node at t = " << t0
        << " s: the quasi-static tangent is singular (the body can move as a rigid body)";
    throw NumericalFailure(why.str());
  }
}

std::vector<Vec2> ImplicitSolver::initial_guess(const DofMap& dofs,
                                                const NewmarkIncrement& integrator,
                                                double dt) const {
  // The prescribed motion on the constrained parts and, on the free dofs, rest
  // (spfem.implicit.predictor = none) or the last increment's motion scaled to this one
  // (extrapolated). Neither wins everywhere: smooth paths like the extrapolation, plastic flow
  // does not, nor does the smaller starting residual tell which is nearer. With inertia the
  // guess is the motion at constant acceleration.
  const double scale_dt = previous_increment_ > 0.0 ? dt / previous_increment_ : 0.0;
  std::vector<Vec2> u(dofs.prescribed);
  for (std::size_t i = 0; i < u.size() && (integrator.inertia || setup_.implicit.extrapolate);
       ++i) {
    const Vec2 guess = integrator.inertia ? integrator.constant_acceleration_guess(i)
                                          : Vec2(scale_dt * previous_u_[i]);
    for (std::int32_t a = dofs.first[i]; a < dofs.first[i + 1]; ++a) {
      const Vec2& d = dofs.direction[std::size_t(a)];
      u[i] += guess.dot(d) * d;
    }
  }
  return u;
}

std::vector<NodeConstraint> ImplicitSolver::release_pulling_contacts(
    const Particles& particles, const IncrementOperator& op,
    const std::vector<NodeConstraint>& constraints) {
  // A rigid body's contact pressure oscillates from node to node with nodal integration's
  // stresses: the release test reads the normal reaction summed over the node and the nodes the
  // same boundary holds within 1.5 dp of it (ImplicitFootingBenchmark tests on footing-deep).
  const std::vector<Vec2>& f_int = op.internal_force();
  std::vector<double> pull(constraints.size(), 0.0);
  for (std::size_t a = 0; a < constraints.size(); ++a) {
    const auto i = std::size_t(constraints[a].node);
    pull[a] = (external_force_[i] - f_int[i]).dot(constraints[a].normal);
  }
  const double near = 1.5 * setup_.spacing;
  for (std::size_t a = 0; a < constraints.size(); ++a) {
    const NodeConstraint& c = constraints[a];
    const NodeBoundary& b = discretisation_.boundaries()[std::size_t(c.boundary)];
    if (!b.rigid_body || b.condition == NodeCondition::bonded || settling_ || !(pull[a] > 0.0)) {
      continue;
    }
    const auto i = std::size_t(c.node);
    double sum = 0.0;
    for (std::size_t o = 0; o < constraints.size(); ++o) {
      const auto j = std::size_t(constraints[o].node);
      if (constraints[o].boundary == c.boundary &&
          (particles.position[j] - particles.position[i]).norm() <= near) {
        sum += pull[o];
      }
    }
    const Vec2 r = external_force_[i] - f_int[i];
    const double size = std::max(1e-9 * r.norm(), 1e-12);
    // Walls hold the nodes they touch both ways (a free-slip wall is mostly a symmetry plane,
    // which carries the cavity's tensile hoop stress); a rigid body lets go of a node whose
    // neighbourhood pulls.
    if (sum > size) {
      if (released_[i] == 0) ++counters_.releases;
      released_[i] = 1;
    }
  }
  std::vector<NodeConstraint> kept;
  for (const NodeConstraint& c : constraints) {
    if (released_[std::size_t(c.node)] == 0 ||
        discretisation_.boundaries()[std::size_t(c.boundary)].condition == NodeCondition::bonded) {
      kept.push_back(c);
    }
  }
  return kept;
}

bool ImplicitSolver::attach_crossing_nodes(const Particles& particles, const std::vector<Vec2>& u,
                                           const std::vector<std::uint8_t>& held, double t0,
                                           double t1, std::vector<NodeConstraint>& kept) {
  const std::size_t n = particles.size();
  std::vector<Vec2> x_end(n);
  for (std::size_t i = 0; i < n; ++i) x_end[i] = particles.position[i] + u[i];
  discretisation_.place_boundaries(t1, settling_);
  std::vector<std::uint8_t> constrained(n, 0);
  for (const NodeConstraint& c : kept) constrained[std::size_t(c.node)] = 1;
  bool attached = false;
  for (const NodeConstraint& c : find_constraints(x_end, t0, t1, true)) {
    if (constrained[std::size_t(c.node)] || held[std::size_t(c.node)]) continue;
    kept.push_back(c);
    ++counters_.attachments;
    attached = true;
  }
  discretisation_.place_boundaries(t0, settling_);
  return attached;
}

std::string ImplicitSolver::refusal(const Particles& particles, const std::vector<Vec2>& u,
                                    double t0, double t1) {
  const duet::SpfemImplicitOptions& o = setup_.implicit;
  // A converged increment that carries a node through a wall is not accepted: the step cuts it.
  // Nodal integration's soft modes let Newton converge to such a state.
  if (std::string crossing = wall_crossing(particles.position, u, t0, t1); !crossing.empty()) {
    return crossing;
  }
  // One that turns a triangle of its mesh inside out or squeezes it below min_area_ratio of its
  // area is a snap-through of nodal integration's soft modes, not the soil's response (a
  // quasi-static increment is small against dp). Cuts avoid some and not others (the discrete
  // path branches there), so by default it is counted and warned of; snap = "refuse" cuts it
  // and fails when the cuts run out.
  const SqueezedTriangle squeezed =
      settling_ ? SqueezedTriangle{} : most_squeezed_triangle(particles.position, u);
  const bool snapped = squeezed.ratio < o.min_area_ratio || squeezed.ratio <= 0.0;
  if (snapped && o.refuse_snaps) return squeezed.describe(o.min_area_ratio);
  if (snapped) {
    if (counters_.snaps++ == 0) counters_.snap_first_time = t1;
    counters_.snap_worst_ratio = std::min(counters_.snap_worst_ratio, squeezed.ratio);
  }
  return "";
}

std::vector<Vec2> ImplicitSolver::reactions(const IncrementOperator& op,
                                            const NewmarkIncrement& integrator,
                                            const std::vector<Vec2>& u,
                                            const std::vector<NodeConstraint>& constraints) const {
  const std::size_t n = u.size();
  std::vector<Vec2> force(boundary_force_.size(), Vec2::Zero());
  const std::vector<Vec2>& f_int = op.internal_force();
  std::vector<std::int32_t> owner(n, -1);
  for (const NodeConstraint& c : constraints) {
    const auto i = std::size_t(c.node);
    if (owner[i] < 0 || c.kind == ConstraintKind::fixed) owner[i] = c.boundary;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (owner[i] >= 0) {
      force[std::size_t(owner[i])] +=
          external_force_[i] - f_int[i] - integrator.inertia_force(i, u[i]);
    }
  }
  add_wall_strip_reactions(discretisation_.wall_strips(), discretisation_.cells(), op.stress(),
                           force);
  return force;
}

void ImplicitSolver::commit(Particles& particles, const IncrementOperator& op,
                            const NewmarkIncrement& integrator, const std::vector<Vec2>& u,
                            const std::vector<NodeConstraint>& constraints, std::vector<Vec2> force,
                            double t1) {
  const std::size_t n = particles.size();
  const double dt = integrator.dt;
  boundary_force_ = std::move(force);
  for (std::size_t b = 0; b < boundary_force_.size(); ++b) {
    const double load = driven_load(b, boundary_force_[b], t1);
    // Not driven now (or gravity loading): the next drive starts a new peak
    load_peak_[b] = std::isnan(load) || settling_ ? 0.0 : std::max(load_peak_[b], load);
  }
  const std::size_t width = particles.internal.width;
  for (std::size_t i = 0; i < n; ++i) {
    particles.position[i] += u[i];
    particles.displacement[i] += u[i];
    if (integrator.inertia) {
      const Vec2 a = integrator.acceleration_at_end(i, u[i]);
      particles.velocity[i] += 0.5 * dt * (acceleration_[i] + a);
      acceleration_[i] = a;
    } else {
      particles.velocity[i] = dt > 0.0 ? Vec2(u[i] / dt) : Vec2(Vec2::Zero());
    }
    particles.stress[i] = op.stress()[i];
    std::copy(op.internal().begin() + std::ptrdiff_t(i * width),
              op.internal().begin() + std::ptrdiff_t((i + 1) * width), particles.internal.of(i));
    const Mat3& d = op.strain_increment()[i];
    particles.strain[i] += d;
    particles.volume[i] *= std::exp(d.trace());
    particles.density[i] = particles.mass[i] / particles.volume[i];
  }
  previous_u_ = u;
  // The contacts at the increment's end: a rigid body keeps them while in reach, a wall while
  // within dp (find_constraints)
  std::fill(held_by_.begin(), held_by_.end(), std::uint64_t{0});
  for (const NodeConstraint& c : constraints) {
    if (released_[std::size_t(c.node)] == 0) {
      held_by_[std::size_t(c.node)] |= std::uint64_t{1} << (c.boundary % 64);
    }
  }
  held_initialised_ = true;
  previous_increment_ = dt;
}

double ImplicitSolver::step(Particles& particles, double time, double end_time) {
  const duet::SpfemImplicitOptions& o = setup_.implicit;
  const double nominal = o.increment > 0.0 ? o.increment : end_time / o.load_steps;
  if (!(nominal > 0.0)) throw NumericalFailure("ispfem: no time left to step");
  if (!(increment_ > 0.0)) increment_ = nominal;
  const double left = end_time - time;
  double dt = std::min(increment_, left);
  if (left - dt < 1e-6 * nominal) dt = left;  // no sliver of an increment at the end
  int cuts = 0;
  while (true) {
    const Attempt attempt = solve_increment(particles, time, time + dt, may_halve(o, dt, nominal));
    if (attempt.converged) {
      ++counters_.increments;
      const int iterations = static_cast<int>(attempt.residuals.size()) - 1;
      counters_.iterations_max = std::max(counters_.iterations_max, iterations);
      counters_.residual_history.push_back(attempt.residuals);
      counters_.increment_min =
          counters_.increments == 1 ? dt : std::min(counters_.increment_min, dt);
      counters_.increment_max = std::max(counters_.increment_max, dt);
      increment_ = next_increment(o, dt, nominal, iterations);
      return dt;
    }
    if (!may_halve(o, dt, nominal)) {
      std::ostringstream why;
      why << "Newton did not converge at t = " << time << " s over the increment " << dt
          << " s (increment " << counters_.increments + 1 << "; "
          << why_not_halved(o, dt, nominal, cuts) << "): " << attempt.why
          << "; last relative residuals: " << format_residuals(attempt.residuals);
      throw NumericalFailure(why.str());
    }
    ++cuts;
    ++counters_.cuts;
    dt *= 0.5;
  }
}

void ImplicitSolver::settle(Particles& particles, int increments) {
  settling_ = true;
  // Gravity in `increments` steps of its factor over the pseudo-time [-1, 0], cut and grown as
  // the load steps are (step()): a strength-reduction trial fails by Newton not converging
  // within its cuts (Griffiths & Lane 1999), not at the first increment that needs a smaller one.
  const duet::SpfemImplicitOptions& o = setup_.implicit;
  const double nominal = 1.0 / std::max(increments, 1);
  double factor = 0.0;
  double size = nominal;
  int cuts = 0;
  while (factor < 1.0) {
    const double next = 1.0 - factor - size < 1e-9 * nominal ? 1.0 : factor + size;
    gravity_factor_ = next;
    const Attempt attempt = solve_increment(particles, factor - 1.0, next - 1.0);
    if (!attempt.converged) {
      if (!may_halve(o, size, nominal)) {
        settling_ = false;
        std::ostringstream why;
        why << "ispfem gravity loading did not converge at gravity factor " << next << " (from "
            << factor << "; " << why_not_halved(o, size, nominal, cuts) << "): " << attempt.why
            << "; last relative residuals: " << format_residuals(attempt.residuals);
        throw NumericalFailure(why.str());
      }
      size *= 0.5;
      ++cuts;
      ++counters_.cuts;
      continue;
    }
    counters_.residual_history.push_back(attempt.residuals);
    size = next_increment(o, size, nominal, static_cast<int>(attempt.residuals.size()) - 1);
    factor = next;
  }
  gravity_factor_ = 1.0;
  settling_ = false;
  particles.start_from_rest();
  previous_u_.assign(particles.size(), Vec2::Zero());
  acceleration_.assign(particles.size(), Vec2::Zero());  // released in equilibrium
  dynamic_started_ = true;
  previous_increment_ = 0.0;
}

Json ImplicitSolver::diagnostics() const {
  const NewtonCounters& c = counters_;
  const MeshCounters& m = discretisation_.counters();
  Json newton = Json::object();
  newton["increments"] = c.increments;
  newton["cuts"] = c.cuts;
  newton["iterations"] = c.iterations;
  newton["iterations_max"] = static_cast<long>(c.iterations_max);
  newton["iterations_per_increment"] =
      c.increments > 0 ? static_cast<double>(c.iterations) / static_cast<double>(c.increments)
                       : 0.0;
  newton["factorisations"] = c.factorisations;
  newton["line_search_halvings"] = c.line_search_halvings;
  newton["increment_min"] = c.increment_min;
  newton["increment_max"] = c.increment_max;
  newton["active_set_passes"] = c.active_set_passes;
  newton["releases"] = c.releases;
  newton["attachments"] = c.attachments;
  newton["constrained_nodes_max"] = c.constrained_nodes_max;
  newton["snaps"] = c.snaps;
  newton["snap_first_time"] = c.snaps > 0 ? Json(c.snap_first_time) : Json();
  newton["snap_worst_area_ratio"] = c.snaps > 0 ? Json(c.snap_worst_ratio) : Json();
  newton["load_drop"] = setup_.implicit.load_drop;
  newton["load_drop_cuts"] = c.load_drop_cuts;
  newton["load_drops_accepted"] = c.load_drops_accepted;
  newton["tolerance"] = setup_.implicit.tolerance;
  newton["displacement_tolerance"] = setup_.implicit.displacement_tolerance;
  newton["residual_scale"] =
      "max(|F_ext|, |reaction|, |inertia|) of the iterate, the reaction and the inertia at most "
      "10 times the largest of the three at the attempt's first evaluation";
  newton["increment_stabilisation"] = setup_.implicit.increment_stabilisation;
  Json history = Json::array();
  for (const std::vector<double>& r : c.residual_history) history.push_back(Json::array(r));
  newton["residual_history"] = history;
  Json j = Json::object();
  j["newton"] = newton;
  j["remeshes"] = m.remeshes;
  j["forced_remeshes"] = m.forced_remeshes;
  j["remesh"] = to_string(setup_.options.remesh);
  j["triangles"] = static_cast<long>(m.triangles);
  j["surface_nodes"] = static_cast<long>(m.surface_nodes);
  j["components"] = static_cast<long>(m.components);
  j["isolated_nodes_max"] = static_cast<long>(m.isolated_nodes_max);
  j["short_edge_triangles_max"] = static_cast<long>(m.short_edge_triangles_max);
  j["smallest_angle"] = m.smallest_angle;
  j["wall_strip_edges"] = static_cast<long>(discretisation_.wall_strips().edges.size());
  return j;
}

}  // namespace duet::spfem

namespace duet::spfem {

void ImplicitSolver::save_state(StateBag& state) const {
  put_integers(state, "solver.released", released_);
  put_bits(state, "solver.rigid_contact", held_by_);  // the key predates walls holding
  put(state, "solver.previous_u", previous_u_);
  put(state, "solver.acceleration", acceleration_);
  put(state, "solver.boundary_force", boundary_force_);
  put(state, "solver.scalars",
      std::vector<double>{held_initialised_ ? 1.0 : 0.0, dynamic_started_ ? 1.0 : 0.0,
                          previous_increment_, increment_});
  const NewtonCounters& c = counters_;
  put(state, "solver.counters",
      std::vector<double>{
          double(c.increments), double(c.cuts), double(c.iterations), double(c.iterations_max),
          double(c.active_set_passes), double(c.releases), double(c.attachments),
          double(c.factorisations), double(c.line_search_halvings), c.increment_min,
          c.increment_max, double(c.constrained_nodes_max), double(c.snaps), c.snap_first_time,
          c.snap_worst_ratio, double(c.load_drop_cuts), double(c.load_drops_accepted)});
  put(state, "solver.load_peak", load_peak_);
  put_lists(state, "solver.residual_history", c.residual_history);
  discretisation_.save_state(state, "solver.mesh_counters");
}

void ImplicitSolver::restore_state(const StateBag& state, std::size_t nodes) {
  const auto sized = [&](const std::string& key, std::size_t size) {
    if (entry(state, key).size() != size) {
      throw std::runtime_error("the saved state's '" + key + "' is not of this scene's " +
                               std::to_string(nodes) + " nodes");
    }
  };
  sized("solver.released", nodes);
  sized("solver.rigid_contact", 2 * nodes);
  sized("solver.previous_u", 2 * nodes);
  sized("solver.acceleration", 2 * nodes);
  sized("solver.boundary_force", 2 * boundary_force_.size());
  sized("solver.scalars", 4);
  // A frame written before spfem.implicit.load_drop has 15 counters and no peaks: it resumes
  // with both at zero
  const bool before_load_drop = entry(state, "solver.counters").size() == 15;
  if (!before_load_drop) {
    sized("solver.counters", 17);
    sized("solver.load_peak", load_peak_.size());
  }
  get_integers(state, "solver.released", released_);
  get_bits(state, "solver.rigid_contact", held_by_);
  get(state, "solver.previous_u", previous_u_);
  get(state, "solver.acceleration", acceleration_);
  get(state, "solver.boundary_force", boundary_force_);
  const std::vector<double>& v = entry(state, "solver.scalars");
  held_initialised_ = v[0] != 0.0;
  dynamic_started_ = v[1] != 0.0;
  previous_increment_ = v[2];
  increment_ = v[3];
  const std::vector<double>& k = entry(state, "solver.counters");
  NewtonCounters& c = counters_;
  c.increments = static_cast<long>(k[0]);
  c.cuts = static_cast<long>(k[1]);
  c.iterations = static_cast<long>(k[2]);
  c.iterations_max = static_cast<int>(k[3]);
  c.active_set_passes = static_cast<long>(k[4]);
  c.releases = static_cast<long>(k[5]);
  c.attachments = static_cast<long>(k[6]);
  c.factorisations = static_cast<long>(k[7]);
  c.line_search_halvings = static_cast<long>(k[8]);
  c.increment_min = k[9];
  c.increment_max = k[10];
  c.constrained_nodes_max = static_cast<long>(k[11]);
  c.snaps = static_cast<long>(k[12]);
  c.snap_first_time = k[13];
  c.snap_worst_ratio = k[14];
  if (before_load_drop) {
    std::fill(load_peak_.begin(), load_peak_.end(), 0.0);
  } else {
    c.load_drop_cuts = static_cast<long>(k[15]);
    c.load_drops_accepted = static_cast<long>(k[16]);
    get(state, "solver.load_peak", load_peak_);
  }
  get_lists(state, "solver.residual_history", c.residual_history);
  discretisation_.restore_state(state, "solver.mesh_counters", nodes);
}

}  // namespace duet::spfem
