#include "common/scene_keys.hpp"

#include <algorithm>

namespace duet {

namespace {

const std::string kReq = "required";

std::vector<SceneKey> make_keys() {
  return {
      // --- top level ---
      {"", "name", "string", "", "(the file's stem)", "the scene's name in output and reports"},
      {"", "description", "string", "", "\"\"", "free text"},
      {"", "spacing", "number", "m", kReq, "particle spacing dp (--spacing overrides it)"},
      {"", "gravity", "[x, y]", "m/s^2", "[0.0, 0.0]", "body force per unit mass"},
      {"", "confined", "boolean", "", "false",
       "every body must lie inside the walls and rigid bodies (checked at load)"},
      {"", "formulation", "string", "", "\"plane-strain\"",
       "\"plane-strain\" (per metre) or \"axisymmetric\" (x = r, axis x = 0; whole circumference)"},
      {"", "time", "table", "", kReq, "[time]: end time and output interval"},
      {"", "domain", "table", "", "(bounding box + padding)",
       "[domain]: a particle leaving it fails the run"},
      {"", "initial_stress", "table", "", "(kind = \"none\")",
       "[initial_stress]: how bodies start"},
      {"", "material", "tables", "", kReq, "[material.<name>]: model, density, model parameters"},
      {"", "body", "tables", "", kReq, "[body.<name>]: a region of soil sampled into particles"},
      {"", "wall", "tables", "", "(none)", "[wall.<name>]: a polyline boundary"},
      {"", "rigid_body", "tables", "", "(none)",
       "[rigid_body.<name>]: a polygon with prescribed motion (a footing, a penetrometer)"},
      {"", "load", "tables", "", "(none)", "[load.<name>]: a force shared by particles of a body"},
      {"", "measure", "tables", "", "(none)", "[measure.<name>]: a quantity recorded each output"},
      {"", "reference", "tables", "", "(none)",
       "[reference.<measure>]: a published value a measure is scored against"},
      {"", "sph", "table", "", "(defaults below)", "[sph]: options of the SPH method"},
      {"", "spfem", "table", "", "(defaults below)", "[spfem]: options of both SPFEM methods"},
      {"", "strength_reduction", "table", "", "(factor = 1)",
       "[strength_reduction]: c and phi divided by a factor (Peng 2015 eqs 39-40)"},
      {"", "checks", "table", "", "(defaults below)",
       "[checks]: thresholds that fail a run that went wrong"},
      // --- [time] ---
      {"time", "end_time", "number", "s", kReq, "simulated time of the run"},
      {"time", "output_interval", "number", "s", "(end_time / 50)",
       "time between frames and measure samples"},
      // --- [domain] ---
      {"domain", "min", "[x, y]", "m", "(bounding box - padding)", "lower-left corner"},
      {"domain", "max", "[x, y]", "m", "(bounding box + padding)", "upper-right corner"},
      {"domain", "padding", "number", "m", "(extent / 4)",
       "margin around bodies, walls and rigid bodies when min/max are not given"},
      // --- [initial_stress] ---
      {"initial_stress", "kind", "string", "", "\"none\"",
       "none | isotropic | geostatic | gravity-loading"},
      {"initial_stress", "pressure", "number", "Pa", "(required for isotropic)",
       "compressive pressure of kind = isotropic"},
      {"initial_stress", "K0", "number", "-", "(required for geostatic)",
       "sigma_h / sigma_v of kind = geostatic"},
      {"initial_stress", "damping", "number", "1/s", "(required for gravity-loading)",
       "velocity damping while gravity is applied before the clock starts"},
      {"initial_stress", "time", "number", "s", "(required for gravity-loading)",
       "duration of the gravity loading before the clock starts"},
      // --- [strength_reduction] ---
      {"strength_reduction", "factor", "number", "-", "1.0", "f: c / f and phi reduced by f"},
      {"strength_reduction", "rule", "string", "", "\"tangent\"",
       "tangent: tan phi / f (Griffiths & Lane 1999) | angle: phi / f (Peng 2015 eq 40)"},
      {"strength_reduction", "stage", "string", "", "\"after-loading\"",
       "after-loading: gravity loading at full strength, then reduced (Peng 2015 5.3) | "
       "throughout: reduced from the first gravity increment"},
      {"strength_reduction", "ramp", "number", "s", "0",
       "after-loading: the strength falls linearly to c / f over this much run time (0: at once)"},
      // --- [checks] ---
      {"checks", "kinetic_energy_factor", "number", "-", "2.0",
       "fail when kinetic energy > this x the energy put in (0: off)"},
      {"checks", "lift_off_fraction", "number", "-", "0.5",
       "fail when this fraction of the particles on a fixed no-slip wall left it (0: off)"},
      {"checks", "lift_off_distance", "number", "spacings", "2.0",
       "distance from the wall that counts as having left it"},
      // --- [material.<name>] ---
      {"material.<name>", "model", "string", "", kReq,
       "constitutive model (duet models lists them and their parameters)"},
      {"material.<name>", "density", "number", "kg/m^3", kReq, "mass density"},
      {"material.<name>", "<parameter>", "number | string", "(per model)", "(per model)",
       "the model's parameters: duet models MODEL"},
      // --- [body.<name>] ---
      {"body.<name>", "material", "string", "", kReq, "name of a [material.<name>]"},
      {"body.<name>", "shape", "string", "", "(polygon if vertices, else rectangle)",
       "rectangle | polygon"},
      {"body.<name>", "min", "[x, y]", "m", "(required for rectangle)", "lower-left corner"},
      {"body.<name>", "max", "[x, y]", "m", "(required for rectangle)", "upper-right corner"},
      {"body.<name>", "vertices", "[[x, y], ...]", "m", "(required for polygon)",
       "outline of a simple polygon, either orientation"},
      {"body.<name>", "initial_velocity", "[x, y]", "m/s", "[0.0, 0.0]", "velocity at t = 0"},
      {"body.<name>", "lattice", "string", "", "\"square\"",
       "square (cell centres) | polar (rings dp apart about lattice_centre, from the outline's "
       "nearest vertex: a cavity's soil)"},
      {"body.<name>", "lattice_centre", "[x, y]", "m", "(required for polar)",
       "centre of the polar lattice's rings"},
      {"body.<name>", "crosses_walls", "boolean", "", "false",
       "a wall through the body, or the body on a wall's far side, is meant (else refused at "
       "load: the methods put soil on one side of each wall segment)"},
      // --- [wall.<name>] ---
      {"wall.<name>", "points", "[[x, y], ...]", "m", kReq,
       "polyline (closed when the last point repeats the first)"},
      {"wall.<name>", "condition", "string", "", "\"no-slip\"",
       "no-slip | free-slip | symmetry (free-slip, held both ways)"},
      {"wall.<name>", "velocity", "[[t, vx, vy], ...]", "s, m/s", "(fixed)",
       "translation speed, piecewise linear in time"},
      {"wall.<name>", "centre", "[x, y]", "m", "(required with radial_velocity)",
       "centre of a radial motion"},
      {"wall.<name>", "radial_velocity", "[[t, v_r], ...]", "s, m/s", "(none)",
       "every point moves away from centre at v_r (cavity expansion)"},
      // --- [rigid_body.<name>] ---
      {"rigid_body.<name>", "vertices", "[[x, y], ...]", "m", kReq,
       "outline of a simple polygon, either orientation"},
      {"rigid_body.<name>", "velocity", "[[t, vx, vy], ...]", "s, m/s", "(fixed)",
       "prescribed velocity, piecewise linear in time"},
      {"rigid_body.<name>", "surface", "string", "", "\"rough\"", "rough | smooth | friction"},
      {"rigid_body.<name>", "friction", "number", "-", "(required for friction)",
       "Coulomb coefficient mu of surface = friction"},
      // --- [load.<name>] ---
      {"load.<name>", "body", "string", "", kReq, "name of the loaded [body.<name>]"},
      {"load.<name>", "min", "[x, y]", "m", kReq, "lower-left corner of the loaded box"},
      {"load.<name>", "max", "[x, y]", "m", kReq, "upper-right corner of the loaded box"},
      {"load.<name>", "force", "[[t, fx, fy], ...]", "s, N/m", kReq,
       "total force, shared equally by the particles initially in the box"},
      // --- [measure.<name>] ---
      {"measure.<name>", "kind", "string", "", kReq,
       "front | height | reaction | wall_stress | max_displacement | displacement | period | "
       "safety_factor | expansion (a radial wall's a / a0) | point_displacement"},
      {"measure.<name>", "target", "string", "", "(required but for safety_factor)",
       "the body, wall or rigid body measured"},
      {"measure.<name>", "component", "string", "", "(per kind)",
       "x | y | magnitude (reaction, wall_stress, displacement: required; max_displacement: "
       "magnitude; period: x | y)"},
      {"measure.<name>", "at", "string", "", "\"end\"", "end | max | series | time | curve"},
      {"measure.<name>", "time", "number", "s", "(required for at = time)",
       "when the value is taken"},
      {"measure.<name>", "window", "number", "s", "(0 for at = time)",
       "at = time: the mean of the samples within time +- window / 2 (0: the value at time)"},
      {"measure.<name>", "min_thickness", "number", "spacings", "(0 for front)",
       "front: ignore columns thinner than this"},
      {"measure.<name>", "min_depth", "number", "m", "(0 for front)",
       "front: ignore columns with less material than this depth (instead of min_thickness)"},
      {"measure.<name>", "column_width", "number", "m", "(the spacing)",
       "front: width of the columns min_thickness or min_depth applies to"},
      {"measure.<name>", "divide_by", "string", "", "\"\"",
       "another measure this one is divided by"},
      {"measure.<name>", "scale", "number", "-", "1.0", "factor applied to the value"},
      {"measure.<name>", "point", "[x, y]", "m", "(required for point_displacement)",
       "where the material point starts (it may lie on the body's edge)"},
      {"measure.<name>", "abscissa", "string", "", "(required for at = curve)",
       "the measure whose series is the curve's x"},
      {"measure.<name>", "x_window", "[x, y]", "(the abscissa's)", "(required for at = curve)",
       "[from, to]: the part of the curve that is scored"},
      // --- [reference.<measure>] ---
      {"reference.<measure>", "value", "number", "(the measure's)", "(required without curve)",
       "the reference value"},
      {"reference.<measure>", "curve", "string", "", "(instead of value)",
       "CSV file of x, y (relative to the scene file; '#' comments, a header line)"},
      {"reference.<measure>", "points", "[[x, y], ...]", "", "(the curve file's)",
       "the curve's [x, y] points (written into a run's resolved scene)"},
      {"reference.<measure>", "holds", "[x, y]", "", "(the curve's x range)",
       "[from, to]: the window of x where the curve holds"},
      {"reference.<measure>", "error", "number", "-", "0.0",
       "the reference's own relative error (e.g. its mesh convergence; 0: not stated)"},
      {"reference.<measure>", "source", "string", "", kReq, "where the value comes from"},
      {"reference.<measure>", "tolerance", "number", "-", "0.0",
       "relative error that passes (0: reported, not scored)"},
      // --- [sph] ---
      {"sph", "kernel", "string", "", "\"cubic-spline\"", "cubic-spline | wendland-c2"},
      {"sph", "h_over_dp", "number", "-", "1.4142135623730951", "smoothing length / spacing"},
      {"sph", "alpha", "number", "-", "1.0", "artificial viscosity, linear term (Monaghan)"},
      {"sph", "beta", "number", "-", "0.1", "artificial viscosity, quadratic term"},
      {"sph", "artificial_stress", "number", "-", "0.0",
       "artificial stress coefficient against tensile instability (0: off)"},
      {"sph", "cfl", "number", "-", "0.05", "Courant number of the time step"},
      {"sph", "sound_speed", "number", "m/s", "100.0",
       "sound speed c_s of the time step (cfl h / c_s) and the viscosity (alpha c_s), used as "
       "given (duet check prints it beside the soil's P-wave speed)"},
      {"sph", "wall_treatment", "string", "", "\"dummy\"", "dummy (layers of dummy particles)"},
      {"sph", "dummy_layers", "integer", "-", "3", "layers of dummy particles behind a wall"},
      {"sph", "wall_stress", "string", "", "\"bui\"",
       "stress of dummy particles: sigma-max (Peng 2015) | bui (Bui 2008)"},
      {"sph", "integrator", "string", "", "\"verlet\"", "verlet | leapfrog"},
      {"sph", "continuity", "boolean", "", "false",
       "evolve density by the continuity equation (else constant)"},
      {"sph", "dummy_velocity", "string", "", "\"extrapolated\"",
       "velocity of no-slip dummy particles: wall | extrapolated (Morris 1997)"},
      // --- [spfem] ---
      {"spfem", "alpha_factor", "number", "-", "1.5", "alpha shape radius / spacing"},
      {"spfem", "min_edge_factor", "number", "-", "0.0",
       "a triangle with an edge below min_edge_factor x spacing is not kept, in [0, 0.5]"},
      {"spfem", "time_step_safety", "number", "-", "0.5", "espfem: safety on the critical step"},
      {"spfem", "damping", "number", "1/s", "0.0", "espfem: viscous damping -damping m v"},
      {"spfem", "local_damping", "number", "-", "0.0",
       "espfem: local non-viscous damping (Cundall), in [0, 1]"},
      {"spfem", "stabilisation", "number", "-", "0.0",
       "weight of the smoothed-strain stabilisation of nodal integration"},
      {"spfem", "remesh", "string", "", "\"every-step\"", "every-step | angle"},
      {"spfem", "remesh_angle", "number", "deg", "15.0",
       "remesh = angle: remesh when a triangle's smallest angle drops below it"},
      {"spfem", "boundary_layer", "boolean", "", "true",
       "extend surface nodes' smoothing cells over the dp/2 layer outside the alpha shape"},
      {"spfem", "time_step", "string", "", "\"gershgorin\"",
       "espfem critical step: cell-size | gershgorin"},
      {"spfem", "implicit", "table", "", "(defaults below)", "[spfem.implicit]: ispfem options"},
      {"spfem", "stress_increment_limit", "number", "-", "0.5",
       "espfem: largest relative stress increment per step of a stiffening model (0: none)"},
      {"spfem", "stiffness_stabilisation", "number", "-", "0.0",
       "hourglass-type stiffness stabilisation of nodal integration (0: off)"},
      {"spfem", "remesh_angle_fraction", "number", "-", "0.0",
       "remesh = angle: limit min(remesh_angle, fraction x angle at the last remesh)"},
      {"spfem", "bulk_viscosity", "number", "-", "0.0",
       "espfem: linear bulk viscosity b1, pressure b1 rho c l tr(D) (0: off)"},
      {"spfem", "wall_node_gap", "number", "-", "0.0",
       "espfem: add a node between two nodes on one wall more than this x spacing apart (0: off)"},
      // --- [spfem.implicit] ---
      {"spfem.implicit", "tolerance", "number", "-", "1e-08", "Newton: relative residual"},
      {"spfem.implicit", "displacement_tolerance", "number", "-", "1e-10",
       "Newton: relative correction accepted with the residual within 100 x tolerance"},
      {"spfem.implicit", "max_iterations", "integer", "-", "40", "Newton iterations per try"},
      {"spfem.implicit", "load_steps", "integer", "-", "100",
       "increments over end_time when increment = 0"},
      {"spfem.implicit", "increment", "number", "s", "0.0",
       "increment of the scene's time (0: end_time / load_steps)"},
      {"spfem.implicit", "adaptive", "boolean", "", "true",
       "halve a failed increment, grow an easy one by 1.5"},
      {"spfem.implicit", "easy_iterations", "integer", "-", "4",
       "an increment converging within this many iterations grows the next"},
      {"spfem.implicit", "max_step_cuts", "integer", "-", "8", "halvings in a row before failing"},
      {"spfem.implicit", "active_set_passes", "integer", "-", "3",
       "contact changes re-solved within one increment"},
      {"spfem.implicit", "min_area_ratio", "number", "-", "0.5",
       "an increment leaving a triangle below this fraction of its area (or inside out) snaps"},
      {"spfem.implicit", "increment_stabilisation", "number", "-", "0.0",
       "stiffness stabilisation anchored to each increment's start, modulus 2 G (0: off)"},
      {"spfem.implicit", "load_drop", "number", "-", "0.0",
       "cut a quasi-static increment whose driven load falls this fraction below its peak, where "
       "no material softens (0: off)"},
      {"spfem.implicit", "snap", "string", "-", "\"warn\"",
       "warn: count snap-throughs and warn | refuse: cut such an increment, fail after the cuts"},
      {"spfem.implicit", "predictor", "string", "-", "\"none\"",
       "Newton's start: extrapolated (the last increment's motion) | none (rest)"},
      {"spfem.implicit", "dynamics", "string", "-", "\"quasi-static\"",
       "quasi-static | newmark (inertia, average acceleration)"},
  };
}

}  // namespace

const std::vector<SceneKey>& scene_keys() {
  static const std::vector<SceneKey> keys = make_keys();
  return keys;
}

std::vector<std::string> scene_keys_of(std::string_view section) {
  std::vector<std::string> out;
  for (const SceneKey& k : scene_keys()) {
    if (k.section == section && k.key != "<parameter>") out.push_back(k.key);
  }
  return out;
}

std::vector<std::string> scene_sections() {
  std::vector<std::string> out;
  for (const SceneKey& k : scene_keys()) {
    if (std::find(out.begin(), out.end(), k.section) == out.end()) out.push_back(k.section);
  }
  return out;
}

bool is_literal_default(const SceneKey& key) {
  return !key.fallback.empty() && key.fallback != "required" && key.fallback.front() != '(';
}

}  // namespace duet
