#include "common/reference_curve.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "common/input_error.hpp"

namespace duet {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string trimmed(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  const auto last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

/// The whole text as one number, or false.
bool parse_number(const std::string& text, double& out) {
  const std::string t = trimmed(text);
  if (t.empty()) return false;
  std::size_t used = 0;
  try {
    out = std::stod(t, &used);
  } catch (const std::exception&) {
    return false;
  }
  return used == t.size() && std::isfinite(out);
}

}  // namespace

std::vector<Vec2> read_reference_csv(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw InputError(path + ": cannot open the reference curve; expected a CSV file");
  std::vector<Vec2> points;
  std::string line;
  bool header = false;
  for (int number = 1; std::getline(file, line); ++number) {
    const std::string t = trimmed(line);
    if (t.empty() || t[0] == '#') continue;
    if (!header) {  // the column names
      header = true;
      continue;
    }
    const auto comma = t.find(',');
    double x = 0.0, y = 0.0;
    if (comma == std::string::npos || t.find(',', comma + 1) != std::string::npos ||
        !parse_number(t.substr(0, comma), x) || !parse_number(t.substr(comma + 1), y)) {
      throw InputError(path + ":" + std::to_string(number) + ": \"" + t +
                       "\"; expected a row of two numbers \"x,y\"");
    }
    if (!points.empty() && !(x > points.back().x())) {
      throw InputError(path + ":" + std::to_string(number) +
                       ": x = " + trimmed(t.substr(0, comma)) +
                       " after x = " + std::to_string(points.back().x()) +
                       "; expected x increasing from row to row");
    }
    points.emplace_back(x, y);
  }
  if (points.size() < 2) {
    throw InputError(path + ": " + std::to_string(points.size()) +
                     " rows of data; expected a header line and at least two rows \"x,y\"");
  }
  return points;
}

double curve_value(const std::vector<Vec2>& curve, double x) {
  if (curve.empty() || !(x >= curve.front().x() && x <= curve.back().x())) return kNaN;
  const auto upper = std::lower_bound(curve.begin(), curve.end(), x,
                                      [](const Vec2& p, double v) { return p.x() < v; });
  if (upper == curve.begin()) return upper->y();
  const Vec2& a = *(upper - 1);
  const Vec2& b = *upper;
  const double s = (x - a.x()) / (b.x() - a.x());
  return a.y() + s * (b.y() - a.y());
}

double series_value_at(const std::vector<double>& x, const std::vector<double>& y, double target) {
  const std::size_t n = std::min(x.size(), y.size());
  for (std::size_t k = 0; k < n; ++k) {
    if (x[k] == target) return y[k];
    if (k == 0) continue;
    const double a = x[k - 1] - target, b = x[k] - target;
    if (a * b < 0.0) {
      const double s = (target - x[k - 1]) / (x[k] - x[k - 1]);
      return y[k - 1] + s * (y[k] - y[k - 1]);
    }
  }
  return kNaN;
}

CurveScore score_curve(const std::vector<double>& x, const std::vector<double>& y, Vec2 window,
                       const std::vector<Vec2>& reference, double value) {
  CurveScore score;
  score.reached = -std::numeric_limits<double>::infinity();
  for (double v : x) {
    if (std::isfinite(v)) score.reached = std::max(score.reached, v);
  }
  auto ref_at = [&](double at) { return reference.empty() ? value : curve_value(reference, at); };
  double sum = 0.0;
  auto score_point = [&](double at, double measured) {
    const double r = ref_at(at);
    const double e = (measured - r) / std::abs(r);
    if (!std::isfinite(e)) {
      score.rel_error = kNaN;  // a sample the run did not compute is not a small error
      return;
    }
    sum += std::abs(e);
    ++score.points;
    if (std::isfinite(score.rel_error) && std::abs(e) >= score.rel_error) {
      score.rel_error = std::abs(e);
      score.signed_error = e;
      score.worst_at = at;
    }
  };
  if (!(score.reached >= window.y())) {  // not scored: nothing about it is a figure
    score.rel_error = score.signed_error = score.worst_at = score.mean_error = kNaN;
    return score;
  }
  score_point(window.x(), series_value_at(x, y, window.x()));
  const std::size_t n = std::min(x.size(), y.size());
  for (std::size_t k = 0; k < n; ++k) {
    if (x[k] > window.x() && x[k] < window.y()) score_point(x[k], y[k]);
  }
  score_point(window.y(), series_value_at(x, y, window.y()));
  score.mean_error = score.points > 0 ? sum / score.points : kNaN;
  if (!std::isfinite(score.rel_error)) score.signed_error = score.worst_at = kNaN;
  return score;
}

}  // namespace duet
