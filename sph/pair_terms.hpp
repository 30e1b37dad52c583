#pragma once
// Small pieces shared by the files of the SPH step (sph_solver.cpp: pair loop and update;
// working_set.cpp: working order, ghosts, Verlet list): in-plane stress block, the artificial
// stress R of Peng 2015 eq 29, the mirror image of a tensor across a wall, and the threading
// threshold of the step.

#include <cstddef>

#include "common/tensor.hpp"

namespace duet::sph::detail {

// Below this many soil particles the step runs on one thread: a parallel region costs a fork and
// a barrier, more than the work of a small scene (and far more on a loaded machine).
inline constexpr std::size_t kParallelMin = 2048;

inline Mat2 in_plane(const Mat3& s) {
  return s.topLeftCorner<2, 2>();
}

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

}  // namespace duet::sph::detail
