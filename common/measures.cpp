#include "common/measures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>

#include "common/geometry.hpp"
#include "common/reference_curve.hpp"

namespace duet {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double component_of(const Vec2& v, const std::string& component) {
  if (component == "x") return v.x();
  if (component == "y") return v.y();
  return v.norm();
}

int body_index(const Scene& scene, const std::string& name) {
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    if (scene.bodies[b].name == name) return static_cast<int>(b);
  }
  return -1;
}

Vec2 reaction_of(const std::vector<Reaction>& reactions, const std::string& name) {
  for (const auto& r : reactions) {
    if (r.name == name) return r.force;
  }
  return Vec2::Constant(kNaN);
}

const Wall* wall_named(const Scene& scene, const std::string& name) {
  for (const auto& w : scene.walls) {
    if (w.name == name) return &w;
  }
  return nullptr;
}

const RigidBody* rigid_body_named(const Scene& scene, const std::string& name) {
  for (const auto& r : scene.rigid_bodies) {
    if (r.name == name) return &r;
  }
  return nullptr;
}

// A front measure's column width and least depth (m): its own, or the lattice column of dp and
// min_thickness spacings.
double front_column_width(const Measure& m, double spacing) {
  return m.column_width > 0.0 ? m.column_width : spacing;
}

double front_min_depth(const Measure& m, double spacing) {
  return m.min_depth > 0.0 ? m.min_depth : m.min_thickness * spacing;
}

double mean_distance(const std::vector<Vec2>& points, const Vec2& centre) {
  double sum = 0.0;
  for (const Vec2& p : points) sum += (p - centre).norm();
  return sum / static_cast<double>(points.size());
}

}  // namespace

double front_position(const Particles& particles, int body, double spacing, double column_width,
                      double min_depth) {
  // A column's depth is its particles' count times dp^2 over its width; the least count that
  // reaches min_depth, with a relative 1e-9 so that 3 particles make "3 spacings" exactly.
  const double area = spacing * spacing;
  const double min_count = min_depth > 0.0 ? min_depth * column_width / area * (1.0 - 1e-9) : 0.0;
  std::map<long, int> column_count;
  auto column = [column_width](double x) {
    return static_cast<long>(std::floor(x / column_width));
  };
  if (min_count > 0.0) {
    for (std::size_t i = 0; i < particles.size(); ++i) {
      if (particles.body[i] == body) ++column_count[column(particles.position[i].x())];
    }
  }
  double front = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (particles.body[i] != body) continue;
    const double x = particles.position[i].x();
    if (min_count > 0.0 && column_count[column(x)] < min_count) continue;
    front = std::max(front, x);
  }
  return std::isfinite(front) ? front : kNaN;
}

Vec2 material_point_displacement(const Particles& particles, int body, const Vec2& point,
                                 double radius) {
  // u(X) = a + G (X - point) by least squares over the particles that start within `radius`
  // (X = x - u); normal equations in the scaled offsets (X - point) / radius.
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Matrix<double, 3, 2> rhs = Eigen::Matrix<double, 3, 2>::Zero();
  int count = 0;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (particles.body[i] != body) continue;
    const Vec2 offset = (particles.position[i] - particles.displacement[i] - point) / radius;
    if (offset.squaredNorm() > 1.0) continue;
    const Eigen::Vector3d row(1.0, offset.x(), offset.y());
    normal += row * row.transpose();
    rhs += row * particles.displacement[i].transpose();
    ++count;
  }
  const Eigen::LDLT<Eigen::Matrix3d> solve(normal);
  if (count < 3 || solve.info() != Eigen::Success ||
      !(std::abs(solve.vectorD().minCoeff()) > 1e-10 * solve.vectorD().cwiseAbs().maxCoeff())) {
    return Vec2(kNaN, kNaN);  // too few particles about the point, or all on one line
  }
  const Eigen::Matrix<double, 3, 2> fit = solve.solve(rhs);
  return fit.row(0).transpose();
}

double wall_vector_area(const std::vector<Vec2>& points, Formulation formulation) {
  if (formulation == Formulation::plane_strain) return (points.back() - points.front()).norm();
  // Axisymmetric: segment i sweeps a cone frustum whose vector area is 2 pi r_mid (dz, -dr)
  // (Pappus; exact, r linear along the segment); the part of a wall drawn across the axis
  // (x < 0) sweeps nothing
  Vec2 area = Vec2::Zero();
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    Vec2 a = points[i];
    Vec2 b = points[i + 1];
    if (a.x() <= 0.0 && b.x() <= 0.0) continue;
    if (a.x() < 0.0) a += (b - a) * (a.x() / (a.x() - b.x()));
    if (b.x() < 0.0) b += (a - b) * (b.x() / (b.x() - a.x()));
    const Vec2 d = b - a;
    const double r_mid = 0.5 * (a.x() + b.x());
    area += 2.0 * std::numbers::pi * r_mid * Vec2(d.y(), -d.x());
  }
  return area.norm();
}

double evaluate_measure(const Measure& measure, const Scene& scene, const Particles& particles,
                        const std::vector<Reaction>& reactions, double time) {
  double value = kNaN;
  switch (measure.kind) {
    case MeasureKind::front:
      value = front_position(particles, body_index(scene, measure.target), scene.spacing,
                             front_column_width(measure, scene.spacing),
                             front_min_depth(measure, scene.spacing));
      break;
    case MeasureKind::height: {
      const int body = body_index(scene, measure.target);
      double top = -std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < particles.size(); ++i) {
        if (particles.body[i] == body) top = std::max(top, particles.position[i].y());
      }
      value = std::isfinite(top) ? top : kNaN;
      break;
    }
    case MeasureKind::max_displacement: {
      const int body = body_index(scene, measure.target);
      double largest = 0.0;
      for (std::size_t i = 0; i < particles.size(); ++i) {
        if (particles.body[i] == body) {
          largest = std::max(largest,
                             std::abs(component_of(particles.displacement[i], measure.component)));
        }
      }
      value = largest;
      break;
    }
    case MeasureKind::point_displacement:
      value = component_of(material_point_displacement(particles, body_index(scene, measure.target),
                                                       measure.point, 2.0 * scene.spacing),
                           measure.component);
      break;
    case MeasureKind::reaction:
      value = component_of(reaction_of(reactions, measure.target), measure.component);
      break;
    case MeasureKind::wall_stress: {
      const Wall* wall = wall_named(scene, measure.target);
      if (!wall) break;
      const auto points = wall_points_at(*wall, time);
      value = component_of(reaction_of(reactions, measure.target), measure.component) /
              wall_vector_area(points, scene.formulation);
      break;
    }
    case MeasureKind::period: {
      const int body = body_index(scene, measure.target);
      Vec2 momentum = Vec2::Zero();
      double mass = 0.0;
      for (std::size_t i = 0; i < particles.size(); ++i) {
        if (particles.body[i] != body) continue;
        momentum += particles.mass[i] * particles.velocity[i];
        mass += particles.mass[i];
      }
      value = mass > 0.0 ? component_of(momentum / mass, measure.component) : kNaN;
      break;
    }
    case MeasureKind::safety_factor:
      value = scene.strength_reduction.factor;
      break;
    case MeasureKind::expansion:
      if (const Wall* wall = wall_named(scene, measure.target)) {
        value = mean_distance(wall_points_at(*wall, time), wall->centre) /
                mean_distance(wall->points, wall->centre);
      }
      break;
    case MeasureKind::displacement:
      if (const Wall* wall = wall_named(scene, measure.target)) {
        value = component_of(schedule_integral(wall->velocity, time), measure.component);
      } else if (const RigidBody* rigid = rigid_body_named(scene, measure.target)) {
        value = component_of(schedule_integral(rigid->velocity, time), measure.component);
      }
      break;
  }
  return value;
}

double period_from_zero_crossings(const std::vector<double>& time,
                                  const std::vector<double>& velocity) {
  std::vector<double> crossings;
  for (std::size_t k = 1; k < velocity.size(); ++k) {
    const double a = velocity[k - 1], b = velocity[k];
    if (!(std::isfinite(a) && std::isfinite(b))) continue;
    if ((a < 0.0 && b >= 0.0) || (a > 0.0 && b <= 0.0)) {
      const double s = a / (a - b);
      crossings.push_back(time[k - 1] + s * (time[k] - time[k - 1]));
    }
  }
  if (crossings.size() < 2) return kNaN;
  return 2.0 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
}

MeasureRecorder::MeasureRecorder(const Scene& scene)
    : scene_(scene),
      divisor_(scene.measures.size(), -1),
      raw_(scene.measures.size()),
      velocity_(scene.measures.size()),
      columns_(scene.measures.size() + 1) {
  for (std::size_t m = 0; m < scene.measures.size(); ++m) {
    for (std::size_t k = 0; k < scene.measures.size(); ++k) {
      if (scene.measures[k].name == scene.measures[m].divide_by) divisor_[m] = static_cast<int>(k);
    }
  }
}

void MeasureRecorder::sample(double time, const Particles& particles,
                             const std::vector<Reaction>& reactions) {
  columns_[0].push_back(time);
  for (std::size_t m = 0; m < scene_.measures.size(); ++m) {
    raw_[m] = evaluate_measure(scene_.measures[m], scene_, particles, reactions, time);
  }
  for (std::size_t m = 0; m < scene_.measures.size(); ++m) {
    const Measure& measure = scene_.measures[m];
    double value = raw_[m];
    if (measure.kind == MeasureKind::period) {
      velocity_[m].push_back(value);
      value = period_from_zero_crossings(columns_[0], velocity_[m]);
    }
    if (divisor_[m] >= 0) value /= raw_[static_cast<std::size_t>(divisor_[m])];
    columns_[m + 1].push_back(value * measure.scale);
  }
}

std::vector<std::string> MeasureRecorder::names() const {
  std::vector<std::string> out{"time"};
  for (const auto& m : scene_.measures) out.push_back(m.name);
  return out;
}

double MeasureRecorder::final_value(const std::string& name) const {
  for (std::size_t m = 0; m < scene_.measures.size(); ++m) {
    if (scene_.measures[m].name != name) continue;
    const auto& series = columns_[m + 1];
    if (series.empty()) return kNaN;
    switch (scene_.measures[m].at) {
      case MeasureAt::end:
      case MeasureAt::series:
        return series.back();
      case MeasureAt::curve: {
        const Measure& measure = scene_.measures[m];
        return series_value_at(series_of(measure.abscissa), series, measure.x_window.y());
      }
      case MeasureAt::max: {
        double largest = kNaN;
        for (double v : series) {
          if (std::isfinite(v) && !(std::abs(v) <= std::abs(largest))) largest = v;
        }
        return largest;
      }
      case MeasureAt::time: {
        const auto& t = columns_[0];
        const double target = scene_.measures[m].time;
        const double half = 0.5 * scene_.measures[m].window;
        if (half > 0.0 && t.back() >= target) {
          // The mean over the window (a dynamic run's reaction rings about its quasi-static
          // value: the cavity's ring breathes with a period of 2 b / c_p); each sample is
          // already the mean since the one before (common/reaction_mean.hpp)
          double sum = 0.0;
          int count = 0;
          for (std::size_t k = 0; k < t.size(); ++k) {
            if (std::abs(t[k] - target) <= half && std::isfinite(series[k])) {
              sum += series[k];
              ++count;
            }
          }
          if (count > 0) return sum / count;
        }
        for (std::size_t k = 1; k < t.size(); ++k) {
          if (t[k] >= target) {
            const double s = (target - t[k - 1]) / (t[k] - t[k - 1]);
            return series[k - 1] + s * (series[k] - series[k - 1]);
          }
        }
        return kNaN;  // the run did not reach that time
      }
    }
    return kNaN;
  }
  return kNaN;
}

Json MeasureRecorder::final_values() const {
  Json out = Json::object();
  for (const auto& m : scene_.measures) out[m.name] = final_value(m.name);
  return out;
}

const std::vector<double>& MeasureRecorder::series_of(const std::string& name) const {
  for (std::size_t m = 0; m < scene_.measures.size(); ++m) {
    if (scene_.measures[m].name == name) return columns_[m + 1];
  }
  throw std::logic_error("no measure " + name);  // the scene's validation names it
}

namespace {

/// A curve measure's entry: the worst relative error over its window, where it is and its sign,
/// the mean error, and the value and reference at the window's end.
void score_curve_into(Json& entry, const Measure& measure, const Reference& ref,
                      const std::vector<double>& x, const std::vector<double>& y) {
  const CurveScore score = score_curve(x, y, measure.x_window, ref.curve, ref.value);
  const double end = measure.x_window.y();
  entry["value"] = series_value_at(x, y, end);
  entry["reference"] = ref.curve.empty() ? ref.value : curve_value(ref.curve, end);
  entry["rel_error"] = score.rel_error;
  entry["signed_error"] = score.signed_error;
  entry["worst_at"] = score.worst_at;
  entry["mean_error"] = score.mean_error;
  entry["scored_points"] = static_cast<double>(score.points);
  Json window = Json::array();
  window.push_back(measure.x_window.x());
  window.push_back(end);
  entry["window"] = window;
  entry["abscissa"] = measure.abscissa;
  entry["reached"] = score.reached;
  if (!ref.curve_file.empty()) entry["curve"] = ref.curve_file;
}

}  // namespace

Json MeasureRecorder::accuracy() const {
  Json out = Json::object();
  for (const auto& ref : scene_.references) {
    const Measure& measure = *std::find_if(scene_.measures.begin(), scene_.measures.end(),
                                           [&](const Measure& m) { return m.name == ref.measure; });
    // A factor of safety is found by a search over runs (duet srf), not by one run, whose
    // safety_factor is the strength-reduction factor it was given: not an accuracy.
    if (measure.kind == MeasureKind::safety_factor) continue;
    Json entry = Json::object();
    if (measure.at == MeasureAt::curve) {
      score_curve_into(entry, measure, ref, series_of(measure.abscissa), series_of(measure.name));
    } else {
      const double value = final_value(ref.measure);
      entry["value"] = value;
      entry["reference"] = ref.value;
      entry["rel_error"] = std::abs(value - ref.value) / std::abs(ref.value);
      entry["signed_error"] = (value - ref.value) / std::abs(ref.value);
    }
    const double error = entry["rel_error"].number();
    entry["source"] = ref.source;
    if (ref.error > 0.0) entry["reference_error"] = ref.error;
    if (ref.tolerance > 0.0) {
      entry["tolerance"] = ref.tolerance;
      entry["passed"] = std::isfinite(error) && error <= ref.tolerance;
    }
    out[ref.measure] = entry;
  }
  return out;
}

}  // namespace duet

namespace duet {

void MeasureRecorder::save_state(StateBag& state) const {
  put_lists(state, "measures.columns", columns_);
  put_lists(state, "measures.velocity", velocity_);
}

void MeasureRecorder::restore_state(const StateBag& state) {
  std::vector<std::vector<double>> columns, velocity;
  get_lists(state, "measures.columns", columns);
  get_lists(state, "measures.velocity", velocity);
  if (columns.size() != columns_.size() || velocity.size() != velocity_.size()) {
    throw std::runtime_error("the saved state's measures are not this scene's");
  }
  columns_ = std::move(columns);
  velocity_ = std::move(velocity);
}

}  // namespace duet
