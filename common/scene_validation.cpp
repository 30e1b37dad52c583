#include "common/scene_validation.hpp"

#include <algorithm>
#include <limits>
#include <sstream>

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

  double distance_to_walls(const Vec2& p) const {
    double best = std::numeric_limits<double>::infinity();
    for (const Wall& w : scene_.walls) best = std::min(best, polyline_distance(p, w.points));
    for (const RigidBody& rb : scene_.rigid_bodies) {
      best = std::min(best, polygon_boundary_distance(p, rb.outline));
    }
    return best;
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
      supported[i] = distance_to_walls(lowest[i]) <= reach;
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
        if (distance_to_walls(0.5 * (a + c)) > reach) {
          fail("body." + b.name,
               "is not enclosed although confined = true: its side " + point_text(a) + " - " +
                   point_text(c) + " has no wall within one spacing",
               "walls along every side of a confined body");
        }
      }
    }
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
  check.no_overlaps();
  check.bodies_supported();
  check.bodies_enclosed();
  check.names();
}

}  // namespace duet
