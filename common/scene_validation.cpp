#include "common/scene_validation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <sstream>
#include <utility>

#include "common/geometry.hpp"
#include "common/input_error.hpp"
#include "common/lattice.hpp"
#include "common/suggest.hpp"

namespace duet {

namespace {

std::string point_text(const Vec2& p) {
  std::ostringstream out;
  out.precision(6);
  out << "(" << p.x() << ", " << p.y() << ")";
  return out.str();
}

std::string length_text(double metres) {
  std::ostringstream out;
  out.precision(3);
  out << metres << " m";
  return out.str();
}

/// The part of the segment [a, b] inside the box [lo, hi] (Liang-Barsky), false when none.
bool clip_to_box(Vec2& a, Vec2& b, const Vec2& lo, const Vec2& hi) {
  double t0 = 0.0, t1 = 1.0;
  const Vec2 d = b - a;
  for (int k = 0; k < 2; ++k) {
    for (const auto& [p, q] : {std::pair{-d[k], a[k] - lo[k]}, std::pair{d[k], hi[k] - a[k]}}) {
      if (p == 0.0) {
        if (q < 0.0) return false;
        continue;
      }
      const double r = q / p;
      if (p < 0.0) t0 = std::max(t0, r);
      if (p > 0.0) t1 = std::min(t1, r);
    }
  }
  if (t0 > t1) return false;
  const Vec2 start = a + t0 * d;
  b = a + t1 * d;
  a = start;
  return true;
}

/// The point of a polyline deepest inside a polygon (the farthest from its outline among the
/// polyline's samples strictly inside it, taken every `step` along each segment's part within
/// the polygon's bounding box, and no closer than the polyline's length / 10^4, so that the
/// whole polyline takes about 10^4 samples at most: a load stays well under a second at any
/// spacing, the sanitizer build included), and its depth; depth 0 when no sample lies inside.
/// The distance to the outline changes by at most the samples' spacing between them, so the
/// depth found is within half of it of the true one.
struct DeepestPoint {
  double depth = 0.0;
  Vec2 point = Vec2::Zero();
};

DeepestPoint deepest_point_inside(std::span<const Vec2> polyline, std::span<const Vec2> polygon,
                                  double step) {
  Vec2 lo, hi;
  bounding_box(polygon, lo, hi);
  step = std::max(step, 1e-4 * polyline_length(polyline));
  DeepestPoint deepest;
  for (std::size_t s = 0; s + 1 < polyline.size(); ++s) {
    Vec2 a = polyline[s];
    Vec2 b = polyline[s + 1];
    if (!clip_to_box(a, b, lo, hi)) continue;
    const int n = static_cast<int>(std::clamp(std::ceil((b - a).norm() / step), 1.0, 1e4));
    for (int k = 0; k <= n; ++k) {
      const Vec2 p = a + (b - a) * (static_cast<double>(k) / n);
      if (!point_in_polygon(p, polygon)) continue;
      const double depth = polygon_boundary_distance(p, polygon);
      if (depth > deepest.depth) deepest = {depth, p};
    }
  }
  return deepest;
}

/// Particles of each body within `reach` of a wall segment that project onto it, on the
/// segment's left and right (the count by which SPH and SPFEM orient the segment).
struct SideCounts {
  std::vector<int> left, right;
};

SideCounts side_counts(const Vec2& a, const Vec2& b, const Particles& particles,
                       std::size_t n_bodies, double reach) {
  SideCounts counts{std::vector<int>(n_bodies, 0), std::vector<int>(n_bodies, 0)};
  const Vec2 t = (b - a).normalized();
  const Vec2 n(-t.y(), t.x());  // the left normal
  const double length = (b - a).norm();
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const double u = (particles.position[i] - a).dot(t);
    const double d = (particles.position[i] - a).dot(n);
    if (u < 0.0 || u > length || std::abs(d) > reach) continue;
    (d >= 0.0 ? counts.left : counts.right)[static_cast<std::size_t>(particles.body[i])] += 1;
  }
  return counts;
}

class Checker {
 public:
  Checker(const Scene& scene, const toml::table& root, const SceneSource& source)
      : scene_(scene), root_(root), source_(source) {}

  [[noreturn]] void fail(const std::string& key, const std::string& problem,
                         const std::string& expected) const {
    const toml::node* node = root_.at_path(key).node();
    // A missing key: point at the nearest enclosing table that exists.
    std::string parent = key;
    while (!node && parent.find('.') != std::string::npos) {
      parent = parent.substr(0, parent.rfind('.'));
      node = root_.at_path(parent).node();
    }
    throw InputError(source_.where(key, node) + ": " + key + ": " + problem + "; expected " +
                     expected);
  }

  void bodies_inside_domain() const {
    const Domain& d = scene_.domain;
    const double tolerance = 1e-9 * (d.max - d.min).norm();
    for (const Body& b : scene_.bodies) {
      for (const Vec2& p : b.outline) {
        if (p.x() < d.min.x() - tolerance || p.y() < d.min.y() - tolerance ||
            p.x() > d.max.x() + tolerance || p.y() > d.max.y() + tolerance) {
          fail("body." + b.name, "the point " + point_text(p) + " lies outside the domain",
               "a body inside the domain " + point_text(d.min) + " - " + point_text(d.max));
        }
      }
    }
  }

  /// Axisymmetric scenes: the bodies on the side x >= 0 of the axis (a wall or rigid body may
  /// reach across it: no particle goes there), gravity along it, and a body
  /// that reaches the axis held on it by a symmetry wall (u_r = 0 at r = 0; the particles nearest
  /// the axis stand dp / 2 off it, and only the hoop stiffness would otherwise keep them there).
  void axisymmetric_half_plane() const {
    if (scene_.formulation != Formulation::axisymmetric) return;
    if (scene_.gravity.x() != 0.0) {
      fail("gravity",
           "has a radial component " + std::to_string(scene_.gravity.x()) +
               " m/s^2 in an axisymmetric scene",
           "gravity along the axis, [0.0, g]");
    }
    const double tolerance = 1e-9 * (scene_.domain.max - scene_.domain.min).norm();
    const auto left_of_axis = [&](const std::vector<Vec2>& outline, const std::string& key) {
      for (const Vec2& p : outline) {
        if (p.x() < -tolerance) {
          fail(key, "the point " + point_text(p) + " lies at r = x < 0",
               "an axisymmetric scene drawn at x = r >= 0 (the axis is x = 0)");
        }
      }
    };
    for (const Body& b : scene_.bodies) left_of_axis(b.outline, "body." + b.name);
    // A load is shared equally by its particles (common/scene_loads.hpp), which about an axis
    // would put the same force on a ring at r = dp / 2 as on one ten times as large
    for (const Load& l : scene_.loads) {
      fail("load." + l.name,
           "a load in an axisymmetric scene (its equal share per particle does "
           "not follow the rings' sizes)",
           "a plane-strain scene for loads, or a rigid body or wall to drive an axisymmetric one");
    }
    bool axis_wall = false;
    for (const Wall& w : scene_.walls) {
      bool on_axis = w.condition == WallCondition::symmetry && !w.radial;
      for (const Vec2& p : w.points) on_axis = on_axis && std::abs(p.x()) <= tolerance;
      axis_wall = axis_wall || on_axis;
    }
    for (const Body& b : scene_.bodies) {
      if (b.min.x() < scene_.spacing && !axis_wall) {
        fail("body." + b.name,
             "reaches the axis (x = " + length_text(b.min.x()) + ") with no symmetry wall along it",
             "a wall on x = 0 with condition = \"symmetry\" (points = [[0.0, y0], [0.0, y1]])");
      }
    }
  }

  void no_overlaps() const {
    const auto& bodies = scene_.bodies;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      for (std::size_t j = i + 1; j < bodies.size(); ++j) {
        if (polygons_overlap(bodies[i].outline, bodies[j].outline)) {
          fail("body." + bodies[j].name, "overlaps body '" + bodies[i].name + "'",
               "bodies that touch at most along their edges");
        }
      }
    }
    for (const RigidBody& rb : scene_.rigid_bodies) {
      for (const Body& b : bodies) {
        if (polygons_overlap(rb.outline, b.outline)) {
          fail("rigid_body." + rb.name, "lies inside soil body '" + b.name + "'",
               "a rigid body outside the soil (it may touch its surface)");
        }
      }
    }
  }

  /// The mean of the body's lowest vertices along gravity.
  Vec2 lowest_point(const Body& b) const {
    const Vec2 down = scene_.gravity.normalized();
    double deepest = -std::numeric_limits<double>::infinity();
    for (const Vec2& p : b.outline) deepest = std::max(deepest, p.dot(down));
    const double tolerance = 1e-9 * (b.max - b.min).norm();
    Vec2 sum = Vec2::Zero();
    int n = 0;
    for (const Vec2& p : b.outline) {
      if (p.dot(down) >= deepest - tolerance) {
        sum += p;
        ++n;
      }
    }
    return sum / n;
  }

  void bodies_supported() const {
    if (scene_.gravity.norm() == 0.0) return;
    const auto& bodies = scene_.bodies;
    const double reach = scene_.spacing * (1.0 + 1e-9);
    std::vector<bool> supported(bodies.size(), false);
    std::vector<Vec2> lowest(bodies.size());
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      lowest[i] = lowest_point(bodies[i]);
      supported[i] = distance_to_walls(scene_, lowest[i]) <= reach;
    }
    // Bodies resting on supported bodies are supported too.
    for (bool changed = true; changed;) {
      changed = false;
      for (std::size_t i = 0; i < bodies.size(); ++i) {
        if (supported[i]) continue;
        for (std::size_t j = 0; j < bodies.size(); ++j) {
          if (supported[j] && polygon_boundary_distance(lowest[i], bodies[j].outline) <= reach) {
            supported[i] = changed = true;
            break;
          }
        }
      }
    }
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      if (!supported[i]) {
        fail("body." + bodies[i].name,
             "rests on no wall under gravity (its lowest point " + point_text(lowest[i]) +
                 " has no wall, rigid body or supported body within one spacing)",
             "a [wall.<name>] under the body, e.g. a floor");
      }
    }
  }

  void bodies_enclosed() const {
    if (!scene_.confined) return;
    const double reach = scene_.spacing * (1.0 + 1e-9);
    for (const Body& b : scene_.bodies) {
      const std::size_t n = b.outline.size();
      for (std::size_t i = 0; i < n; ++i) {
        const Vec2& a = b.outline[i];
        const Vec2& c = b.outline[(i + 1) % n];
        if (distance_to_walls(scene_, 0.5 * (a + c)) > reach) {
          fail("body." + b.name,
               "is not enclosed although confined = true: its side " + point_text(a) + " - " +
                   point_text(c) + " has no wall within one spacing",
               "walls along every side of a confined body");
        }
      }
    }
  }

  /// No wall passes through a body by more than half a spacing (the lattice's outer row lies dp/2
  /// inside the drawn edge, so a wall within that depth has no particle beyond it), unless the
  /// body says it is meant (crosses_walls).
  void walls_outside_bodies() const {
    const double dp = scene_.spacing;
    for (const Body& b : scene_.bodies) {
      if (b.crosses_walls) continue;
      for (const Wall& w : scene_.walls) {
        const DeepestPoint in = deepest_point_inside(w.points, b.outline, 0.1 * dp);
        if (in.depth <= 0.5 * dp) continue;
        fail("body." + b.name,
             "wall '" + w.name + "' passes through the body: its point " + point_text(in.point) +
                 " lies " + length_text(in.depth) +
                 " inside the body's outline (more than half a spacing, " + length_text(0.5 * dp) +
                 ")",
             "each wall on one side of the body, touching it at most along its edge (or "
             "crosses_walls = true in [body." +
                 b.name + "] if the wall is meant to cut it)");
      }
    }
  }

  /// Each segment of a wall holds soil on one side: the side with more particles within reach
  /// (SPH orients it by the soil within its kernel's support 2h, SPFEM within 2 dp; sph/walls.cpp,
  /// spfem/node_contact.cpp). A body with particles on the other side lies beyond the wall: the
  /// methods put the wall's dummy particles or contact there. Scenes over 2 million particles
  /// are not sampled here (the crossing check above still holds for them).
  void bodies_on_soil_side() const {
    if (scene_.walls.empty() || estimated_particles(scene_) > 2.0e6) return;
    const Particles particles = sample_bodies(scene_);
    const double reach = std::max(2.0, 2.0 * scene_.sph.h_over_dp) * scene_.spacing;
    const std::size_t n_bodies = scene_.bodies.size();
    for (const Wall& w : scene_.walls) {
      for (std::size_t s = 0; s + 1 < w.points.size(); ++s) {
        const Vec2& a = w.points[s];
        const Vec2& c = w.points[s + 1];
        const SideCounts counts = side_counts(a, c, particles, n_bodies, reach);
        int left = 0, right = 0;
        for (std::size_t k = 0; k < n_bodies; ++k) {
          left += counts.left[k];
          right += counts.right[k];
        }
        if (left == right) continue;  // no soil, or a tie the methods settle by the neighbours
        const std::vector<int>& beyond = left > right ? counts.right : counts.left;
        const std::vector<int>& held = left > right ? counts.left : counts.right;
        for (std::size_t k = 0; k < n_bodies; ++k) {
          if (beyond[k] == 0 || scene_.bodies[k].crosses_walls) continue;
          fail_beyond(w, a, c, k, beyond[k], held);
        }
      }
    }
  }

  [[noreturn]] void fail_beyond(const Wall& w, const Vec2& a, const Vec2& c, std::size_t body,
                                int n_beyond, const std::vector<int>& held) const {
    std::size_t most = 0;
    for (std::size_t k = 0; k < held.size(); ++k) {
      if (held[k] > held[most]) most = k;
    }
    const std::string name = scene_.bodies[body].name;
    fail("body." + name,
         "lies beyond wall '" + w.name + "': " + std::to_string(n_beyond) +
             " of its particles near the wall's segment " + point_text(a) + " - " + point_text(c) +
             " are on its far side, away from the soil it holds (body '" +
             scene_.bodies[most].name + "', " + std::to_string(held[most]) + " particles)",
         "the body on the soil's side of every wall (or crosses_walls = true in [body." + name +
             "] if it is meant)");
  }

  /// A body must sample to enough particles to be a body at all: at 0 or 1 particles every
  /// measure of it is empty or NaN and no method has a gradient to compute.
  void bodies_resolved() const {
    constexpr std::size_t minimum = 4;
    const double dp = scene_.spacing;
    for (std::size_t i = 0; i < scene_.bodies.size(); ++i) {
      const Body& b = scene_.bodies[i];
      // Count only where it could fail (a large body is not visited cell by cell here).
      if (std::abs(signed_area(b.outline)) / (dp * dp) > 100.0 * minimum) continue;
      const std::size_t n = count_body_samples(scene_, i);
      if (n >= minimum) continue;
      const Vec2 size = b.max - b.min;
      std::ostringstream what;
      what.precision(6);
      what << "samples to " << n << " particle" << (n == 1 ? "" : "s") << " at spacing " << dp
           << " m (the body spans " << size.x() << " m x " << size.y() << " m)";
      std::ostringstream expected;
      expected.precision(3);
      expected << "at least " << minimum << " particles per body: a spacing of at most "
               << std::min(size.x(), size.y()) / 2.0 << " m, or a larger body";
      fail("body." + b.name, what.str(), expected.str());
    }
  }

  void names() const {
    std::vector<std::string> bodies, boundaries, walls, radial_walls;
    for (const Body& b : scene_.bodies) bodies.push_back(b.name);
    for (const Wall& w : scene_.walls) {
      walls.push_back(w.name);
      if (w.radial) radial_walls.push_back(w.name);
    }
    boundaries = walls;
    for (const RigidBody& rb : scene_.rigid_bodies) boundaries.push_back(rb.name);
    auto require_name = [&](const std::string& key, const std::string& name,
                            const std::vector<std::string>& candidates, const std::string& what) {
      if (std::find(candidates.begin(), candidates.end(), name) != candidates.end()) return;
      fail(key, "unknown " + what + " \"" + name + "\"" + did_you_mean(name, candidates),
           candidates.empty() ? "a " + what + " of the scene" : "one of " + join(candidates));
    };
    std::vector<std::string> measures;
    for (const Measure& m : scene_.measures) {
      measures.push_back(m.name);
      const std::string key = "measure." + m.name + ".target";
      switch (m.kind) {
        case MeasureKind::safety_factor:
          break;
        case MeasureKind::front:
        case MeasureKind::height:
        case MeasureKind::period:
        case MeasureKind::max_displacement:
        case MeasureKind::point_displacement:
          require_name(key, m.target, bodies, "body");
          break;
        case MeasureKind::wall_stress:
          require_name(key, m.target, walls, "wall");
          break;
        case MeasureKind::expansion:
          require_name(key, m.target, radial_walls, "wall with radial_velocity");
          break;
        default:
          require_name(key, m.target, boundaries, "wall or rigid body");
          break;
      }
    }
    for (const Measure& m : scene_.measures) {
      if (m.divide_by.empty()) continue;
      std::vector<std::string> others;
      for (const std::string& n : measures) {
        if (n != m.name) others.push_back(n);
      }
      require_name("measure." + m.name + ".divide_by", m.divide_by, others, "measure");
    }
    for (const Measure& m : scene_.measures) {
      if (m.at != MeasureAt::curve) continue;
      std::vector<std::string> others;
      for (const Measure& o : scene_.measures) {
        if (o.name != m.name && o.at != MeasureAt::curve) others.push_back(o.name);
      }
      require_name("measure." + m.name + ".abscissa", m.abscissa, others,
                   "measure (not itself a curve)");
    }
    for (const Reference& r : scene_.references) {
      require_name("reference." + r.measure, r.measure, measures, "measure");
      if (r.curve.empty()) continue;
      const Measure& m = *std::find_if(scene_.measures.begin(), scene_.measures.end(),
                                       [&](const Measure& x) { return x.name == r.measure; });
      if (m.at != MeasureAt::curve) {
        fail("reference." + r.measure + ".curve",
             "scores measure." + m.name + ", which is not a curve",
             "a measure with at = \"curve\" (its abscissa and x_window)");
      }
      if (m.x_window.x() < r.holds.x() || m.x_window.y() > r.holds.y()) {
        std::ostringstream what;
        what << "measure." << m.name << ".x_window [" << m.x_window.x() << ", " << m.x_window.y()
             << "] reaches outside the window where the curve holds [" << r.holds.x() << ", "
             << r.holds.y() << "]";
        fail("measure." + m.name + ".x_window", what.str(), "a window inside the reference's");
      }
    }
    for (const Load& l : scene_.loads)
      require_name("load." + l.name + ".body", l.body, bodies, "body");
  }

 private:
  const Scene& scene_;
  const toml::table& root_;
  const SceneSource& source_;
};

}  // namespace

void validate_scene(const Scene& scene, const toml::table& root, const SceneSource& source) {
  const Checker check(scene, root, source);
  check.bodies_inside_domain();
  check.bodies_resolved();
  check.axisymmetric_half_plane();
  check.no_overlaps();
  check.walls_outside_bodies();
  check.bodies_on_soil_side();
  check.bodies_supported();
  check.bodies_enclosed();
  check.names();
}

double distance_to_walls(const Scene& scene, const Vec2& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const Wall& w : scene.walls) best = std::min(best, polyline_distance(p, w.points));
  for (const RigidBody& rb : scene.rigid_bodies) {
    best = std::min(best, polygon_boundary_distance(p, rb.outline));
  }
  return best;
}

}  // namespace duet
