// Tests of the cell-linked-list neighbour search (sph/neighbours.hpp) against brute force.
#include "sph/neighbours.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace duet::sph {
namespace {

std::vector<Vec2> random_points(std::size_t n, double width, double height, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> ux(-0.3, width), uy(0.1, height);
  std::vector<Vec2> x(n);
  for (auto& p : x) p = Vec2(ux(rng), uy(rng));
  return x;
}

std::vector<std::uint32_t> brute_force(const std::vector<Vec2>& x, std::size_t i, double radius) {
  std::vector<std::uint32_t> out;
  for (std::size_t j = 0; j < x.size(); ++j) {
    if (j != i && (x[j] - x[i]).norm() < radius) out.push_back(static_cast<std::uint32_t>(j));
  }
  return out;
}

TEST(Neighbours, CellListFindsExactlyThePairsWithinTheRadius) {
  // Arrange: 3000 random points, the first 2000 queried (as soil among boundary particles)
  const auto x = random_points(3000, 1.0, 0.6, 7);
  const double radius = 0.04;
  CellList cells;
  NeighbourLists lists;
  // Act
  cells.build(x, radius);
  lists.build(cells, x, 2000, radius);
  // Assert
  ASSERT_EQ(lists.size(), 2000u);
  for (std::size_t i = 0; i < 2000; ++i) {
    std::vector<std::uint32_t> found(lists.of(i).begin(), lists.of(i).end());
    std::sort(found.begin(), found.end());
    EXPECT_EQ(found, brute_force(x, i, radius)) << "particle " << i;
  }
}

TEST(Neighbours, RowsListIndicesFromLateFromAfterAllOthers) {
  // Arrange: the SPH step puts dummy particles (here the last 1000) after soil and ghosts
  const auto x = random_points(3000, 1.0, 0.6, 9);
  const double radius = 0.04;
  CellList cells;
  NeighbourLists lists;
  cells.build(x, radius);
  // Act
  lists.build(cells, x, 2000, radius, 2000);
  // Assert: early = the brute-force neighbours below 2000, late = those from 2000 on
  for (std::size_t i = 0; i < 2000; ++i) {
    std::vector<std::uint32_t> early(lists.early(i).begin(), lists.early(i).end());
    std::vector<std::uint32_t> late(lists.late(i).begin(), lists.late(i).end());
    std::sort(early.begin(), early.end());
    std::sort(late.begin(), late.end());
    std::vector<std::uint32_t> expected_early, expected_late;
    for (const auto j : brute_force(x, i, radius))
      (j < 2000 ? expected_early : expected_late).push_back(j);
    EXPECT_EQ(early, expected_early) << "particle " << i;
    EXPECT_EQ(late, expected_late) << "particle " << i;
    EXPECT_EQ(lists.of(i).size(), early.size() + late.size());
  }
}

TEST(Neighbours, DroppingLowerPairsKeepsEachSoilPairOnceAndEveryBoundaryNeighbour) {
  // Arrange: soil 0..1499, ghosts 1500..1999 (early, kept whole), dummies from 2000 (late)
  const auto x = random_points(3000, 1.0, 0.6, 11);
  const double radius = 0.04;
  CellList cells;
  NeighbourLists lists;
  cells.build(x, radius);
  lists.build(cells, x, 2000, radius, 2000);
  // Act
  lists.drop_lower_pairs(1500);
  // Assert: row i keeps soil j > i, every ghost and every dummy; so each soil pair {i, j} sits in
  // exactly one row, the row of its lower index.
  for (std::size_t i = 0; i < 2000; ++i) {
    std::vector<std::uint32_t> early(lists.early(i).begin(), lists.early(i).end());
    std::vector<std::uint32_t> late(lists.late(i).begin(), lists.late(i).end());
    std::sort(early.begin(), early.end());
    std::sort(late.begin(), late.end());
    std::vector<std::uint32_t> expected_early, expected_late;
    for (const auto j : brute_force(x, i, radius)) {
      if (j >= 2000) {
        expected_late.push_back(j);
      } else if (j >= 1500 || j > i) {
        expected_early.push_back(j);
      }
    }
    EXPECT_EQ(early, expected_early) << "particle " << i;
    EXPECT_EQ(late, expected_late) << "particle " << i;
  }
}

TEST(Neighbours, RowsGrowWhenAParticleHasMoreNeighboursThanTheInitialCapacity) {
  // Arrange: 400 points in a tiny cluster, so every one sees 399 neighbours
  const auto x = random_points(400, 0.001, 0.101, 3);
  CellList cells;
  NeighbourLists lists;
  // Act
  cells.build(x, 1.0);
  lists.build(cells, x, x.size(), 1.0);
  // Assert
  EXPECT_EQ(lists.max_count(), 399u);
  EXPECT_GE(lists.stride(), 399u);
  for (std::size_t i = 0; i < x.size(); ++i) EXPECT_EQ(lists.of(i).size(), 399u);
}

TEST(Neighbours, CellListSortsEveryParticleIntoItsCell) {
  // Arrange
  const auto x = random_points(500, 0.5, 0.5, 11);
  CellList cells;
  // Act
  cells.build(x, 0.05);
  // Assert: every index appears once, and each lies in the cell that lists it
  std::vector<int> seen(x.size(), 0);
  for (int cy = 0; cy < cells.n_cells_y(); ++cy) {
    for (int cx = 0; cx < cells.n_cells_x(); ++cx) {
      for (const auto j : cells.in_cell(cx, cy)) {
        ++seen[j];
        EXPECT_EQ(cells.cell_x(x[j]), cx);
        EXPECT_EQ(cells.cell_y(x[j]), cy);
      }
    }
  }
  EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; }));
}

TEST(Neighbours, NonFinitePositionIsRefused) {
  std::vector<Vec2> x{Vec2(0, 0), Vec2(std::nan(""), 0.0)};
  CellList cells;
  EXPECT_THROW(cells.build(x, 0.1), std::domain_error);
}

}  // namespace
}  // namespace duet::sph
