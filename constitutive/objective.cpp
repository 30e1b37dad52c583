#include "constitutive/objective.hpp"

namespace duet::constitutive {

Mat3 rotation_increment(const Mat3& d_spin) {
  const Mat3 I = Mat3::Identity();
  return (I - 0.5 * d_spin).inverse() * (I + 0.5 * d_spin);
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
