#include "constitutive/principal_return.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace duet::constitutive {

namespace {

/// Trial eigenvalues closer than this fraction of their scale count as repeated (tangent).
constexpr double repeated_tolerance = 1e-10;
/// The continuum rate probes the return mapping this fraction of the stress scale away.
constexpr double probe_distance = 1e-6;

bool is_sorted(const Vec3& s, double tolerance) {
  return s(0) + tolerance >= s(1) && s(1) + tolerance >= s(2);
}

/// Rotates the columns first..first+n-1 of `directions` so that they diagonalise the matching
/// block of the rate (in the principal frame), largest rate first.
void diagonalise_block(int first, int n, Mat3& directions, Mat3& rate_in_frame) {
  const Eigen::MatrixXd block = rate_in_frame.block(first, first, n, n);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(block);
  const Eigen::MatrixXd ascending = solver.eigenvectors();
  Eigen::MatrixXd rotation(n, n);
  for (int k = 0; k < n; ++k) rotation.col(k) = ascending.col(n - 1 - k);
  Eigen::MatrixXd rotated_directions = directions.middleCols(first, n) * rotation;
  directions.middleCols(first, n) = rotated_directions;
  Eigen::MatrixXd q = Eigen::MatrixXd::Identity(3, 3);
  q.block(first, first, n, n) = rotation;
  rate_in_frame = (q.transpose() * rate_in_frame * q).eval();
}

}  // namespace

SpectralDecomposition spectral_decomposition(const Mat3& symmetric) {
  const Eigen::SelfAdjointEigenSolver<Mat3> solver(symmetric);  // ascending eigenvalues
  SpectralDecomposition d;
  for (int a = 0; a < 3; ++a) {
    d.values(a) = solver.eigenvalues()(2 - a);
    d.directions.col(a) = solver.eigenvectors().col(2 - a);
  }
  return d;
}

Mat3 assemble_from_principal(const Vec3& values, const Mat3& directions) {
  return directions * values.asDiagonal() * directions.transpose();
}

Mat3 principal_elasticity(double bulk, double shear) {
  Mat3 D = Mat3::Constant(bulk - 2.0 / 3.0 * shear);
  D.diagonal().array() += 2.0 * shear;
  return D;
}

std::string_view principal_regime_name(PrincipalRegime regime) {
  switch (regime) {
    case PrincipalRegime::elastic:
      return "elastic";
    case PrincipalRegime::main_plane:
      return "main plane";
    case PrincipalRegime::right_edge:
      return "right edge";
    case PrincipalRegime::left_edge:
      return "left edge";
    case PrincipalRegime::apex:
      return "apex";
  }
  return "unknown";
}

PrincipalReturn return_to_plane(const Vec3& trial, const PrincipalPlane& plane,
                                const Mat3& elasticity) {
  // de Souza Neto 2008 Box 8.1 (Tresca) / Box 8.4 (Mohr-Coulomb), perfect plasticity:
  // sigma = sigma_trial - d_gamma D N with f(sigma) = 0, so d_gamma = f_trial / (n . D N).
  const Vec3 DN = elasticity * plane.flow;
  const double stiffness = plane.normal.dot(DN);  // 4G for Tresca
  PrincipalReturn r;
  r.regime = PrincipalRegime::main_plane;
  r.multipliers(0) = plane.value(trial) / stiffness;
  r.stress = trial - r.multipliers(0) * DN;
  r.jacobian = Mat3::Identity() - DN * plane.normal.transpose() / stiffness;
  return r;
}

PrincipalReturn return_to_edge(const Vec3& trial, const PrincipalPlane& a, const PrincipalPlane& b,
                               const Mat3& elasticity) {
  // de Souza Neto 2008 Box 8.2 (Tresca) / Box 8.5 (Mohr-Coulomb), perfect plasticity:
  // sigma = sigma_trial - D (d_gamma_a N_a + d_gamma_b N_b), f_a = f_b = 0, a 2x2 linear system
  // A d_gamma = f_trial with A_ij = n_i . D N_j.
  Eigen::Matrix<double, 3, 2> DN;
  DN.col(0) = elasticity * a.flow;
  DN.col(1) = elasticity * b.flow;
  Eigen::Matrix<double, 3, 2> n;
  n.col(0) = a.normal;
  n.col(1) = b.normal;
  const Mat2 A = n.transpose() * DN;
  const Mat2 A_inverse = A.inverse();
  PrincipalReturn r;
  r.multipliers = A_inverse * Vec2(a.value(trial), b.value(trial));
  r.stress = trial - DN * r.multipliers;
  r.jacobian = Mat3::Identity() - DN * A_inverse * n.transpose();
  return r;
}

PrincipalReturn principal_return(const Vec3& trial, const FacetedSurface& surface,
                                 const Mat3& elasticity, double tolerance) {
  PrincipalReturn r;
  r.stress = trial;
  if (surface.main.value(trial) <= tolerance) return r;  // elastic: trial admissible

  // One-vector return first; valid when sigma1 >= sigma2 >= sigma3 still holds (Box 8.3 / 8.7).
  r = return_to_plane(trial, surface.main, elasticity);
  if (is_sorted(r.stress, tolerance)) return r;

  // The result left the sextant: return to the edge on the side it crossed. (The book picks the
  // side from the sign of a scalar product with the trial; the crossing says the same directly.)
  const double past_right = r.stress(2) - r.stress(1);  // sigma3 climbed above sigma2
  const double past_left = r.stress(1) - r.stress(0);   // sigma1 fell below sigma2
  const bool right = past_right >= past_left;
  PrincipalReturn edge =
      return_to_edge(trial, surface.main, right ? surface.right : surface.left, elasticity);
  edge.regime = right ? PrincipalRegime::right_edge : PrincipalRegime::left_edge;
  const bool multipliers_positive =
      edge.multipliers.minCoeff() >= -1e-12 * edge.multipliers.cwiseAbs().maxCoeff();
  if ((is_sorted(edge.stress, tolerance) && multipliers_positive) || !surface.apex) {
    // On the edge two principal stresses are equal: make them equal to the last bit, so the
    // tangent's eigenvector-rotation term (y_a - y_b)/(x_a - x_b) is exactly zero there.
    const int i = right ? 1 : 0;
    const double mean = 0.5 * (edge.stress(i) + edge.stress(i + 1));
    edge.stress(i) = edge.stress(i + 1) = mean;
    return edge;
  }

  // Beyond the apex: every plane is active, the stress is the apex (Box 8.6). Perfect
  // plasticity fixes it completely, so the Jacobian is zero.
  PrincipalReturn apex;
  apex.regime = PrincipalRegime::apex;
  apex.stress = Vec3::Constant(*surface.apex);
  apex.jacobian = Mat3::Zero();
  return apex;
}

StressReturn return_mapping(const Mat3& trial, const FacetedSurface& surface,
                            const Mat3& elasticity, double tolerance) {
  StressReturn r;
  r.trial = spectral_decomposition(trial);
  r.principal = principal_return(r.trial.values, surface, elasticity, tolerance);
  switch (r.principal.regime) {
    case PrincipalRegime::elastic:
      r.stress = trial;
      break;
    case PrincipalRegime::apex:  // isotropic: exact, free of the round-off of Q diag Q^T
      r.stress = r.principal.stress(0) * Mat3::Identity();
      break;
    default:
      r.stress = assemble_from_principal(r.principal.stress, r.trial.directions);
  }
  return r;
}

Mat6 isotropic_function_tangent(const SpectralDecomposition& trial, const Vec3& values,
                                const Mat3& jacobian) {
  // de Souza Neto 2008 appendix A.3 (Box A.2): for Y(X) = sum_a y_a(x) e_a (x) e_a,
  // dY = sum_ab (dy_a/dx_b) dX_bb E_a + sum_{a != b} (y_a - y_b)/(x_a - x_b) dX_ab e_a (x) e_b,
  // with dX_ab = e_a . dX . e_b. Built column by column in the principal frame.
  const Mat3& Q = trial.directions;
  const Vec3& x = trial.values;
  const double scale = std::max(x.cwiseAbs().maxCoeff(), values.cwiseAbs().maxCoeff());
  Mat3 rotation_factor = Mat3::Zero();
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) {
      if (a == b) continue;
      const double gap = x(a) - x(b);
      rotation_factor(a, b) =
          std::abs(gap) > repeated_tolerance * scale
              ? (values(a) - values(b)) / gap
              : 0.5 * (jacobian(a, a) - jacobian(a, b) + jacobian(b, b) - jacobian(b, a));
    }
  }
  Mat6 tangent;
  for (int j = 0; j < 6; ++j) {
    const Mat3 dX = Q.transpose() * voigt_to_stress(Vec6::Unit(j)) * Q;
    Mat3 dY = rotation_factor.cwiseProduct(dX);
    dY.diagonal() = jacobian * dX.diagonal();
    tangent.col(j) = stress_to_voigt(Q * dY * Q.transpose());
  }
  return tangent;
}

Mat6 consistent_tangent(const StressReturn& result, const Mat6& elastic_stiffness) {
  if (result.principal.regime == PrincipalRegime::elastic) return elastic_stiffness;
  return isotropic_function_tangent(result.trial, result.principal.stress,
                                    result.principal.jacobian) *
         elastic_stiffness;  // chain rule: d sigma_trial / d eps = C
}

double equivalent_plastic_strain_increment(const Mat3& trial, const Mat3& stress, double bulk,
                                           double shear) {
  const Mat3 d_stress = trial - stress;
  const Mat3 d_plastic =
      deviator(d_stress) / (2.0 * shear) + mean_stress(d_stress) / (3.0 * bulk) * Mat3::Identity();
  return std::sqrt(2.0 / 3.0 * contract(d_plastic, d_plastic));
}

Mat3 continuum_rate(const Mat3& stress, const Mat3& elastic_rate, const FacetedSurface& surface,
                    const Mat3& elasticity, double tolerance) {
  SpectralDecomposition d = spectral_decomposition(stress);
  double scale = std::max(d.values.cwiseAbs().maxCoeff(), std::abs(surface.main.level));
  if (surface.main.value(d.values) < -probe_distance * scale) return elastic_rate;

  // Repeated principal stresses (an edge or the apex): any basis of the eigenspace is principal;
  // take the one that diagonalises the elastic rate there, larger rate first, so the principal
  // rates are the diagonal of the rate in the frame.
  Mat3 rate_in_frame = d.directions.transpose() * elastic_rate * d.directions;
  const double tie = repeated_tolerance * scale;
  const bool tie01 = d.values(0) - d.values(1) <= tie;
  const bool tie12 = d.values(1) - d.values(2) <= tie;
  if (tie01 && tie12) {
    diagonalise_block(0, 3, d.directions, rate_in_frame);
  } else if (tie01) {
    diagonalise_block(0, 2, d.directions, rate_in_frame);
  } else if (tie12) {
    diagonalise_block(1, 2, d.directions, rate_in_frame);
  }
  const Vec3 principal_rate = rate_in_frame.diagonal();
  const double rate_size = principal_rate.norm();
  if (rate_size == 0.0) return elastic_rate;

  // The return mapping is piecewise affine in principal space: its directional derivative at the
  // stress is the Jacobian of the regime that a short step along the elastic rate falls in.
  if (scale == 0.0) scale = rate_size;  // the cone of a cohesionless soil at the origin
  const Vec3 probe = d.values + probe_distance * scale / rate_size * principal_rate;
  std::array<int, 3> order{0, 1, 2};  // sorted position -> frame index
  std::sort(order.begin(), order.end(), [&](int i, int j) { return probe(i) > probe(j); });
  const Vec3 sorted_probe(probe(order[0]), probe(order[1]), probe(order[2]));
  const PrincipalReturn r = principal_return(sorted_probe, surface, elasticity, tolerance);
  Vec3 sorted_rate(principal_rate(order[0]), principal_rate(order[1]), principal_rate(order[2]));
  sorted_rate = (r.jacobian * sorted_rate).eval();
  for (int k = 0; k < 3; ++k) rate_in_frame(order[k], order[k]) = sorted_rate(k);
  // Off the diagonal the eigenvector-rotation factor (y_a - y_b)/(x_a - x_b) tends to 1 as the
  // trial tends to the (returned) stress itself: shear in the principal frame is elastic.
  return d.directions * rate_in_frame * d.directions.transpose();
}

}  // namespace duet::constitutive
