#include "constitutive/element_test.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string_view>

#include "common/input_error.hpp"
#include "common/suggest.hpp"

namespace duet::constitutive {

namespace {

constexpr int max_iterations = 50;
constexpr int max_backtracks = 8;
constexpr int max_cuts = 6;  // an increment is cut at most to 1/64

std::string number(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

/// The material point: accumulated strain, stress, internal variables.
struct PointState {
  Mat3 strain = Mat3::Zero();
  Mat3 stress = Mat3::Zero();
  std::vector<double> internal;
};

/// Mixed control of one increment: the Voigt strain components solved for (their stress held at
/// `held`), every other component prescribed.
struct Control {
  std::vector<int> free;  // Voigt indices (xx yy zz xy yz zx)
  Vec6 held = Vec6::Zero();
};

/// Stress and internal variables after integrate() and correct() from `state` along d_strain.
struct Response {
  Mat3 stress;
  std::vector<double> internal;
};

Response respond(const Model& model, const PointState& state, const Vec6& d_voigt) {
  Response r{state.stress, state.internal};
  model.integrate(voigt_to_strain(d_voigt), r.stress, r.internal);
  model.correct(r.stress, r.internal);
  return r;
}

Eigen::VectorXd residual(const Control& control, const Response& response) {
  const Vec6 s = stress_to_voigt(response.stress);
  Eigen::VectorXd r(control.free.size());
  for (std::size_t i = 0; i < control.free.size(); ++i)
    r(i) = s(control.free[i]) - control.held(control.free[i]);
  return r;
}

Vec6 with_free(Vec6 d_voigt, const Control& control, const Eigen::VectorXd& x) {
  for (std::size_t i = 0; i < control.free.size(); ++i) d_voigt(control.free[i]) = x(i);
  return d_voigt;
}

/// Jacobian d(held stress)/d(free strain) from the model's tangent.
Eigen::MatrixXd tangent_jacobian(const Model& model, const PointState& state, const Vec6& d_voigt,
                                 const Control& control) {
  const Mat6 t = model.tangent(voigt_to_strain(d_voigt), state.stress, state.internal);
  const auto n = static_cast<Eigen::Index>(control.free.size());
  Eigen::MatrixXd j(n, n);
  for (Eigen::Index a = 0; a < n; ++a)
    for (Eigen::Index b = 0; b < n; ++b) j(a, b) = t(control.free[a], control.free[b]);
  return j;
}

/// Central finite-difference Jacobian of the full response (integrate + correct).
Eigen::MatrixXd finite_difference_jacobian(const Model& model, const PointState& state,
                                           const Vec6& d_voigt, const Control& control) {
  const auto n = static_cast<Eigen::Index>(control.free.size());
  const double step = 1e-7 * std::max(d_voigt.cwiseAbs().maxCoeff(), 1e-6);
  Eigen::MatrixXd j(n, n);
  for (Eigen::Index b = 0; b < n; ++b) {
    Vec6 plus = d_voigt, minus = d_voigt;
    plus(control.free[b]) += step;
    minus(control.free[b]) -= step;
    j.col(b) = (residual(control, respond(model, state, plus)) -
                residual(control, respond(model, state, minus))) /
               (2.0 * step);
  }
  return j;
}

struct Solve {
  bool converged = false;
  Vec6 d_voigt;
  Response response;
  double relative_residual = 0.0;
  int iterations = 0;
  bool finite = true;
};

/// Newton on the held stress components: the model's tangent first; when a tangent step does
/// not reduce the residual (even backtracked), a finite-difference Jacobian from then on.
Solve solve_increment(const Model& model, const PointState& state, const Vec6& prescribed,
                      const Control& control, const Eigen::VectorXd& guess, double stress_scale) {
  Solve s;
  Eigen::VectorXd x = guess;
  s.d_voigt = with_free(prescribed, control, x);
  s.response = respond(model, state, s.d_voigt);
  if (control.free.empty()) {
    s.converged = true;
    return s;
  }
  Eigen::VectorXd r = residual(control, s.response);
  bool finite_differences = false;
  for (s.iterations = 0; s.iterations <= max_iterations; ++s.iterations) {
    const double scale = std::max({stress_scale, norm(s.response.stress), 1.0});
    s.relative_residual = r.cwiseAbs().maxCoeff() / scale;
    if (!r.allFinite()) return s;
    if (s.relative_residual <= element_test_tolerance) {
      s.converged = true;
      return s;
    }
    const Eigen::MatrixXd j = finite_differences
                                  ? finite_difference_jacobian(model, state, s.d_voigt, control)
                                  : tangent_jacobian(model, state, s.d_voigt, control);
    const Eigen::VectorXd dx = j.fullPivLu().solve(-r);
    bool reduced = false;
    if (dx.allFinite()) {
      double alpha = 1.0;
      for (int b = 0; b <= max_backtracks && !reduced; ++b, alpha *= 0.5) {
        const Eigen::VectorXd x_try = x + alpha * dx;
        const Vec6 d_try = with_free(prescribed, control, x_try);
        Response trial = respond(model, state, d_try);
        const Eigen::VectorXd r_try = residual(control, trial);
        if (r_try.allFinite() && r_try.norm() < r.norm()) {
          x = x_try;
          s.d_voigt = d_try;
          s.response = std::move(trial);
          r = r_try;
          reduced = true;
        }
      }
    }
    if (!reduced) {
      if (finite_differences) return s;  // neither Jacobian makes progress
      finite_differences = true;
    }
  }
  return s;
}

/// Advances the point over one prescribed increment; when Newton does not converge (or the
/// response is not finite) the increment is cut in halves, at most max_cuts times, as a
/// non-smooth response (a correction switching on, a change of sub-step count) can leave the
/// held stress unreachable at one step size and reachable at a smaller one.
struct Stepper {
  const Model& model;
  const Control& control;
  double stress_scale;

  /// `guess`: free strains for this increment. Returns false (state untouched, `failed` set)
  /// when even the smallest cut does not converge.
  bool advance(PointState& state, const Vec6& prescribed, const Eigen::VectorXd& guess, int cuts,
               Solve& failed) const {
    Solve s = solve_increment(model, state, prescribed, control, guess, stress_scale);
    s.finite = s.response.stress.allFinite() &&
               std::all_of(s.response.internal.begin(), s.response.internal.end(),
                           [](double v) { return std::isfinite(v); });
    if (s.converged && s.finite) {
      state.strain += voigt_to_strain(s.d_voigt);
      state.stress = s.response.stress;
      state.internal = std::move(s.response.internal);
      return true;
    }
    if (cuts == max_cuts) {
      failed = std::move(s);
      return false;
    }
    const PointState before = state;
    const Eigen::VectorXd half_guess = 0.5 * guess;
    if (advance(state, 0.5 * prescribed, half_guess, cuts + 1, failed)) {
      const Vec6 taken = strain_to_voigt(state.strain - before.strain);
      Eigen::VectorXd next(control.free.size());
      for (std::size_t i = 0; i < control.free.size(); ++i) next(i) = taken(control.free[i]);
      if (advance(state, 0.5 * prescribed, next, cuts + 1, failed)) return true;
    }
    state = before;
    return false;
  }
};

int index_of(const std::vector<InternalVariable>& variables, std::string_view name) {
  for (std::size_t i = 0; i < variables.size(); ++i)
    if (variables[i].name == name) return static_cast<int>(i);
  return -1;
}

ElementRow make_row(const PointState& state, int void_ratio_index, int corrections_index) {
  ElementRow row;
  row.axial_strain = state.strain(1, 1);
  row.lateral_strain = state.strain(0, 0);
  row.volumetric_strain = state.strain.trace();
  row.shear_strain = 2.0 * state.strain(0, 1);
  row.axial_stress = state.stress(1, 1);
  row.lateral_stress = state.stress(0, 0);
  row.out_of_plane_stress = state.stress(2, 2);
  row.shear_stress = state.stress(0, 1);
  row.p = mean_stress(state.stress);
  row.q = von_mises(state.stress);
  row.void_ratio = void_ratio_index >= 0 ? state.internal[void_ratio_index]
                                         : std::numeric_limits<double>::quiet_NaN();
  row.corrections = corrections_index >= 0 ? state.internal[corrections_index] : 0.0;
  return row;
}

/// Control of `kind`: which strain components are solved for and the stress they hold.
Control control_for(const ElementTest& test) {
  Control c;
  switch (test.kind) {
    case ElementTestKind::oedometer:
      break;
    case ElementTestKind::triaxial:
      c.free = {0, 2};  // eps_xx, eps_zz solved so that sigma_xx = sigma_zz = initial stress
      c.held(0) = test.initial_stress;
      c.held(2) = test.initial_stress;
      break;
    case ElementTestKind::simple_shear:
      c.free = {1};  // eps_yy solved so that sigma_yy = initial stress
      c.held(1) = test.initial_stress;
      break;
  }
  return c;
}

/// The prescribed part of an increment of the controlled strain `d` (free components zero).
Vec6 prescribed_increment(ElementTestKind kind, double d) {
  Vec6 v = Vec6::Zero();
  if (kind == ElementTestKind::simple_shear)
    v(3) = d;  // engineering gamma_xy
  else
    v(1) = d;  // eps_yy
  return v;
}

}  // namespace

std::string element_test_name(ElementTestKind kind) {
  switch (kind) {
    case ElementTestKind::oedometer:
      return "oedometer";
    case ElementTestKind::triaxial:
      return "triaxial";
    case ElementTestKind::simple_shear:
      return "simple-shear";
  }
  return "unknown";
}

std::vector<std::string> element_test_names() {
  return {"oedometer", "triaxial", "simple-shear"};
}

ElementTestKind parse_element_test_kind(const std::string& name) {
  for (auto kind :
       {ElementTestKind::oedometer, ElementTestKind::triaxial, ElementTestKind::simple_shear}) {
    if (element_test_name(kind) == name) return kind;
  }
  throw InputError("--test " + name + ": unknown element test" +
                   did_you_mean(name, element_test_names()) +
                   "; known tests: " + join(element_test_names()));
}

void validate(const ElementTest& test) {
  if (!std::isfinite(test.initial_stress)) {
    throw InputError("element.initial_stress = " + number(test.initial_stress) +
                     ": isotropic initial stress must be a finite number (unit Pa)");
  }
  if (test.increments < 1) {
    throw InputError("element.increments = " + std::to_string(test.increments) +
                     ": number of strain increments must be >= 1 (unit -)");
  }
  if (!std::isfinite(test.strain) || test.strain == 0.0) {
    throw InputError("element.strain = " + number(test.strain) +
                     ": final strain must be a non-zero finite number (unit -)");
  }
  if (!test.unload_to) return;
  if (test.kind != ElementTestKind::oedometer) {
    throw InputError("element.unload_to = " + number(*test.unload_to) +
                     ": unloading is only defined for the oedometer test, not " +
                     element_test_name(test.kind));
  }
  const double u = *test.unload_to;
  const bool reverses = test.strain < 0.0 ? u > test.strain : u < test.strain;
  if (!std::isfinite(u) || !reverses) {
    throw InputError("element.unload_to = " + number(u) + ": axial strain to unload to must lie " +
                     (test.strain < 0.0 ? "> " : "< ") + number(test.strain) +
                     " (a reversal from element.strain; unit -)");
  }
}

int unloading_increments(const ElementTest& test) {
  if (!test.unload_to) return 0;
  const double step = std::abs(test.strain) / test.increments;
  const double span = std::abs(*test.unload_to - test.strain);
  return std::max(1, static_cast<int>(std::ceil(span / step - 1e-9)));
}

std::vector<ElementRow> run_element_test(const Model& model, const ElementTest& test) {
  validate(test);
  const auto variables = model.internal_variables();
  const int void_ratio_index = index_of(variables, "void_ratio");
  const int corrections_index = index_of(variables, "corrections");

  PointState state;
  state.stress = test.initial_stress * Mat3::Identity();
  for (const auto& v : variables) state.internal.push_back(v.initial);

  const Control control = control_for(test);
  const int n_unload = unloading_increments(test);
  std::vector<double> steps(test.increments, test.strain / test.increments);
  if (test.unload_to)
    steps.insert(steps.end(), n_unload, (*test.unload_to - test.strain) / n_unload);

  std::vector<ElementRow> rows;
  rows.reserve(steps.size() + 1);
  rows.push_back(make_row(state, void_ratio_index, corrections_index));
  Eigen::VectorXd guess = Eigen::VectorXd::Zero(control.free.size());
  const Stepper stepper{model, control, std::abs(test.initial_stress)};
  double controlled = 0.0;
  for (std::size_t n = 0; n < steps.size(); ++n) {
    const Vec6 prescribed = prescribed_increment(test.kind, steps[n]);
    const Vec6 strain_before = strain_to_voigt(state.strain);
    Solve failed;
    controlled += steps[n];
    if (!stepper.advance(state, prescribed, guess, 0, failed)) {
      std::ostringstream why;
      why << element_test_name(test.kind) << " with " << model.name() << ": increment " << n + 1
          << " of " << steps.size() << " (controlled strain " << controlled << "), cut to 1/"
          << (1 << max_cuts) << ": ";
      if (!failed.finite)
        why << "non-finite stress or internal variable";
      else
        why << "held stress not converged after " << failed.iterations
            << " Newton iterations, relative residual " << failed.relative_residual
            << " (tolerance " << element_test_tolerance << ")";
      throw ElementTestFailure(why.str(), std::move(rows));
    }
    // Next guess: this increment's free strains, scaled to the next step (same size or reversed).
    const Vec6 taken = strain_to_voigt(state.strain) - strain_before;
    for (std::size_t i = 0; i < control.free.size(); ++i) guess(i) = taken(control.free[i]);
    if (n + 1 < steps.size()) guess *= steps[n + 1] / steps[n];
    rows.push_back(make_row(state, void_ratio_index, corrections_index));
  }
  return rows;
}

}  // namespace duet::constitutive
