#include "constitutive/model.hpp"

namespace duet::constitutive {

Mat6 Model::tangent(const Mat3& d_strain, const Mat3& stress,
                    std::span<const double> internal) const {
  return finite_difference_tangent(*this, d_strain, stress, internal);
}

void Model::integrate_with_tangent(const Mat3& d_strain, Mat3& stress, std::span<double> internal,
                                   Mat6& tangent) const {
  tangent = this->tangent(d_strain, stress, internal);  // on the state before the increment
  integrate(d_strain, stress, internal);
}

Mat6 finite_difference_tangent(const Model& model, const Mat3& d_strain, const Mat3& stress,
                               std::span<const double> internal, double h) {
  const Vec6 e0 = strain_to_voigt(d_strain);
  const double scale = std::max(e0.norm(), 1e-6);
  const double step = h * scale;
  std::vector<double> work(internal.begin(), internal.end());
  Mat6 tangent;
  for (int j = 0; j < 6; ++j) {
    Vec6 plus = e0, minus = e0;
    plus(j) += step;
    minus(j) -= step;
    Mat3 s_plus = stress, s_minus = stress;
    std::copy(internal.begin(), internal.end(), work.begin());
    model.integrate(voigt_to_strain(plus), s_plus, work);
    std::copy(internal.begin(), internal.end(), work.begin());
    model.integrate(voigt_to_strain(minus), s_minus, work);
    tangent.col(j) = (stress_to_voigt(s_plus) - stress_to_voigt(s_minus)) / (2.0 * step);
  }
  return tangent;
}

}  // namespace duet::constitutive
