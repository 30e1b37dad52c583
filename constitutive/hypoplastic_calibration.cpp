#include "constitutive/hypoplastic_calibration.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace duet::constitutive {

namespace {

using Coefficients = Eigen::RowVector4d;  // multiplies (c1, c2, c3, c4)

double radians(double degrees) {
  return degrees * std::numbers::pi / 180.0;
}

// Peng 2015 eq 15 on a triaxial state sigma = sigma_3 diag(R, 1, 1) with the strain rate
// deps_1 diag(1, -nu, -nu), deps_1 < 0 (compression), so |deps| = -deps_1 sqrt(1 + 2 nu^2),
// tr deps = deps_1 (1 - 2 nu), tr(sigma deps) = sigma_3 deps_1 (R - 2 nu), sigma* = sigma_3/3
// diag(2 (R - 1), 1 - R, 1 - R). Each rate component is sigma_3 deps_1 (coefficients . c).
Coefficients axial_rate(double R, double nu) {
  const double norm = std::sqrt(1.0 + 2.0 * nu * nu);
  // dsigma_1/(sigma_3 deps_1): c1 tr(sigma) + c2 tr(deps) sigma_1 + c3 tr(sigma deps)/tr(sigma)
  // sigma_1 + c4 (sigma_1 + sigma_1*) |deps|
  return {R + 2.0, (1.0 - 2.0 * nu) * R, (R - 2.0 * nu) * R / (R + 2.0),
          -(5.0 * R - 2.0) / 3.0 * norm};
}

Coefficients lateral_rate(double R, double nu) {
  const double norm = std::sqrt(1.0 + 2.0 * nu * nu);
  return {-nu * (R + 2.0), 1.0 - 2.0 * nu, (R - 2.0 * nu) / (R + 2.0), -(4.0 - R) / 3.0 * norm};
}

}  // namespace

double failure_stress_ratio(double friction_angle_deg) {
  const double s = std::sin(radians(friction_angle_deg));
  return (1.0 + s) / (1.0 - s);  // Peng 2015 eq 17
}

double failure_poisson_ratio(double dilatancy_angle_deg) {
  return 0.5 * (1.0 + std::tan(radians(dilatancy_angle_deg)));  // Peng 2015 eq 18
}

HypoplasticConstants calibrate_hypoplastic(const TriaxialProperties& triaxial) {
  const double nu_i = triaxial.initial_poisson_ratio;
  const double R_f = failure_stress_ratio(triaxial.friction_angle);
  const double nu_f = failure_poisson_ratio(triaxial.dilatancy_angle);
  Eigen::Matrix4d A;
  Eigen::Vector4d b;
  // Initial state R = 1: E_i = (dsigma_1 - dsigma_3)/deps_1 and dsigma_3 = 0 (drained, sigma_3
  // held) with deps_3/deps_1 = -nu_i.
  A.row(0) = axial_rate(1.0, nu_i) - lateral_rate(1.0, nu_i);
  b(0) = triaxial.initial_modulus / triaxial.confining_stress;
  A.row(1) = lateral_rate(1.0, nu_i);
  b(1) = 0.0;
  // Failure R = R_f (eq 17): the stress is stationary, dsigma_1 = dsigma_3 = 0, while the strain
  // keeps flowing with deps_3/deps_1 = -nu_f (eq 18).
  A.row(2) = axial_rate(R_f, nu_f);
  b(2) = 0.0;
  A.row(3) = lateral_rate(R_f, nu_f);
  b(3) = 0.0;
  const Eigen::FullPivLU<Eigen::Matrix4d> lu(A);
  if (!lu.isInvertible()) {
    throw std::domain_error("hypoplastic calibration: the triaxial conditions are singular");
  }
  const Eigen::Vector4d c = lu.solve(b);
  return {c(0), c(1), c(2), c(3)};
}

double oedometer_k0(const HypoplasticConstants& constants) {
  const double c1 = constants.c1;
  const double c4 = constants.c4;
  // Peng 2015 eq 38: a K0^2 + b K0 + c = 0
  const double a = 6.0 * c1 + 2.0 * c4;
  const double b = 3.0 * c1 - c4;
  const double c = -c4;
  const double discriminant = b * b - 4.0 * a * c;
  if (a == 0.0 || discriminant < 0.0) return std::numeric_limits<double>::quiet_NaN();
  const double root = std::sqrt(discriminant);
  for (const double k0 : {(-b + root) / (2.0 * a), (-b - root) / (2.0 * a)}) {
    if (k0 > 0.0 && k0 < 1.0) return k0;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace duet::constitutive
