// Tests of the kept triangulation of build_alpha_mesh (spfem/alpha_mesh.cpp): a call on moved
// points moves the vertices of the last triangulation and restores the Delaunay property by edge
// flips, falling back to a fresh build when a face turns over. Either way the kept faces must be
// the interior faces of CGAL::Alpha_shape_2 of the new points.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "spfem/alpha_mesh.hpp"
#include "tests/spfem/alpha_shape_oracle.hpp"

namespace duet::spfem {
namespace {

using testing::alpha_shape_interior_faces;
using testing::FaceSet;
using testing::kept_faces;

constexpr double kSpacing = 0.01;
constexpr double kAlpha = 1.5 * kSpacing;

/// A 20 x 12 cell-centred lattice, every node moved by up to 0.2 dp (no cocircular ties).
std::vector<Vec2> perturbed_lattice(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-0.2 * kSpacing, 0.2 * kSpacing);
  std::vector<Vec2> x;
  for (int j = 0; j < 12; ++j) {
    for (int i = 0; i < 20; ++i)
      x.push_back(kSpacing * Vec2(i + 0.5, j + 0.5) + Vec2(u(rng), u(rng)));
  }
  return x;
}

TEST(AlphaMeshUpdate, CloudMovedStepByStepKeepsTheAlphaShapeInteriorFaces) {
  // Arrange: a perturbed lattice meshed once; then 40 small random steps (0.05 dp per component),
  // so that diagonals flip as the cloud wanders
  std::mt19937 rng(11);
  std::vector<Vec2> x = perturbed_lattice(rng);
  AlphaMesh mesh;
  build_alpha_mesh(x, kAlpha, mesh);
  std::uniform_real_distribution<double> step(-0.05 * kSpacing, 0.05 * kSpacing);
  int changed = 0;
  for (int k = 0; k < 40; ++k) {
    const FaceSet before = kept_faces(mesh);
    for (Vec2& p : x) p += Vec2(step(rng), step(rng));
    // Act
    build_alpha_mesh(x, kAlpha, mesh);
    // Assert
    const FaceSet faces = kept_faces(mesh);
    if (faces != before) ++changed;
    ASSERT_EQ(faces, alpha_shape_interior_faces(x, kAlpha)) << "after step " << k;
  }
  EXPECT_GT(changed, 0);  // the connectivity did change on the way
}

TEST(AlphaMeshUpdate, NodePushedThroughItsNeighboursGetsTheFreshMesh) {
  // Arrange: a meshed perturbed lattice, then one interior node moved 2.5 dp (faces turn over)
  std::mt19937 rng(5);
  std::vector<Vec2> x = perturbed_lattice(rng);
  AlphaMesh mesh;
  build_alpha_mesh(x, kAlpha, mesh);
  x[5 * 20 + 8] += Vec2(2.5 * kSpacing, 0.3 * kSpacing);
  // Act
  build_alpha_mesh(x, kAlpha, mesh);
  // Assert
  EXPECT_EQ(kept_faces(mesh), alpha_shape_interior_faces(x, kAlpha));
}

TEST(AlphaMeshUpdate, AnotherCloudOfTheSameSizeGetsItsOwnMesh) {
  // Arrange: two different clouds of the same node count meshed in turn (one thread, one kept
  // triangulation)
  std::mt19937 rng(3);
  const std::vector<Vec2> a = perturbed_lattice(rng);
  std::vector<Vec2> b = perturbed_lattice(rng);
  for (Vec2& p : b) p = Vec2(p.y(), -p.x()) + Vec2(1.0, 2.0);  // turned and moved far away
  AlphaMesh mesh;
  // Act / Assert
  build_alpha_mesh(a, kAlpha, mesh);
  EXPECT_EQ(kept_faces(mesh), alpha_shape_interior_faces(a, kAlpha));
  build_alpha_mesh(b, kAlpha, mesh);
  EXPECT_EQ(kept_faces(mesh), alpha_shape_interior_faces(b, kAlpha));
  build_alpha_mesh(a, kAlpha, mesh);
  EXPECT_EQ(kept_faces(mesh), alpha_shape_interior_faces(a, kAlpha));
}

}  // namespace
}  // namespace duet::spfem
