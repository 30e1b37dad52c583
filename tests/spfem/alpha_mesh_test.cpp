// Tests of the Delaunay + alpha-shape mesh of SPFEM (spfem/alpha_mesh.hpp): the direct
// circumradius test against CGAL::Alpha_shape_2, bodies and isolated nodes, surface nodes, area and
// the smallest-angle measure.
#include "spfem/alpha_mesh.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "tests/spfem/alpha_shape_oracle.hpp"

namespace duet::spfem {
namespace {

using testing::alpha_shape_interior_faces;
using testing::FaceSet;
using testing::kept_faces;

/// Cell-centred square lattice of nx x ny nodes, spacing dp, cells starting at `origin`.
std::vector<Vec2> lattice(int nx, int ny, double dp, const Vec2& origin = Vec2::Zero()) {
  std::vector<Vec2> x;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) x.push_back(origin + dp * Vec2(i + 0.5, j + 0.5));
  }
  return x;
}

/// Moves every node by a uniform random offset in [-amplitude, amplitude]^2.
void perturb(std::vector<Vec2>& x, double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  for (auto& p : x) p += Vec2(u(rng), u(rng));
}

TEST(AlphaMesh, KeptFacesAreTheAlphaShapeInteriorFacesOnAPerturbedLattice) {
  // Arrange: 40 x 30 nodes moved by up to 0.3 dp, so circumradii spread around 0.7 dp; one alpha
  // that cuts into that spread and the scene default 1.5 dp
  const double dp = 0.01;
  auto x = lattice(40, 30, dp);
  perturb(x, 0.3 * dp, 11);
  for (const double alpha_factor : {0.75, 1.5}) {
    SCOPED_TRACE(alpha_factor);
    AlphaMesh mesh;
    // Act
    build_alpha_mesh(x, alpha_factor * dp, mesh);
    // Assert: same faces, and the test is not trivial (some Delaunay faces are dropped)
    EXPECT_EQ(kept_faces(mesh), alpha_shape_interior_faces(x, alpha_factor * dp));
    EXPECT_GT(mesh.triangles.size(), 0u);
    EXPECT_LT(mesh.triangles.size(), mesh.n_delaunay);
  }
}

TEST(AlphaMesh, KeptFacesAreTheAlphaShapeInteriorFacesOnACloudWithHoles) {
  // Arrange: 60 x 40 lattice moved by up to 0.3 dp with two round holes (radius 5 dp and 4 dp)
  // cut out; the same two alphas
  const double dp = 0.01;
  auto full = lattice(60, 40, dp);
  perturb(full, 0.3 * dp, 5);
  const Vec2 centre_a(0.15, 0.2), centre_b(0.42, 0.18);
  std::vector<Vec2> x;
  for (const Vec2& p : full) {
    if ((p - centre_a).norm() > 5 * dp && (p - centre_b).norm() > 4 * dp) x.push_back(p);
  }
  for (const double alpha_factor : {0.75, 1.5}) {
    SCOPED_TRACE(alpha_factor);
    AlphaMesh mesh;
    // Act
    build_alpha_mesh(x, alpha_factor * dp, mesh);
    // Assert
    EXPECT_EQ(kept_faces(mesh), alpha_shape_interior_faces(x, alpha_factor * dp));
    EXPECT_LT(mesh.triangles.size(), mesh.n_delaunay);
  }
}

TEST(AlphaMesh, ParticleMovedFarAwayIsIsolatedAndTheRestIsOneBody) {
  // Arrange: 20 x 10 lattice, an interior particle moved 100 m away
  const double dp = 0.1;
  auto x = lattice(20, 10, dp);
  const std::size_t moved = 4 * 20 + 7;
  x[moved] += Vec2(100.0, 0.0);
  AlphaMesh mesh;
  // Act
  build_alpha_mesh(x, 1.5 * dp, mesh);
  // Assert
  EXPECT_EQ(mesh.n_components, 1);
  EXPECT_EQ(mesh.component[moved], -1);
  EXPECT_EQ(mesh.surface[moved], 1);
  EXPECT_EQ(std::count(mesh.component.begin(), mesh.component.end(), -1), 1);
}

TEST(AlphaMesh, TwoBlocksFartherApartThanTwiceAlphaAreTwoBodies) {
  // Arrange: two 10 x 10 blocks whose facing nodes are 4 dp apart; a bridging triangle has a
  // circumradius of at least half the gap, 2 dp > alpha = 1.5 dp
  const double dp = 0.1;
  auto x = lattice(10, 10, dp);
  const auto right = lattice(10, 10, dp, Vec2(1.0 + 3 * dp, 0.0));
  x.insert(x.end(), right.begin(), right.end());
  AlphaMesh mesh;
  // Act
  build_alpha_mesh(x, 1.5 * dp, mesh);
  // Assert
  ASSERT_EQ(mesh.n_components, 2);
  for (std::size_t i = 0; i < x.size(); ++i) EXPECT_EQ(mesh.component[i], i < 100 ? 0 : 1) << i;
}

TEST(AlphaMesh, TwoBlocksInContactAreOneBody) {
  // Arrange: the same blocks with their facing nodes dp apart (re-contact)
  const double dp = 0.1;
  auto x = lattice(10, 10, dp);
  const auto right = lattice(10, 10, dp, Vec2(1.0, 0.0));
  x.insert(x.end(), right.begin(), right.end());
  AlphaMesh mesh;
  // Act
  build_alpha_mesh(x, 1.5 * dp, mesh);
  // Assert
  EXPECT_EQ(mesh.n_components, 1);
  EXPECT_EQ(std::count(mesh.component.begin(), mesh.component.end(), 0), 200);
}

TEST(AlphaMesh, TrianglesSharingOnlyANodeAreOneBody) {
  // Arrange: a bow tie, two triangles meeting at node 2
  const std::vector<Vec2> x = {{0, 0}, {1, 0}, {0.5, 0.5}, {0, 1}, {1, 1}};
  AlphaMesh mesh;
  mesh.triangles = {{0, 1, 2}, {2, 4, 3}};
  // Act
  label_mesh(x.size(), mesh);
  // Assert
  EXPECT_EQ(mesh.n_components, 1);
  EXPECT_EQ(mesh.component, (std::vector<std::int32_t>{0, 0, 0, 0, 0}));
}

TEST(AlphaMesh, SurfaceNodesOfARectangleLatticeAreItsPerimeterNodes) {
  // Arrange
  const int nx = 17, ny = 9;
  const auto x = lattice(nx, ny, 0.1);
  AlphaMesh mesh;
  // Act
  build_alpha_mesh(x, 1.5 * 0.1, mesh);
  // Assert
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const bool perimeter = i == 0 || j == 0 || i == nx - 1 || j == ny - 1;
      EXPECT_EQ(mesh.surface[j * nx + i], perimeter ? 1 : 0) << "node " << i << ", " << j;
    }
  }
}

TEST(AlphaMesh, AreaOfARectangleLatticeIsTheHullOfItsCellCentres) {
  // Arrange: 2.0 m x 1.2 m sampled at dp = 0.05 m
  const double dp = 0.05, width = 2.0, height = 1.2;
  const auto x = lattice(40, 24, dp);
  AlphaMesh mesh;
  // Act
  build_alpha_mesh(x, 1.5 * dp, mesh);
  // Assert: the nodes span [dp/2, width - dp/2] x [dp/2, height - dp/2]
  EXPECT_NEAR(mesh_area(mesh, x), (width - dp) * (height - dp), 1e-12);
}

// Two nodes landed side by side on a floor, 0.004 dp apart (collapse-bui through espfem at
// alpha 1.2 dp: nodes 597 and 759, RESULTS.md "Item 1 again"): the alpha test alone keeps the
// slivers between them; with a shortest edge of 0.1 dp none of those is kept, and the rest of the
// mesh is the one without the extra node.
TEST(AlphaMesh, NoKeptTriangleHasAnEdgeBelowTheShortestEdge) {
  // Arrange: a 10 x 4 lattice, a node added 0.004 dp beside the bottom row's fifth node
  const double dp = 0.1;
  auto x = lattice(10, 4, dp);
  const auto without = x;
  x.push_back(x[4] + Vec2(0.004 * dp, 0.0));
  const auto added = static_cast<std::int32_t>(x.size() - 1);
  auto shortest_edge = [&x](const Triangle& t) {
    double e = 1e300;
    for (int k = 0; k < 3; ++k) e = std::min(e, (x[t[k]] - x[t[(k + 1) % 3]]).norm());
    return e;
  };
  AlphaMesh plain, guarded, reference;
  // Act
  build_alpha_mesh(x, 1.5 * dp, plain, true);
  build_alpha_mesh(x, 1.5 * dp, guarded, true, 0.1 * dp);
  build_alpha_mesh(without, 1.5 * dp, reference, true);
  // Assert: slivers without the guard; with it, no edge below 0.1 dp, and every kept triangle
  // without the added node is one of the lattice's own
  const auto slivers =
      std::count_if(plain.triangles.begin(), plain.triangles.end(),
                    [&](const Triangle& t) { return shortest_edge(t) < 0.1 * dp; });
  EXPECT_GE(slivers, 1);
  const FaceSet lattice_faces = kept_faces(reference);
  std::size_t at_added = 0;
  for (const Triangle& t : guarded.triangles) {
    EXPECT_GE(shortest_edge(t), 0.1 * dp);
    if (std::find(t.begin(), t.end(), added) != t.end()) {
      ++at_added;
    } else {
      EXPECT_TRUE(lattice_faces.contains(testing::sorted(t)));
    }
  }
  EXPECT_EQ(guarded.triangles.size(), plain.triangles.size() - static_cast<std::size_t>(slivers));
  EXPECT_EQ(guarded.component[static_cast<std::size_t>(added)], 0);  // still in the body
  EXPECT_GE(at_added, 1u);
}

TEST(AlphaMesh, SmallestAngleOfARightIsoscelesMeshIs45Degrees) {
  // Arrange: a square lattice splits into right isosceles triangles
  const auto x = lattice(12, 7, 0.1);
  AlphaMesh mesh;
  build_alpha_mesh(x, 1.5 * 0.1, mesh);
  // Act
  const double angle = smallest_angle(mesh, x);
  // Assert
  EXPECT_NEAR(angle, 45.0, 1e-10);
}

TEST(AlphaMesh, SmallestAngleIsNegativeAfterANodeIsPushedThroughItsOppositeEdge) {
  // Arrange: the unit square as two right isosceles triangles; node 1 pushed from (1, 0) across
  // the diagonal 0-2 to (0.25, 0.75)
  std::vector<Vec2> x = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  AlphaMesh mesh;
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  const double before = smallest_angle(mesh, x);
  x[1] = Vec2(0.25, 0.75);
  // Act
  const double after = smallest_angle(mesh, x);
  // Assert: the inverted triangle's largest angle, at the pushed node, with a minus sign:
  // cos = (-0.25, -0.75).(0.75, 0.25) / 0.625 = -0.6
  EXPECT_NEAR(before, 45.0, 1e-12);
  EXPECT_NEAR(after, -std::acos(-0.6) * 180.0 / std::numbers::pi, 1e-10);
}

}  // namespace
}  // namespace duet::spfem
