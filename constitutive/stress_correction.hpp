#pragma once
// Stress correction for hypoplastic models (simhypo-sand paper sec 3.3, after Potts & Gens): when
// an explicit step leaves the stress outside the failure surface, f(sigma) > tolerance, bring it
// back. Model-agnostic: the failure function and the directions are passed in, so the three
// methods are tested alone on a surface with a closed-form answer.
//
//   Method A (eq 36): sigma <- sigma - alpha_A B,         alpha_A = f / (df/dsigma : B)
//   Method B (eq 37): sigma <- sigma - alpha_B sigma_dot, alpha_B = f / (df/dsigma : sigma_dot)
//   Method C (eq 38): s <- alpha_c s with I1 kept, alpha_c in [0, 1] found numerically
//
// The linearised projections of A and B are re-evaluated at the projected stress until
// |f| <= tolerance (a Newton iteration along the direction), so every method ends on the
// surface unless the direction is (nearly) tangent to it (the model then falls back to C).

#include <functional>
#include <string>
#include <vector>

#include "common/tensor.hpp"

namespace duet::constitutive {

/// Which correction a model applies; parsed once from the input word.
enum class CorrectionMethod { none, A, B, C };

/// "A", "B", "C", "none" (the words accepted in input files).
std::vector<std::string> correction_method_names();
std::string correction_method_name(CorrectionMethod method);
/// Maps a word from correction_method_names() to the enum (the caller validated it).
CorrectionMethod parse_correction_method(const std::string& word);

/// A failure function f(sigma): f <= 0 on or inside the surface.
using FailureFunction = std::function<double(const Mat3&)>;
/// A correction direction at a stress (Method A: the flow tensor B of the state).
using CorrectionDirection = std::function<Mat3(const Mat3&)>;

/// Central-difference gradient df/dsigma as a symmetric tensor, so df = gradient : dsigma.
/// Step relative to the stress norm.
Mat3 failure_gradient(const FailureFunction& f, const Mat3& stress, double relative_step = 1e-6);

/// Eqs 36-37: sigma <- sigma - alpha d(sigma), alpha = f / (df/dsigma : d), repeated (at most
/// max_iterations) until |f| <= tolerance; nothing is done when f <= tolerance at the start.
/// Returns false, leaving the last iterate, when the direction is (nearly) tangent to the surface,
/// so that one step would be longer than the stress itself, or when the iteration does not reach
/// the tolerance.
bool project_along(const FailureFunction& f, const CorrectionDirection& direction, Mat3& stress,
                   double tolerance, int max_iterations = 25);

/// Eq 38: scales the deviator, s <- alpha_c s, keeping I1, with alpha_c in [0, 1] chosen so that
/// -tolerance <= f <= tolerance (Illinois regula falsi on the bracket [0, 1]). When even the
/// isotropic state (alpha_c = 0) violates the surface, returns that state. Returns alpha_c.
double scale_deviator_to_surface(const FailureFunction& f, Mat3& stress, double tolerance);

}  // namespace duet::constitutive
