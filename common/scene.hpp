#pragma once
// The scene: what a TOML scene file describes, physics only (DESIGN.md "one scene, several
// methods"). Plain data; common/scene_loader.hpp fills every default, so a solver never sees a
// missing value. SI units (m, s, kg, Pa); angles in the file are degrees; tension positive.
// Plane strain: forces are per metre of thickness, masses kg/m, areas m^2.

#include <map>
#include <string>
#include <vector>

#include "common/parameter_value.hpp"
#include "common/tensor.hpp"

namespace duet {

/// A piecewise-linear schedule of a 2-vector (a velocity in m/s, or a force in N/m): knots
/// (time, x, y), held constant before the first knot and after the last. Empty: zero (a fixed
/// wall, no load). Evaluate with schedule_value / schedule_integral (common/geometry.hpp).
struct Knot {
  double time = 0.0;  // s
  Vec2 value = Vec2::Zero();
};
using Schedule = std::vector<Knot>;

struct Material {
  std::string name;
  std::string model;     // registry name: "hypoplastic", "drucker-prager", ...
  double density = 0.0;  // kg/m^3
  // Every other key of [material.<name>]: the model's parameters, as the user gave them.
  std::map<std::string, ParameterValue> parameters;
  // The parameters as the model read them (defaults and derived values included).
  std::map<std::string, ParameterValue> resolved;
  // `parameters` before the strength reduction (equal to them at factor 1): what gravity loading
  // uses under strength_reduction.stage = "after-loading" (common/strength_reduction.hpp).
  std::map<std::string, ParameterValue> full_strength;
};

enum class ShapeKind { rectangle, polygon };
// square: cell centres of a square lattice; polar: rings about a centre (a cavity's soil).
enum class LatticeKind { square, polar };

/// A body of soil. Both shapes are kept as a counter-clockwise polygon in `outline` (a rectangle
/// as its four corners), so geometry code needs one case only.
struct Body {
  std::string name;
  std::string material;
  int material_index = -1;  // index into Scene::materials
  ShapeKind shape = ShapeKind::rectangle;
  Vec2 min = Vec2::Zero();  // rectangle corners (also the bounding box of a polygon)
  Vec2 max = Vec2::Zero();
  std::vector<Vec2> outline;  // counter-clockwise, not repeating the first point
  Vec2 initial_velocity = Vec2::Zero();
  LatticeKind lattice = LatticeKind::square;
  Vec2 lattice_centre = Vec2::Zero();  // polar only
  // A wall through the body, or the body on a wall's far side, is meant: not refused at load
  // (common/scene_validation.hpp, bodies_within_walls).
  bool crosses_walls = false;
};

// symmetry: a free-slip plane of symmetry, which holds the normal motion both ways (the material
// on its other side is the mirror image); a free-slip wall only pushes.
enum class WallCondition { no_slip, free_slip, symmetry };

/// A wall: a polyline (open, or closed when the last point repeats the first). It either
/// translates with `velocity` or, when `radial` is set, every point moves away from `centre`
/// at the radial speed of `radial_velocity` (its vx is the radial speed; cavity expansion).
struct Wall {
  std::string name;
  std::vector<Vec2> points;
  WallCondition condition = WallCondition::no_slip;
  Schedule velocity;
  bool radial = false;
  Vec2 centre = Vec2::Zero();
  Schedule radial_velocity;  // knots (time, v_r, 0)
};

enum class Surface { rough, smooth, friction };

/// A rigid body: a counter-clockwise polygon moving with a prescribed velocity.
struct RigidBody {
  std::string name;
  std::vector<Vec2> outline;  // counter-clockwise, not repeating the first point
  Schedule velocity;
  Surface surface = Surface::rough;
  double friction = 0.0;  // Coulomb coefficient mu, used when surface == friction
};

enum class InitialStressKind { none, isotropic, geostatic, gravity_loading };

/// How the bodies start. isotropic: sigma = -pressure I. geostatic: sigma_v = rho g (surface - y)
/// with each body's top as its surface, sigma_h = sigma_zz = K0 sigma_v (compression negative).
/// gravity-loading: gravity applied from zero stress with a velocity damping force
/// -damping m v for `time` seconds before the clock starts.
struct InitialStress {
  InitialStressKind kind = InitialStressKind::none;
  double pressure = 0.0;  // Pa, isotropic
  double K0 = 0.5;        // -, geostatic
  double damping = 0.0;   // 1/s, gravity-loading
  double time = 0.0;      // s, gravity-loading
};

/// A point or distributed load: a total force (N/m), piecewise-linear in time, shared equally by
/// the particles of `body` that lie initially in the box [min, max].
struct Load {
  std::string name;
  std::string body;
  int body_index = -1;
  Vec2 min = Vec2::Zero();
  Vec2 max = Vec2::Zero();
  Schedule force;  // knots (time, fx, fy), N/m
};

/// Strength reduction (Peng 2015 eqs 39-40): every material's `c` and friction angle `phi` are
/// reduced by `factor` before its model is built. rule "angle": phi_f = phi / f (Peng eq 40);
/// rule "tangent": tan phi_f = tan phi / f (Griffiths & Lane 1999). c_f = c / f (Peng eq 39).
/// stage, with gravity loading: "after-loading" settles at full strength and reduces it over the
/// run's first `ramp` seconds (Peng 2015 5.3); "throughout" settles at the reduced strength.
struct StrengthReduction {
  double factor = 1.0;
  std::string rule = "tangent";
  std::string stage = "after-loading";
  double ramp = 0.0;  // s
};

struct Time {
  double end_time = 0.0;         // s
  double output_interval = 0.0;  // s; default end_time / 50
};

/// Thresholds of the driver's checks of a running state, beyond the always-on ones (non-finite
/// values, leaving the domain, crossing a wall). 0 turns a check off.
struct RunCheckOptions {
  // Kinetic energy above this multiple of the energy put in (initial kinetic energy + work of
  // gravity, loads, walls and rigid bodies) + a floor: the method made energy (a blow-up).
  double kinetic_energy_factor = 2.0;
  // A fixed no-slip wall: the run fails when more than this fraction of the particles within one
  // spacing of it at t = 0 are further than lift_off_distance spacings from it.
  double lift_off_fraction = 0.5;
  double lift_off_distance = 2.0;  // spacings
};

struct Domain {
  Vec2 min = Vec2::Zero();
  Vec2 max = Vec2::Zero();
  double padding = 0.0;  // m, used when min/max were not given
};

enum class MeasureKind {
  front,
  height,
  reaction,
  wall_stress,
  max_displacement,
  displacement,
  period,
  safety_factor,
  expansion,
  point_displacement
};
// curve: the series against another measure's series (its abscissa), scored over a window of
// that abscissa against a reference curve or value (common/reference_curve.hpp).
enum class MeasureAt { end, max, series, time, curve };

/// A quantity recorded during a run.
///  front: max x of the target body's particles (min_thickness: ignore particles in columns with
///    fewer than that many spacings of material, so a lone particle does not count; or
///    min_depth, in metres, over columns of column_width, so that the toe's definition does not
///    shrink with the spacing).
///  height: max y of the body.
///  max_displacement: largest particle displacement of the body (component x | y | magnitude).
///  reaction: force of the soil on a wall or rigid body, component x | y | magnitude (N/m; N of
///    the whole circumference in an axisymmetric scene, the x component the sum of the radial
///    forces).
///  wall_stress: that reaction divided by the chord (end-to-end length) of the wall's current
///    polyline; for a straight wall the chord is its length, and for a uniformly loaded curved
///    wall the resultant equals the pressure times the chord, so this is the mean pressure.
///    Axisymmetric: divided by the magnitude of the vector area the polyline sweeps about the
///    axis, sum 2 pi r_mid (dz, -dr) (the chord's counterpart: for a uniform pressure the reaction
///    is the pressure times it, so magnitude is again the mean pressure).
///  displacement: of a wall or rigid body, integrated from its velocity schedule.
///  point_displacement: of the material point of the target body that starts at `point`
///    (component x | y, signed, or magnitude), from the particles that start within two spacings
///    of it by a linear least-squares fit (exact for a linear field; a point on the body's edge,
///    such as a beam's tip at mid-depth, has no particle on it).
///  period: period of the oscillation of the body's centre of mass along component x | y, from
///    successive zero crossings of its velocity (elastic bar).
///  expansion: a radial wall's mean distance from its centre over that at t = 0 (a / a0 of a
///    cavity).
///  safety_factor: the run's strength_reduction.factor; a sweep over it (duet stability --vary
///    strength_reduction.factor=...) finds the factor at which the slope fails (Peng 2015 5.3).
/// at: the value at the end, the maximum over the run, the whole series, the value at `time`,
/// or a curve: the series against the series of the measure `abscissa`, scored over `x_window`
/// of it; its one value is the series at the window's end.
/// divide_by: another measure; the recorded value is this one divided by that one (K0 as the
/// ratio of a side wall's stress to the top plate's). scale multiplies the result (e.g. 1/c_u).
struct Measure {
  std::string name;
  MeasureKind kind = MeasureKind::front;
  std::string target;
  std::string component;  // "x" | "y" | "magnitude"; "" where the kind has none
  MeasureAt at = MeasureAt::end;
  double time = 0.0;  // s, at == time
  // s, at == time: the mean of the samples within time +- window / 2 (those the run reached)
  // instead of the value at `time`; 0: the value at `time`
  double window = 0.0;
  double min_thickness = 0.0;  // spacings, front only
  double min_depth = 0.0;      // m, front only (instead of min_thickness)
  double column_width = 0.0;   // m, front only; 0: the spacing
  std::string divide_by;       // "" or the name of another measure
  double scale = 1.0;
  Vec2 point = Vec2::Zero();     // m, point_displacement: where the material point starts
  std::string abscissa;          // at == curve: the measure whose series is the curve's x
  Vec2 x_window = Vec2::Zero();  // at == curve: [from, to] of the abscissa that is scored
};

/// What a measure is scored against: a value, or a curve of points (x, y) (read from a CSV file,
/// common/reference_curve.hpp) for a measure with at = curve. A curve states the window of x
/// where it holds and its own error (for a computed reference, its mesh convergence).
struct Reference {
  std::string measure;
  double value = 0.0;
  std::string source;
  double tolerance = 0.0;     // relative; 0: not scored pass/fail, only reported
  std::vector<Vec2> curve;    // (x, y), x increasing; empty: the reference is `value`
  std::string curve_file;     // where the curve was read from, as the scene gave it
  Vec2 holds = Vec2::Zero();  // [from, to] of x where the curve holds
  double error = 0.0;         // the reference's own relative error (0: not stated)
};

enum class SphKernel { cubic_spline, wendland_c2 };
enum class SphWallStress { sigma_max, bui };
enum class SphIntegrator { verlet, leapfrog };
/// Velocity of a no-slip dummy particle: the wall's (Peng 2015 section 4.2) or extrapolated
/// through the wall from the soil particle it interacts with (Morris 1997 / Bui 2008,
/// sph/dummy_velocity.hpp).
enum class SphDummyVelocity { wall, extrapolated };

/// [sph] (Peng 2015 section 5: h/dp = sqrt(2), alpha = 1, beta = 0.1; artificial stress only
/// where there is tension, so off by default).
struct SphOptions {
  SphKernel kernel = SphKernel::cubic_spline;
  double h_over_dp = 1.4142135623730951;
  double alpha = 1.0;
  double beta = 0.1;
  double artificial_stress = 0.0;
  double cfl = 0.05;
  double sound_speed = 100.0;  // m/s
  std::string wall_treatment = "dummy";
  int dummy_layers = 3;
  // Bui 2008's dummies (the soil particle's stress, the velocity extrapolated through the wall):
  // with Peng's pair a footing's or a base's dummies make energy and the run fails (sph/README.md).
  SphWallStress wall_stress = SphWallStress::bui;
  SphDummyVelocity dummy_velocity = SphDummyVelocity::extrapolated;
  SphIntegrator integrator = SphIntegrator::verlet;
  bool continuity = false;
};

enum class Remesh { every_step, angle };

/// espfem critical time step: `cell-size` (papers/004 Algorithm 1 step 3, safety min_k sqrt(A_k) /
/// c_max) or `gershgorin` (safety x 2 / omega_max with omega_max bounded from the assembled
/// stiffness and the nodes' masses; needs moduli that bound the model's tangent).
enum class SpfemTimeStep { cell_size, gershgorin };

/// [spfem] (Zhang 2018 / Yuan 2019): alpha shape alpha = alpha_factor * dp.
struct SpfemOptions {
  double alpha_factor = 1.5;
  // A Delaunay triangle with an edge shorter than min_edge_factor * dp is not kept: two nodes
  // that near are one point to the mesh, and the sliver between them has a cell too small to
  // resist its strain (spfem/README.md, step 1); 0 = every triangle the alpha test keeps.
  double min_edge_factor = 0.0;
  double time_step_safety = 0.5;
  // Largest relative stress increment M / |sigma| |D| dt a step may give a node whose stiffness
  // grows with its stress (hypoplastic); 0 = no limit.
  double stress_increment_limit = 0.5;
  // The cell-size rule falls with any sliver at the surface (spfem/README.md, step 2)
  SpfemTimeStep time_step = SpfemTimeStep::gershgorin;
  double damping = 0.0;        // 1/s: viscous damping force -damping m v (quasi-static runs)
  double local_damping = 0.0;  // -: local non-viscous damping, -local_damping |F| sign(v) (Cundall)
  // Stabilisation of nodal integration: weight of the smoothed-strain stabilisation term
  // (0 = pure node-based smoothing as in the slides; 0.1 is a common NS-FEM choice).
  double stabilisation = 0.0;
  // Stiffness (hourglass-type) stabilisation of nodal integration, s_k (-): the energy
  // 1/2 (A0_e / 3) s_k M_e |F_e - Fbar_k|^2 per triangle and node
  // (spfem/stiffness_stabilisation.hpp); 0 = off.
  double stiffness_stabilisation = 0.0;
  // espfem: linear bulk viscosity b1 (-), the pressure b1 rho c l tr(D) of explicit finite element
  // codes (Abaqus/Explicit's, default 0.06 there; LS-DYNA's): it damps volumetric ringing and
  // adds nothing to an isochoric flow; 0 = off.
  double bulk_viscosity = 0.0;
  Remesh remesh = Remesh::every_step;
  double remesh_angle = 15.0;  // deg
  // remesh = angle: a triangle's limit is min(remesh_angle, fraction x its angle at the last
  // remesh) (spfem/remesh_trigger.hpp); 0 = remesh_angle for every triangle.
  double remesh_angle_fraction = 0.0;
  // The particles are cell-centred (shared with SPH), so the alpha shape lies dp/2 inside the
  // material; true: each surface node's smoothing cell is extended over that dp/2 layer.
  bool boundary_layer = true;
  // espfem: a node is added between two nodes touching the same wall once they are more than
  // wall_node_gap x dp apart (spfem/wall_node_insertion.hpp), so a wall that stretches the soil
  // along it (the cavity) keeps a row of nodes about dp apart on it; 0 = off.
  double wall_node_gap = 0.0;
};

/// [spfem.implicit] (Zhang 2018: Newton-Raphson with load steps and step cutting). An increment
/// advances the scene's time by `increment` s (0: end_time / load_steps); adaptive: halved when
/// Newton fails (up to max_step_cuts times in a row), grown by 1.5 after an increment that
/// converged within easy_iterations, never beyond its nominal size. Converged when the relative
/// residual |R_free| / max(|F_ext|, |reaction|) <= tolerance, or when the last correction
/// |du| / |u| <= displacement_tolerance with the residual within 100 x tolerance (round-off).
struct SpfemImplicitOptions {
  double tolerance = 1e-8;
  double displacement_tolerance = 1e-10;
  int max_iterations = 40;
  int load_steps = 100;
  double increment = 0.0;  // s; 0 = end_time / load_steps
  bool adaptive = true;
  int easy_iterations = 4;
  int max_step_cuts = 8;
  int active_set_passes = 3;  // contact changes re-solved within one increment
  // A converged increment that leaves a triangle of its mesh less than this fraction of its area
  // (or turns one inside out) is a snap-through: counted and warned of, or with refuse_snaps
  // refused and cut (snap = "refuse")
  double min_area_ratio = 0.5;
  bool refuse_snaps = false;
  // A converged quasi-static increment that leaves a driven wall's or rigid body's load more than
  // this fraction below its peak, in a scene whose materials cannot soften and whose strength is
  // not reduced, is refused and cut (a snap of nodal integration's soft modes, not the soil's
  // response); accepted and counted when the cuts run out, the peak then starting again from it;
  // 0 (the default) = accept every converged increment
  double load_drop = 0.0;
  // The stiffness stabilisation's energy anchored to each increment's start, with 2 G as its
  // modulus (spfem/increment_operator.hpp); 0 = off
  double increment_stabilisation = 0.0;
  // Newton's start on the free dofs: the last increment's motion scaled to this one
  // (extrapolated) or rest (none, the linearised step from the converged state)
  bool extrapolate = false;
  // dynamics = "newmark": the inertia M a in the residual, a and v by Newmark's average
  // acceleration (beta 1/4, gamma 1/2; unconditionally stable, no numerical damping); the
  // default "quasi-static" has none
  bool newmark = false;
};

/// How the plane of the scene is read. Plane strain: x horizontal, y vertical, per metre of
/// thickness. Axisymmetric: x = r (the axis is x = 0), y = z; a particle stands for the ring it
/// sweeps about the axis (volume 2 pi r A, mass, forces and energies of the whole circumference).
enum class Formulation { plane_strain, axisymmetric };

struct Scene {
  std::string path;  // the file it came from
  std::string name;  // `name` key, default the file's stem
  std::string description;
  double spacing = 0.0;         // m, particle spacing dp
  Vec2 gravity = Vec2::Zero();  // m/s^2, default zero: a scene says it
  bool confined = false;        // every body must be enclosed by walls and rigid bodies
  Formulation formulation = Formulation::plane_strain;
  std::vector<Material> materials;
  std::vector<Body> bodies;
  std::vector<Wall> walls;
  std::vector<RigidBody> rigid_bodies;
  std::vector<Load> loads;
  InitialStress initial_stress;
  StrengthReduction strength_reduction;
  Time time;
  RunCheckOptions checks;
  Domain domain;
  std::vector<Measure> measures;
  std::vector<Reference> references;
  SphOptions sph;
  SpfemOptions spfem;
  SpfemImplicitOptions spfem_implicit;
  std::string resolved_toml;  // the whole scene with every default filled in

  int material_index(const std::string& material_name) const {
    for (std::size_t i = 0; i < materials.size(); ++i) {
      if (materials[i].name == material_name) return static_cast<int>(i);
    }
    return -1;
  }
};

/// The enum spellings used in scene files, for the loader and for output.
const char* to_string(WallCondition c);
const char* to_string(Surface s);
const char* to_string(InitialStressKind k);
const char* to_string(MeasureKind k);
const char* to_string(MeasureAt a);
const char* to_string(SphKernel k);
const char* to_string(SphWallStress w);
const char* to_string(SphIntegrator i);
const char* to_string(Remesh r);

}  // namespace duet
