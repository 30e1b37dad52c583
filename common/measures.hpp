#pragma once
// The scene's measures, sampled during a run as time series, reduced to one value each (at end,
// or the maximum), and scored against the scene's references.

#include <string>
#include <vector>

#include "common/json.hpp"
#include "common/particles.hpp"
#include "common/scene.hpp"
#include "common/solver.hpp"
#include "common/state_bag.hpp"

namespace duet {

/// The divisor of a wall_stress measure for the wall polyline `points`: its chord in plane strain,
/// the magnitude of the vector area it sweeps about the axis in an axisymmetric scene.
double wall_vector_area(const std::vector<Vec2>& points, Formulation formulation);

/// Instantaneous raw value of one measure for the current state (see Measure in
/// common/scene.hpp), before divide_by and scale. For `period` it is the velocity of the body's
/// centre of mass along the component, from which the recorder derives the period.
double evaluate_measure(const Measure& measure, const Scene& scene, const Particles& particles,
                        const std::vector<Reaction>& reactions, double time);

/// Toe of a body: the largest x among particles whose column (x cut into strips of
/// `column_width`, from x = 0) holds at least `min_depth` of material, its particles' lattice area
/// dp^2 spread over the strip (every particle counts when min_depth <= 0).
double front_position(const Particles& particles, int body, double spacing, double column_width,
                      double min_depth);

/// Displacement of the material point of `body` that starts at `point`: a linear least-squares
/// fit of the displacements of the particles that start (x - u) within `radius` of it, so exact
/// for a linear field and defined on the body's edge; NaN with fewer than three particles there
/// or all on one line.
Vec2 material_point_displacement(const Particles& particles, int body, const Vec2& point,
                                 double radius);

/// Period of an oscillation from its velocity samples: twice the mean interval between successive
/// zero crossings (linear interpolation between samples); NaN before two crossings.
double period_from_zero_crossings(const std::vector<double>& time,
                                  const std::vector<double>& velocity);

/// Samples every measure as a time series. A measure with divide_by is divided by the other
/// measure's raw value at the same sample, then multiplied by its scale.
class MeasureRecorder {
 public:
  explicit MeasureRecorder(const Scene& scene);

  void sample(double time, const Particles& particles, const std::vector<Reaction>& reactions);

  /// "time" then every measure's name, and the sampled columns in the same order.
  std::vector<std::string> names() const;
  const std::vector<std::vector<double>>& columns() const { return columns_; }

  /// One value per measure: the last sample (at = end | series), the largest in magnitude
  /// (at = max), or the series interpolated at the measure's time (at = time).
  /// A curve (at = curve): the series at the end of its x_window, NaN when not reached.
  Json final_values() const;
  double final_value(const std::string& name) const;
  /// The samples of one measure so far.
  const std::vector<double>& series_of(const std::string& name) const;

  /// {"<measure>": {"value", "reference", "rel_error", "signed_error", "source", "tolerance",
  /// "passed"}} for every reference of the scene but a factor of safety's (found by `duet srf`
  /// over many runs: one run's safety_factor is the factor it was given). A curve's rel_error is
  /// the largest over its window, with "worst_at", "mean_error", "window", "reached" beside it.
  Json accuracy() const;

  /// The samples so far into / from a frame's state (`duet run --resume`), keys "measures.*".
  void save_state(StateBag& state) const;
  void restore_state(const StateBag& state);

 private:
  const Scene& scene_;
  std::vector<int> divisor_;                   // per measure: index of its divide_by, or -1
  std::vector<double> raw_;                    // scratch: raw values of one sample
  std::vector<std::vector<double>> velocity_;  // per measure: centre-of-mass velocity (period)
  std::vector<std::vector<double>> columns_;   // [0] time, then one per measure
};

}  // namespace duet
