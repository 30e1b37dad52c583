#include "common/scene_loader.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include <toml++/toml.h>

#include "common/enum_names.hpp"
#include "common/geometry.hpp"
#include "common/input_error.hpp"
#include "common/reference_curve.hpp"
#include "common/scene_keys.hpp"
#include "common/scene_schema.hpp"
#include "common/scene_validation.hpp"
#include "common/strength_reduction.hpp"
#include "common/suggest.hpp"

namespace duet {

namespace {

// The schema: keys of every table, from common/scene_keys.cpp (what `duet keys` prints).
const std::vector<std::string> kRootKeys = scene_keys_of("");
const std::vector<std::string> kCollections = {"material", "body",    "wall",     "rigid_body",
                                               "load",     "measure", "reference"};
const std::vector<std::string> kTimeKeys = scene_keys_of("time");
const std::vector<std::string> kDomainKeys = scene_keys_of("domain");
const std::vector<std::string> kInitialStressKeys = scene_keys_of("initial_stress");
const std::vector<std::string> kBodyKeys = scene_keys_of("body.<name>");
const std::vector<std::string> kWallKeys = scene_keys_of("wall.<name>");
const std::vector<std::string> kRigidKeys = scene_keys_of("rigid_body.<name>");
const std::vector<std::string> kLoadKeys = scene_keys_of("load.<name>");
const std::vector<std::string> kMeasureKeys = scene_keys_of("measure.<name>");
const std::vector<std::string> kStrengthReductionKeys = scene_keys_of("strength_reduction");
const std::vector<std::string> kCheckKeys = scene_keys_of("checks");
const std::vector<std::string> kReferenceKeys = scene_keys_of("reference.<measure>");

/// The value of a choice key spelled by `table`; `fallback` (the struct's default) when absent.
template <class Enum, std::size_t N>
Enum read_named(SectionReader& r, std::string_view key, Enum fallback,
                const EnumName<Enum> (&table)[N]) {
  return value_named(r.choice(key, names_of(table), std::string(name_of(fallback, table))), table);
}
const std::vector<std::string> kSphKeys = scene_keys_of("sph");
const std::vector<std::string> kSpfemKeys = scene_keys_of("spfem");
const std::vector<std::string> kImplicitKeys = scene_keys_of("spfem.implicit");

std::string trim(std::string s) {
  const auto not_space = [](unsigned char c) { return !std::isspace(c); };
  s.erase(s.begin(), std::find_if(s.begin(), s.end(), not_space));
  s.erase(std::find_if(s.rbegin(), s.rend(), not_space).base(), s.end());
  return s;
}

std::vector<std::string> split(const std::string& s, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(s);
  while (std::getline(in, part, separator)) parts.push_back(part);
  if (!s.empty() && s.back() == separator) parts.emplace_back();
  return parts;
}

std::vector<std::string> names_of(const toml::table* table) {
  std::vector<std::string> names;
  if (table) {
    for (const auto& [k, v] : *table) names.emplace_back(k.str());
  }
  return names;
}

/// Applies one --set override to the parsed file. Creating a new named entry of a collection
/// (a material that does not exist) is refused with a did-you-mean; other missing tables are
/// created, so [sph] options can be set on a scene without an [sph] table.
void apply_override(toml::table& root, const std::string& text, SceneSource& source) {
  const auto eq = text.find('=');
  if (eq == std::string::npos) {
    throw InputError("--set " + text + ": missing '='; expected dotted.key=value");
  }
  const std::string key = trim(text.substr(0, eq));
  const std::string value_text = trim(text.substr(eq + 1));
  const std::vector<std::string> segments = split(key, '.');
  if (key.empty() || std::any_of(segments.begin(), segments.end(),
                                 [](const std::string& s) { return s.empty(); })) {
    throw InputError("--set " + text + ": empty key; expected dotted.key=value");
  }
  // The value as TOML (number, bool, "string", [array]); a bare word is taken as a string.
  toml::table holder;
  try {
    holder = toml::parse("v = " + value_text);
  } catch (const toml::parse_error&) {
    holder.insert_or_assign("v", value_text);
  }
  const toml::node& value = *holder.get("v");

  toml::table* current = &root;
  std::string path;
  for (std::size_t i = 0; i + 1 < segments.size(); ++i) {
    const std::string& segment = segments[i];
    path += (i ? "." : "") + segment;
    toml::node* child = current->get(segment);
    if (!child) {
      const bool named_entry = i == 1 && std::find(kCollections.begin(), kCollections.end(),
                                                   segments[0]) != kCollections.end();
      if (named_entry) {
        const std::vector<std::string> names = names_of(current);
        throw InputError("--set " + text + ": " + path + ": no " + segments[0] + " named '" +
                         segment + "'" + did_you_mean(segment, names) + "; expected one of " +
                         (names.empty() ? std::string("(none in the file)") : join(names)));
      }
      child = &current->insert_or_assign(segment, toml::table{}).first->second;
    }
    if (!child->is_table()) {
      throw InputError("--set " + text + ": " + path + " is " + describe_type(*child) +
                       ", not a table; expected a key path that exists in the scene");
    }
    current = child->as_table();
  }
  current->insert_or_assign(segments.back(), value);
  source.overrides[key] = value_text;
}

/// Peng 2015 eqs 39-40 at the scene's factor (common/strength_reduction.hpp); the full-strength
/// parameters kept for gravity loading.
void reduce_material_strength(Material& m, const StrengthReduction& reduction, SectionReader& r) {
  m.full_strength = m.parameters;
  if (reduction.factor == 1.0) return;
  if (!duet::reduce_strength(m.parameters, reduction.factor, reduction.rule)) {
    r.fail("", "strength_reduction.factor is set but this material has no phi or c",
           "materials given with phi (deg) and/or c (Pa)");
  }
}

Material read_material(const std::string& name, const toml::node& node,
                       const StrengthReduction& reduction, const SceneSource& source,
                       const MaterialCheck& check, toml::table& resolved) {
  const std::string path = "material." + name;
  SectionReader r(node.as_table(), path, {}, source, resolved);
  if (!node.is_table()) r.fail("", "wrong type: " + describe_type(node), "a table [" + path + "]");
  Material m;
  m.name = name;
  m.model = r.string("model");
  m.density = r.number("density", positive("a density (kg/m^3)"));
  for (const auto& [k, v] : *node.as_table()) {
    const std::string key(k.str());
    if (key == "model" || key == "density") continue;
    if (auto d = v.value_exact<double>()) {
      m.parameters[key] = *d;
    } else if (auto i = v.value_exact<std::int64_t>()) {
      m.parameters[key] = static_cast<double>(*i);
    } else if (auto s = v.value_exact<std::string>()) {
      m.parameters[key] = *s;
    } else {
      r.fail(key, "wrong type: " + describe_type(v), "a number or a string (a model parameter)");
    }
  }
  reduce_material_strength(m, reduction, r);
  if (!check) {
    m.resolved = m.parameters;
  } else {
    try {
      m.resolved = check(m.model, m.parameters, path);
    } catch (const InputError& e) {
      // Point at the parameter the message names ("material.sand.nu = ..."), else the model key.
      const std::string message = e.what();
      std::string at = "model";
      for (const auto& [key, value] : m.parameters) {
        const std::string prefix = path + "." + key;
        if (message.starts_with(prefix + " ") || message.starts_with(prefix + ":")) at = key;
      }
      throw InputError(r.where(at) + ": " + message);
    }
  }
  // The resolved scene is loaded again by `duet run --resume`, which reduces the strength again:
  // a reduced material keeps the parameters as given (its derived values, a Drucker-Prager
  // tension cut-off or hypoplastic c1..c4, follow the reduced c and phi when its model is built).
  const bool reduced = reduction.factor != 1.0;
  for (const auto& [key, value] : reduced ? m.full_strength : m.resolved) {
    if (const double* d = std::get_if<double>(&value)) {
      resolved.insert_or_assign(key, *d);
    } else {
      resolved.insert_or_assign(key, std::get<std::string>(value));
    }
  }
  return m;
}

std::vector<Vec2> read_polygon(SectionReader& r, std::string_view key) {
  std::vector<Vec2> polygon = r.points(key, 3);
  if (polygon.size() > 3 && (polygon.front() - polygon.back()).norm() == 0.0) polygon.pop_back();
  if (!is_simple_polygon(polygon) || std::abs(signed_area(polygon)) <= 0.0) {
    r.fail(key, "the outline crosses itself, repeats a vertex or encloses no area",
           "the vertices of a simple polygon, in order (either orientation)");
  }
  make_counter_clockwise(polygon);
  toml::array resolved;
  for (const Vec2& p : polygon) resolved.push_back(toml::array{p.x(), p.y()});
  r.resolved().insert_or_assign(key, std::move(resolved));
  return polygon;
}

Body read_body(const std::string& name, SectionReader& r, const std::vector<Material>& materials) {
  Body b;
  b.name = name;
  b.material = r.string("material");
  std::vector<std::string> known;
  for (std::size_t i = 0; i < materials.size(); ++i) {
    known.push_back(materials[i].name);
    if (materials[i].name == b.material) b.material_index = static_cast<int>(i);
  }
  if (b.material_index < 0) {
    r.fail("material", "unknown material \"" + b.material + "\"" + did_you_mean(b.material, known),
           known.empty() ? "a [material." + b.material + "] table" : "one of " + join(known));
  }
  const std::string shape =
      r.choice("shape", {"rectangle", "polygon"}, r.has("vertices") ? "polygon" : "rectangle");
  if (shape == "rectangle") {
    b.shape = ShapeKind::rectangle;
    b.min = r.vec2("min");
    b.max = r.vec2("max");
    if (!(b.max.x() > b.min.x() && b.max.y() > b.min.y())) {
      r.fail("max", "not above and to the right of min", "max > min in x and in y (m)");
    }
    b.outline = {b.min, {b.max.x(), b.min.y()}, b.max, {b.min.x(), b.max.y()}};
  } else {
    b.shape = ShapeKind::polygon;
    b.outline = read_polygon(r, "vertices");
    bounding_box(b.outline, b.min, b.max);
  }
  b.initial_velocity = r.vec2("initial_velocity", Vec2::Zero());
  if (r.choice("lattice", {"square", "polar"}, "square") == "polar") {
    b.lattice = LatticeKind::polar;
    b.lattice_centre = r.vec2("lattice_centre");
  } else if (r.has("lattice_centre")) {
    r.fail("lattice_centre", "given with a square lattice", "lattice = \"polar\" to use it");
  }
  b.crosses_walls = r.boolean("crosses_walls", false);
  r.finish();
  return b;
}

Wall read_wall(const std::string& name, SectionReader& r) {
  Wall w;
  w.name = name;
  w.points = r.points("points", 2);
  // A segment of zero length has no normal: the solvers cannot orient it (the fuzzer's repeated
  // points reached the SPH wall set-up as an internal error, exit 1).
  for (std::size_t k = 1; k < w.points.size(); ++k) {
    if (w.points[k] == w.points[k - 1]) {
      r.fail("points", "point " + std::to_string(k + 1) + " repeats the one before it",
             "a polyline of distinct consecutive [x, y] points");
    }
  }
  w.condition = value_named(r.choice("condition", names_of(kWallConditionNames), "no-slip"),
                            kWallConditionNames);
  if (r.has("radial_velocity")) {
    if (r.has("velocity")) {
      r.fail("velocity", "given together with radial_velocity",
             "either a translation (velocity) or a radial motion (centre, radial_velocity)");
    }
    w.radial = true;
    w.centre = r.vec2("centre");
    w.radial_velocity = r.schedule("radial_velocity", 2);
  } else {
    w.velocity = r.schedule("velocity", 3);
  }
  r.finish();
  return w;
}

RigidBody read_rigid_body(const std::string& name, SectionReader& r) {
  RigidBody rb;
  rb.name = name;
  rb.outline = read_polygon(r, "vertices");
  rb.velocity = r.schedule("velocity", 3);
  rb.surface = value_named(r.choice("surface", names_of(kSurfaceNames), "rough"), kSurfaceNames);
  if (rb.surface == Surface::friction) {
    rb.friction = r.number("friction", non_negative("a friction coefficient mu (-)"));
  }
  r.finish();
  return rb;
}

Load read_load(const std::string& name, SectionReader& r) {
  Load l;
  l.name = name;
  l.body = r.string("body");
  l.min = r.vec2("min");
  l.max = r.vec2("max");
  if (!(l.max.x() >= l.min.x() && l.max.y() >= l.min.y())) {
    r.fail("max", "below or left of min", "a box with max >= min (m)");
  }
  l.force = r.schedule("force", 3);
  if (l.force.empty()) r.fail("force", "missing key", "a schedule [[t, fx, fy], ...] (N/m)");
  r.finish();
  return l;
}

Measure read_measure(const std::string& name, SectionReader& r) {
  Measure m;
  m.name = name;
  m.kind =
      value_named(r.choice("kind", names_of(kMeasureKindNames), std::nullopt), kMeasureKindNames);
  if (m.kind != MeasureKind::safety_factor) m.target = r.string("target");
  switch (m.kind) {
    case MeasureKind::reaction:
    case MeasureKind::wall_stress:
    case MeasureKind::displacement:
      m.component = r.choice("component", {"x", "y", "magnitude"}, std::nullopt);
      break;
    case MeasureKind::max_displacement:
      m.component = r.choice("component", {"x", "y", "magnitude"}, "magnitude");
      break;
    case MeasureKind::point_displacement:
      m.component = r.choice("component", {"x", "y", "magnitude"}, std::nullopt);
      m.point = r.vec2("point");
      break;
    case MeasureKind::period:
      m.component = r.choice("component", {"x", "y"}, std::nullopt);
      break;
    default:
      break;
  }
  m.at = value_named(r.choice("at", names_of(kMeasureAtNames), "end"), kMeasureAtNames);
  if (m.at == MeasureAt::time) {
    m.time = r.number("time", non_negative("a time (s)"));
    m.window = r.number("window", 0.0, non_negative("a duration (s)"));
  }
  if (m.at == MeasureAt::curve) {
    m.abscissa = r.string("abscissa");
    m.x_window = r.vec2("x_window");
    if (!(m.x_window.y() > m.x_window.x())) {
      r.fail("x_window", "not increasing", "[from, to] with to > from (the abscissa's unit)");
    }
  }
  if (m.kind == MeasureKind::front) {
    m.min_thickness = r.number("min_thickness", 0.0, non_negative("a count of spacings"));
    m.min_depth = r.number("min_depth", 0.0, non_negative("a depth (m)"));
    m.column_width = r.number("column_width", 0.0, non_negative("a width (m)"));
    if (m.min_thickness > 0.0 && m.min_depth > 0.0) {
      r.fail("min_depth", "given with min_thickness", "one of them: spacings or metres");
    }
  }
  m.divide_by = r.string("divide_by", "");
  m.scale = r.number("scale", 1.0, any_number());
  r.finish();
  return m;
}

/// A reference value, or a curve: `points` as given, else read from the CSV file `curve`
/// (relative to the scene file's folder) and written into the resolved scene as `points`, so a
/// run's own copy of its scene (run.h5, --resume) carries the curve it was scored against.
Reference read_reference(const std::string& measure, SectionReader& r,
                         const std::string& scene_file) {
  Reference ref;
  ref.measure = measure;
  if (r.has("value")) ref.value = r.number("value", any_number());
  if (r.has("curve")) {
    ref.curve_file = r.string("curve");
    if (!r.has("points")) {
      std::filesystem::path file(ref.curve_file);
      if (file.is_relative()) file = std::filesystem::path(scene_file).parent_path() / file;
      try {
        ref.curve = read_reference_csv(file.lexically_normal().string());
      } catch (const InputError& e) {
        r.fail("curve", e.what(), "a CSV file of x, y beside the scene (a path relative to it)");
      }
      toml::array resolved;
      for (const Vec2& p : ref.curve) resolved.push_back(toml::array{p.x(), p.y()});
      r.resolved().insert_or_assign("points", std::move(resolved));
    }
  }
  if (r.has("points")) {
    ref.curve = r.points("points", 2);
    for (std::size_t k = 1; k < ref.curve.size(); ++k) {
      if (!(ref.curve[k].x() > ref.curve[k - 1].x())) {
        r.fail("points", "x not increasing at point " + std::to_string(k + 1),
               "points [x, y] with x increasing");
      }
    }
  }
  if (r.has("value") == !ref.curve.empty()) {
    r.fail(ref.curve.empty() ? "value" : "curve",
           ref.curve.empty() ? "missing key" : "given with value",
           "either a value or a curve (a CSV file of x, y)");
  }
  if (!ref.curve.empty()) {
    ref.holds = r.vec2("holds", Vec2(ref.curve.front().x(), ref.curve.back().x()));
    if (!(ref.holds.x() >= ref.curve.front().x() && ref.holds.y() <= ref.curve.back().x() &&
          ref.holds.y() > ref.holds.x())) {
      r.fail("holds", "outside the curve's x or not increasing",
             "[from, to] within the curve's first and last x");
    }
  }
  ref.source = r.string("source");
  if (trim(ref.source).empty()) r.fail("source", "empty", "where the value comes from");
  ref.tolerance = r.number("tolerance", 0.0, non_negative("a relative tolerance (-)"));
  ref.error = r.number("error", 0.0, non_negative("the reference's own relative error (-)"));
  r.finish();
  return ref;
}

InitialStress read_initial_stress(SectionReader& r) {
  InitialStress s;
  s.kind = value_named(r.choice("kind", names_of(kInitialStressKindNames), "none"),
                       kInitialStressKindNames);
  if (s.kind == InitialStressKind::isotropic) {
    s.pressure = r.number("pressure", positive("a compressive pressure (Pa)"));
  } else if (s.kind == InitialStressKind::geostatic) {
    s.K0 = r.number("K0", positive("an earth pressure coefficient at rest (-)"));
  } else if (s.kind == InitialStressKind::gravity_loading) {
    s.damping = r.number("damping", positive("a damping coefficient (1/s)"));
    s.time = r.number("time", positive("a duration (s)"));
  }
  r.finish();
  return s;
}

SphOptions read_sph(SectionReader& r) {
  SphOptions o;
  // Each choice's default is the struct's (common/scene.hpp), through the enum's name table.
  o.kernel = read_named(r, "kernel", o.kernel, kSphKernelNames);
  o.h_over_dp = r.number("h_over_dp", o.h_over_dp, positive("a ratio h/dp (-)"));
  o.alpha = r.number("alpha", o.alpha, non_negative("an artificial viscosity coefficient (-)"));
  o.beta = r.number("beta", o.beta, non_negative("an artificial viscosity coefficient (-)"));
  o.artificial_stress = r.number("artificial_stress", o.artificial_stress,
                                 non_negative("an artificial stress coefficient (-)"));
  o.cfl = r.number("cfl", o.cfl, positive("a Courant number (-)"));
  o.sound_speed = r.number("sound_speed", o.sound_speed, positive("a speed (m/s)"));
  o.wall_treatment = r.choice("wall_treatment", {"dummy"}, o.wall_treatment);
  o.dummy_layers = r.integer("dummy_layers", o.dummy_layers, 1);
  o.wall_stress = read_named(r, "wall_stress", o.wall_stress, kSphWallStressNames);
  o.dummy_velocity = read_named(r, "dummy_velocity", o.dummy_velocity, kSphDummyVelocityNames);
  o.integrator = read_named(r, "integrator", o.integrator, kSphIntegratorNames);
  o.continuity = r.boolean("continuity", o.continuity);
  r.finish();
  return o;
}

SpfemOptions read_spfem(SectionReader& r) {
  SpfemOptions o;
  o.alpha_factor = r.number("alpha_factor", o.alpha_factor, positive("a multiple of dp (-)"));
  o.min_edge_factor =
      r.number("min_edge_factor", o.min_edge_factor, in_closed(0.0, 0.5, "a fraction of dp (-)"));
  o.time_step_safety =
      r.number("time_step_safety", o.time_step_safety, positive("a safety factor (-)"));
  o.time_step = read_named(r, "time_step", o.time_step, kSpfemTimeStepNames);
  o.damping = r.number("damping", o.damping, non_negative("a damping coefficient (1/s)"));
  o.local_damping = r.number("local_damping", o.local_damping,
                             in_closed(0.0, 1.0, "a local damping coefficient (-)"));
  o.stabilisation =
      r.number("stabilisation", o.stabilisation, non_negative("a stabilisation weight (-)"));
  o.stiffness_stabilisation = r.number("stiffness_stabilisation", o.stiffness_stabilisation,
                                       non_negative("a stiffness stabilisation coefficient (-)"));
  o.bulk_viscosity = r.number("bulk_viscosity", o.bulk_viscosity,
                              in_closed(0.0, 1.0, "a linear bulk viscosity (-)"));
  o.stress_increment_limit = r.number("stress_increment_limit", o.stress_increment_limit,
                                      non_negative("a relative stress increment per step (-)"));
  o.remesh = read_named(r, "remesh", o.remesh, kRemeshNames);
  o.remesh_angle = r.number("remesh_angle", o.remesh_angle, in_closed(0.0, 90.0, "an angle (deg)"));
  o.remesh_angle_fraction =
      r.number("remesh_angle_fraction", o.remesh_angle_fraction,
               in_closed(0.0, 1.0, "a fraction of a triangle's angle at its remesh (-)"));
  o.boundary_layer = r.boolean("boundary_layer", o.boundary_layer);
  // Below 1.2 dp a row of nodes as sampled (dp apart) would be split at once.
  o.wall_node_gap = r.number("wall_node_gap", o.wall_node_gap, [](double v) {
    return v == 0.0 || (v >= 1.2 && v <= 3.0)
               ? std::string()
               : std::string("0 (off) or a multiple of dp in [1.2, 3] (-)");
  });
  r.finish({"implicit"});
  return o;
}

SpfemImplicitOptions read_implicit(SectionReader& r) {
  SpfemImplicitOptions o;
  o.tolerance = r.number("tolerance", o.tolerance, positive("a relative residual (-)"));
  o.displacement_tolerance = r.number("displacement_tolerance", o.displacement_tolerance,
                                      positive("a relative displacement correction (-)"));
  o.max_iterations = r.integer("max_iterations", o.max_iterations, 1);
  o.load_steps = r.integer("load_steps", o.load_steps, 1);
  o.increment = r.number("increment", o.increment,
                         non_negative("an increment of the scene's time (s); 0: from load_steps"));
  o.adaptive = r.boolean("adaptive", o.adaptive);
  o.easy_iterations = r.integer("easy_iterations", o.easy_iterations, 1);
  o.max_step_cuts = r.integer("max_step_cuts", o.max_step_cuts, 0);
  o.active_set_passes = r.integer("active_set_passes", o.active_set_passes, 1);
  o.min_area_ratio = r.number("min_area_ratio", o.min_area_ratio,
                              in_closed(0.0, 0.99, "a fraction of a triangle's area (-)"));
  o.increment_stabilisation = r.number("increment_stabilisation", o.increment_stabilisation,
                                       non_negative("an increment stabilisation coefficient (-)"));
  o.load_drop = r.number("load_drop", o.load_drop,
                         in_closed(0.0, 0.99, "a fraction of a driven boundary's peak load (-)"));
  o.refuse_snaps =
      r.choice("snap", {"warn", "refuse"}, o.refuse_snaps ? "refuse" : "warn") == "refuse";
  o.extrapolate = r.choice("predictor", {"extrapolated", "none"},
                           o.extrapolate ? "extrapolated" : "none") == "extrapolated";
  o.newmark = r.choice("dynamics", {"quasi-static", "newmark"},
                       o.newmark ? "newmark" : "quasi-static") == "newmark";
  r.finish();
  return o;
}

/// Reads every [kind.<name>] table of a collection with `read(name, reader)`.
template <typename T, typename Read>
std::vector<T> read_collection(SectionReader& root, const std::string& kind,
                               const std::vector<std::string>& keys, const SceneSource& source,
                               toml::table& resolved, Read read) {
  std::vector<T> out;
  const toml::table* table = root.table(kind);
  if (!table) return out;
  toml::table& resolved_kind = resolved_child(resolved, kind);
  for (const auto& [k, v] : *table) {
    const std::string name(k.str());
    SectionReader r(v.as_table(), kind + "." + name, keys, source,
                    resolved_child(resolved_kind, name));
    if (!v.is_table()) {
      r.fail("", "wrong type: " + describe_type(v), "a table [" + kind + "." + name + "]");
    }
    out.push_back(read(name, r));
  }
  return out;
}

/// Default domain: the bounding box of bodies, walls and rigid bodies, padded.
void fill_domain(Scene& scene, SectionReader& r) {
  std::vector<Vec2> points;
  for (const Body& b : scene.bodies)
    points.insert(points.end(), b.outline.begin(), b.outline.end());
  for (const Wall& w : scene.walls) points.insert(points.end(), w.points.begin(), w.points.end());
  for (const RigidBody& rb : scene.rigid_bodies) {
    points.insert(points.end(), rb.outline.begin(), rb.outline.end());
  }
  Vec2 lo, hi;
  bounding_box(points, lo, hi);
  const double extent = (hi - lo).maxCoeff();
  // Default padding: a quarter of the scene's larger extent (room for run-out beyond the walls).
  scene.domain.padding = r.number("padding", 0.25 * extent, non_negative("a length (m)"));
  if (r.has("min") || r.has("max")) {
    scene.domain.min = r.vec2("min");
    scene.domain.max = r.vec2("max");
    if (!(scene.domain.max.x() > scene.domain.min.x() &&
          scene.domain.max.y() > scene.domain.min.y())) {
      r.fail("max", "not above and to the right of min", "max > min in x and in y (m)");
    }
  } else {
    scene.domain.min = r.vec2("min", lo - Vec2::Constant(scene.domain.padding));
    scene.domain.max = r.vec2("max", hi + Vec2::Constant(scene.domain.padding));
  }
  r.finish();
}

Scene read_scene(const toml::table& root, const SceneSource& source, const MaterialCheck& check) {
  Scene scene;
  scene.path = source.file;
  toml::table resolved;
  SectionReader r(&root, "", kRootKeys, source, resolved);
  auto section = [&](const std::string& key, const std::vector<std::string>& keys) {
    return SectionReader(r.table(key), key, keys, source, resolved_child(resolved, key));
  };

  scene.name = r.string("name", std::filesystem::path(source.file).stem().string());
  scene.description = r.string("description", "");
  scene.spacing = r.number("spacing", positive("a particle spacing (m)"));
  scene.gravity = r.vec2("gravity", Vec2::Zero());
  scene.confined = r.boolean("confined", false);
  scene.formulation = read_named(r, "formulation", scene.formulation, kFormulationNames);

  SectionReader time = section("time", kTimeKeys);
  scene.time.end_time = time.number("end_time", positive("an end time (s)"));
  scene.time.output_interval = time.number("output_interval", scene.time.end_time / 50.0,
                                           positive("an output interval (s)"));
  if (scene.time.output_interval > scene.time.end_time) {
    time.fail("output_interval", "longer than end_time", "an interval <= end_time (s)");
  }
  time.finish();

  SectionReader initial = section("initial_stress", kInitialStressKeys);
  scene.initial_stress = read_initial_stress(initial);

  SectionReader reduction = section("strength_reduction", kStrengthReductionKeys);
  scene.strength_reduction.factor =
      reduction.number("factor", 1.0, positive("a strength reduction factor (-)"));
  scene.strength_reduction.rule = reduction.choice("rule", {"tangent", "angle"}, "tangent");
  scene.strength_reduction.stage =
      reduction.choice("stage", {"after-loading", "throughout"}, "after-loading");
  scene.strength_reduction.ramp =
      reduction.number("ramp", 0.0, non_negative("a time (s) over which the strength falls"));
  if (scene.strength_reduction.ramp > 0.0) {
    if (scene.strength_reduction.stage != "after-loading") {
      reduction.fail("ramp", "a ramp with stage = \"throughout\" (nothing changes in the run)",
                     "stage = \"after-loading\", or no ramp");
    }
    if (scene.strength_reduction.ramp >= scene.time.end_time) {
      reduction.fail("ramp", "the strength would not reach c / f before time.end_time",
                     "a ramp shorter than the run (s)");
    }
  }
  reduction.finish();

  SectionReader checks = section("checks", kCheckKeys);
  scene.checks.kinetic_energy_factor =
      checks.number("kinetic_energy_factor", scene.checks.kinetic_energy_factor,
                    non_negative("a multiple of the energy put in (0: off)"));
  scene.checks.lift_off_fraction =
      checks.number("lift_off_fraction", scene.checks.lift_off_fraction,
                    in_closed(0.0, 1.0, "a fraction (0: off)"));
  scene.checks.lift_off_distance = checks.number(
      "lift_off_distance", scene.checks.lift_off_distance, positive("a count of spacings"));
  checks.finish();

  // Materials first: bodies refer to them.
  if (const toml::table* materials = r.table("material")) {
    toml::table& resolved_materials = resolved_child(resolved, "material");
    for (const auto& [k, v] : *materials) {
      const std::string name(k.str());
      scene.materials.push_back(read_material(name, v, scene.strength_reduction, source, check,
                                              resolved_child(resolved_materials, name)));
    }
  }
  scene.bodies = read_collection<Body>(r, "body", kBodyKeys, source, resolved,
                                       [&](const std::string& name, SectionReader& b) {
                                         return read_body(name, b, scene.materials);
                                       });
  if (scene.bodies.empty()) {
    r.fail("body", "no body in the scene", "at least one [body.<name>] table");
  }
  scene.walls = read_collection<Wall>(r, "wall", kWallKeys, source, resolved, read_wall);
  scene.rigid_bodies =
      read_collection<RigidBody>(r, "rigid_body", kRigidKeys, source, resolved, read_rigid_body);
  scene.loads = read_collection<Load>(r, "load", kLoadKeys, source, resolved, read_load);
  for (Load& l : scene.loads) {
    for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
      if (scene.bodies[b].name == l.body) l.body_index = static_cast<int>(b);
    }
  }
  scene.measures =
      read_collection<Measure>(r, "measure", kMeasureKeys, source, resolved, read_measure);
  scene.references =
      read_collection<Reference>(r, "reference", kReferenceKeys, source, resolved,
                                 [&](const std::string& measure, SectionReader& ref) {
                                   return read_reference(measure, ref, source.file);
                                 });

  SectionReader domain = section("domain", kDomainKeys);
  fill_domain(scene, domain);

  SectionReader sph = section("sph", kSphKeys);
  scene.sph = read_sph(sph);
  SectionReader spfem = section("spfem", kSpfemKeys);
  scene.spfem = read_spfem(spfem);
  SectionReader implicit(spfem.table("implicit"), "spfem.implicit", kImplicitKeys, source,
                         resolved_child(resolved_child(resolved, "spfem"), "implicit"));
  scene.spfem_implicit = read_implicit(implicit);

  r.finish({"time", "domain", "initial_stress", "strength_reduction", "checks", "material", "body",
            "wall", "rigid_body", "load", "measure", "reference", "sph", "spfem"});

  std::ostringstream text;
  text << "# " << scene.name << ": resolved scene (every default filled in)\n" << resolved << "\n";
  scene.resolved_toml = text.str();
  return scene;
}

}  // namespace

Scene load_scene_from_string(const std::string& toml_text, const std::string& path,
                             const std::vector<std::string>& overrides,
                             const MaterialCheck& check) {
  SceneSource source;
  source.file = path;
  toml::table root;
  try {
    root = toml::parse(toml_text, path);
  } catch (const toml::parse_error& e) {
    throw InputError(path + ":" + std::to_string(e.source().begin.line) + ": " +
                     std::string(e.description()) + "; expected valid TOML");
  }
  for (const std::string& o : overrides) apply_override(root, o, source);
  Scene scene = read_scene(root, source, check);
  validate_scene(scene, root, source);
  return scene;
}

Scene load_scene(const std::string& path, const std::vector<std::string>& overrides,
                 const MaterialCheck& check) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path + ": cannot open the scene file; expected a readable TOML file");
  std::ostringstream text;
  text << file.rdbuf();
  return load_scene_from_string(text.str(), path, overrides, check);
}

}  // namespace duet
