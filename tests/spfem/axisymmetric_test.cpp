// The axisymmetric smoothed operator (spfem/smoothing.hpp, SmoothingCells::ring and hoop): the
// cell volumes V_k = 2 pi r_k A_k and the smoothed hoop strain. Checked on Delaunay meshes
// of cell-centred lattices in the r-z plane (built here, not by build_alpha_mesh) against
// a uniform radial stretch (exact hoop strain), equilibrium: a hydrostatic stress balances at
// every interior node exactly, and the nodal
// stresses of Lame's thick cylinder (an exact elastic equilibrium of sigma_rr, sigma_tt) leave a
// residual that vanishes as the spacing does.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "spfem/smoothing.hpp"
#include "tests/spfem/delaunay_mesh.hpp"

namespace duet::spfem {
namespace {

using testing::delaunay_mesh;

constexpr double kPi = std::numbers::pi;

/// Cell-centred nodes of r in [r0, r0 + W], z in [0, H] at spacing dp, with the cells of their
/// Delaunay mesh and the rings 2 pi r.
struct RzPatch {
  double dp = 0.0;
  double r0 = 0.0;
  std::vector<Vec2> x;
  AlphaMesh mesh;
  SmoothingCells cells;
  RzPatch(double spacing, double inner, double width, double height) : dp(spacing), r0(inner) {
    const int nr = static_cast<int>(std::lround(width / dp));
    const int nz = static_cast<int>(std::lround(height / dp));
    for (int j = 0; j < nz; ++j) {
      for (int i = 0; i < nr; ++i) x.emplace_back(r0 + (i + 0.5) * dp, (j + 0.5) * dp);
    }
    mesh = delaunay_mesh(x);
    build_smoothing_cells(mesh, x, cells);
    fill_axisymmetric_terms(mesh, x, cells);
  }
  /// Nodes at least two spacings inside every side: their rows see only interior cells.
  bool interior(std::size_t k, double width, double height) const {
    return x[k].x() > r0 + 2.0 * dp && x[k].x() < r0 + width - 2.0 * dp && x[k].y() > 2.0 * dp &&
           x[k].y() < height - 2.0 * dp;
  }
};

TEST(AxisymmetricCells, AHydrostaticStressIsInEquilibriumAtEveryInteriorNode) {
  // Arrange: r in [0.5, 1.5] m, z in [0, 0.6] m, dp 0.05 m; sigma = -p I
  const double width = 1.0;
  const double height = 0.6;
  const RzPatch patch(0.05, 0.5, width, height);
  const double p = 1.0e5;
  const std::vector<Mat3> stress(patch.x.size(), -p * Mat3::Identity());
  Mat3 no_hoop = -p * Mat3::Identity();
  no_hoop(2, 2) = 0.0;
  const std::vector<Mat3> in_plane_only(patch.x.size(), no_hoop);
  // Act
  std::vector<Vec2> force;
  std::vector<Vec2> force_without_hoop_stress;
  internal_forces(patch.cells, stress, force);
  internal_forces(patch.cells, in_plane_only, force_without_hoop_stress);
  // Assert: zero to round-off at interior nodes; without the hoop stress the in-plane part alone
  // pushes each interior node outwards by 2 pi p A_l (sum_k r_k A_k b_kl = -A_l e_r): the hoop
  // force is what closes the balance
  int checked = 0;
  for (std::size_t l = 0; l < patch.x.size(); ++l) {
    if (!patch.interior(l, width, height)) continue;
    const double scale = 2.0 * kPi * p * patch.cells.area[l];
    EXPECT_LT(force[l].norm(), 1e-11 * scale) << "node " << l;
    EXPECT_NEAR(force_without_hoop_stress[l].x(), scale, 1e-11 * scale) << "node " << l;
    EXPECT_NEAR(force_without_hoop_stress[l].y(), 0.0, 1e-11 * scale) << "node " << l;
    ++checked;
  }
  EXPECT_GT(checked, 100);
}

TEST(AxisymmetricCells, TheSmoothedHoopStrainIsExactForAUniformRadialStretch) {
  // Arrange: r in [0.1, 1.1] m (the first column dp / 2 off r = 0.05 m's), z in [0, 0.4] m, dp
  // 0.05 m, with the boundary layer; u_r = a r (eps_tt = a everywhere) and u_r = c (eps_tt = c / r)
  const double dp = 0.05;
  RzPatch patch(dp, 0.1, 1.0, 0.4);
  build_smoothing_cells(patch.mesh, patch.x, patch.cells, 0.5 * dp);
  fill_axisymmetric_terms(patch.mesh, patch.x, patch.cells);
  const double a = 1e-3;
  const double c = 2e-4;
  std::vector<Vec2> stretch(patch.x.size());
  std::vector<Vec2> shift(patch.x.size(), Vec2(c, 0.0));
  for (std::size_t k = 0; k < patch.x.size(); ++k) stretch[k] = Vec2(a * patch.x[k].x(), 0.0);
  // Act and assert: a to round-off at every node, surface ones included (every term of the row
  // is a triangle's centroid value, which a linear field carries exactly); for the shift the mean
  // of c / r over the cell: within c dp^2 / r^3 of c / r_k inside (a centred mean), within
  // c dp / r^2 at the surface (the layer strips lean on the triangles inside: first order there)
  for (std::size_t k = 0; k < patch.x.size(); ++k) {
    const double r = patch.x[k].x();
    EXPECT_NEAR(smoothed_hoop_rate(patch.cells, stretch, k), a, 1e-13) << "node " << k;
    const double bound = patch.interior(k, 1.0, 0.4) ? c * dp * dp / (r * r * r) : c * dp / (r * r);
    EXPECT_NEAR(smoothed_hoop_rate(patch.cells, shift, k), c / r, bound) << "node " << k;
  }
}

/// Lame's thick cylinder in plane strain along z: sigma_rr = A - B / r^2, sigma_tt = A + B / r^2,
/// sigma_zz = nu (sigma_rr + sigma_tt); an exact equilibrium, d sigma_rr / dr + (sigma_rr -
/// sigma_tt) / r = 0. Returns the largest interior residual |F_l| over 2 pi A_l B / r_l^2 (the
/// hoop force's own scale) at spacing dp.
double lame_residual(double dp) {
  const double width = 1.0;
  const double height = 0.6;
  const RzPatch patch(dp, 0.5, width, height);
  const double a = -2.0e4;  // Pa
  const double b = 1.0e4;   // Pa m^2
  const double nu = 0.3;
  std::vector<Mat3> stress(patch.x.size(), Mat3::Zero());
  for (std::size_t k = 0; k < patch.x.size(); ++k) {
    const double r2 = patch.x[k].x() * patch.x[k].x();
    stress[k](0, 0) = a - b / r2;
    stress[k](2, 2) = a + b / r2;
    stress[k](1, 1) = nu * (stress[k](0, 0) + stress[k](2, 2));
  }
  std::vector<Vec2> force;
  internal_forces(patch.cells, stress, force);
  double worst = 0.0;
  for (std::size_t l = 0; l < patch.x.size(); ++l) {
    if (!patch.interior(l, width, height)) continue;
    const double r2 = patch.x[l].x() * patch.x[l].x();
    worst = std::max(worst, force[l].norm() / (2.0 * kPi * patch.cells.area[l] * b / r2));
  }
  return worst;
}

TEST(AxisymmetricCells, LamesThickCylinderLeavesAResidualThatVanishesWithTheSpacing) {
  // Act: the nodal stresses of the exact solution at dp 0.05 and 0.025 m
  const double coarse = lame_residual(0.05);
  const double fine = lame_residual(0.025);
  ::testing::Test::RecordProperty("residual_dp_0_05", std::to_string(coarse));
  ::testing::Test::RecordProperty("residual_dp_0_025", std::to_string(fine));
  // Assert: a small fraction of the hoop force at each node, falling at least linearly with dp
  // (a hoop force from sigma_rr instead of sigma_tt would leave 2 B / r^2 there: ratio 2)
  EXPECT_LT(coarse, 0.05);
  EXPECT_LT(fine, 0.55 * coarse);
}

}  // namespace
}  // namespace duet::spfem
