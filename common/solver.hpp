#pragma once
// The interface a method (SPH, explicit SPFEM, implicit SPFEM) implements, and the registry that
// names them. The driver (common/driver.hpp) owns the loop, the output and failure handling; a
// solver only advances the particle state and reports the forces on walls and rigid bodies.

#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "common/frame_geometry.hpp"
#include "common/json.hpp"
#include "common/particles.hpp"
#include "common/state_bag.hpp"
#include "common/tensor.hpp"
#include "common/timers.hpp"

namespace duet {

struct Scene;

/// Force that the soil exerts on a wall or a rigid body (N per metre of thickness), by name.
struct Reaction {
  std::string name;
  Vec2 force = Vec2::Zero();
};

/// A numerical failure detected inside a solver step (Newton not converging after its step cuts,
/// an inverted mesh cell, ...). The driver stops cleanly, keeps the frames and reports it.
class NumericalFailure : public std::runtime_error {
 public:
  NumericalFailure(const std::string& reason, long particle = -1)
      : std::runtime_error(reason), particle_(particle) {}
  long particle() const { return particle_; }

 private:
  long particle_;
};

class Solver {
 public:
  virtual ~Solver() = default;

  /// Set up from the scene and the sampled particles (walls, dummy particles, mesh, initial state).
  /// The driver has already sampled the particles, set their internal variables to the models'
  /// initial values and applied a geostatic initial stress when the scene asks for one.
  virtual void initialise(const Scene& scene, Particles& particles) = 0;

  /// Advance one step from `time`; returns the time step taken (s). Throws NumericalFailure.
  virtual double step(const Scene& scene, Particles& particles, double time) = 0;

  /// Current reaction on every wall and rigid body of the scene.
  virtual std::vector<Reaction> reactions() const = 0;

  /// Per-phase wall time so far (neighbours, constitutive, forces, mesh, solve, ...).
  virtual const Timers& timers() const = 0;

  /// The triangle mesh in use (rows of `particles`, the state the solver advances), for the
  /// frames; null without one (SPH).
  virtual const std::vector<MeshTriangle>* mesh_triangles(const Particles& /*particles*/) {
    return nullptr;
  }

  /// Method-specific counters for metrics.json (penetrations, remeshes, Newton iterations, ...).
  virtual Json diagnostics() const { return Json::object(); }

  /// false: this run solves for equilibrium (ispfem quasi-static): its velocities are increments
  /// over a load step, not inertia, so the kinetic-energy checks and warnings do not apply.
  virtual bool inertial() const { return true; }

  /// `duet run --resume`: empty when this solver can write into each frame all it carries from
  /// one step to the next, else why not (the run is then refused before any work).
  virtual std::string resume_refusal() const {
    return "this method does not save its state in the frames";
  }
  /// What this solver carries from one step to the next (keys "solver.*"), after a step.
  virtual void save_state(StateBag& /*state*/) const {}
  /// Restores save_state's entries on a solver initialised on the same scene, `particles` as the
  /// frame holds them: the run then goes on as if it had never stopped. Throws std::runtime_error
  /// when an entry is missing or does not fit.
  virtual void restore_state(const StateBag& /*state*/, const Particles& /*particles*/) {}
  /// Called after each frame that holds the state, and after restore_state: from here both the
  /// run that goes on and a run resumed from that frame must take the same steps (the explicit
  /// solver builds its next mesh anew, as a resumed run must).
  virtual void restart_point() {}
};

struct MethodInfo {
  std::string name;     // "sph", "espfem", "ispfem"
  std::string summary;  // one line
  std::function<std::unique_ptr<Solver>(const Scene&)> make;
  // false: quasi-static (ispfem): it has nothing to say on a dynamic scene (a collapse)
  bool dynamic = true;
  // Peak memory per particle, measured (benchmarks/RESULTS.md "Reliability"): what `duet run`
  // refuses a scene by before any work when it would not fit in the machine's memory.
  double bytes_per_particle = 2048.0;
  // The scene tables whose keys it reads (`duet methods`, `duet keys SECTION`).
  std::vector<std::string> option_sections;
};

class MethodRegistry {
 public:
  void add(MethodInfo info) { methods_.push_back(std::move(info)); }
  /// Throws InputError naming the registered methods when `name` is not one of them.
  const MethodInfo& find(const std::string& name) const;
  std::vector<std::string> names() const;
  bool empty() const { return methods_.empty(); }

 private:
  std::vector<MethodInfo> methods_;
};

}  // namespace duet
