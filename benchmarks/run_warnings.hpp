#pragma once
// What a finished run's own figures say that a user must not miss, each with what to try: said on
// the terminal at the end of the run and listed under `warnings` in metrics.json.

#include <map>
#include <string>
#include <vector>

#include "common/energy_budget.hpp"
#include "common/kinetic_energy.hpp"
#include "common/scene.hpp"
#include "common/solver.hpp"
#include "constitutive/scene_models.hpp"

namespace duet {

/// The load a boundary with prescribed motion carries while it moves, one value per measure
/// sample: the resistance it meets along its motion, -F . v / |v| (F the soil's force on it, v
/// its velocity), or |F| for a radial wall.
struct BoundaryLoad {
  std::string name;          // a wall or rigid body
  std::vector<double> time;  // s
  std::vector<double> load;  // N/m
};

/// One empty record per wall and rigid body whose schedule ever moves it, in the scene's order.
std::vector<BoundaryLoad> driven_boundaries(const Scene& scene);

/// Appends to each record the load at `time` from the reactions sampled then (those the measures
/// take), where its boundary moves at that time.
void record_boundary_loads(const Scene& scene, double time, const std::vector<Reaction>& reactions,
                           std::vector<BoundaryLoad>& loads);

/// The largest fall of a load below its running maximum, as a fraction of that maximum, with the
/// peak and the low. Counted once the maximum exceeds a tenth of the largest load of the series:
/// the first contact's loads are small and noisy.
struct LoadDrop {
  double fraction = 0.0;
  double peak = 0.0;
  double peak_time = 0.0;
  double low = 0.0;
  double low_time = 0.0;
};
LoadDrop largest_load_drop(const std::vector<double>& time, const std::vector<double>& load);

/// No material can soften and the strength stays as given (constitutive/scene_models.hpp).
using constitutive::cannot_soften;

/// - a deposit not at rest: a dynamic method, gravity, nothing driven at the end (every wall and
///   rigid body still, no load), kinetic energy at the end above 1e-3 of its peak and 1e-4 of the
///   energy put in; when at most 1 % of the particles (at least one) carry half of it, said as
///   particles thrown off the body, with the one that carries most (energy.end_carriers);
/// - not at rest while driven: a dynamic method, walls or rigid bodies driven at the end (no
///   load), and the soil's kinetic energy at the end above 1/2 M v^2, M its mass
///   (energy.end_carriers.mass) and v the fastest driven speed then;
/// - close to the energy check: the kinetic energy reached more than 1.2 times the energy put in
///   (the check fails a run at kinetic_energy_factor, 2 by default).
/// - a moving boundary that never touched: a rigid body or wall with a prescribed motion whose
///   reaction was zero at every step (`largest_reaction`: the largest |F| of each named reaction
///   over the run); its measures read 0 and the run scored nothing (a footing that starts above
///   the soil's top row: common/lattice.hpp lattice_misfits);
/// - a moving boundary that touched late: its load stayed 0 until it had moved more than a quarter
///   spacing (`loads`), so the measures before then read 0.
/// From the method's diagnostics (the keys named), when it reports them:
/// - penetrations (penetrations_max > 0): particles inside a wall or rigid body;
/// - isolated nodes (isolated_nodes_max > 5 % of the particles): nodes in no triangle of the
///   SPFEM mesh, which move without stress;
/// - energy drift of the explicit step (energy_drift_max > 2 %) where the energy must be
///   conserved: linear-elastic materials, no gravity, loads, moving walls or damping;
/// - steps limited by a safeguard: more than 10 % of the steps cut by the stress increment limit
///   (stress_limited_steps of steps), or an increment within two halvings of the max_step_cuts
///   that fail an ispfem run (newton.increment_min below 4 x nominal / 2^max_step_cuts).
/// - load-drop: in a quasi-static run (not `inertial`: its reactions are equilibrium loads, not
///   an explicit step's ringing ones), a boundary's load (`loads`) fell more than 5 % below its
///   running maximum in a scene that cannot soften (cannot_soften): a perfectly plastic load does
///   not fall.
std::vector<std::string> run_warnings(const Scene& scene, bool inertial,
                                      const KineticEnergyRecord& energy, const EnergyBudget& budget,
                                      double end_time, const Json& diagnostics,
                                      std::size_t particles,
                                      const std::map<std::string, double>& largest_reaction = {},
                                      const std::vector<BoundaryLoad>& loads = {});

}  // namespace duet
