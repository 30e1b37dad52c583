#pragma once
// SPH smoothing kernels in two dimensions (plane strain), both with support radius 2h:
// the cubic spline (Peng 2015 eq 2) and the Wendland C2 kernel (simhypo-sand paper, eq 23).
// value() and gradient() are inline: the pair loops call them for every neighbour pair.

#include <algorithm>
#include <bit>
#include <cstdint>
#include <string>

#include "common/scene.hpp"
#include "common/tensor.hpp"

namespace duet::sph {

/// The scene's [sph] kernel choice (parsed and checked by the scene loader).
using KernelKind = SphKernel;

/// take_a ? a : b by a bit mask, for the pair loops: GCC compiles such a choice between doubles
/// into a branch (and moves the work of the chosen side into it), which costs a misprediction
/// whenever the choice follows no pattern. Both sides must be computed; the result is exactly
/// one of them.
inline double select_without_branch(bool take_a, double a, double b) {
  const std::uint64_t mask = -static_cast<std::uint64_t>(take_a);  // all ones or none
  return std::bit_cast<double>((std::bit_cast<std::uint64_t>(a) & mask) |
                               (std::bit_cast<std::uint64_t>(b) & ~mask));
}

std::string kernel_name(KernelKind kind);

class Kernel {
 public:
  Kernel(KernelKind kind, double h);

  KernelKind kind() const { return kind_; }
  double smoothing_length() const { return h_; }
  /// Radius of the compact support, 2h for both kernels.
  double support_radius() const { return 2.0 * h_; }

  /// W(r, h).
  double value(double r) const {
    const double q = r * inv_h_;
    if (kind_ == KernelKind::cubic_spline) {
      // Peng 2015 eq 2 (alpha_C = 10 / (7 pi h^2) in 2D)
      if (q < 1.0) return alpha_ * (1.0 - 1.5 * q * q + 0.75 * q * q * q);
      if (q < 2.0) return alpha_ * 0.25 * (2.0 - q) * (2.0 - q) * (2.0 - q);
      return 0.0;
    }
    // simhypo-sand eq 23: W = alpha_d (1 - q/2)^4 (2q + 1)
    if (q >= 2.0) return 0.0;
    const double a = 1.0 - 0.5 * q;
    return alpha_ * a * a * a * a * (2.0 * q + 1.0);
  }

  /// dW/dr (<= 0).
  double derivative(double r) const {
    const double q = r * inv_h_;
    if (kind_ == KernelKind::cubic_spline) {
      // d/dr of Peng 2015 eq 2
      if (q < 1.0) return alpha_ * inv_h_ * (-3.0 * q + 2.25 * q * q);
      if (q < 2.0) return -alpha_ * inv_h_ * 0.75 * (2.0 - q) * (2.0 - q);
      return 0.0;
    }
    // d/dr of simhypo-sand eq 23: -5 q (1 - q/2)^3 alpha_d / h
    if (q >= 2.0) return 0.0;
    const double a = 1.0 - 0.5 * q;
    return -5.0 * alpha_ * inv_h_ * q * a * a * a;
  }

  /// (dW/dr) / r, so that grad_i W_ij = gradient_factor(r) r_ij; zero at r = 0 and beyond 2h.
  /// The pair loop's form: q / r = 1 / h removes the division inside the support's core.
  double gradient_factor(double r) const {
    if (r <= 0.0) return 0.0;
    const double q = r * inv_h_;
    if (kind_ == KernelKind::cubic_spline) {
      // d/dr of Peng 2015 eq 2, divided by r
      if (q < 1.0) return alpha_ * inv_h_ * inv_h_ * (-3.0 + 2.25 * q);
      if (q < 2.0) return -alpha_ * inv_h_ * 0.75 * (2.0 - q) * (2.0 - q) / r;
      return 0.0;
    }
    // d/dr of simhypo-sand eq 23, divided by r: -5 (1 - q/2)^3 alpha_d / h^2
    if (q >= 2.0) return 0.0;
    const double a = 1.0 - 0.5 * q;
    return -5.0 * alpha_ * inv_h_ * inv_h_ * a * a * a;
  }

  /// The same as gradient_factor(r), branch free, for the pair loop: r >= 0 and inv_r = 1 / r
  /// (any finite value at r = 0, where the gradient f r_ij vanishes with r_ij). Both pieces of
  /// the cubic spline are evaluated and one is selected, so a pair costs the same wherever it
  /// lies in the support (and beyond it, where the factor is zero). Selected without a branch:
  /// which piece a neighbour falls in is a coin toss for the diagonal neighbours of a lattice at
  /// h / dp = sqrt 2.
  double gradient_factor(double r, double inv_r) const {
    const double q = r * inv_h_;
    if (kind_ == KernelKind::cubic_spline) {
      // d/dr of Peng 2015 eq 2, divided by r
      const double inner = alpha_ * inv_h_ * inv_h_ * (-3.0 + 2.25 * q);
      const double t = std::max(2.0 - q, 0.0);
      const double outer = -0.75 * alpha_ * inv_h_ * t * t * inv_r;
      return select_without_branch(q < 1.0, inner, outer);
    }
    // d/dr of simhypo-sand eq 23, divided by r
    const double a = std::max(1.0 - 0.5 * q, 0.0);
    return -5.0 * alpha_ * inv_h_ * inv_h_ * a * a * a;
  }

  /// grad_i W_ij for r_ij = x_i - x_j with |r_ij| = r (zero at r = 0).
  Vec2 gradient(const Vec2& r_ij, double r) const {
    if (r <= 0.0) return Vec2::Zero();
    return (derivative(r) / r) * r_ij;
  }

 private:
  KernelKind kind_;
  double h_;
  double inv_h_;
  double alpha_;  // 2D normalisation factor
};

}  // namespace duet::sph
