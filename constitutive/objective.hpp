#pragma once
// Objective stress update (Jaumann rate, Peng 2015 eq 13; Bui 2008 eq 11), shared by every solver.
//
// Incremental form: the stress is first rotated by the spin increment with the Hughes-Winget
// rotation R = (I - dW/2)^-1 (I + dW/2), which is exactly orthogonal, so a rigid rotation leaves
// every invariant unchanged to round-off; then the model integrates the co-rotational increment.
// Rate form: d(sigma)/dt = objective_rate(D) + W sigma - sigma W (eq 13 solved for the material
// rate).

#include <span>

#include "common/tensor.hpp"
#include "constitutive/model.hpp"

namespace duet::constitutive {

/// Hughes-Winget rotation increment for a spin increment dW = W dt (skew).
Mat3 rotation_increment(const Mat3& d_spin);

/// Objective update over one step: d_strain = D dt, d_spin = W dt.
void update_stress(const Model& model, const Mat3& d_strain, const Mat3& d_spin, Mat3& stress,
                   std::span<double> internal);

/// Material stress rate: model's objective rate plus the Jaumann spin terms W sigma - sigma W.
Mat3 stress_rate(const Model& model, const Mat3& stretching, const Mat3& spin, const Mat3& stress,
                 std::span<const double> internal);

}  // namespace duet::constitutive
