#include "spfem/method.hpp"

#include <algorithm>
#include <memory>

#include "common/geometry.hpp"
#include "common/input_error.hpp"
#include "common/scene.hpp"
#include "common/scene_loads.hpp"
#include "constitutive/registry.hpp"
#include "spfem/explicit_solver.hpp"

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

EspfemSetup make_setup(const Scene& scene) {
  EspfemSetup setup;
  setup.options = scene.spfem;
  setup.spacing = scene.spacing;
  setup.gravity = scene.gravity;
  for (const Material& m : scene.materials) {
    setup.models.push_back(constitutive::make_model(m.model, m.parameters, "material." + m.name));
  }
  for (const Wall& w : scene.walls) {
    NodeBoundary b;
    b.name = w.name;
    b.polyline = w.points;
    // A no-slip wall holds its nodes (a clamp carries tension); a free-slip wall is a unilateral
    // smooth contact.
    b.condition =
        w.condition == WallCondition::no_slip ? NodeCondition::bonded : NodeCondition::smooth;
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

class EspfemMethod final : public Solver {
 public:
  explicit EspfemMethod(const Scene& scene) : solver_(make_setup(scene)) {}

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
    return solver_.step(particles, time);
  }

  std::vector<Reaction> reactions() const override {
    std::vector<Reaction> out;
    for (std::size_t b = 0; b < solver_.boundaries().size(); ++b) {
      out.push_back({solver_.boundaries()[b].name, solver_.boundary_forces()[b]});
    }
    return out;
  }

  const Timers& timers() const override { return solver_.timers(); }

  Json diagnostics() const override { return solver_.diagnostics(); }

 private:
  ExplicitSolver solver_;
  LoadedParticles loaded_;
};

}  // namespace

void register_espfem(MethodRegistry& registry) {
  registry.add({"espfem",
                "explicit smoothed particle finite element method (Yuan et al. 2019; papers/004)",
                [](const Scene& scene) { return std::make_unique<EspfemMethod>(scene); }});
}

}  // namespace duet::spfem
