#include "benchmarks/run_warnings.hpp"

#include <cstdio>

#include "common/geometry.hpp"

namespace duet {

namespace {

bool driven_at(const Scene& scene, double time) {
  if (!scene.loads.empty()) return true;
  for (const Wall& w : scene.walls) {
    if (w.radial || schedule_value(w.velocity, time) != Vec2::Zero()) return true;
  }
  for (const RigidBody& rb : scene.rigid_bodies) {
    if (schedule_value(rb.velocity, time) != Vec2::Zero()) return true;
  }
  return false;
}

}  // namespace

std::vector<std::string> run_warnings(const Scene& scene, const MethodInfo& method,
                                      const KineticEnergyRecord& energy, const EnergyBudget& budget,
                                      double end_time) {
  std::vector<std::string> out;
  char text[400];
  const bool settling =
      method.dynamic && scene.gravity != Vec2::Zero() && !driven_at(scene, end_time);
  // Both relative to the peak and to the energy put in: a slope creeping from rest has its peak
  // at the end, at a millionth of the work of gravity.
  if (settling && energy.end_over_peak() > 1e-3 && energy.end > 1e-4 * budget.input()) {
    std::snprintf(text, sizeof text,
                  "not at rest: the kinetic energy at t = %g s is %.2g of its peak (at t = %g s); "
                  "measures of the final state (a deposit's run-out and height) may still move. "
                  "Try a longer time.end_time, or more damping",
                  end_time, energy.end_over_peak(), energy.peak_time);
    out.emplace_back(text);
  }
  if (method.dynamic && !budget.incomplete() && budget.peak_ratio() > 1.2) {
    std::snprintf(text, sizeof text,
                  "the kinetic energy reached %.3g times the energy put in (near t = %g s; the run "
                  "fails at checks.kinetic_energy_factor = %g): look at the frames there for "
                  "particles thrown off a wall or a rigid body",
                  budget.peak_ratio(), budget.peak_ratio_time(),
                  scene.checks.kinetic_energy_factor);
    out.emplace_back(text);
  }
  return out;
}

}  // namespace duet
