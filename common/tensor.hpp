#pragma once
// Tensor helpers on Eigen and the stress invariants used everywhere (one place, one test).
// Convention: tension positive (as the papers), stress is a full symmetric 3x3 even in plane
// strain. Voigt order for 6-vectors: (xx, yy, zz, xy, yz, zx); strain 6-vectors carry engineering
// shear (gamma_xy = 2 eps_xy), stress 6-vectors carry the plain components.

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace duet {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat2 = Eigen::Matrix2d;
using Mat3 = Eigen::Matrix3d;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

inline Mat3 identity3() {
  return Mat3::Identity();
}

inline Mat3 deviator(const Mat3& a) {
  return a - a.trace() / 3.0 * Mat3::Identity();
}

/// Double contraction a : b.
inline double contract(const Mat3& a, const Mat3& b) {
  return (a.array() * b.array()).sum();
}

/// Euclidean (Frobenius) norm sqrt(a : a).
inline double norm(const Mat3& a) {
  return std::sqrt(contract(a, a));
}

/// Mean stress p = tr(sigma)/3 (tension positive: negative in compression).
inline double mean_stress(const Mat3& s) {
  return s.trace() / 3.0;
}

/// Second invariant of the deviator J2 = s:s/2.
inline double j2(const Mat3& s) {
  const Mat3 d = deviator(s);
  return 0.5 * contract(d, d);
}

/// Third invariant of the deviator J3 = det(s).
inline double j3(const Mat3& s) {
  return deviator(s).determinant();
}

/// Von Mises equivalent stress q = sqrt(3 J2).
inline double von_mises(const Mat3& s) {
  return std::sqrt(3.0 * j2(s));
}

/// Lode angle theta in [-pi/6, pi/6], defined by sin(3 theta) = -(3 sqrt3 / 2) J3 / J2^(3/2).
/// theta = +pi/6 on triaxial compression (tension-positive stress), -pi/6 on triaxial extension.
/// Returns 0 for a hydrostatic state. Evaluated from the ordered principal deviatoric stresses
/// s1 >= s2 >= s3 as tan(theta) = (2 s2 - s1 - s3) / (sqrt3 (s1 - s3)), which is equivalent and,
/// unlike asin of the invariant ratio, well conditioned at the meridians theta = +-pi/6.
inline double lode_angle(const Mat3& s) {
  if (j2(s) <= 1e-300) return 0.0;
  const Eigen::SelfAdjointEigenSolver<Mat3> eigen(deviator(s), Eigen::EigenvaluesOnly);
  const Vec3& l = eigen.eigenvalues();  // ascending: l(2) = s1, l(1) = s2, l(0) = s3
  return std::atan((2.0 * l(1) - l(2) - l(0)) / (std::sqrt(3.0) * (l(2) - l(0))));
}

inline Mat3 sym(const Mat3& a) {
  return 0.5 * (a + a.transpose());
}
inline Mat3 skew(const Mat3& a) {
  return 0.5 * (a - a.transpose());
}

/// Strain tensor -> Voigt 6-vector with engineering shear.
inline Vec6 strain_to_voigt(const Mat3& e) {
  Vec6 v;
  v << e(0, 0), e(1, 1), e(2, 2), 2.0 * e(0, 1), 2.0 * e(1, 2), 2.0 * e(2, 0);
  return v;
}

/// Voigt 6-vector with engineering shear -> symmetric strain tensor.
inline Mat3 voigt_to_strain(const Vec6& v) {
  Mat3 e;
  e << v(0), 0.5 * v(3), 0.5 * v(5), 0.5 * v(3), v(1), 0.5 * v(4), 0.5 * v(5), 0.5 * v(4), v(2);
  return e;
}

/// Stress tensor -> Voigt 6-vector (plain components).
inline Vec6 stress_to_voigt(const Mat3& s) {
  Vec6 v;
  v << s(0, 0), s(1, 1), s(2, 2), s(0, 1), s(1, 2), s(2, 0);
  return v;
}

inline Mat3 voigt_to_stress(const Vec6& v) {
  Mat3 s;
  s << v(0), v(3), v(5), v(3), v(1), v(4), v(5), v(4), v(2);
  return s;
}

/// True when every entry is finite.
template <typename Derived>
bool all_finite(const Eigen::MatrixBase<Derived>& m) {
  return m.allFinite();
}

}  // namespace duet
