#pragma once
// Principal-stress-space machinery shared by the Tresca and Mohr-Coulomb return mappings
// (de Souza Neto, Peric & Owen 2008, "Computational Methods for Plasticity", ch. 8 and
// appendix A; theory pages constitutive/docs/tresca.md and mohr_coulomb.md).
//
// Both surfaces are faceted: in the sextant sigma1 >= sigma2 >= sigma3 (tension positive, sigma1
// the largest) only the main plane is active, its edges with the neighbouring sextants are the
// right edge (sigma2 = sigma3) and the left edge (sigma1 = sigma2), and Mohr-Coulomb closes at an
// apex on the hydrostatic axis. With isotropic elasticity the return keeps the eigenvectors of
// the elastic trial stress, so it is a map between sorted principal values; with perfect
// plasticity and flat facets that map is piecewise affine, solved here in closed form.
//
// Parts: spectral decomposition (sorted), reassembly, the one-vector return to one plane and the
// two-vector return to an edge, the regime selection, the derivative of the resulting isotropic
// tensor function (the consistent tangent in spectral form) and the continuum rate.

#include <optional>
#include <string_view>

#include "common/tensor.hpp"

namespace duet::constitutive {

/// Spectral decomposition of a symmetric 3x3, principal values sorted descending.
struct SpectralDecomposition {
  Vec3 values = Vec3::Zero();          // sigma1 >= sigma2 >= sigma3
  Mat3 directions = Mat3::Identity();  // column a: unit eigenvector of values(a)
};

SpectralDecomposition spectral_decomposition(const Mat3& symmetric);

/// sum_a values(a) e_a (x) e_a.
Mat3 assemble_from_principal(const Vec3& values, const Mat3& directions);

/// Isotropic elasticity between principal values: d sigma_a = sum_b (K - 2G/3 + 2G delta_ab)
/// d eps_b.
Mat3 principal_elasticity(double bulk, double shear);

/// A flat facet in sorted principal space: f = normal . sigma - level (<= 0 admissible), plastic
/// flow d eps_p = d_gamma * flow (the gradient of the plastic potential).
struct PrincipalPlane {
  Vec3 normal = Vec3::Zero();
  Vec3 flow = Vec3::Zero();
  double level = 0.0;  // Pa

  double value(const Vec3& principal) const { return normal.dot(principal) - level; }
};

/// A Coulomb-type faceted surface in the sextant sigma1 >= sigma2 >= sigma3.
struct FacetedSurface {
  PrincipalPlane main;         // sigma1 against sigma3: the plane active inside the sextant
  PrincipalPlane right;        // sigma1 against sigma2: with `main`, the right edge sigma2 = sigma3
  PrincipalPlane left;         // sigma2 against sigma3: with `main`, the left edge sigma1 = sigma2
  std::optional<double> apex;  // mean stress of the apex (c cot phi); none when there is none
};

/// Which branch of the return mapping an increment took.
enum class PrincipalRegime {
  elastic,     // trial on or inside the surface
  main_plane,  // one-vector return to the main plane
  right_edge,  // two-vector return to the edge sigma2 = sigma3
  left_edge,   // two-vector return to the edge sigma1 = sigma2
  apex,        // return to the apex (all planes active)
};

std::string_view principal_regime_name(PrincipalRegime regime);

/// A return in sorted principal space.
struct PrincipalReturn {
  PrincipalRegime regime = PrincipalRegime::elastic;
  Vec3 stress = Vec3::Zero();        // principal stresses after the return, in trial order
  Vec2 multipliers = Vec2::Zero();   // d_gamma on (main, right or left); zero at the apex
  Mat3 jacobian = Mat3::Identity();  // d stress / d trial, constant within a regime
};

/// One-vector return of `trial` to `plane` along elasticity * flow (perfect plasticity).
PrincipalReturn return_to_plane(const Vec3& trial, const PrincipalPlane& plane,
                                const Mat3& elasticity);

/// Two-vector return of `trial` to the intersection of planes a and b.
PrincipalReturn return_to_edge(const Vec3& trial, const PrincipalPlane& a, const PrincipalPlane& b,
                               const Mat3& elasticity);

/// Selects and performs the return of a sorted trial: elastic if main.value <= tolerance; else
/// the main plane if the result stays sorted; else the edge on the side it crossed; else the
/// apex. `tolerance` (Pa) is the on-surface and ordering tolerance.
PrincipalReturn principal_return(const Vec3& trial, const FacetedSurface& surface,
                                 const Mat3& elasticity, double tolerance);

/// The return mapping of a full trial stress tensor: decomposition, principal return, reassembly.
struct StressReturn {
  Mat3 stress = Mat3::Zero();
  SpectralDecomposition trial;
  PrincipalReturn principal;
};

StressReturn return_mapping(const Mat3& trial, const FacetedSurface& surface,
                            const Mat3& elasticity, double tolerance);

/// Consistent tangent d sigma_{n+1} / d eps (Voigt, engineering shear) of a return from the
/// trial sigma_n + C : d_eps: the elastic stiffness when elastic, else
/// isotropic_function_tangent : C.
Mat6 consistent_tangent(const StressReturn& result, const Mat6& elastic_stiffness);

/// Equivalent plastic strain increment sqrt(2/3 d_eps_p : d_eps_p) of a return from `trial` to
/// `stress`, with d_eps_p = C^-1 : (trial - stress) (isotropic elasticity K, G).
double equivalent_plastic_strain_increment(const Mat3& trial, const Mat3& stress, double bulk,
                                           double shear);

/// d sigma / d sigma_trial of the isotropic tensor function sigma = sum_a y_a(x) e_a (x) e_a of
/// the trial stress (eigenvalues x, eigenvectors e), in Voigt form with plain stress components
/// on both sides. `jacobian` = d y_a / d x_b (sorted order). Repeated trial eigenvalues use the
/// limit y_a - y_b -> (J_aa - J_ab)(x_a - x_b).
Mat6 isotropic_function_tangent(const SpectralDecomposition& trial, const Vec3& values,
                                const Mat3& jacobian);

/// Continuum rate of perfect plasticity on the faceted surface: the directional derivative of
/// return_mapping at `stress` along `elastic_rate` (= C : D). Elastic rate when `stress` is
/// inside (f < -tolerance) or the rate unloads. Repeated eigenvalues (edges, apex) take the
/// eigenvectors that diagonalise the elastic rate in their eigenspace.
Mat3 continuum_rate(const Mat3& stress, const Mat3& elastic_rate, const FacetedSurface& surface,
                    const Mat3& elasticity, double tolerance);

}  // namespace duet::constitutive
