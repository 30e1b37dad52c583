#include "constitutive/hypoplastic.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "common/input_error.hpp"
#include "common/suggest.hpp"

namespace duet::constitutive {

namespace {

constexpr std::array<const char*, 4> kDirectKeys{"c1", "c2", "c3", "c4"};
constexpr std::array<const char*, 4> kTriaxialKeys{"Ei", "nu", "phi", "psi"};

// Sub-step size: |d_strain| per sub-step times the rate bound stays below this (RK4 is accurate to
// about 1e-7 relative per sub-step there and stable up to 2.78).
constexpr double kSubstepProduct = 0.1;
// A strain increment that needs more sub-steps than this is not integrated: the stress is set to
// NaN and the solver reports it (an explicit run fails, an implicit increment is halved). With the
// sand's constants (rate bound 1,360) that is |d_strain| > 0.74, far beyond any step; a scene
// with c2 = -1e308 took a million sub-steps per particle and step, and a run hung (scene fuzzer).
constexpr int kMaxSubsteps = 10000;

std::vector<std::string> given(const Parameters& parameters,
                               const std::array<const char*, 4>& keys) {
  std::vector<std::string> out;
  for (const char* k : keys) {
    if (parameters.has(k)) out.emplace_back(k);
  }
  return out;
}

std::vector<std::string> missing(const Parameters& parameters,
                                 const std::array<const char*, 4>& keys) {
  std::vector<std::string> out;
  for (const char* k : keys) {
    if (!parameters.has(k)) out.emplace_back(k);
  }
  return out;
}

std::string where(const Parameters& parameters) {
  return parameters.context().empty() ? std::string("hypoplastic") : parameters.context();
}

Mat3 apex() {
  return -apex_pressure * Mat3::Identity();
}

// One classical Runge-Kutta step of d eta = H(eta, d_strain) (H is homogeneous of degree one in
// the strain increment, so the increment plays the role of rate x time step).
Mat3 runge_kutta_step(const HypoplasticConstants& c, const Mat3& eta, const Mat3& d_strain) {
  const Mat3 k1 = hypoplastic_rate(c, eta, d_strain);
  const Mat3 k2 = hypoplastic_rate(c, eta + 0.5 * k1, d_strain);
  const Mat3 k3 = hypoplastic_rate(c, eta + 0.5 * k2, d_strain);
  const Mat3 k4 = hypoplastic_rate(c, eta + k3, d_strain);
  return eta + (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0;
}

// Bound M on the hypoplastic rate for the Gershgorin time step (ElasticModuli::tangent_bound):
// |L(eta):D + N(eta)|D||_2 <= M |v| |b| for every in-plane stretching D = sym(v (x) b), the rate
// one node's velocity v gives a cell through one smoothed gradient b. Term by term (Peng 2015
// eq 15 on eta, eqs 24-25), with |.|_2 the spectral norm, |D|_2 <= |v||b|, |tr D| = |v . b| <=
// |v||b|, |tr(eta D)| = |v . eta b| <= |eta|_2 |v||b| and |D| = sqrt(tr D^2) <= |v||b| (eq 14):
//   c1 (tr eta) D                     <= |c1| |tr eta| |v||b|
//   c2 (tr D) eta                     <= |c2| |eta|_2 |v||b|
//   c3 tr(eta D) / tr(eta) eta        <= |c3| |eta|_2^2 / |tr eta| |v||b|
//   c4 (eta + eta*) |D|  (eq 16)      <= |c4| |eta + eta*|_2 |v||b|.
// The sum bounds the tangent along any direction, L + N (x) D/|D|, and the secant of the
// degree-one rate. Each term is attained with v = b along the major principal axis of an
// isotropic eta (there M = (3|c1| + |c2| + |c3|/3 + |c4|) p), and the sum stays within 1 % of a
// 1-degree sweep over v, b at K0 = 0.5 and two sheared states (tests/spfem/time_step_test.cpp),
// within 10 % on the stresses of the sand collapse; the isotropic projection
// |lambda| + 2G of L alone undershoots it by 1.33 (isotropic) to 2.5 (K0 = 0.5: 2.2). It bounds
// the rate at the stress of the step's start only: the stiffness grows with the stress, so a node
// near the apex compressed by |d_eps| in one step stiffens by up to exp(rate_bound_ |d_eps|).
double rate_bound(const HypoplasticConstants& c, const Mat3& eta) {
  const Vec3 lambda =
      Eigen::SelfAdjointEigenSolver<Mat3>(eta, Eigen::EigenvaluesOnly).eigenvalues();  // ascending
  const double trace = eta.trace();
  const double eta_norm = std::max(std::abs(lambda(0)), std::abs(lambda(2)));
  // eta + eta* = 2 eta - tr(eta)/3 I (eq 16): eigenvalues 2 lambda_i - tr(eta)/3
  const double n_norm =
      std::max(std::abs(2.0 * lambda(0) - trace / 3.0), std::abs(2.0 * lambda(2) - trace / 3.0));
  const double c3_term = trace < 0.0 ? std::abs(c.c3) * eta_norm * eta_norm / -trace : 0.0;
  return std::abs(c.c1) * std::abs(trace) + std::abs(c.c2) * eta_norm + c3_term +
         std::abs(c.c4) * n_norm;
}

void count_correction(std::span<double> internal) {
  assert(!internal.empty() && "hypoplastic keeps one internal variable, corrections");
  if (!internal.empty()) internal[0] += 1.0;
}

}  // namespace

HypoplasticParameters HypoplasticParameters::read(Parameters& parameters) {
  const auto direct = given(parameters, kDirectKeys);
  const auto triaxial = given(parameters, kTriaxialKeys);
  if (!direct.empty() && !triaxial.empty()) {
    throw InputError(where(parameters) + ": give either c1 c2 c3 c4 or Ei nu phi psi, not both (" +
                     join(direct) + " and " + join(triaxial) + " given)");
  }
  if (direct.empty() && triaxial.empty()) {
    throw InputError(where(parameters) +
                     ": hypoplastic needs either c1 c2 c3 c4 or Ei nu phi psi (none given)");
  }
  const bool is_direct = !direct.empty();
  const auto& keys = is_direct ? kDirectKeys : kTriaxialKeys;
  if (const auto absent = missing(parameters, keys); !absent.empty()) {
    throw InputError(where(parameters) + ": incomplete hypoplastic parameters: " +
                     join(is_direct ? direct : triaxial) + " given, " + join(absent) + " missing");
  }

  HypoplasticParameters out;
  if (is_direct) {
    HypoplasticConstants& c = out.constants;
    c.c1 = parameters.require("c1", Range::negative(), "-", "hypoplastic constant c1");
    c.c2 = parameters.require("c2", Range::any(), "-", "hypoplastic constant c2");
    c.c3 = parameters.require("c3", Range::any(), "-", "hypoplastic constant c3");
    c.c4 = parameters.require("c4", Range::negative(), "-", "hypoplastic constant c4");
  } else {
    TriaxialProperties t;
    t.initial_modulus =
        parameters.require("Ei", Range::positive(), "Pa", "initial tangent modulus");
    t.initial_poisson_ratio =
        parameters.require("nu", Range::closed_open(0.0, 0.5), "-", "initial Poisson's ratio");
    t.friction_angle = parameters.require("phi", Range::open(0.0, 90.0), "deg", "friction angle");
    t.dilatancy_angle =
        parameters.require("psi", Range::closed_open(0.0, 45.0), "deg", "dilatancy angle");
    HypoplasticConstants c;
    try {
      c = calibrate_hypoplastic(t);
    } catch (const std::domain_error&) {
      throw InputError(where(parameters) +
                       ": Ei nu phi psi give a singular calibration; give c1 c2 c3 c4 instead");
    }
    if (!(c.c1 < 0.0 && c.c4 < 0.0 && std::isfinite(c.c2) && std::isfinite(c.c3))) {
      throw InputError(where(parameters) + ": Ei nu phi psi give c1 = " + std::to_string(c.c1) +
                       ", c4 = " + std::to_string(c.c4) + " (both must be negative)");
    }
    out.constants = c;
    parameters.record("c1", c.c1);
    parameters.record("c2", c.c2);
    parameters.record("c3", c.c3);
    parameters.record("c4", c.c4);
  }
  out.cohesion = parameters.optional("c", 0.0, Range::non_negative(), "Pa", "cohesion");
  return out;
}

Mat3 linear_rate(const HypoplasticConstants& c, const Mat3& eta, const Mat3& stretching) {
  const double trace = eta.trace();
  // Guarded ratio: outside the admissible region (tr eta >= 0) the c3 term is dropped instead of
  // dividing by zero; integrate() never evaluates there, it returns to the apex first.
  const double ratio = trace < 0.0 ? contract(eta, stretching) / trace : 0.0;
  // Peng 2015 eq 15 (eq 25 on eta): c1 (tr eta) D + c2 (tr D) eta + c3 tr(eta D)/tr(eta) eta
  return c.c1 * trace * stretching + (c.c2 * stretching.trace() + c.c3 * ratio) * eta;
}

Mat3 nonlinear_direction(const HypoplasticConstants& c, const Mat3& eta) {
  // Peng 2015 eq 15 with eq 16: c4 (eta + eta*), eta* = eta - tr(eta)/3 I
  return c.c4 * (eta + deviator(eta));
}

Mat3 hypoplastic_rate(const HypoplasticConstants& c, const Mat3& eta, const Mat3& stretching) {
  // Peng 2015 eq 15: L : D + c4 (eta + eta*) |D|, |D| = sqrt(tr D^2) (eq 14)
  return linear_rate(c, eta, stretching) + nonlinear_direction(c, eta) * norm(stretching);
}

bool admissible(const Mat3& eta) {
  return eta.allFinite() && eta.trace() <= -1.5 * apex_pressure;
}

Hypoplastic::Hypoplastic(HypoplasticParameters parameters) : parameters_(parameters) {
  const HypoplasticConstants& c = parameters_.constants;
  // |L:D + N |D|| / (|eta| |D|) <= sqrt3 |c1| + sqrt3 |c2| + |c3| |eta|/|tr eta| + 2 |c4|, with
  // |eta|/|tr eta| about 1 inside the failure cone.
  rate_bound_ =
      std::sqrt(3.0) * (std::abs(c.c1) + std::abs(c.c2)) + std::abs(c.c3) + 2.0 * std::abs(c.c4);
}

std::vector<InternalVariable> Hypoplastic::internal_variables() const {
  return {{"corrections", 0.0, "-"}};
}

int Hypoplastic::substeps(double strain_norm) const {
  const double n = std::ceil(strain_norm * rate_bound_ / kSubstepProduct);
  if (!(n <= kMaxSubsteps)) return 0;  // too many (or NaN): not integrated
  return n >= 1.0 ? static_cast<int>(n) : 1;
}

Mat3 Hypoplastic::admissible_eta(const Mat3& stress) const {
  const Mat3 eta = stress - parameters_.cohesion * Mat3::Identity();  // Peng 2015 eq 24
  return admissible(eta) ? eta : apex();
}

void Hypoplastic::integrate(const Mat3& d_strain, Mat3& stress, std::span<double> internal) const {
  const double strain_norm = norm(d_strain);
  if (strain_norm == 0.0) return;  // rate independent: no strain, no stress change
  if (!std::isfinite(strain_norm)) {
    stress.setConstant(std::numeric_limits<double>::quiet_NaN());  // reported by the solver
    return;
  }
  const Mat3 cohesion = parameters_.cohesion * Mat3::Identity();
  Mat3 eta = stress - cohesion;  // Peng 2015 eq 24
  if (!admissible(eta)) {
    eta = apex();
    count_correction(internal);
  }
  const int n = substeps(strain_norm);
  if (n == 0) {
    stress.setConstant(std::numeric_limits<double>::quiet_NaN());  // reported by the solver
    return;
  }
  const Mat3 step = d_strain / n;
  for (int k = 0; k < n; ++k) {
    eta = runge_kutta_step(parameters_.constants, eta, step);
    if (!admissible(eta)) {
      eta = apex();
      count_correction(internal);
    }
  }
  stress = eta + cohesion;
}

Mat3 Hypoplastic::objective_rate(const Mat3& stretching, const Mat3& stress,
                                 std::span<const double>) const {
  // Peng 2015 eq 25: the rate of eta equals the rate of sigma (c is constant)
  return hypoplastic_rate(parameters_.constants, admissible_eta(stress), stretching);
}

Mat6 Hypoplastic::tangent(const Mat3& d_strain, const Mat3& stress, std::span<const double>) const {
  const HypoplasticConstants& c = parameters_.constants;
  const Mat3 eta = admissible_eta(stress);
  Mat6 tangent;
  // L in Voigt form: column j is L applied to the strain of unit Voigt component j (engineering
  // shear, so a unit gamma_xy is eps_xy = eps_yx = 1/2).
  for (int j = 0; j < 6; ++j) {
    tangent.col(j) = stress_to_voigt(linear_rate(c, eta, voigt_to_strain(Vec6::Unit(j))));
  }
  const double strain_norm = norm(d_strain);
  if (strain_norm > 0.0) {
    // d|d_eps|/d(Voigt strain) = d_eps_ij/|d_eps| with the tensor (not engineering) shear
    // components, since |d_eps|^2 = ... + 2 eps_xy^2 = ... + gamma_xy^2/2.
    tangent += stress_to_voigt(nonlinear_direction(c, eta)) *
               stress_to_voigt(d_strain / strain_norm).transpose();
  }
  return tangent;
}

ElasticModuli Hypoplastic::moduli(const Mat3& stress, std::span<const double>) const {
  const HypoplasticConstants& c = parameters_.constants;
  const Mat3 eta = admissible_eta(stress);
  // Isotropic projections of L(eta): K = I : L : I / 9, G = sum_k B_k : L : B_k / 10 over an
  // orthonormal basis B_k of deviators (exact for an isotropic L = 3K P_vol + 2G P_dev).
  const Mat3 I = Mat3::Identity();
  const double bulk = contract(I, linear_rate(c, eta, I)) / 9.0;
  std::array<Mat3, 5> basis;
  basis[0] << 1, 0, 0, 0, -1, 0, 0, 0, 0;
  basis[1] << 1, 0, 0, 0, 1, 0, 0, 0, -2;
  basis[2] << 0, 1, 0, 1, 0, 0, 0, 0, 0;
  basis[3] << 0, 0, 0, 0, 0, 1, 0, 1, 0;
  basis[4] << 0, 0, 1, 0, 0, 0, 1, 0, 0;
  double shear = 0.0;
  for (Mat3& b : basis) {
    b /= norm(b);
    shear += contract(b, linear_rate(c, eta, b));
  }
  shear /= 10.0;
  ElasticModuli e;
  e.bulk = std::max(bulk, 0.0);
  e.shear = std::max(shear, 0.0);
  e.tangent_bound = rate_bound(c, eta);  // L + N, not L's isotropic part: see rate_bound
  return e;
}

void Hypoplastic::correct(Mat3& stress, std::span<double> internal) const {
  const Mat3 cohesion = parameters_.cohesion * Mat3::Identity();
  if (admissible(stress - cohesion)) return;
  stress = apex() + cohesion;
  count_correction(internal);
}

void register_hypoplastic(ModelRegistry& registry) {
  // Example: Peng 2015 Table 1, sand collapse row (c1..c4 = -55.6, -171.2, -540.9, -170.9).
  registry.add({"hypoplastic",
                "Wang/Wu 4-parameter hypoplastic model with cohesion (c1..c4 or Ei, nu, phi, "
                "psi; c)",
                [](Parameters& p) -> std::unique_ptr<Model> {
                  return std::make_unique<Hypoplastic>(HypoplasticParameters::read(p));
                },
                {{"Ei", 20e6}, {"nu", 0.2}, {"phi", 30.0}, {"psi", 1.0}, {"c", 0.0}},
                {{{"c1", -55.6}, {"c2", -171.2}, {"c3", -540.9}, {"c4", -170.9}, {"c", 0.0}}}});
}

}  // namespace duet::constitutive
