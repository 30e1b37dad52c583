#include "benchmarks/run_warnings.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "common/geometry.hpp"
#include "common/units.hpp"

namespace duet {

namespace {

/// The fastest prescribed boundary speed at `time` (m/s): a translating wall's or rigid body's
/// speed, a radial wall's radial speed; 0 when nothing moves.
double fastest_driven_speed(const Scene& scene, double time) {
  double v = 0.0;
  for (const Wall& w : scene.walls) {
    v = std::max(v, w.radial ? std::abs(schedule_value(w.radial_velocity, time).x())
                             : schedule_value(w.velocity, time).norm());
  }
  for (const RigidBody& rb : scene.rigid_bodies) {
    v = std::max(v, schedule_value(rb.velocity, time).norm());
  }
  return v;
}

/// A load, a radial wall (at any speed) or a boundary moving at `time`.
bool driven_at(const Scene& scene, double time) {
  if (!scene.loads.empty()) return true;
  for (const Wall& w : scene.walls) {
    if (w.radial) return true;
  }
  return fastest_driven_speed(scene, time) > 0.0;
}

/// A number of the diagnostics at a dotted path ("newton.cuts"); NaN when absent.
double diagnostic(const Json& diagnostics, const std::string& path) {
  const Json* node = &diagnostics;
  std::size_t start = 0;
  while (node) {
    const std::size_t dot = path.find('.', start);
    node = node->is_object() ? node->find(path.substr(start, dot - start)) : nullptr;
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return node && node->is_number() ? node->number() : std::nan("");
}

/// Energy must be conserved: every material linear-elastic, nothing puts energy in or takes it
/// out (gravity, loads, moving walls or rigid bodies, damping).
bool conservative(const Scene& scene) {
  for (const Material& m : scene.materials) {
    if (m.model != "linear-elastic") return false;
  }
  if (scene.gravity != Vec2::Zero() || !scene.loads.empty()) return false;
  for (const Wall& w : scene.walls) {
    if (w.radial || !w.velocity.empty()) return false;
  }
  for (const RigidBody& rb : scene.rigid_bodies) {
    if (!rb.velocity.empty()) return false;
  }
  return scene.spfem.damping == 0.0 && scene.spfem.local_damping == 0.0;
}

void add_diagnostic_warnings(const Scene& scene, const Json& diagnostics, std::size_t particles,
                             std::vector<std::string>& out) {
  char text[400];
  const double n = static_cast<double>(particles);
  if (const double most = diagnostic(diagnostics, "penetrations_max"); most > 0.0) {
    std::snprintf(text, sizeof text,
                  "penetrations: up to %.0f particle%s (%.2g %%) inside a wall or rigid body at "
                  "once (%.0f at the last step, %.0f particle-steps in all); forces on those "
                  "boundaries are off. Try more sph.dummy_layers, a smaller sph.cfl or a finer "
                  "spacing",
                  most, most == 1.0 ? "" : "s", 100.0 * most / n,
                  diagnostic(diagnostics, "penetrations_last_step"),
                  diagnostic(diagnostics, "penetrations_total"));
    out.emplace_back(text);
  }
  if (const double isolated = diagnostic(diagnostics, "isolated_nodes_max"); isolated > 0.05 * n) {
    std::snprintf(text, sizeof text,
                  "isolated nodes: up to %.0f nodes (%.2g %%) belonged to no triangle of the mesh "
                  "at once; they move without stress. Try a larger spfem.alpha_factor (now %g)",
                  isolated, 100.0 * isolated / n, scene.spfem.alpha_factor);
    out.emplace_back(text);
  }
  if (const double drift = diagnostic(diagnostics, "energy_drift_max");
      drift > 0.02 && conservative(scene)) {
    std::snprintf(text, sizeof text,
                  "energy drift: the total energy of this conservative run drifted by up to %.3g "
                  "%% of its value after the first step. Try a smaller spfem.time_step_safety "
                  "(now %g)",
                  100.0 * drift, scene.spfem.time_step_safety);
    out.emplace_back(text);
  }
  const double limited = diagnostic(diagnostics, "stress_limited_steps");
  const double steps = diagnostic(diagnostics, "steps");
  if (limited > 0.1 * steps) {
    std::snprintf(
        text, sizeof text,
        "safeguard: %.0f of %.0f steps (%.0f %%) were shortened by "
        "spfem.stress_increment_limit = %g (a stiffening model near zero stress); the run "
        "took more steps than its critical step needs. Raising the limit is faster and "
        "less safe",
        limited, steps, 100.0 * limited / steps, scene.spfem.stress_increment_limit);
    out.emplace_back(text);
  }
  // ispfem: the increment halves when Newton fails, max_step_cuts times in a row before the run
  // fails; an increment within two halvings of that limit nearly ended the run.
  const double smallest = diagnostic(diagnostics, "newton.increment_min");
  const SpfemImplicitOptions& implicit = scene.spfem_implicit;
  const double nominal =
      implicit.increment > 0.0 ? implicit.increment : scene.time.end_time / implicit.load_steps;
  const double limit = nominal / std::ldexp(1.0, implicit.max_step_cuts);
  if (smallest < 4.0 * limit) {
    std::snprintf(text, sizeof text,
                  "safeguard: Newton needed increments down to %.3g s, 1/%.0f of the nominal %.3g "
                  "s, within two halvings of the %d that fail the run (%.0f halvings in all); "
                  "try more spfem.implicit.load_steps or a larger max_step_cuts",
                  smallest, nominal / smallest, nominal, implicit.max_step_cuts,
                  diagnostic(diagnostics, "newton.cuts"));
    out.emplace_back(text);
  }
  // ispfem: converged increments whose solution squeezed a triangle (spfem/implicit_solver.cpp):
  // the curve jumps there
  if (const double snaps = diagnostic(diagnostics, "newton.snaps"); snaps > 0.0) {
    std::snprintf(text, sizeof text,
                  "snap-through: %.0f converged increment%s squeezed a triangle of the mesh below "
                  "%g of its area or turned it inside out (worst area ratio %.3g), the first "
                  "ending at t = %.4g s: nodal integration's soft modes jumped, and measures may "
                  "jump with them. spfem.implicit.snap = \"refuse\" makes such an increment fail",
                  snaps, snaps == 1.0 ? "" : "s", implicit.min_area_ratio,
                  diagnostic(diagnostics, "newton.snap_worst_area_ratio"),
                  diagnostic(diagnostics, "newton.snap_first_time"));
    out.emplace_back(text);
  }
}

bool ever_moves(const Schedule& schedule) {
  for (const Knot& k : schedule) {
    if (k.value != Vec2::Zero()) return true;
  }
  return false;
}

void add_untouched_boundary_warnings(const Scene& scene,
                                     const std::map<std::string, double>& largest_reaction,
                                     std::vector<std::string>& out) {
  const auto untouched = [&](const std::string& name) {
    const auto it = largest_reaction.find(name);
    return it != largest_reaction.end() && it->second == 0.0;
  };
  for (const RigidBody& rb : scene.rigid_bodies) {
    if (ever_moves(rb.velocity) && untouched(rb.name)) {
      out.push_back("rigid_body." + rb.name +
                    " moved but carried no force at any step: it never touched the material, "
                    "and its reaction measures read 0. Check where it starts against what it "
                    "should push (a lattice's outer row lies dp/2 inside the drawn edge)");
    }
  }
  for (const Wall& w : scene.walls) {
    if ((w.radial ? ever_moves(w.radial_velocity) : ever_moves(w.velocity)) && untouched(w.name)) {
      out.push_back("wall." + w.name +
                    " moved but carried no force at any step: it never touched the material, "
                    "and its reaction measures read 0");
    }
  }
}

void add_load_drop_warnings(const Scene& scene, const std::vector<BoundaryLoad>& loads,
                            std::vector<std::string>& out) {
  if (!cannot_soften(scene)) return;
  for (const BoundaryLoad& b : loads) {
    const LoadDrop drop = largest_load_drop(b.time, b.load);
    if (drop.fraction <= 0.05) continue;
    char text[640];
    std::snprintf(text, sizeof text,
                  "load-drop: the load on %s fell %.0f %% below its maximum, from %.4g %s at t "
                  "= %.4g s to %.4g %s at t = %.4g s, while it was driven, though no material "
                  "of the scene can soften and no strength reduction runs: a perfectly plastic "
                  "load does not fall. Look at the frames there (a mesh snap, contact lost, a "
                  "dynamic overshoot); the measures after it are in doubt",
                  b.name.c_str(), 100.0 * drop.fraction, drop.peak, force_unit(scene.formulation),
                  drop.peak_time, drop.low, force_unit(scene.formulation), drop.low_time);
    out.emplace_back(text);
  }
}

/// A driven boundary that carried nothing until it had travelled more than a quarter spacing: it
/// started off the material (a gap a lattice misfit leaves under a footing drawn on the body's
/// edge), and the measures read 0 until then.
void add_late_contact_warnings(const Scene& scene, const std::vector<BoundaryLoad>& loads,
                               std::vector<std::string>& out) {
  for (const BoundaryLoad& b : loads) {
    std::size_t first = 0;
    while (first < b.load.size() && b.load[first] == 0.0) ++first;
    if (first == 0 || first == b.load.size()) continue;  // at once, or never (said elsewhere)
    const double t = b.time[first];
    Vec2 travel = Vec2::Zero();
    std::string key;
    for (const Wall& w : scene.walls) {
      if (w.name != b.name) continue;
      travel = schedule_integral(w.radial ? w.radial_velocity : w.velocity, t);
      key = "wall." + w.name;
    }
    for (const RigidBody& rb : scene.rigid_bodies) {
      if (rb.name != b.name) continue;
      travel = schedule_integral(rb.velocity, t);
      key = "rigid_body." + rb.name;
    }
    if (travel.norm() <= 0.25 * scene.spacing) continue;
    char text[480];
    std::snprintf(text, sizeof text,
                  "%s carried no force until t = %.4g s, after it had moved %.3g m: it started "
                  "off the material, and the measures read 0 until then (a body whose lattice "
                  "ends short of its drawn edge leaves such a gap: see the lattice warning)",
                  key.c_str(), t, travel.norm());
    out.emplace_back(text);
  }
}

/// The velocity of a wall or rigid body's schedule at t, and whether it is radial.
struct BoundaryMotion {
  Vec2 velocity = Vec2::Zero();
  double radial_speed = 0.0;
  bool radial = false;
};

std::optional<BoundaryMotion> motion_of(const Scene& scene, const std::string& name, double t) {
  for (const Wall& w : scene.walls) {
    if (w.name != name) continue;
    if (w.radial)
      return BoundaryMotion{Vec2::Zero(), schedule_value(w.radial_velocity, t).x(), true};
    return BoundaryMotion{schedule_value(w.velocity, t), 0.0, false};
  }
  for (const RigidBody& rb : scene.rigid_bodies) {
    if (rb.name == name) return BoundaryMotion{schedule_value(rb.velocity, t), 0.0, false};
  }
  return std::nullopt;
}

}  // namespace

std::vector<BoundaryLoad> driven_boundaries(const Scene& scene) {
  std::vector<BoundaryLoad> out;
  for (const Wall& w : scene.walls) {
    if (ever_moves(w.radial ? w.radial_velocity : w.velocity)) out.push_back({w.name, {}, {}});
  }
  for (const RigidBody& rb : scene.rigid_bodies) {
    if (ever_moves(rb.velocity)) out.push_back({rb.name, {}, {}});
  }
  return out;
}

void record_boundary_loads(const Scene& scene, double time, const std::vector<Reaction>& reactions,
                           std::vector<BoundaryLoad>& loads) {
  for (BoundaryLoad& b : loads) {
    const std::optional<BoundaryMotion> m = motion_of(scene, b.name, time);
    if (!m) continue;
    for (const Reaction& r : reactions) {
      if (r.name != b.name) continue;
      if (m->radial ? m->radial_speed == 0.0 : m->velocity == Vec2::Zero()) break;
      b.time.push_back(time);
      b.load.push_back(m->radial ? r.force.norm() : -r.force.dot(m->velocity.normalized()));
      break;
    }
  }
}

LoadDrop largest_load_drop(const std::vector<double>& time, const std::vector<double>& load) {
  LoadDrop worst;
  if (load.empty()) return worst;
  const double largest = *std::max_element(load.begin(), load.end());
  if (!(largest > 0.0)) return worst;
  double peak = load.front();
  double peak_time = time.front();
  for (std::size_t k = 0; k < load.size(); ++k) {
    if (load[k] > peak) {
      peak = load[k];
      peak_time = time[k];
    }
    if (peak < 0.1 * largest) continue;
    const double fraction = (peak - load[k]) / peak;
    if (fraction > worst.fraction) worst = {fraction, peak, peak_time, load[k], time[k]};
  }
  return worst;
}

std::vector<std::string> run_warnings(const Scene& scene, bool inertial,
                                      const KineticEnergyRecord& energy, const EnergyBudget& budget,
                                      double end_time, const Json& diagnostics,
                                      std::size_t particles,
                                      const std::map<std::string, double>& largest_reaction,
                                      const std::vector<BoundaryLoad>& loads) {
  std::vector<std::string> out;
  char text[640];
  const bool settling = inertial && scene.gravity != Vec2::Zero() && !driven_at(scene, end_time);
  // Both relative to the peak and to the energy put in: a slope creeping from rest has its peak
  // at the end, at a millionth of the work of gravity.
  if (settling && energy.end_over_peak() > 1e-3 && energy.end > 1e-4 * budget.input()) {
    const KineticEnergyCarriers& c = energy.end_carriers;
    // A few particles holding half of it were thrown off the body: no longer end time settles
    // them, and a measure that takes an extreme particle (a height, a front) reads them.
    if (c.half > 0 && c.half <= std::max<std::size_t>(1, particles / 100)) {
      std::snprintf(text, sizeof text,
                    "not at rest, and thrown off: the kinetic energy at t = %g s is %.2g of its "
                    "peak (at t = %g s), and %zu of %zu particles carry half of it; the most, "
                    "particle %zu at (%.4g, %.4g) m, moves at %.3g m/s. Measures that take an "
                    "extreme particle (a height, a front without min_thickness) may read it; "
                    "look at the frames for where it left the body",
                    end_time, energy.end_over_peak(), energy.peak_time, c.half, particles,
                    c.largest, c.position.x(), c.position.y(), c.speed);
    } else {
      std::snprintf(text, sizeof text,
                    "not at rest: the kinetic energy at t = %g s is %.2g of its peak (at t = %g "
                    "s); measures of the final state (a deposit's run-out and height) may still "
                    "move. Try a longer time.end_time, or more damping",
                    end_time, energy.end_over_peak(), energy.peak_time);
    }
    out.emplace_back(text);
  }
  // While walls or bodies are driven, the soil they move follows them: a mechanism moves part of
  // the soil at about the driven speed v, so the whole soil's kinetic energy above 1/2 M v^2 says
  // that it flows faster than anything drives it (a collapse beside the footing, particles thrown
  // off). A load drives by force, with no speed to compare: not judged.
  if (inertial && scene.loads.empty()) {
    const double v = fastest_driven_speed(scene, end_time);
    const double bound = 0.5 * energy.end_carriers.mass * v * v;
    if (v > 0.0 && energy.end > bound) {
      const KineticEnergyCarriers& c = energy.end_carriers;
      std::snprintf(text, sizeof text,
                    "not at rest while driven: the soil's kinetic energy at t = %g s, %.3g %s, is "
                    "%.3g times what all of it would have at the fastest driven speed, %.3g m/s: "
                    "it moves faster than anything drives it (a collapse, or particles thrown off; "
                    "%zu of %zu particles carry half of it, the most, particle %zu at (%.4g, %.4g) "
                    "m, at %.3g m/s)",
                    end_time, energy.end, energy_unit(scene.formulation), energy.end / bound, v,
                    c.half, particles, c.largest, c.position.x(), c.position.y(), c.speed);
      out.emplace_back(text);
    }
  }
  if (inertial && !budget.incomplete() && budget.peak_ratio() > 1.2) {
    std::snprintf(text, sizeof text,
                  "the kinetic energy reached %.3g times the energy put in (near t = %g s; the run "
                  "fails at checks.kinetic_energy_factor = %g): look at the frames there for "
                  "particles thrown off a wall or a rigid body",
                  budget.peak_ratio(), budget.peak_ratio_time(),
                  scene.checks.kinetic_energy_factor);
    out.emplace_back(text);
  }
  add_untouched_boundary_warnings(scene, largest_reaction, out);
  add_late_contact_warnings(scene, loads, out);
  // A quasi-static run's reactions are equilibrium loads. An explicit run's sampled reaction rings
  // about its trend by more than 5 % in a run that is right (footing.toml through espfem at dp
  // 0.25, 0.1 % off Prandtl: 17 kN/m at the footing's first step, 0.05 kN/m 0.02 s later; 58.3
  // then 49.4 kN/m at t = 3.56 and 3.66 s), so a fall there says nothing.
  if (!inertial) add_load_drop_warnings(scene, loads, out);
  add_diagnostic_warnings(scene, diagnostics, particles, out);
  return out;
}

}  // namespace duet
