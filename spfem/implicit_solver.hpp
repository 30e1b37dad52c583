#pragma once
// The implicit SPFEM (Zhang 2018 slides, "Implicit SPFEM" and "Numerical procedure of iSPFEM";
// Zhang et al. 2018): updated Lagrangian and quasi-static. Per
// increment of the scene's time [t_n, t_n+1]: (re)mesh the nodes at their configuration x_n
// (NodalDiscretisation, shared with the explicit solver), collect the walls and rigid bodies the
// nodes touch as constraints (node_constraints.hpp: prescribed by the boundaries' motion over the
// increment, eliminated from the unknowns), then Newton-Raphson on R(u) = F_ext(t_n+1) -
// F_int(u) with the exact tangent of IncrementOperator, solved by UMFPACK (the tangent is not
// symmetric). The stress is committed only when the increment converges. A contact whose
// reaction turns tensile is released, a node that crosses a boundary is attached, and the
// increment is solved again (the active set, a few passes). Newton failures halve the increment
// (up to max_step_cuts in a row); then the run fails as data. This class knows nothing of the
// scene file: spfem/method.cpp translates a Scene into an IspfemSetup. Its layers: the increment
// controller (step, settle), the increment (solve_increment: contacts, Newton, active set,
// acceptance, commit), Newton itself (newton_increment.hpp) and the integrator (newmark.hpp).

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/json.hpp"
#include "common/particles.hpp"
#include "common/scene.hpp"
#include "common/tensor.hpp"
#include "common/timers.hpp"
#include "constitutive/model.hpp"
#include "spfem/newmark.hpp"
#include "spfem/nodal_discretisation.hpp"
#include "spfem/node_constraints.hpp"
#include "spfem/node_contact.hpp"

namespace duet::spfem {

class IncrementOperator;

struct IspfemSetup {
  duet::SpfemOptions options;           // [spfem]: the shared discretisation's options
  duet::SpfemImplicitOptions implicit;  // [spfem.implicit]
  double spacing = 0.0;                 // dp, m
  Vec2 gravity = Vec2::Zero();          // m/s^2
  std::vector<std::unique_ptr<constitutive::Model>> models;  // by material index
  std::vector<NodeBoundary> boundaries;                      // walls, then rigid bodies
  bool axisymmetric = false;  // x = r about the axis x = 0 (Scene::formulation)
  // No material can soften and no strength reduction runs: a driven load does not fall
  // (spfem.implicit.load_drop)
  bool monotonic = false;
};

struct NewtonCounters {
  long increments = 0;         // converged increments
  long cuts = 0;               // increments halved after Newton failed
  long iterations = 0;         // Newton iterations (linear solves), all attempts
  int iterations_max = 0;      // most iterations of a converged increment
  long active_set_passes = 0;  // increments solved again because the contacts changed
  long releases = 0;           // contacts released (tensile reaction)
  long attachments = 0;        // nodes attached after crossing a boundary
  long factorisations = 0;
  long line_search_halvings = 0;
  double increment_min = 0.0;  // s
  double increment_max = 0.0;  // s
  long constrained_nodes_max = 0;
  long snaps = 0;                 // increments that squeezed a triangle below min_area_ratio
  double snap_first_time = 0.0;   // s, the first one's end
  double snap_worst_ratio = 1.0;  // the smallest area ratio among them (< 0: inside out)
  long load_drop_cuts = 0;        // converged increments refused for a load drop, then cut
  long load_drops_accepted = 0;   // drops kept when the cuts ran out
  // The relative residual after each iteration, one list per converged increment.
  std::vector<std::vector<double>> residual_history;
};

class ImplicitSolver {
 public:
  explicit ImplicitSolver(IspfemSetup setup);

  /// Orients the boundaries and sizes the buffers. Particles must have position, mass, volume,
  /// density, stress, material and internal variables set.
  void initialise(Particles& particles);

  /// External nodal forces at a time (N/m per node; scene loads), filled into the vector.
  using LoadFunction = std::function<void(double time, std::vector<Vec2>& force)>;
  void set_loads(LoadFunction loads) { loads_ = std::move(loads); }

  /// The material models in effect at a time (a strength reduced during the run:
  /// common/strength_reduction.hpp), asked for each increment's end time; null: the setup's.
  using Models = std::vector<std::unique_ptr<constitutive::Model>>;
  using ModelsFunction = std::function<const Models*(double time)>;
  void set_models(ModelsFunction models) { models_at_ = std::move(models); }

  /// One converged increment from `time`, no further than `end_time`; returns its size (s).
  /// Throws NumericalFailure when Newton fails after max_step_cuts halvings.
  double step(Particles& particles, double time, double end_time);

  /// Gravity loading: gravity ramped up over `increments` increments with the walls held, then
  /// displacements and strains zeroed.
  void settle(Particles& particles, int increments);

  const std::vector<Vec2>& boundary_forces() const { return boundary_force_; }
  const std::vector<NodeBoundary>& boundaries() const { return discretisation_.boundaries(); }
  const NodalDiscretisation& discretisation() const { return discretisation_; }
  const Timers& timers() const { return timers_; }
  const NewtonCounters& counters() const { return counters_; }
  Json diagnostics() const;

  /// `duet run --resume` (common/solver.hpp): what an increment carries to the next (its size,
  /// the contacts held and let go, the predictor's and Newmark's vectors, the counters, the walls'
  /// attachments and a kept mesh), keys "solver.*"; a frame is a restart point
  /// (NodalDiscretisation::restart_point).
  void save_state(StateBag& state) const;
  void restore_state(const StateBag& state, std::size_t nodes);
  void restart_point() { discretisation_.restart_point(); }

 private:
  struct Attempt {
    bool converged = false;
    std::string why;                 // when not converged
    std::vector<double> residuals;   // relative residual after each iteration
    std::vector<Vec2> displacement;  // u over the increment
  };
  /// One increment [t0, t1]: mesh, contacts, Newton, the active set's passes, the acceptance
  /// checks, and the commit of a converged and accepted one.
  /// `may_cut`: the increment may still be halved (a load drop refuses it only then).
  Attempt solve_increment(Particles& particles, double t0, double t1, bool may_cut = false);
  /// The contacts at the increment's start (and the nodes still let go of).
  std::vector<NodeConstraint> start_contacts(const Particles& particles, double t0, double t1);
  /// F_ext at t1 into external_force_; returns its norm.
  double update_external_force(const Particles& particles, double t1);
  /// The wall strips' wall points' motion over the increment (two per edge).
  std::vector<Vec2> wall_strip_increments(double t0, double t1) const;
  /// Throws NumericalFailure when nothing holds the body and no inertia does either.
  void refuse_if_unheld(const DofMap& dofs, const std::vector<std::uint8_t>& held, bool inertia,
                        double t0);
  /// Newton's start: the prescribed motion, and a guess on the free dofs.
  std::vector<Vec2> initial_guess(const DofMap& dofs, const NewmarkIncrement& integrator,
                                  double dt) const;
  /// The active set's release: the constraints kept after letting go of a rigid body's nodes
  /// whose neighbourhood pulls (fewer than given: some were let go).
  std::vector<NodeConstraint> release_pulling_contacts(
      const Particles& particles, const IncrementOperator& op,
      const std::vector<NodeConstraint>& constraints);
  /// The active set's attachment: nodes whose path crosses a boundary join `kept`; true if any.
  bool attach_crossing_nodes(const Particles& particles, const std::vector<Vec2>& u,
                             const std::vector<std::uint8_t>& held, double t0, double t1,
                             std::vector<NodeConstraint>& kept);
  /// Why a converged increment is not accepted (a node through a wall, a refused snap), or "";
  /// counts the snaps it lets through.
  std::string refusal(const Particles& particles, const std::vector<Vec2>& u, double t0, double t1);
  /// Per boundary, the force the soil puts on it at the converged increment: the residual at the
  /// constrained parts, to the boundary that holds each node, plus the wall strips'.
  std::vector<Vec2> reactions(const IncrementOperator& op, const NewmarkIncrement& integrator,
                              const std::vector<Vec2>& u,
                              const std::vector<NodeConstraint>& constraints) const;
  /// Why a converged quasi-static increment with these reactions at t1 is refused for a load
  /// drop (spfem.implicit.load_drop; "" when it is not, or `may_cut` is false: then a drop is
  /// kept, counted, and its load becomes the boundary's peak).
  std::string load_drop(const std::vector<Vec2>& force, double t1, bool may_cut);
  /// A driven boundary's load at t: -F . v / |v| for a translating one, |F| for a radial wall;
  /// NaN when it does not move at t.
  double driven_load(std::size_t boundary, const Vec2& force, double t) const;
  /// The converged state into the particles; reactions, contacts held and Newmark's vectors.
  void commit(Particles& particles, const IncrementOperator& op, const NewmarkIncrement& integrator,
              const std::vector<Vec2>& u, const std::vector<NodeConstraint>& constraints,
              std::vector<Vec2> force, double t1);
  std::vector<NodeConstraint> find_constraints(const std::vector<Vec2>& x, double t0, double t1,
                                               bool crossed_only) const;
  /// The first node whose path x -> x + u crosses a wall (in the frame of a translating wall),
  /// described; "" when none does.
  std::string wall_crossing(const std::vector<Vec2>& x, const std::vector<Vec2>& u, double t0,
                            double t1);
  /// The fair-sized triangle of the increment's mesh whose area x -> x + u shrinks most
  /// (ratio 1 and no triangle when none shrinks).
  struct SqueezedTriangle {
    double ratio = 1.0;  // area at the end over area at the start; <= 0: inside out
    Triangle triangle{};
    Vec2 at = Vec2::Zero();
    std::string describe(double floor) const;
  };
  SqueezedTriangle most_squeezed_triangle(const std::vector<Vec2>& x,
                                          const std::vector<Vec2>& u) const;

  IspfemSetup setup_;
  NodalDiscretisation discretisation_;
  LoadFunction loads_;
  ModelsFunction models_at_;
  double gravity_factor_ = 1.0;  // < 1 while gravity is ramped up (settle)
  bool settling_ = false;
  std::vector<std::uint8_t> released_;  // per node: let go of a tensile contact, until it leaves
  std::vector<std::uint64_t> held_by_;  // per node: bit b = held by boundary b (mod 64)
  bool held_initialised_ = false;       // false: the first increment takes every rigid touch
  std::vector<Vec2> previous_u_;        // the last increment's displacement (predictor)
  std::vector<Vec2> acceleration_;      // Newmark: a_n per node
  bool dynamic_started_ = false;        // Newmark: a_0 set
  double previous_increment_ = 0.0;
  double increment_ = 0.0;  // the current (adaptive) increment size
  std::vector<Vec2> external_force_;
  std::vector<Vec2> boundary_force_;
  std::vector<double>
      load_peak_;  // per boundary: its driven load's peak (spfem.implicit.load_drop)
  Timers timers_;
  NewtonCounters counters_;
};

}  // namespace duet::spfem
