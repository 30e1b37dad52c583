// Tests of node insertion along a wall (spfem/wall_node_insertion.hpp): a stretched row gets a
// node between two nodes that have drawn apart, with mass, volume and momentum kept; a pair that
// lay that far apart from the start, and soil that parted, get none.
#include "spfem/wall_node_insertion.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace duet::spfem {
namespace {

constexpr double kSpacing = 0.1;  // m

/// A free-slip floor at y = 0 from x = -1 to 2, soil above.
NodeBoundary floor_wall() {
  NodeBoundary wall;
  wall.name = "floor";
  wall.condition = NodeCondition::smooth;
  wall.polyline = {Vec2(-1.0, 0.0), Vec2(2.0, 0.0)};
  return wall;
}

/// One row of nodes dp/2 over the floor at `x` (the row as it is now), moved there from
/// `x_start` (their displacement), and one node 3 dp up (not on the wall). Each node carries dp^2
/// at 1800 kg/m^3, a stress and an internal variable that grow along the row.
Particles row(const std::vector<double>& x, const std::vector<double>& x_start) {
  Particles p;
  p.internal.width = 1;
  p.resize(x.size() + 1);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const bool on_row = i < x.size();
    p.position[i] = on_row ? Vec2(x[i], 0.5 * kSpacing) : Vec2(0.0, 3.0 * kSpacing);
    p.displacement[i] = on_row ? Vec2(x[i] - x_start[i], 0.0) : Vec2::Zero();
    p.velocity[i] = Vec2(0.1 * static_cast<double>(i), -0.02 * static_cast<double>(i));
    p.volume[i] = kSpacing * kSpacing * (1.0 + 0.1 * static_cast<double>(i));
    p.mass[i] = 1800.0 * p.volume[i];
    p.density[i] = 1800.0;
    p.stress[i] = -1.0e4 * static_cast<double>(i + 1) * Mat3::Identity();
    p.internal.values[i] = static_cast<double>(i);
    p.body[i] = 0;
    p.material[i] = 0;
  }
  return p;
}

struct Totals {
  double mass = 0.0;
  double volume = 0.0;
  Vec2 momentum = Vec2::Zero();
};

Totals totals(const Particles& p) {
  Totals t;
  for (std::size_t i = 0; i < p.size(); ++i) {
    t.mass += p.mass[i];
    t.volume += p.volume[i];
    t.momentum += p.mass[i] * p.velocity[i];
  }
  return t;
}

std::vector<InsertedNode> insert(Particles& p, double gap_factor) {
  const std::vector<NodeBoundary> walls = {floor_wall()};
  std::vector<BoundaryGeometry> geometry = {orient_boundary(walls[0], p.position, 2.0 * kSpacing)};
  return insert_wall_nodes(walls, geometry, kSpacing, gap_factor, p);
}

TEST(WallNodeInsertion, AStretchedGapGetsANodeAndMassVolumeAndMomentumAreKept) {
  // Arrange: four nodes sampled dp apart; the floor has drawn the middle pair 1.6 dp apart
  Particles p = row({0.05, 0.15, 0.31, 0.41}, {0.05, 0.15, 0.25, 0.35});
  const Totals before = totals(p);
  const std::size_t n = p.size();
  // Act
  const std::vector<InsertedNode> added = insert(p, 1.5);
  // Assert: one node, between nodes 1 and 2, on the row, with what the two gave it
  ASSERT_EQ(added.size(), 1U);
  EXPECT_EQ(p.size(), n + 1);
  EXPECT_EQ(added[0].node, static_cast<std::int32_t>(n));
  EXPECT_EQ(added[0].parents[0], 1);
  EXPECT_EQ(added[0].parents[1], 2);
  EXPECT_NEAR(p.position[n].x(), 0.23, 1e-12);
  EXPECT_NEAR(p.position[n].y(), 0.5 * kSpacing, 1e-12);
  const Totals after = totals(p);
  EXPECT_NEAR(after.mass, before.mass, 1e-12 * before.mass);
  EXPECT_NEAR(after.volume, before.volume, 1e-12 * before.volume);
  EXPECT_LT((after.momentum - before.momentum).norm(), 1e-12 * before.mass);
  // the new node's state lies between its parents', and its density is theirs
  EXPECT_NEAR(p.density[n], 1800.0, 1e-9);
  EXPECT_GT(-p.stress[n](0, 0), 2.0e4);
  EXPECT_LT(-p.stress[n](0, 0), 3.0e4);
  EXPECT_GT(p.internal.values[n], 1.0);
  EXPECT_LT(p.internal.values[n], 2.0);
  // its displacement is its parents' mean: x - u lies between where they started
  const double start = p.position[n].x() - p.displacement[n].x();
  EXPECT_GT(start, 0.15);
  EXPECT_LT(start, 0.25);
}

TEST(WallNodeInsertion, APairSampledThatFarApartOrSoilThatPartedGetsNone) {
  // Arrange: 0 -> 1 lay 2 dp apart from the start and still do (a lattice's first row, one ring
  // in two within reach of a symmetry plane); 1 -> 2 started dp apart and are now 4 dp apart,
  // beyond twice the limit (the soil parted)
  Particles p = row({0.05, 0.25, 0.65}, {0.05, 0.25, 0.35});
  // Act
  const std::vector<InsertedNode> added = insert(p, 1.5);
  // Assert
  EXPECT_TRUE(added.empty());
  EXPECT_EQ(p.size(), 4U);
}

TEST(WallNodeInsertion, ArcPositionIsTheDistanceAlongThePolylineToTheNearestPoint) {
  const std::vector<Vec2> polyline = {Vec2(0.0, 0.0), Vec2(1.0, 0.0), Vec2(1.0, 2.0)};
  EXPECT_NEAR(arc_position(polyline, Vec2(0.4, 0.1)), 0.4, 1e-12);
  EXPECT_NEAR(arc_position(polyline, Vec2(0.9, 1.5)), 2.5, 1e-12);
  EXPECT_NEAR(arc_position(polyline, Vec2(-1.0, 0.0)), 0.0, 1e-12);
}

}  // namespace
}  // namespace duet::spfem
