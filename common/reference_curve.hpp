#pragma once
// Reference curves: a measured series y(x) scored against a curve of points (x, y) from an
// independent source (a standard finite element code run on the same geometry, an experiment)
// or against a constant, over a window of x. The file format is CSV: '#' comment lines (the
// provenance), one header line naming the two columns, then rows "x,y" with x increasing.

#include <string>
#include <vector>

#include "common/tensor.hpp"

namespace duet {

/// Reads a reference CSV; throws InputError naming the file and line on anything else (missing
/// file, a row without two numbers, x not increasing, fewer than two rows).
std::vector<Vec2> read_reference_csv(const std::string& path);

/// The curve's y at x, linear between points; NaN outside [first x, last x].
double curve_value(const std::vector<Vec2>& curve, double x);

/// y of the series at x = target, linear between the first pair of samples that brackets it (the
/// abscissa need not be monotone: the first crossing counts); NaN when the series never reaches
/// it.
double series_value_at(const std::vector<double>& x, const std::vector<double>& y, double target);

/// A series scored over a window of x: the largest relative error |y - y_ref| / |y_ref| among
/// the samples with x in the window and at the window's two ends (interpolated).
struct CurveScore {
  double rel_error = 0.0;     // the largest; NaN when the series does not cover the window
  double signed_error = 0.0;  // (y - y_ref) / |y_ref| where the largest is
  double worst_at = 0.0;      // x where the largest is
  double mean_error = 0.0;    // the mean of |y - y_ref| / |y_ref| over the scored points
  int points = 0;             // scored points (samples in the window and its two ends)
  double reached = 0.0;       // the largest x the series reached
};

/// `reference` empty: the constant `value`.
CurveScore score_curve(const std::vector<double>& x, const std::vector<double>& y, Vec2 window,
                       const std::vector<Vec2>& reference, double value);

}  // namespace duet
