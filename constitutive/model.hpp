#pragma once
// The interface every soil model implements. A model maps (old state, strain increment) to a new
// state and, when asked, a tangent. It sees no particle, no mesh, no solver: SPH, explicit SPFEM
// and implicit SPFEM call the very same functions.
//
// Conventions: tension positive (compression negative, as in the papers); stress is a full
// symmetric 3x3 (plane strain keeps sigma_zz); velocity gradient L_ij = dv_i/dx_j, stretching
// D = sym(L), spin W = skew(L). Rotation is handled once, in objective.hpp (Jaumann rate, Peng 2015
// eq 13), so a model integrates only the co-rotational (objective) part.

#include <cmath>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/tensor.hpp"

namespace duet::constitutive {

/// One internal variable a model keeps per material point (stored as a double; counters too).
struct InternalVariable {
  std::string name;      // "void_ratio", "plastic_strain", "corrections", ...
  double initial = 0.0;  // value at the start of a run (may come from the parameters, e.g. e0)
  std::string unit;      // "-" when dimensionless
};

/// Elastic moduli at the current state, for time steps and sound speeds.
struct ElasticModuli {
  double bulk = 0.0;   // K, Pa
  double shear = 0.0;  // G, Pa
  // Bound M on the tangent for the explicit SPFEM time step, Pa: |dsigma|_2 <= M |v| |b| for every
  // in-plane strain rate D = sym(v (x) b). 0 = use |lambda| + 2G (exact for isotropic elasticity).
  double tangent_bound = 0.0;
};

/// M, the bound on the in-plane tangent acting between two gradients: the model's own
/// tangent_bound where it gives one (hypoplastic: L + N), else |lambda| + 2 G with
/// lambda = K - 2 G / 3 (= K + 4 G / 3 for lambda >= 0). sqrt(M / rho) is the fastest wave the
/// explicit SPFEM step follows (its time step and stiffness stabilisation; duet check's estimate).
inline double block_modulus(const ElasticModuli& e) {
  if (e.tangent_bound > 0.0) return e.tangent_bound;
  return std::abs(e.bulk - 2.0 * e.shear / 3.0) + 2.0 * std::abs(e.shear);
}

class Model {
 public:
  virtual ~Model() = default;

  /// Registry name ("hypoplastic", "drucker-prager", ...).
  virtual std::string_view name() const = 0;

  /// Internal variables of this model in storage order; their initial values.
  virtual std::vector<InternalVariable> internal_variables() const { return {}; }

  /// Integrate the objective stress over a co-rotational strain increment d_strain (symmetric),
  /// updating `stress` and `internal` in place. Plastic models return to their surface here.
  virtual void integrate(const Mat3& d_strain, Mat3& stress, std::span<double> internal) const = 0;

  /// Objective (Jaumann) stress rate for a stretching rate D at the current state, for explicit
  /// integrators that want a rate (Peng 2015 eq 34). Plastic models give the continuum rate.
  virtual Mat3 objective_rate(const Mat3& stretching, const Mat3& stress,
                              std::span<const double> internal) const = 0;

  /// Tangent d(sigma_{n+1})/d(d_strain) of integrate() from (stress, internal) along d_strain,
  /// in Voigt form (stress plain, strain with engineering shear; order xx yy zz xy yz zx).
  /// Drucker-Prager and Tresca: the consistent (algorithmic) tangent. Hypoplastic models: the
  /// tangent along the increment's direction, L + N (x) d_eps/|d_eps|. The default is a central
  /// finite difference of integrate().
  virtual Mat6 tangent(const Mat3& d_strain, const Mat3& stress,
                       std::span<const double> internal) const;

  /// integrate() and tangent() in one call, for Newton iterations that need both: updates
  /// `stress` and `internal` exactly as integrate() does (bitwise the same values) and returns in
  /// `tangent` what tangent(d_strain, stress, internal) returns for the state before the call
  /// (same Voigt order and conventions). Return-mapping models override it to form the consistent
  /// tangent from the same return, instead of running the return mapping a second time. The
  /// default evaluates tangent() on the inputs, then calls integrate().
  virtual void integrate_with_tangent(const Mat3& d_strain, Mat3& stress,
                                      std::span<double> internal, Mat6& tangent) const;

  /// Elastic moduli at the state, for the time step (sound speed) and stabilisation.
  virtual ElasticModuli moduli(const Mat3& stress, std::span<const double> internal) const = 0;

  /// Post-step correction some models need (simhypo-sand Methods A/B/C, hypoplastic apex
  /// return). Default: nothing.
  virtual void correct(Mat3& /*stress*/, std::span<double> /*internal*/) const {}
};

/// Finite-difference tangent of model.integrate (central differences, step h relative).
Mat6 finite_difference_tangent(const Model& model, const Mat3& d_strain, const Mat3& stress,
                               std::span<const double> internal, double h = 1e-7);

}  // namespace duet::constitutive
