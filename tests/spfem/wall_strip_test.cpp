// Tests of the wall strips (spfem/wall_strip.hpp): no-slip walls enter the node-based smoothing as
// strips between the surface edges at the wall and the wall, whose wall vertices move with it.
// Checked: which edges get a strip, the linear patch test with walls moving with the field, the
// cell areas (the body's true area), virtual power with the wall points, the balance of the nodal
// and wall-point forces, and the release rule (a strip holds in tension).
#include "spfem/wall_strip.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "spfem/smoothing.hpp"
#include "tests/spfem/delaunay_mesh.hpp"
#include "tests/spfem/straight_wall.hpp"

namespace duet::spfem {
namespace {

using testing::delaunay_mesh;
using testing::Lattice;
using testing::straight_wall;

// Jittered by up to 0.2 dp; the first row and column bowed towards their walls instead (convex,
// so every edge of theirs stays on the surface): between 0.3 dp (middle) and 0.5 dp (ends) off
// them, tilted strips of uneven depth.
std::vector<Vec2> jittered(const Lattice& lattice, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  std::vector<Vec2> x = lattice.points();
  const Vec2 centre(0.5 * lattice.width(), 0.5 * lattice.height());
  const auto bowed = [&](double along, double half) {
    const double s = (along - half) / half;
    return lattice.dp * (0.3 + 0.2 * s * s);
  };
  for (Vec2& p : x) {
    const bool first_column = p.x() < lattice.dp;
    const bool first_row = p.y() < lattice.dp;
    const Vec2 shift = lattice.dp * Vec2(u(random), u(random));
    if (!first_column && !first_row) p += shift;
    if (first_column) p.x() = bowed(p.y(), centre.y());
    if (first_row) p.y() = bowed(p.x(), centre.x());
  }
  return x;
}

// A no-slip floor and left wall around the lattice (reaching past its corners).
std::vector<NodeBoundary> floor_and_left_wall(const Lattice& lattice,
                                              NodeCondition left = NodeCondition::bonded) {
  return {straight_wall("floor", Vec2(-lattice.dp, 0.0), Vec2(lattice.width() + lattice.dp, 0.0),
                        NodeCondition::bonded),
          straight_wall("left", Vec2(0.0, -lattice.dp), Vec2(0.0, lattice.height() + lattice.dp),
                        left)};
}

WallStrips strips_of(const AlphaMesh& mesh, const std::vector<Vec2>& x,
                     const std::vector<NodeBoundary>& boundaries, double dp) {
  std::vector<BoundaryGeometry> geometry;
  for (const NodeBoundary& b : boundaries) geometry.push_back(orient_boundary(b, x, 2.0 * dp));
  WallStrips strips;
  find_wall_strips(mesh, x, boundaries, geometry, dp, 0.5 * dp, strips);
  return strips;
}

const Mat2 kGeneralGradient = (Mat2() << 0.7, -1.3, 0.45, -0.2).finished();

TEST(WallStrip, EveryEdgeAlongAWallGetsAStripAndOnlyNoSlipStripsHoldTheirNodes) {
  // Arrange: lattice on a no-slip floor beside a free-slip left wall
  const Lattice lattice;
  const std::vector<Vec2> x = lattice.points();
  const AlphaMesh mesh = delaunay_mesh(x);
  // Act
  const WallStrips strips =
      strips_of(mesh, x, floor_and_left_wall(lattice, NodeCondition::smooth), lattice.dp);
  // Assert: the nx - 1 bottom edges, each a -> b left to right (soil on its left), projected on
  // y = 0 straight below its nodes; the ny - 1 edges along the left wall, flagged free-slip; only
  // the floor holds (its nodes released from plain contact)
  ASSERT_EQ(strips.edges.size(), std::size_t(lattice.nx - 1 + lattice.ny - 1));
  std::size_t on_floor = 0;
  for (const WallEdge& e : strips.edges) {
    const Vec2 foot_a =
        e.boundary == 0 ? Vec2(x[std::size_t(e.a)].x(), 0.0) : Vec2(0.0, x[std::size_t(e.a)].y());
    const Vec2 foot_b =
        e.boundary == 0 ? Vec2(x[std::size_t(e.b)].x(), 0.0) : Vec2(0.0, x[std::size_t(e.b)].y());
    EXPECT_EQ(e.free_slip, e.boundary == 1);
    EXPECT_NEAR((e.a_wall - foot_a).norm(), 0.0, 1e-15);
    EXPECT_NEAR((e.b_wall - foot_b).norm(), 0.0, 1e-15);
    if (e.boundary == 0) {
      ++on_floor;
      EXPECT_GT(x[std::size_t(e.b)].x(), x[std::size_t(e.a)].x());
    }
  }
  EXPECT_EQ(on_floor, std::size_t(lattice.nx - 1));
  for (std::size_t i = 0; i < x.size(); ++i) {
    EXPECT_EQ(strips.held[i], x[i].y() < lattice.dp ? 1u : 0u) << "node " << i;
  }
}

TEST(WallStrip, AUniformlyStressedConfinedSampleIsInEquilibrium) {
  // Arrange: the oedometer's walls around the lattice: no-slip floor and top, free-slip sides; a
  // uniform stress with no shear (a free-slip wall carries none)
  const Lattice lattice;
  const std::vector<Vec2> x = lattice.points();
  const AlphaMesh mesh = delaunay_mesh(x);
  const double w = lattice.width();
  const double h = lattice.height();
  const double d = lattice.dp;
  const std::vector<NodeBoundary> walls = {
      straight_wall("floor", Vec2(-d, 0.0), Vec2(w + d, 0.0), NodeCondition::bonded),
      straight_wall("top", Vec2(w + d, h), Vec2(-d, h), NodeCondition::bonded),
      straight_wall("left", Vec2(0.0, h + d), Vec2(0.0, -d), NodeCondition::smooth),
      straight_wall("right", Vec2(w, -d), Vec2(w, h + d), NodeCondition::smooth)};
  const WallStrips strips = strips_of(mesh, x, walls, d);
  SmoothingCells cells;
  build_smoothing_cells(mesh, x, cells, 0.5 * d, &strips);
  const double sxx = -3.0e4;
  const double syy = -6.0e4;
  const std::vector<Mat3> stress(x.size(), Vec3(sxx, syy, sxx).asDiagonal().toDenseMatrix());
  // Act
  std::vector<Vec2> force;
  internal_forces(cells, stress, force);
  std::vector<Vec2> reaction(walls.size(), Vec2::Zero());
  add_wall_strip_reactions(strips, cells, stress, reaction);
  std::vector<Vec2> wall_force;
  wall_point_forces(cells, stress, wall_force);
  // Assert: no node is pushed along a wall, nor off it, except into a free-slip wall (the body's
  // side force there); the left half, cut at x = W/2, balances the cut's sigma_xx H through its
  // side nodes and the no-slip walls' points (which carry the corners' share); the no-slip walls
  // carry sigma_yy W
  const double tolerance = 1e-10 * std::abs(syy) * d;
  double left_half = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const bool at_side = x[i].x() < d || x[i].x() > w - d;
    EXPECT_NEAR(force[i].y(), 0.0, tolerance) << "node " << i;
    if (at_side) {
      EXPECT_GT(std::abs(force[i].x()), 0.1 * std::abs(sxx) * d) << "node " << i;
    } else {
      EXPECT_NEAR(force[i].x(), 0.0, tolerance) << "node " << i;
    }
    if (x[i].x() < d) left_half += force[i].x();
  }
  for (std::size_t e = 0; e < strips.edges.size(); ++e) {
    if (strips.edges[e].a_wall.x() < 0.5 * w) left_half += wall_force[2 * e].x();
    if (strips.edges[e].b_wall.x() < 0.5 * w) left_half += wall_force[2 * e + 1].x();
  }
  std::printf("floor %.6e %.6e, top %.6e %.6e, left half %.6e\n", reaction[0].x(), reaction[0].y(),
              reaction[1].x(), reaction[1].y(), left_half);
  EXPECT_NEAR(left_half, -sxx * h, 1e-10 * std::abs(sxx) * h);
  EXPECT_NEAR(reaction[0].y(), syy * w, 1e-10 * std::abs(syy) * w);
  EXPECT_NEAR(reaction[1].y(), -syy * w, 1e-10 * std::abs(syy) * w);
  EXPECT_NEAR(reaction[0].x(), 0.0, 1e-10 * std::abs(syy) * w);
}

TEST(WallStrip, LinearVelocityStaysExactWithTheWallsMovingWithTheField) {
  // Arrange: irregular mesh on a no-slip floor and left wall, v = v0 + G (x - x_c), and the wall
  // points moving with the same field, v_w = v(x_w)
  const Lattice lattice;
  const std::vector<Vec2> x = jittered(lattice, 7);
  const AlphaMesh mesh = delaunay_mesh(x);
  WallStrips strips = strips_of(mesh, x, floor_and_left_wall(lattice), lattice.dp);
  const Vec2 centre(0.5 * lattice.width(), 0.5 * lattice.height());
  const auto field = [&](const Vec2& p) {
    return Vec2(Vec2(0.03, -0.08) + kGeneralGradient * (p - centre));
  };
  for (WallEdge& e : strips.edges) {
    e.a_wall_velocity = field(e.a_wall);
    e.b_wall_velocity = field(e.b_wall);
  }
  std::vector<Vec2> v(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) v[i] = field(x[i]);
  SmoothingCells cells;
  build_smoothing_cells(mesh, x, cells, 0.5 * lattice.dp, &strips);
  // Act
  std::vector<Mat2> l;
  smoothed_velocity_gradients(cells, v, l);
  // Assert: every cell, wall strips included, integrates exact element gradients
  double worst = 0.0;
  for (const Mat2& l_k : l) {
    worst = std::max(worst, (l_k - kGeneralGradient).norm() / kGeneralGradient.norm());
  }
  std::printf("patch test with %zu wall strips: relative error %.2e\n", strips.edges.size(), worst);
  EXPECT_EQ(strips.edges.size(), std::size_t(lattice.nx - 1 + lattice.ny - 1));
  EXPECT_LT(worst, 1e-12);
}

TEST(WallStrip, CellAreasSumToTheBodyAreaAgainstTwoNoSlipWalls) {
  // Arrange: the mesh covers (W - dp)(H - dp); strips (wall or layer) dp/2 deep along all four
  // sides and the four corner wedges (dp/2)^2, the one between the walls carried by its strips
  const Lattice lattice;
  const std::vector<Vec2> x = lattice.points();
  const AlphaMesh mesh = delaunay_mesh(x);
  const WallStrips strips = strips_of(mesh, x, floor_and_left_wall(lattice), lattice.dp);
  SmoothingCells cells;
  // Act
  build_smoothing_cells(mesh, x, cells, 0.5 * lattice.dp, &strips);
  // Assert: sum A_k = W H
  double sum = 0.0;
  for (const double a_k : cells.area) sum += a_k;
  const double body = lattice.width() * lattice.height();
  std::printf("%zu strips, cell areas %.12f, W H = %.12f\n", strips.edges.size(), sum, body);
  EXPECT_EQ(strips.edges.size(), std::size_t(lattice.nx - 1 + lattice.ny - 1));
  EXPECT_NEAR(sum, body, 1e-12 * body);
}

struct RandomState {
  std::vector<Vec2> velocity;
  std::vector<Mat3> stress;
};

RandomState random_state(std::size_t n, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  RandomState s{std::vector<Vec2>(n), std::vector<Mat3>(n, Mat3::Zero())};
  for (std::size_t k = 0; k < n; ++k) {
    s.velocity[k] = Vec2(u(random), u(random));
    s.stress[k](0, 0) = 1.0e5 * u(random);
    s.stress[k](1, 1) = 1.0e5 * u(random);
    s.stress[k](0, 1) = s.stress[k](1, 0) = 1.0e5 * u(random);
  }
  return s;
}

TEST(WallStrip, InternalPowerWithTheWallPointsEqualsStressPower) {
  // Arrange: arbitrary node and wall-point velocities and node stresses on an irregular mesh
  const Lattice lattice;
  const std::vector<Vec2> x = jittered(lattice, 9);
  const AlphaMesh mesh = delaunay_mesh(x);
  WallStrips strips = strips_of(mesh, x, floor_and_left_wall(lattice), lattice.dp);
  std::mt19937 random(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (WallEdge& e : strips.edges) {
    e.a_wall_velocity = Vec2(u(random), u(random));
    e.b_wall_velocity = Vec2(u(random), u(random));
  }
  SmoothingCells cells;
  build_smoothing_cells(mesh, x, cells, 0.5 * lattice.dp, &strips);
  const RandomState s = random_state(x.size(), 10);
  // Act
  std::vector<Vec2> force;
  internal_forces(cells, s.stress, force);
  std::vector<Vec2> wall_force;
  wall_point_forces(cells, s.stress, wall_force);
  std::vector<Mat2> l;
  smoothed_velocity_gradients(cells, s.velocity, l);
  // Assert: sum_l F_l . v_l + sum_w F_w . v_w == sum_k A_k sigma_k : L_k
  double internal_power = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) internal_power += force[k].dot(s.velocity[k]);
  for (std::size_t w = 0; w < wall_force.size(); ++w) {
    internal_power += wall_force[w].dot(cells.wall_velocity[w]);
  }
  double stress_power = 0.0;
  double scale = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const Mat2 sk = s.stress[k].topLeftCorner<2, 2>();
    stress_power += cells.area[k] * (sk.array() * l[k].array()).sum();
    scale += cells.area[k] * (sk.array() * l[k].array()).abs().sum();
  }
  std::printf("internal power %.12e, stress power %.12e\n", internal_power, stress_power);
  ASSERT_EQ(wall_force.size(), 2 * strips.edges.size());
  EXPECT_NEAR(internal_power, stress_power, 1e-12 * scale);
}

TEST(WallStrip, NodalAndWallPointForcesBalanceForAnyStress) {
  // Arrange: arbitrary stresses; a rigid translation has L = 0 at every node, so the internal
  // forces of the nodes and of the wall points sum to zero and the force of the soil on the walls
  // is the resultant of the nodal internal forces
  const Lattice lattice;
  const std::vector<Vec2> x = jittered(lattice, 5);
  const AlphaMesh mesh = delaunay_mesh(x);
  const WallStrips strips = strips_of(mesh, x, floor_and_left_wall(lattice), lattice.dp);
  SmoothingCells cells;
  build_smoothing_cells(mesh, x, cells, 0.5 * lattice.dp, &strips);
  const RandomState s = random_state(x.size(), 12);
  // Act
  std::vector<Vec2> force;
  internal_forces(cells, s.stress, force);
  std::vector<Vec2> reaction(2, Vec2::Zero());
  add_wall_strip_reactions(strips, cells, s.stress, reaction);
  // Assert: sum_l F_l = -sum_w F_w = the force on the walls
  Vec2 nodal = Vec2::Zero();
  for (const Vec2& f : force) nodal += f;
  const Vec2 on_walls = reaction[0] + reaction[1];
  std::printf("nodal resultant %.6e %.6e, force on the walls %.6e %.6e\n", nodal.x(), nodal.y(),
              on_walls.x(), on_walls.y());
  EXPECT_LT((nodal - on_walls).norm(), 1e-9 * 1.0e5 * lattice.width());
  EXPECT_GT(on_walls.norm(), 1.0);  // the walls do carry force
}

TEST(WallStrip, AStripHoldsItsNodesInTensionAndLetsGoBeyondTwoSpacings) {
  // Arrange: strips found with the bottom row dp/2 over the floor, then the block lifted
  const Lattice lattice;
  std::vector<Vec2> x = lattice.points();
  const AlphaMesh mesh = delaunay_mesh(x);
  const std::vector<NodeBoundary> floor = {straight_wall("floor", Vec2(-lattice.dp, 0.0),
                                                         Vec2(lattice.width() + lattice.dp, 0.0),
                                                         NodeCondition::bonded)};
  std::vector<BoundaryGeometry> geometry = {orient_boundary(floor[0], x, 2.0 * lattice.dp)};
  WallStrips strips;
  find_wall_strips(mesh, x, floor, geometry, lattice.dp, 0.5 * lattice.dp, strips);
  const std::size_t attached_edges = strips.edges.size();
  // Act: lifted by one spacing (bottom row 1.5 dp off the floor, beyond contact), then by two
  for (Vec2& p : x) p.y() += lattice.dp;
  find_wall_strips(mesh, x, floor, geometry, lattice.dp, 0.5 * lattice.dp, strips);
  const std::size_t lifted_edges = strips.edges.size();
  for (Vec2& p : x) p.y() += lattice.dp;
  find_wall_strips(mesh, x, floor, geometry, lattice.dp, 0.5 * lattice.dp, strips);
  // Assert: still held at 1.5 dp (a clamp carries tension), let go at 2.5 dp
  EXPECT_EQ(attached_edges, std::size_t(lattice.nx - 1));
  EXPECT_EQ(lifted_edges, attached_edges);
  EXPECT_TRUE(strips.edges.empty());
}

}  // namespace
}  // namespace duet::spfem
