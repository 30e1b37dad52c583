#include "sph/method.hpp"

#include <memory>
#include <optional>

#include "common/geometry.hpp"
#include "common/input_error.hpp"
#include "common/scene.hpp"
#include "common/scene_loads.hpp"
#include "common/strength_reduction.hpp"
#include "constitutive/scene_models.hpp"
#include "sph/sph_solver.hpp"

namespace duet::sph {

namespace {

WallVelocity wall_velocity(const Wall& wall) {
  if (wall.radial) {
    // Radial wall (cavity): every point moves away from the centre at the scheduled speed.
    return [schedule = wall.radial_velocity, centre = wall.centre](double t, const Vec2& x) {
      const Vec2 r = x - centre;
      const double d = r.norm();
      return d > 0.0 ? Vec2(schedule_value(schedule, t).x() / d * r) : Vec2(Vec2::Zero());
    };
  }
  if (wall.velocity.empty()) return {};
  return [schedule = wall.velocity](double t, const Vec2&) { return schedule_value(schedule, t); };
}

SphSetup make_setup(const Scene& scene) {
  if (scene.formulation == Formulation::axisymmetric) {
    throw InputError(
        "formulation = \"axisymmetric\": the SPH solver is plane strain only; run "
        "this scene through espfem or ispfem");
  }
  if (scene.sph.wall_treatment != "dummy") {
    throw InputError("sph.wall_treatment = \"" + scene.sph.wall_treatment +
                     "\": the SPH solver implements \"dummy\" only");
  }
  SphSetup setup;
  setup.options = scene.sph;
  setup.spacing = scene.spacing;
  setup.gravity = scene.gravity;
  setup.models = constitutive::make_scene_models(scene, loading_strength_factor(scene));
  for (const Wall& w : scene.walls) {
    // A symmetry plane is a free-slip wall to SPH: its ghost particles mirror the material.
    const WallCondition condition =
        w.condition == WallCondition::symmetry ? WallCondition::free_slip : w.condition;
    setup.walls.push_back(
        {w.name, w.points, condition, wall_velocity(w), w.condition == WallCondition::symmetry});
  }
  for (const RigidBody& b : scene.rigid_bodies) {
    WallVelocity velocity;
    if (!b.velocity.empty()) {
      velocity = [schedule = b.velocity](double t, const Vec2&) {
        return schedule_value(schedule, t);
      };
    }
    if (b.surface == Surface::friction) {
      // simhypo-sand eqs 39-40 (sph/rigid_contact.hpp): the penalty stiffness 2 m / dt^2 is
      // stable with the leapfrog update only (Verlet's velocity leap over 2 dt amplifies it).
      if (scene.sph.integrator != SphIntegrator::leapfrog) {
        throw InputError("rigid_body." + b.name +
                         ".surface = \"friction\": the frictional contact (simhypo-sand eqs "
                         "39-40) needs sph.integrator = \"leapfrog\" (the three-level verlet "
                         "scheme is unstable with its penalty stiffness 2 m / dt^2)");
      }
      setup.frictional_bodies.push_back({b.name, b.outline, std::move(velocity), b.friction});
      continue;
    }
    // A rigid body with prescribed motion: its closed outline as a wall, rough = dummy particles
    // (no slip), smooth = ghost particles (free slip).
    std::vector<Vec2> outline = b.outline;
    outline.push_back(outline.front());
    setup.walls.push_back(
        {b.name, std::move(outline),
         b.surface == Surface::smooth ? WallCondition::free_slip : WallCondition::no_slip,
         std::move(velocity)});
  }
  return setup;
}

class SphMethod final : public Solver {
 public:
  explicit SphMethod(const Scene& scene) : solver_(make_setup(scene)), strength_(scene) {}

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
    std::vector<Reaction> out;
    for (std::size_t w = 0; w < solver_.walls().size(); ++w) {
      out.push_back({solver_.walls()[w].name, solver_.wall_forces()[w]});
    }
    const RigidContact& contact = solver_.rigid_contact();
    for (std::size_t b = 0; b < contact.bodies.size(); ++b) {
      out.push_back({contact.bodies[b].name, contact.reaction[b]});
    }
    return out;
  }

  const Timers& timers() const override { return solver_.timers(); }

  Json diagnostics() const override {
    const SphCounters& c = solver_.counters();
    Json j = Json::object();
    j["kernel"] = kernel_name(solver_.kernel().kind());
    j["smoothing_length"] = solver_.kernel().smoothing_length();
    j["dummy_particles"] = static_cast<long>(c.dummy_particles);
    j["ghost_particles_max"] = static_cast<long>(c.ghost_particles_max);
    j["neighbours_max"] = static_cast<long>(c.neighbours_max);
    j["neighbour_builds"] = c.neighbour_builds;
    j["penetrations_max"] = c.penetrations_max;
    j["penetrations_total"] = c.penetrations_total;
    j["penetrations_last_step"] = c.penetrations_last_step;
    j["symmetry_reflections"] = c.symmetry_reflections;
    j["rigid_contacts_last_step"] = solver_.rigid_contact().contacts;
    j["dt_min"] = c.dt_min;
    j["dt_max"] = c.dt_max;
    j["steps"] = c.steps;
    return j;
  }

  std::string resume_refusal() const override { return ""; }
  void save_state(StateBag& state) const override { solver_.save_state(state); }
  void restore_state(const StateBag& state, const Particles& /*particles*/) override {
    solver_.restore_state(state);
  }
  void restart_point() override { solver_.restart_point(); }

 private:
  SphSolver solver_;
  LoadedParticles loaded_;
  constitutive::StrengthInRun strength_;
};

}  // namespace

void register_sph(MethodRegistry& registry) {
  registry.add({"sph",
                "smoothed particle hydrodynamics for soils (Peng et al. 2015; Bui et al. 2008)",
                [](const Scene& scene) { return std::make_unique<SphMethod>(scene); },
                /*dynamic=*/true,
                /*bytes_per_particle=*/2048.0,
                /*option_sections=*/{"sph"}});
}

}  // namespace duet::sph
