#pragma once
// Small pieces shared by the files of the SPH step (sph_solver.cpp: pair loop and update;
// velocity_gradient_pass.cpp: the leapfrog's second pass; working_set.cpp: working order, ghosts,
// Verlet list): a particle's pair sums, in-plane stress block, the artificial
// stress R of Peng 2015 eq 29, the mirror image of a tensor across a wall, and the threading
// threshold of the step.

#include <algorithm>
#include <cstddef>
#include <limits>

#include "common/tensor.hpp"

namespace duet::sph::detail {

// Below this many soil particles the step runs on one thread: a parallel region costs a fork and
// a barrier, more than the work of a small scene (and far more on a loaded machine).
inline constexpr std::size_t kParallelMin = 2048;

inline Mat2 in_plane(const Mat3& s) {
  return s.topLeftCorner<2, 2>();
}

/// One soil particle's pair sums (the force pass and the leapfrog's velocity pass): eq 30's
/// acceleration, eq 21's velocity gradient, simhypo eq 24's density rate and eq 31's smallest
/// normal stresses among its soil neighbours. Per thread and particle, summed over threads.
struct PairSum {
  double ax = 0.0, ay = 0.0;
  double lxx = 0.0, lxy = 0.0, lyx = 0.0, lyy = 0.0;
  double rho_rate = 0.0;
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

  /// Adds another share of the same particle's sums (another row, another thread).
  PairSum& operator+=(const PairSum& o) {
    ax += o.ax;
    ay += o.ay;
    lxx += o.lxx;
    lxy += o.lxy;
    lyx += o.lyx;
    lyy += o.lyy;
    rho_rate += o.rho_rate;
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
