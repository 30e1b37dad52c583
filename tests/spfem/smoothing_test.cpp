// Tests of the node-based strain smoothing (spfem/smoothing.hpp): patch test, cell areas, rigid
// rotation, internal forces against the boundary traction, virtual power, the transpose map.
// Meshes are CGAL Delaunay triangulations of random clouds, built here (not by build_alpha_mesh)
// so these tests pin the smoothing alone.
#include "spfem/smoothing.hpp"
#include "tests/spfem/delaunay_mesh.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <set>
#include <utility>
#include <vector>

namespace duet::spfem {
namespace {

using testing::delaunay_mesh;
using testing::signed_area;

// Keeps a measured number in the test's XML output (--gtest_output=xml) for the record.
void record(const char* key, double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3e", value);
  ::testing::Test::RecordProperty(key, text);
}

double circumradius(const Triangle& t, const std::vector<Vec2>& x) {
  const double a = (x[t[1]] - x[t[2]]).norm();
  const double b = (x[t[2]] - x[t[0]]).norm();
  const double c = (x[t[0]] - x[t[1]]).norm();
  return a * b * c / (4.0 * signed_area(t, x));
}

// An arbitrary cloud: uniform random points in [0, 2] x [0, 1].
std::vector<Vec2> random_cloud(std::size_t n, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec2> points(n);
  for (Vec2& p : points) p = Vec2(2.0 * u(random), u(random));
  return points;
}

// Random points filling the rectangle [0, a] x [0, b], with the four corners and random points on
// each side, so that the Delaunay mesh covers exactly the rectangle.
struct RectangleCloud {
  double a = 2.0;
  double b = 1.0;
  std::vector<Vec2> points;
};

RectangleCloud rectangle_cloud(std::size_t n_inside, std::size_t n_per_side, unsigned seed) {
  RectangleCloud cloud;
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double a = cloud.a;
  const double b = cloud.b;
  cloud.points = {Vec2(0, 0), Vec2(a, 0), Vec2(a, b), Vec2(0, b)};
  for (std::size_t i = 0; i < n_per_side; ++i) {
    cloud.points.emplace_back(a * (0.02 + 0.96 * u(random)), 0.0);
    cloud.points.emplace_back(a * (0.02 + 0.96 * u(random)), b);
    cloud.points.emplace_back(0.0, b * (0.02 + 0.96 * u(random)));
    cloud.points.emplace_back(a, b * (0.02 + 0.96 * u(random)));
  }
  for (std::size_t i = 0; i < n_inside; ++i) {
    cloud.points.emplace_back(a * (0.01 + 0.98 * u(random)), b * (0.01 + 0.98 * u(random)));
  }
  return cloud;
}

// Per node: 1 when it lies on an edge that belongs to one triangle only (the mesh boundary).
std::vector<std::uint8_t> boundary_nodes(const AlphaMesh& mesh, std::size_t n_nodes) {
  std::map<std::pair<std::int32_t, std::int32_t>, int> edge_count;
  for (const Triangle& t : mesh.triangles) {
    for (int i = 0; i < 3; ++i) {
      const std::int32_t p = t[i];
      const std::int32_t q = t[(i + 1) % 3];
      ++edge_count[{std::min(p, q), std::max(p, q)}];
    }
  }
  std::vector<std::uint8_t> surface(n_nodes, 0);
  for (const auto& [edge, count] : edge_count) {
    if (count == 1) surface[edge.first] = surface[edge.second] = 1;
  }
  return surface;
}

std::vector<Mat2> gradients_of(const SmoothingCells& cells, const std::vector<Vec2>& v) {
  std::vector<Mat2> gradient;
  smoothed_velocity_gradients(cells, v, gradient);
  return gradient;
}

// A general (non-symmetric, trace-carrying) velocity gradient and a non-zero translation.
const Mat2 kGeneralGradient = (Mat2() << 0.7, -1.3, 0.45, -0.2).finished();
const Vec2 kTranslation(0.3, -0.8);

std::vector<Vec2> linear_velocity(const std::vector<Vec2>& x, const Vec2& v0, const Mat2& g) {
  std::vector<Vec2> v(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) v[i] = v0 + g * x[i];
  return v;
}

// Largest |L_k - G| / |G| over the nodes with the given surface flag.
double patch_error(const std::vector<Mat2>& l, const Mat2& g,
                   const std::vector<std::uint8_t>& surface, std::uint8_t on_surface) {
  double worst = 0.0;
  for (std::size_t k = 0; k < l.size(); ++k) {
    if (surface[k] == on_surface) worst = std::max(worst, (l[k] - g).norm() / g.norm());
  }
  return worst;
}

TEST(Smoothing, TwoTriangleSquareMatchesHandComputedGradients) {
  // Arrange: unit square split along (0,0)-(1,1). Triangle (0,1,2): N0 = 1 - x, N1 = x - y,
  // N2 = y; triangle (0,2,3): N0 = 1 - y, N2 = x, N3 = y - x; each of area 1/2.
  const std::vector<Vec2> x = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};
  AlphaMesh mesh;
  mesh.triangles = {Triangle{0, 1, 2}, Triangle{0, 2, 3}};
  SmoothingCells cells;
  // Act
  build_smoothing_cells(mesh, x, cells);
  // Assert: A_0 = 2 (1/2)/3 = 1/3, A_1 = 1/6; b_0l = average of the two triangles' gradients.
  EXPECT_DOUBLE_EQ(cells.area[0], 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(cells.area[1], 1.0 / 6.0);
  std::map<std::int32_t, Vec2> row0;
  std::map<std::int32_t, Vec2> row1;
  for (std::int32_t e = cells.offset[0]; e < cells.offset[1]; ++e) {
    row0[cells.column[e]] = cells.gradient[e];
  }
  for (std::int32_t e = cells.offset[1]; e < cells.offset[2]; ++e) {
    row1[cells.column[e]] = cells.gradient[e];
  }
  ASSERT_EQ(row0.size(), 4u);
  ASSERT_EQ(row1.size(), 3u);
  EXPECT_NEAR((row0[0] - Vec2(-0.5, -0.5)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((row0[1] - Vec2(0.5, -0.5)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((row0[2] - Vec2(0.5, 0.5)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((row0[3] - Vec2(-0.5, 0.5)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((row1[0] - Vec2(-1.0, 0.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((row1[1] - Vec2(1.0, -1.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((row1[2] - Vec2(0.0, 1.0)).norm(), 0.0, 1e-15);
}

TEST(Smoothing, LinearVelocityGivesExactGradientAtInteriorNodes) {
  // Arrange: irregular Delaunay mesh of an arbitrary random cloud, v = v0 + G x
  const std::vector<Vec2> x = random_cloud(3000, 11);
  const AlphaMesh mesh = delaunay_mesh(x);
  const std::vector<std::uint8_t> surface = boundary_nodes(mesh, x.size());
  SmoothingCells cells;
  build_smoothing_cells(mesh, x, cells);
  // Act
  const std::vector<Mat2> l =
      gradients_of(cells, linear_velocity(x, kTranslation, kGeneralGradient));
  // Assert
  const double error = patch_error(l, kGeneralGradient, surface, 0);
  record("interior_relative_error", error);
  EXPECT_LT(error, 1e-12);
}

TEST(Smoothing, LinearVelocityGivesExactGradientAtSurfaceNodes) {
  // Arrange: each node's cell integrates exact element gradients, so surface nodes pass too
  const std::vector<Vec2> x = random_cloud(3000, 12);
  const AlphaMesh mesh = delaunay_mesh(x);
  const std::vector<std::uint8_t> surface = boundary_nodes(mesh, x.size());
  ASSERT_GT(std::count(surface.begin(), surface.end(), 1), 10);
  SmoothingCells cells;
  build_smoothing_cells(mesh, x, cells);
  // Act
  const std::vector<Mat2> l =
      gradients_of(cells, linear_velocity(x, kTranslation, kGeneralGradient));
  // Assert
  const double error = patch_error(l, kGeneralGradient, surface, 1);
  record("surface_relative_error", error);
  EXPECT_LT(error, 1e-12);
}

TEST(Smoothing, LinearVelocityGivesExactGradientOnAlphaTrimmedMesh) {
  // Arrange: drop the triangles whose circumradius exceeds alpha (a concave mesh with holes and
  // nodes left in no triangle, as the alpha shape makes); L_k = G wherever A_k > 0, zero elsewhere
  const std::vector<Vec2> x = random_cloud(1500, 13);
  AlphaMesh mesh = delaunay_mesh(x);
  std::erase_if(mesh.triangles, [&](const Triangle& t) { return circumradius(t, x) > 0.03; });
  SmoothingCells cells;
  build_smoothing_cells(mesh, x, cells);
  // Act
  const std::vector<Mat2> l =
      gradients_of(cells, linear_velocity(x, kTranslation, kGeneralGradient));
  // Assert
  double worst = 0.0;
  int n_isolated = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    if (cells.area[k] > 0.0) {
      worst = std::max(worst, (l[k] - kGeneralGradient).norm() / kGeneralGradient.norm());
    } else {
      ++n_isolated;
      EXPECT_EQ(l[k].norm(), 0.0);
    }
  }
  EXPECT_GT(n_isolated, 0);  // the trimmed mesh does leave nodes out
  record("relative_error", worst);
  EXPECT_LT(worst, 1e-12);
}

TEST(Smoothing, CellAreasSumToRectangleArea) {
  // Arrange: the Delaunay mesh of a cloud with points on every side covers the rectangle a x b
  const RectangleCloud cloud = rectangle_cloud(2000, 40, 21);
  const AlphaMesh mesh = delaunay_mesh(cloud.points);
  SmoothingCells cells;
  // Act
  build_smoothing_cells(mesh, cloud.points, cells);
  // Assert
  double sum = 0.0;
  for (const double a_k : cells.area) sum += a_k;
  record("relative_error", std::abs(sum - cloud.a * cloud.b) / (cloud.a * cloud.b));
  EXPECT_NEAR(sum, cloud.a * cloud.b, 1e-12 * cloud.a * cloud.b);
}

TEST(Smoothing, CellAreasSumToAlphaTrimmedMeshArea) {
  // Arrange: a concave mesh (circumradius test as in the alpha shape); its area from the triangles
  const std::vector<Vec2> x = random_cloud(2000, 22);
  AlphaMesh mesh = delaunay_mesh(x);
  std::erase_if(mesh.triangles, [&](const Triangle& t) { return circumradius(t, x) > 0.025; });
  double mesh_area = 0.0;
  for (const Triangle& t : mesh.triangles) mesh_area += signed_area(t, x);
  SmoothingCells cells;
  // Act
  build_smoothing_cells(mesh, x, cells);
  // Assert
  double sum = 0.0;
  for (const double a_k : cells.area) sum += a_k;
  EXPECT_LT(mesh_area, 1.99);  // trimmed: less than the 2 x 1 box
  record("relative_error", std::abs(sum - mesh_area) / mesh_area);
  EXPECT_NEAR(sum, mesh_area, 1e-12 * mesh_area);
}

TEST(Smoothing, RigidRotationGivesZeroStretchingAndItsSpin) {
  // Arrange: v = v0 + W x with W skew (angular velocity omega)
  const double omega = 2.5;
  const Mat2 w = (Mat2() << 0.0, -omega, omega, 0.0).finished();
  const std::vector<Vec2> x = random_cloud(2000, 31);
  const AlphaMesh mesh = delaunay_mesh(x);
  SmoothingCells cells;
  build_smoothing_cells(mesh, x, cells);
  // Act
  const std::vector<Mat2> l = gradients_of(cells, linear_velocity(x, kTranslation, w));
  // Assert
  double worst_stretching = 0.0;
  double worst_spin = 0.0;
  for (const Mat2& l_k : l) {
    worst_stretching = std::max(worst_stretching, (0.5 * (l_k + l_k.transpose())).norm());
    worst_spin = std::max(worst_spin, (0.5 * (l_k - l_k.transpose()) - w).norm());
  }
  record("stretching_over_omega", worst_stretching / omega);
  record("spin_error_over_omega", worst_spin / omega);
  EXPECT_LT(worst_stretching, 1e-12 * omega);
  EXPECT_LT(worst_spin, 1e-12 * omega);
}

// Closed form for a uniform stress on the rectangle: F_int,l = sigma int grad N_l dOmega
// = sigma oint N_l n dGamma, so a node on a side gets sigma n times half the lengths of its two
// side edges (a corner sums its two sides) and an interior node gets exactly zero.
std::vector<Vec2> boundary_traction_forces(const RectangleCloud& cloud, const Mat2& sigma) {
  std::vector<Vec2> force(cloud.points.size(), Vec2::Zero());
  const auto add_side = [&](auto on_side, auto coordinate, const Vec2& normal) {
    std::vector<std::pair<double, std::size_t>> nodes;
    for (std::size_t i = 0; i < cloud.points.size(); ++i) {
      if (on_side(cloud.points[i])) nodes.emplace_back(coordinate(cloud.points[i]), i);
    }
    std::sort(nodes.begin(), nodes.end());
    for (std::size_t j = 0; j + 1 < nodes.size(); ++j) {
      const Vec2 half_edge = sigma * normal * (nodes[j + 1].first - nodes[j].first) / 2.0;
      force[nodes[j].second] += half_edge;
      force[nodes[j + 1].second] += half_edge;
    }
  };
  const auto x = [](const Vec2& p) { return p.x(); };
  const auto y = [](const Vec2& p) { return p.y(); };
  add_side([](const Vec2& p) { return p.y() == 0.0; }, x, Vec2(0, -1));
  add_side([&](const Vec2& p) { return p.y() == cloud.b; }, x, Vec2(0, 1));
  add_side([](const Vec2& p) { return p.x() == 0.0; }, y, Vec2(-1, 0));
  add_side([&](const Vec2& p) { return p.x() == cloud.a; }, y, Vec2(1, 0));
  return force;
}

TEST(Smoothing, UniformStressGivesBoundaryTractionOnSurfaceNodesOnly) {
  // Arrange
  const RectangleCloud cloud = rectangle_cloud(1500, 30, 41);
  const AlphaMesh mesh = delaunay_mesh(cloud.points);
  SmoothingCells cells;
  build_smoothing_cells(mesh, cloud.points, cells);
  Mat3 sigma;
  sigma << -3.0e5, 1.2e5, 0.0, 1.2e5, -1.0e5, 0.0, 0.0, 0.0, -1.5e5;  // Pa, plane strain
  const std::vector<Mat3> stress(cloud.points.size(), sigma);
  const std::vector<Vec2> expected = boundary_traction_forces(cloud, sigma.topLeftCorner<2, 2>());
  // Act
  std::vector<Vec2> force;
  internal_forces(cells, stress, force);
  // Assert
  const double scale = sigma.norm() * cloud.a;  // N/m
  double worst = 0.0;
  for (std::size_t l = 0; l < force.size(); ++l) {
    worst = std::max(worst, (force[l] - expected[l]).norm() / scale);
  }
  record("relative_error", worst);
  EXPECT_LT(worst, 1e-12);
}

TEST(Smoothing, InternalForcesOfAnyStressFieldSumToZero) {
  // Arrange: random symmetric stresses per node; sum_l b_kl = 0 (partition of unity)
  const std::vector<Vec2> x = random_cloud(2000, 51);
  const AlphaMesh mesh = delaunay_mesh(x);
  SmoothingCells cells;
  build_smoothing_cells(mesh, x, cells);
  std::mt19937 random(52);
  std::uniform_real_distribution<double> u(-1.0e5, 1.0e5);
  std::vector<Mat3> stress(x.size());
  for (std::size_t k = 0; k < x.size(); ++k) {
    Mat3 s;
    s << u(random), u(random), 0.0, 0.0, u(random), 0.0, 0.0, 0.0, u(random);
    stress[k] = s + s.transpose();
  }
  // Act
  std::vector<Vec2> force;
  internal_forces(cells, stress, force);
  // Assert: relative to the sum of the force magnitudes
  Vec2 total = Vec2::Zero();
  double scale = 0.0;
  for (const Vec2& f : force) {
    total += f;
    scale += f.norm();
  }
  record("relative_total", total.norm() / scale);
  EXPECT_LT(total.norm(), 1e-12 * scale);
}

TEST(Smoothing, InternalPowerEqualsStressPower) {
  // Arrange: arbitrary nodal velocities and stresses
  const std::vector<Vec2> x = random_cloud(2000, 61);
  const AlphaMesh mesh = delaunay_mesh(x);
  SmoothingCells cells;
  build_smoothing_cells(mesh, x, cells);
  std::mt19937 random(62);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec2> v(x.size());
  std::vector<Mat3> stress(x.size());
  for (std::size_t k = 0; k < x.size(); ++k) {
    v[k] = Vec2(u(random), u(random));
    Mat3 s = Mat3::Zero();
    s(0, 0) = u(random);
    s(1, 1) = u(random);
    s(2, 2) = u(random);
    s(0, 1) = s(1, 0) = u(random);
    stress[k] = 1.0e5 * s;
  }
  // Act
  std::vector<Vec2> force;
  internal_forces(cells, stress, force);
  const std::vector<Mat2> l = gradients_of(cells, v);
  // Assert: sum_l F_l . v_l == sum_k A_k sigma_k : L_k
  double internal_power = 0.0;
  double stress_power = 0.0;
  double scale = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    internal_power += force[k].dot(v[k]);
    const Mat2 s = stress[k].topLeftCorner<2, 2>();
    stress_power += cells.area[k] * (s.array() * l[k].array()).sum();
    scale += cells.area[k] * (s.array() * l[k].array()).abs().sum();
  }
  record("relative_error", std::abs(internal_power - stress_power) / scale);
  EXPECT_NEAR(internal_power, stress_power, 1e-12 * scale);
}

TEST(Smoothing, RowsHoldTheNodesSharingATriangleAndTransposeMirrorsThem) {
  // Arrange
  const std::vector<Vec2> x = random_cloud(1000, 71);
  const AlphaMesh mesh = delaunay_mesh(x);
  std::vector<std::set<std::int32_t>> sharing(x.size());
  for (const Triangle& t : mesh.triangles) {
    for (const std::int32_t a : t) sharing[a].insert(t.begin(), t.end());
  }
  SmoothingCells cells;
  // Act
  build_smoothing_cells(mesh, x, cells);
  // Assert
  for (std::size_t k = 0; k < x.size(); ++k) {
    const std::set<std::int32_t> row(cells.column.begin() + cells.offset[k],
                                     cells.column.begin() + cells.offset[k + 1]);
    EXPECT_EQ(row, sharing[k]) << "row " << k;
    EXPECT_EQ(std::size_t(cells.offset[k + 1] - cells.offset[k]), row.size()) << "duplicates";
    for (std::int32_t e = cells.offset[k]; e < cells.offset[k + 1]; ++e) {
      const std::int32_t mirror = cells.transpose[e];
      const std::int32_t l = cells.column[e];
      ASSERT_GE(mirror, cells.offset[l]);
      ASSERT_LT(mirror, cells.offset[l + 1]);
      EXPECT_EQ(cells.column[mirror], std::int32_t(k));
      EXPECT_EQ(cells.transpose[mirror], e);
    }
  }
}

TEST(Smoothing, RebuildInUsedStorageMatchesAFreshBuild) {
  // Arrange: cells first built on a larger cloud, then on a smaller, moved one
  const std::vector<Vec2> big = random_cloud(3000, 81);
  std::vector<Vec2> small = random_cloud(800, 82);
  for (Vec2& p : small) p += Vec2(0.01 * p.y(), 0.02 * p.x() * p.x());
  const AlphaMesh big_mesh = delaunay_mesh(big);
  const AlphaMesh small_mesh = delaunay_mesh(small);
  SmoothingCells reused;
  build_smoothing_cells(big_mesh, big, reused);
  SmoothingCells fresh;
  // Act
  build_smoothing_cells(small_mesh, small, reused);
  build_smoothing_cells(small_mesh, small, fresh);
  // Assert
  EXPECT_EQ(reused.area, fresh.area);
  EXPECT_EQ(reused.offset, fresh.offset);
  EXPECT_EQ(reused.column, fresh.column);
  EXPECT_EQ(reused.gradient, fresh.gradient);
  EXPECT_EQ(reused.transpose, fresh.transpose);
}

TEST(Smoothing, NodeOfHighDegreeGetsItsFullRowAndExactGradient) {
  // Arrange: a fan of 40 triangles around node 0 (more than the rows gathered on the stack)
  const int n_fan = 40;
  std::vector<Vec2> x = {Vec2(0.1, -0.2)};
  for (int i = 0; i < n_fan; ++i) {
    const double angle = 2.0 * 3.141592653589793 * i / n_fan;
    x.emplace_back(std::cos(angle) * (1.0 + 0.1 * (i % 3)),
                   std::sin(angle) * (1.0 + 0.1 * (i % 3)));
  }
  AlphaMesh mesh;
  for (int i = 0; i < n_fan; ++i) mesh.triangles.push_back({0, 1 + i, 1 + (i + 1) % n_fan});
  SmoothingCells cells;
  // Act
  build_smoothing_cells(mesh, x, cells);
  const std::vector<Mat2> l =
      gradients_of(cells, linear_velocity(x, kTranslation, kGeneralGradient));
  // Assert
  EXPECT_EQ(cells.offset[1] - cells.offset[0], n_fan + 1);
  for (std::size_t k = 0; k < x.size(); ++k) {
    EXPECT_LT((l[k] - kGeneralGradient).norm(), 1e-12 * kGeneralGradient.norm()) << "node " << k;
  }
}

TEST(Smoothing, NodeInNoTriangleHasNoCellAndNoForce) {
  // Arrange: one triangle and a stray node 3
  const std::vector<Vec2> x = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1), Vec2(5, 5)};
  AlphaMesh mesh;
  mesh.triangles = {Triangle{0, 1, 2}};
  SmoothingCells cells;
  build_smoothing_cells(mesh, x, cells);
  const std::vector<Mat3> stress(x.size(), Mat3::Identity());
  // Act
  std::vector<Vec2> force;
  internal_forces(cells, stress, force);
  const std::vector<Mat2> l = gradients_of(cells, std::vector<Vec2>(x.size(), Vec2(1, 2)));
  // Assert
  EXPECT_EQ(cells.area[3], 0.0);
  EXPECT_EQ(cells.offset[4], cells.offset[3]);
  EXPECT_EQ(force[3].norm(), 0.0);
  EXPECT_EQ(l[3].norm(), 0.0);
}

}  // namespace
}  // namespace duet::spfem
