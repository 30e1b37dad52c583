#include "constitutive/stress_correction.hpp"

#include <cmath>
#include <stdexcept>

namespace duet::constitutive {

std::vector<std::string> correction_method_names() {
  return {"A", "B", "C", "none"};
}

std::string correction_method_name(CorrectionMethod method) {
  switch (method) {
    case CorrectionMethod::A:
      return "A";
    case CorrectionMethod::B:
      return "B";
    case CorrectionMethod::C:
      return "C";
    case CorrectionMethod::none:
      return "none";
  }
  return "none";
}

CorrectionMethod parse_correction_method(const std::string& word) {
  if (word == "A") return CorrectionMethod::A;
  if (word == "B") return CorrectionMethod::B;
  if (word == "C") return CorrectionMethod::C;
  if (word == "none") return CorrectionMethod::none;
  throw std::invalid_argument("unknown stress correction method \"" + word + "\"");
}

Mat3 failure_gradient(const FailureFunction& f, const Mat3& stress, double relative_step) {
  const double h = relative_step * std::max(norm(stress), 1e-12);
  Mat3 gradient = Mat3::Zero();
  for (int i = 0; i < 3; ++i) {
    for (int j = i; j < 3; ++j) {
      Mat3 bump = Mat3::Zero();
      bump(i, j) = h;
      bump(j, i) = h;  // symmetric perturbation: df = 2 g_ij h off the diagonal
      const double df = f(stress + bump) - f(stress - bump);
      const double g = df / (2.0 * h) / (i == j ? 1.0 : 2.0);
      gradient(i, j) = g;
      gradient(j, i) = g;
    }
  }
  return gradient;
}

bool project_along(const FailureFunction& f, const CorrectionDirection& direction, Mat3& stress,
                   double tolerance, int max_iterations) {
  double value = f(stress);
  if (value <= tolerance) return true;
  // Newton along the direction until |f| <= tolerance: a linearised step can also overshoot
  // inside the surface, and the correction should end on it.
  for (int k = 0; k < max_iterations && std::abs(value) > tolerance; ++k) {
    const Mat3 d = direction(stress);
    const Mat3 g = failure_gradient(f, stress);
    const double slope = contract(g, d);
    // A direction (nearly) tangent to the surface cannot bring the stress back.
    if (!(std::abs(slope) > 1e-12 * norm(g) * norm(d))) return false;
    const double alpha = value / slope;  // eq 36 (alpha_A) / eq 37 (alpha_B)
    // A step longer than the stress itself is no correction (direction nearly tangent).
    if (!(norm(alpha * d) <= norm(stress))) return false;
    const Mat3 projected = stress - alpha * d;
    const double projected_value = f(projected);
    if (!std::isfinite(projected_value)) return false;
    stress = projected;
    value = projected_value;
  }
  return std::abs(value) <= tolerance;
}

double scale_deviator_to_surface(const FailureFunction& f, Mat3& stress, double tolerance) {
  const Mat3 hydrostatic = mean_stress(stress) * Mat3::Identity();
  const Mat3 s = deviator(stress);
  const auto f_at = [&](double alpha) { return f(hydrostatic + alpha * s); };  // eq 38

  double hi = 1.0, f_hi = f_at(hi);
  if (f_hi <= tolerance) return 1.0;
  double lo = 0.0, f_lo = f_at(lo);
  if (f_lo >= -tolerance) {
    // Even the isotropic state is on or outside the surface: it is the closest admissible one.
    stress = hydrostatic;
    return 0.0;
  }
  // Illinois regula falsi on [lo, hi] with f(lo) < 0 < f(hi).
  double alpha = 0.0;
  int side = 0;
  for (int k = 0; k < 100; ++k) {
    alpha = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
    const double value = f_at(alpha);
    if (std::abs(value) <= tolerance || hi - lo < 1e-14) break;
    if (value > 0.0) {
      hi = alpha;
      f_hi = value;
      if (side == 1) f_lo *= 0.5;
      side = 1;
    } else {
      lo = alpha;
      f_lo = value;
      if (side == -1) f_hi *= 0.5;
      side = -1;
    }
  }
  stress = hydrostatic + alpha * s;
  return alpha;
}

}  // namespace duet::constitutive
