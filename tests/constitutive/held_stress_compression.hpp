#pragma once
// Shared by the material-point tests: compression along y (axial) from an isotropic start, with
// the lateral components in `held` (indices 0 and/or 2) iterated by Newton on the model's tangent
// until their stress equals the start value; the other strain components are zero. Drained
// triaxial holds {0, 2}; plane strain holds {0} (eps_zz = 0).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "constitutive/model.hpp"

namespace duet::constitutive {

/// Runs `n_increments` equal axial increments and calls on_step(stress, d_strain) after each;
/// returns the largest number of Newton iterations an increment needed. A non-converging
/// increment is a test failure (after 30 iterations), never silent.
template <typename OnStep>
int compress_holding_lateral_stress(const Model& model, double lateral, double axial_strain,
                                    int n_increments, const std::vector<int>& held,
                                    OnStep on_step) {
  std::vector<double> internal;
  for (const auto& v : model.internal_variables()) internal.push_back(v.initial);
  Mat3 start = lateral * Mat3::Identity();
  Vec3 d_principal(0.0, axial_strain / n_increments, 0.0);
  const int m = static_cast<int>(held.size());
  int max_iterations = 0;
  for (int step = 0; step < n_increments; ++step) {
    Mat3 stress;
    std::vector<double> work;
    int iteration = 0;
    for (;; ++iteration) {
      stress = start;
      work = internal;
      const Mat3 d_strain = d_principal.asDiagonal();
      model.integrate(d_strain, stress, work);
      Eigen::VectorXd residual(m);
      for (int i = 0; i < m; ++i) residual(i) = stress(held[i], held[i]) - lateral;
      if (residual.lpNorm<Eigen::Infinity>() <= 1e-12 * std::abs(lateral)) break;
      if (iteration == 30) {
        ADD_FAILURE() << "lateral Newton iteration did not converge at step " << step;
        break;
      }
      const Mat6 tangent = model.tangent(d_strain, start, internal);
      Eigen::MatrixXd jacobian(m, m);
      for (int i = 0; i < m; ++i) {
        for (int j = 0; j < m; ++j) jacobian(i, j) = tangent(held[i], held[j]);
      }
      const Eigen::VectorXd correction = jacobian.fullPivLu().solve(residual);
      for (int i = 0; i < m; ++i) d_principal(held[i]) -= correction(i);
    }
    max_iterations = std::max(max_iterations, iteration);
    start = stress;
    internal = work;
    on_step(stress, Mat3(d_principal.asDiagonal()));
  }
  return max_iterations;
}

}  // namespace duet::constitutive
