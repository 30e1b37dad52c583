#include "spfem/method.hpp"

#include <algorithm>
#include <memory>

#include "common/geometry.hpp"
#include "common/input_error.hpp"
#include "common/scene.hpp"
#include "common/scene_loads.hpp"
#include "common/standing_faces.hpp"
#include "common/strength_reduction.hpp"
#include "constitutive/scene_models.hpp"
#include "spfem/explicit_solver.hpp"
#include "spfem/implicit_solver.hpp"

namespace duet::spfem {

namespace {

NodeCondition condition_of(Surface surface) {
  switch (surface) {
    case Surface::rough:
      return NodeCondition::rough;
    case Surface::smooth:
      return NodeCondition::smooth;
    case Surface::friction:
      return NodeCondition::friction;
  }
  return NodeCondition::rough;
}

/// The models and boundaries of the scene, as both SPFEM solvers see them.
template <typename Setup>
Setup make_setup(const Scene& scene) {
  Setup setup;
  setup.options = scene.spfem;
  setup.spacing = scene.spacing;
  setup.gravity = scene.gravity;
  setup.axisymmetric = scene.formulation == Formulation::axisymmetric;
  setup.models = constitutive::make_scene_models(scene, loading_strength_factor(scene));
  for (const Wall& w : scene.walls) {
    NodeBoundary b;
    b.name = w.name;
    b.polyline = w.points;
    // A no-slip wall holds its nodes (a clamp carries tension); a free-slip wall is a unilateral
    // smooth contact; a symmetry plane holds the normal motion both ways.
    b.condition = w.condition == WallCondition::no_slip    ? NodeCondition::bonded
                  : w.condition == WallCondition::symmetry ? NodeCondition::symmetry
                                                           : NodeCondition::smooth;
    b.velocity = w.velocity;
    b.radial = w.radial;
    b.centre = w.centre;
    b.radial_velocity = w.radial_velocity;
    setup.boundaries.push_back(std::move(b));
  }
  for (const RigidBody& r : scene.rigid_bodies) {
    // A rigid body with prescribed motion: its closed outline, node-to-segment contact.
    NodeBoundary b;
    b.name = r.name;
    b.polyline = r.outline;
    make_counter_clockwise(b.polyline);
    b.polyline.push_back(b.polyline.front());
    b.rigid_body = true;
    b.condition = condition_of(r.surface);
    b.friction = r.friction;
    b.velocity = r.velocity;
    setup.boundaries.push_back(std::move(b));
  }
  return setup;
}

IspfemSetup make_implicit_setup(const Scene& scene) {
  // Quasi-static: a body set moving cannot be honoured, and a run would "complete" standing
  // still (bar.toml: period NaN)
  for (const Body& b : scene.bodies) {
    if (b.initial_velocity.squaredNorm() > 0.0 && !scene.spfem_implicit.newmark) {
      throw InputError("body." + b.name +
                       ".initial_velocity: ispfem is quasi-static by default and cannot start a "
                       "body moving; set spfem.implicit.dynamics = \"newmark\" for inertia");
    }
  }
  if (!scene.spfem_implicit.newmark) {
    const std::string steep = face_steeper_than_friction(scene);
    if (!steep.empty()) {
      throw InputError(steep +
                       "; ispfem is quasi-static by default: run sph or espfem, or set "
                       "spfem.implicit.dynamics = \"newmark\" for inertia");
    }
  }
  IspfemSetup setup = make_setup<IspfemSetup>(scene);
  setup.implicit = scene.spfem_implicit;
  setup.monotonic = constitutive::cannot_soften(scene);
  return setup;
}

std::vector<Reaction> named_reactions(const std::vector<NodeBoundary>& boundaries,
                                      const std::vector<Vec2>& forces) {
  std::vector<Reaction> out;
  for (std::size_t b = 0; b < boundaries.size(); ++b)
    out.push_back({boundaries[b].name, forces[b]});
  return out;
}

/// The mesh of the last step, or before the first step the one it will build (a frame at t = 0).
const std::vector<MeshTriangle>* mesh_in_use(const NodalDiscretisation& discretisation,
                                             const Particles& particles, AlphaMesh& preview) {
  if (!discretisation.mesh().triangles.empty()) return &discretisation.mesh().triangles;
  const SpfemOptions& o = discretisation.options();
  build_alpha_mesh(particles.position, o.alpha_factor * discretisation.spacing(), preview, false,
                   o.min_edge_factor * discretisation.spacing());
  return &preview.triangles;
}

class EspfemMethod final : public Solver {
 public:
  explicit EspfemMethod(const Scene& scene)
      : solver_(make_setup<EspfemSetup>(scene)), strength_(scene) {}

  void initialise(const Scene& scene, Particles& particles) override {
    solver_.initialise(particles);
    loaded_ = loaded_particles(scene, particles);
    if (scene.initial_stress.kind == InitialStressKind::gravity_loading) {
      apply_loads(scene, loaded_, 0.0, solver_.external_force());
      solver_.settle(particles, scene.initial_stress.time, scene.initial_stress.damping);
    }
  }

  double step(const Scene& scene, Particles& particles, double time) override {
    apply_loads(scene, loaded_, time, solver_.external_force());
    if (strength_.changes_at(scene, time)) solver_.use_models(strength_.models(scene));
    return solver_.step(particles, time);
  }

  std::vector<Reaction> reactions() const override {
    return named_reactions(solver_.boundaries(), solver_.boundary_forces());
  }

  const Timers& timers() const override { return solver_.timers(); }

  Json diagnostics() const override { return solver_.diagnostics(); }

  std::string resume_refusal() const override {
    return solver_.discretisation().options().wall_node_gap > 0.0
               ? "spfem.wall_node_gap adds nodes as the run goes, and a frame does not say "
                 "which nodes the run had added by then"
               : "";
  }
  void save_state(StateBag& state) const override { solver_.save_state(state); }
  void restore_state(const StateBag& state, const Particles& particles) override {
    solver_.restore_state(state, particles.size());
  }
  void restart_point() override { solver_.restart_point(); }

  const std::vector<MeshTriangle>* mesh_triangles(const Particles& particles) override {
    return mesh_in_use(solver_.discretisation(), particles, preview_);
  }

 private:
  ExplicitSolver solver_;
  AlphaMesh preview_;
  LoadedParticles loaded_;
  constitutive::StrengthInRun strength_;
};

/// The implicit SPFEM: one step of the driver is one converged increment.
class IspfemMethod final : public Solver {
 public:
  explicit IspfemMethod(const Scene& scene)
      : newmark_(scene.spfem_implicit.newmark),
        solver_(make_implicit_setup(scene)),
        strength_(scene) {}

  void initialise(const Scene& scene, Particles& particles) override {
    solver_.initialise(particles);
    loaded_ = loaded_particles(scene, particles);
    solver_.set_loads([this, &scene](double t, std::vector<Vec2>& force) {
      apply_loads(scene, loaded_, t, force);
    });
    if (scene.initial_stress.kind == InitialStressKind::gravity_loading) {
      solver_.settle(particles, kSettleIncrements);
    }
    // Peng's order: each increment at the strength of its end time (a cut increment also cuts
    // the fall of the strength it carries)
    if (strength_changes_in_run(scene)) {
      solver_.set_models([this, &scene](double t) {
        if (strength_.changes_at(scene, t)) models_ = strength_.models(scene);
        return models_.empty() ? nullptr : &models_;
      });
    }
  }

  double step(const Scene& scene, Particles& particles, double time) override {
    return solver_.step(particles, time, scene.time.end_time);
  }

  std::vector<Reaction> reactions() const override {
    return named_reactions(solver_.boundaries(), solver_.boundary_forces());
  }

  const Timers& timers() const override { return solver_.timers(); }

  Json diagnostics() const override { return solver_.diagnostics(); }

  bool inertial() const override { return newmark_; }

  std::string resume_refusal() const override { return ""; }
  void save_state(StateBag& state) const override { solver_.save_state(state); }
  void restore_state(const StateBag& state, const Particles& particles) override {
    solver_.restore_state(state, particles.size());
  }
  void restart_point() override { solver_.restart_point(); }

  const std::vector<MeshTriangle>* mesh_triangles(const Particles& particles) override {
    return mesh_in_use(solver_.discretisation(), particles, preview_);
  }

 private:
  bool newmark_ = false;
  // Gravity loading: gravity in this many equal increments to a static equilibrium
  static constexpr int kSettleIncrements = 10;
  ImplicitSolver solver_;
  LoadedParticles loaded_;
  AlphaMesh preview_;
  constitutive::StrengthInRun strength_;
  ImplicitSolver::Models models_;  // at strength_'s factor, once it has left the loading's
};

}  // namespace

void register_espfem(MethodRegistry& registry) {
  registry.add({"espfem",
                "explicit smoothed particle finite element method (Yuan et al. 2019; papers/004)",
                [](const Scene& scene) { return std::make_unique<EspfemMethod>(scene); },
                /*dynamic=*/true,
                /*bytes_per_particle=*/2048.0,
                /*option_sections=*/{"spfem"}});
}

void register_ispfem(MethodRegistry& registry) {
  registry.add({"ispfem",
                "implicit (Newton-Raphson) smoothed particle finite element method, quasi-static, "
                "or dynamic with spfem.implicit.dynamics = newmark (Zhang, Yuan & Dai 2018; "
                "papers/004)",
                [](const Scene& scene) { return std::make_unique<IspfemMethod>(scene); },
                /*dynamic=*/false,
                // the sparse tangent and its LU factors: 2.0 GB at 62,500 nodes (footing, dp 0.02)
                /*bytes_per_particle=*/32768.0,
                /*option_sections=*/{"spfem", "spfem.implicit"}});
}

}  // namespace duet::spfem
