#pragma once
// Shared by the model tests: Model::integrate_with_tangent must update the state exactly as
// integrate() does (bitwise) and return the tangent that tangent() gives for the state before
// the increment (constitutive/model.hpp).

#include <gtest/gtest.h>

#include <vector>

#include "constitutive/model.hpp"

namespace duet::constitutive {

inline void expect_integrate_with_tangent_matches(const Model& model, const Mat3& d_strain,
                                                  const Mat3& start,
                                                  const std::vector<double>& internal_start) {
  // Reference: the separate calls.
  const Mat6 reference_tangent = model.tangent(d_strain, start, internal_start);
  Mat3 reference_stress = start;
  std::vector<double> reference_internal = internal_start;
  model.integrate(d_strain, reference_stress, reference_internal);
  // Act
  Mat3 stress = start;
  std::vector<double> internal = internal_start;
  Mat6 tangent = Mat6::Constant(-1.0);
  model.integrate_with_tangent(d_strain, stress, internal, tangent);
  // Assert: the same stress and internal variables to the last bit, the same tangent to round-off
  // (exactly zero where the reference is, e.g. at an apex).
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) EXPECT_EQ(stress(i, j), reference_stress(i, j)) << i << j;
  }
  EXPECT_EQ(internal, reference_internal);
  EXPECT_LE((tangent - reference_tangent).norm(), 1e-10 * reference_tangent.norm())
      << "tangent\n"
      << tangent << "\nreference\n"
      << reference_tangent;
}

}  // namespace duet::constitutive
