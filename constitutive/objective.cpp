#include "constitutive/objective.hpp"

namespace duet::constitutive {

Mat3 rotation_increment(const Mat3& d_spin) {
  // Closed form of the Cayley transform (I - A)^-1 (I + A) of the skew A = dW/2 with axial
  // vector a: I + 2 (A + A^2) / (1 + a.a). Exactly what the inverse gives, without a division
  // per entry.
  const Mat3 A = 0.5 * d_spin;
  const double a2 = A(2, 1) * A(2, 1) + A(0, 2) * A(0, 2) + A(1, 0) * A(1, 0);
  return Mat3::Identity() + (2.0 / (1.0 + a2)) * (A + A * A);
}

void update_stress(const Model& model, const Mat3& d_strain, const Mat3& d_spin, Mat3& stress,
                   std::span<double> internal) {
  if (d_spin.squaredNorm() > 0.0) {
    const Mat3 R = rotation_increment(d_spin);
    stress = R * stress * R.transpose();
  }
  model.integrate(d_strain, stress, internal);
}

Mat3 stress_rate(const Model& model, const Mat3& stretching, const Mat3& spin, const Mat3& stress,
                 std::span<const double> internal) {
  return model.objective_rate(stretching, stress, internal) + spin * stress - stress * spin;
}

}  // namespace duet::constitutive
