#pragma once
// Small pieces shared by the files of the SPH step (sph_solver.cpp: pair loop and update;
// velocity_gradient_pass.cpp: the leapfrog's second pass; working_set.cpp: working order, ghosts,
// Verlet list): what the pair loops read of a particle, the terms of one pair of the force pass
// (Peng 2015 eqs 26-30) and a particle's pair sums, the in-plane stress block, the artificial
// stress R of eq 29, the mirror image of a tensor across a wall, and the threading threshold of
// the step.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>

#include "common/scene.hpp"
#include "common/tensor.hpp"
#include "sph/kernel.hpp"

namespace duet::sph::detail {

// Below this many soil particles the step runs on one thread: a parallel region costs a fork and
// a barrier, more than the work of a small scene (and far more on a loaded machine).
inline constexpr std::size_t kParallelMin = 2048;

inline Mat2 in_plane(const Mat3& s) {
  return s.topLeftCorner<2, 2>();
}

/// Axisymmetric: the ring weight 2 pi |r| of a particle at x = r (Garcia-Senz et al. 2009: a
/// particle is the ring it sweeps, its mass m = 2 pi r rho A, its plane density eta = 2 pi r rho;
/// an image beyond the axis, at -r, stands for the same ring). Kept off zero (1 pm, so that a
/// stress over it stays finite): a soil particle on the axis fails the step first
/// (SphSolver::check_off_axis), a dummy there weighs next to nothing.
inline double ring_weight(double x) {
  constexpr double kOffAxis = 1e-12;  // m
  return 2.0 * std::numbers::pi * std::max(std::abs(x), kOffAxis);
}

/// What the pair loops read of particle j, in the solver's working order (soil sorted by cell,
/// then ghost candidates, then dummies), packed so that one neighbour is one or two cache lines:
/// position, velocity, mass, density, volume m / rho and the in-plane stress / rho^2 (symmetric).
struct PairData {
  double x, y, vx, vy, m, rho, vol, sxx, syy, sxy;
};

/// Axisymmetric: the plane area A = V / (2 pi |r|) of a particle whose working volume is its
/// ring's.
inline double plane_area(const PairData& p) {
  return p.vol / ring_weight(p.x);
}

/// Peng 2015 eq 29 artificial stress R (symmetric), in working order; only with b > 0.
struct SymR {
  double xx, yy, xy;
};

/// The terms of one pair (i, j) of the force pass that both ends share: grad_i W_ij (gx, gy),
/// v_i - v_j (vx, vy) and the bracket of Peng 2015 eq 30, sigma_i/rho_i^2 + sigma_j/rho_j^2
/// - Pi_ij I + S_ij (cxx, cyy, cxy).
struct ForcePair {
  double gx, gy, vx, vy, cxx, cyy, cxy;

  /// The bracket of eq 30 times grad_i W_ij: the pair's acceleration of i per unit mass of j,
  /// its force on i per unit m_i m_j.
  Vec2 bracket_times_gradient() const { return Vec2(cxx * gx + cxy * gy, cxy * gx + cyy * gy); }
};

/// Evaluates ForcePair for the force pass, with the scene's constants resolved once per pass.
class ForcePairTerms {
 public:
  /// w_dp = W(dp) and exponent_n = W(0) / W(dp), Peng 2015 eq 28.
  /// ring: axisymmetric (the viscosity over the pair's mean ring weight, as the stresses are).
  ForcePairTerms(const Kernel& kernel, const SphOptions& options, double h, double w_dp,
                 double exponent_n, bool ring = false)
      : ring_(ring),
        kernel_(&kernel),
        h_(h),
        support2_(kernel.support_radius() * kernel.support_radius()),
        alpha_cs_(options.alpha * options.sound_speed),
        beta_(options.beta),
        eps_h2_(0.01 * h * h),
        b_(options.artificial_stress),
        w_dp_(w_dp),
        exponent_n_(exponent_n) {}

  /// Pair (i, j) with j's density rho_j and stress / rho_j^2 (txx, tyy, txy) given apart from
  /// pj, whose position and velocity it takes: a dummy carries the density of i and eq 31's
  /// stress (or, with Bui 2008, that of i). r_i, r_j: eq 29's R (read only with b > 0). cached:
  /// the pair's gradient factor from the leapfrog's velocity pass at these same positions, or
  /// null. False when j lies in the skin, beyond 2h.
  bool evaluate(const PairData& pi, const PairData& pj, double rho_j, double txx, double tyy,
                double txy, const SymR& r_i, const SymR& r_j, const double* cached,
                ForcePair& p) const {
    const double dx = pi.x - pj.x, dy = pi.y - pj.y;
    const double r2 = dx * dx + dy * dy;
    if (r2 >= support2_) return false;
    double r = 0.0;  // only the artificial stress needs it, and then nothing is cached
    double f;
    if (cached != nullptr) {
      f = *cached;  // the same arithmetic on the same positions, done in the velocity pass
    } else {
      r = std::sqrt(r2);
      f = kernel_->gradient_factor(r, 1.0 / std::max(r, kTiny));
    }
    p.gx = f * dx;  // grad_i W_ij
    p.gy = f * dy;
    p.vx = pi.vx - pj.vx;
    p.vy = pi.vy - pj.vy;
    // Peng 2015 eqs 26-27: artificial viscosity on approaching pairs (vr < 0), evaluated for
    // every pair and selected without a branch: about half the pairs approach, in no pattern.
    const double vr = p.vx * dx + p.vy * dy;
    const double phi = h_ * vr / (r2 + eps_h2_);
    const double viscosity = (-alpha_cs_ * phi + beta_ * phi * phi) * 2.0 / (pi.rho + rho_j);
    double pi_ij = select_without_branch(vr < 0.0, viscosity, 0.0);
    // Axisymmetric: the bracket holds stress / (rho^2 2 pi r) (the pair sums run over the ring
    // masses, Garcia-Senz et al. 2009), so the viscous pressure is over the pair's mean ring
    if (ring_) pi_ij /= std::numbers::pi * (std::abs(pi.x) + std::abs(pj.x));
    // Peng 2015 eq 30: sigma_i/rho_i^2 + sigma_j/rho_j^2 - Pi_ij I + S_ij
    p.cxx = pi.sxx + txx - pi_ij;
    p.cyy = pi.syy + tyy - pi_ij;
    p.cxy = pi.sxy + txy;
    if (b_ > 0.0) {
      // Peng 2015 eq 28: S_ij = f_ij^n (R_i + R_j), f_ij = W_ij / W(dp)
      const double fn = std::pow(kernel_->value(r) / w_dp_, exponent_n_);
      p.cxx += fn * (r_i.xx + r_j.xx);
      p.cyy += fn * (r_i.yy + r_j.yy);
      p.cxy += fn * (r_i.xy + r_j.xy);
    }
    return true;
  }

 private:
  // 1 / max(r, kTiny) stays finite at r = 0, where grad_i W_ij vanishes with r_ij.
  static constexpr double kTiny = std::numeric_limits<double>::min();
  bool ring_;
  const Kernel* kernel_;
  double h_;
  double support2_;  // (2h)^2
  double alpha_cs_;  // alpha c_s, eq 27
  double beta_;
  double eps_h2_;  // 0.01 h^2 in eq 27's denominator: no singularity as r_ij -> 0
  double b_;       // artificial stress coefficient, eq 29 (0 = off)
  double w_dp_;
  double exponent_n_;
};

/// One soil particle's pair sums (the force pass and the leapfrog's velocity pass): eq 30's
/// acceleration, eq 21's velocity gradient, simhypo eq 24's density rate and eq 31's smallest
/// normal stresses among its soil neighbours. Per thread and particle, summed over threads.
struct PairSum {
  double ax = 0.0, ay = 0.0;
  double lxx = 0.0, lxy = 0.0, lyx = 0.0, lyy = 0.0;
  double rho_rate = 0.0;
  // Axisymmetric: the r-z plane's SPH gradient of |r|, sum_j A_j (|r_j| - r_i) d_r W_ij (A_j the
  // plane area m_j / (2 pi |r_j| rho_j)): the radial direction as the pair sums see it
  double ring_r = 0.0;
  double min_xx = std::numeric_limits<double>::infinity();
  double min_yy = std::numeric_limits<double>::infinity();

  /// What pair (i, j) adds to eq 21 and eq 24 at one end, given g = grad_i W_ij, v = v_i - v_j
  /// and the other end's mass m and volume V: the same at both ends (v and g both flip).
  void add_rates(double gx, double gy, double vx, double vy, double m, double volume) {
    // Peng 2015 eq 21: grad v_i = sum_j (v_j - v_i) (x) grad_i W_ij m_j / rho_j
    lxx -= vx * gx * volume;
    lxy -= vx * gy * volume;
    lyx -= vy * gx * volume;
    lyy -= vy * gy * volume;
    // simhypo-sand eq 24: d rho_i / dt = sum_j m_j (v_i - v_j) . grad_i W_ij
    rho_rate += m * (vx * gx + vy * gy);
  }

  /// What pair (i, j) adds at end i with the other end's mass m_j and volume V_j: eq 30's
  /// acceleration and, with `rates`, eqs 21 and 24. The other end's share has the same form with
  /// m_i, V_i and sign -1 (grad_j W_ji = -grad_i W_ij; Newton's third law for the force).
  void add_force(const ForcePair& p, double m_j, double volume_j, double sign, bool rates) {
    const Vec2 a = p.bracket_times_gradient();
    ax += sign * m_j * a.x();  // Peng 2015 eq 30
    ay += sign * m_j * a.y();
    if (rates) add_rates(p.gx, p.gy, p.vx, p.vy, m_j, volume_j);
  }

  /// Axisymmetric: what pair (i, j) adds to ring_r at one end, given g_x = (grad_i W_ij)_x and
  /// dr = |r_j| - r_i, and the other end's plane area A: the same at both ends of a soil pair
  /// (from j, r_i - r_j and grad_j W_ji both flip).
  void add_ring(double gx, double dr, double area) { ring_r += area * dr * gx; }

  /// Peng 2015 eq 31: keeps the smallest normal stresses among the particle's soil neighbours
  /// (the stress of a dummy it sees).
  void take_min_normal_stress(const PairData& pj) {
    min_xx = std::min(min_xx, pj.sxx * pj.rho * pj.rho);
    min_yy = std::min(min_yy, pj.syy * pj.rho * pj.rho);
  }

  /// Adds another share of the same particle's sums (another row, another thread).
  PairSum& operator+=(const PairSum& o) {
    ax += o.ax;
    ay += o.ay;
    lxx += o.lxx;
    lxy += o.lxy;
    lyx += o.lyx;
    lyy += o.lyy;
    rho_rate += o.rho_rate;
    ring_r += o.ring_r;
    min_xx = std::min(min_xx, o.min_xx);
    min_yy = std::min(min_yy, o.min_yy);
    return *this;
  }
};

/// Peng 2015 eq 29: R^{mn} = -b sigma^{mn} / rho^2 where sigma^{mn} > 0, else 0.
inline Mat2 artificial_stress_term(const Mat2& sigma, double rho, double b) {
  Mat2 r = Mat2::Zero();
  for (int m = 0; m < 2; ++m) {
    for (int n = 0; n < 2; ++n) {
      if (sigma(m, n) > 0.0) r(m, n) = -b * sigma(m, n) / (rho * rho);
    }
  }
  return r;
}

/// Mirror image R s R of an in-plane tensor across a line with unit normal n, R = I - 2 n n^T.
inline Mat2 mirror(const Mat2& s, const Vec2& n) {
  const Mat2 r = Mat2::Identity() - 2.0 * n * n.transpose();
  return r * s * r;
}

/// The same for a full tensor, the out-of-plane direction unchanged.
inline Mat3 mirror(const Mat3& s, const Vec2& n) {
  Mat3 r = Mat3::Identity();
  r.topLeftCorner<2, 2>() -= 2.0 * n * n.transpose();
  return r * s * r;
}

/// Mirror image of a vector across a line with unit normal n: its normal part reversed.
inline Vec2 mirror(const Vec2& v, const Vec2& n) {
  return v - 2.0 * v.dot(n) * n;
}

}  // namespace duet::sph::detail
