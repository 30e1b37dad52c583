#pragma once
// Neighbour search by cell-linked lists (cells of the kernel's support radius 2h, so the
// neighbours of a particle lie in its own and the eight surrounding cells). The cell list is
// rebuilt each step as particles move, by a counting sort of particle indices by cell; the
// neighbour lists are then gathered per query particle in parallel (each thread writes only its
// own particles' rows: no data races, no atomics). Buffers grow only when a build needs more room
// than any build before it, so a step allocates nothing once sizes settle.

#include <cstdint>
#include <span>
#include <vector>

#include "common/tensor.hpp"

namespace duet::sph {

class CellList {
 public:
  /// Sorts `positions` into square cells of side `cell_size` covering their bounding box.
  /// Every position must be finite.
  void build(std::span<const Vec2> positions, double cell_size);

  double cell_size() const { return cell_size_; }
  int n_cells_x() const { return nx_; }
  int n_cells_y() const { return ny_; }
  /// Cell coordinates of a point (clamped to the grid).
  int cell_x(const Vec2& x) const;
  int cell_y(const Vec2& x) const;
  /// Particle indices sorted by cell (row-major cells: x fastest).
  std::span<const std::uint32_t> sorted() const { return sorted_; }
  /// Indices of the particles in cell (cx, cy).
  std::span<const std::uint32_t> in_cell(int cx, int cy) const {
    const std::size_t c =
        static_cast<std::size_t>(cy) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(cx);
    return {sorted_.data() + start_[c], sorted_.data() + start_[c + 1]};
  }

 private:
  double cell_size_ = 0.0;
  Vec2 origin_ = Vec2::Zero();
  int nx_ = 0;
  int ny_ = 0;
  std::vector<std::uint32_t> start_;    // n_cells + 1 offsets into sorted_
  std::vector<std::uint32_t> sorted_;   // particle indices by cell
  std::vector<std::uint32_t> cell_of_;  // cell of each particle (scratch)
};

/// Neighbour lists of the first n_query particles among all positions, as fixed-stride rows.
/// A particle is not its own neighbour; only pairs closer than the radius are kept. Each row is
/// split in two: first the neighbours with index below `late_from`, then the others (the SPH
/// step puts dummy particles last, so it can finish the soil and ghost pairs before them).
class NeighbourLists {
 public:
  /// Finds, for each i < n_query, every j != i with |x_i - x_j| < radius, using `cells` built
  /// on the same `positions` with cell size >= radius. Within each part of a row, j is in cell
  /// order.
  void build(const CellList& cells, std::span<const Vec2> positions, std::size_t n_query,
             double radius, std::size_t late_from = static_cast<std::size_t>(-1));

  std::size_t size() const { return count_.size(); }
  std::span<const std::uint32_t> of(std::size_t i) const {
    return {index_.data() + i * stride_, count_[i]};
  }
  /// The part of row i with j < late_from, and the part with j >= late_from.
  std::span<const std::uint32_t> early(std::size_t i) const {
    return {index_.data() + i * stride_, early_[i]};
  }
  std::span<const std::uint32_t> late(std::size_t i) const {
    return {index_.data() + i * stride_ + early_[i], count_[i] - early_[i]};
  }
  /// Keeps each pair among the first `below` indices once: row i loses every j < i (j < below)
  /// of its early part, so a pair loop over the rows can scatter to both ends (Newton's third
  /// law) and touch each pair once. Rows of the other indices are unchanged.
  void drop_lower_pairs(std::size_t below);
  /// Largest row length of the last build.
  std::size_t max_count() const;
  /// Capacity of a row (grows by rebuild when a row overflows).
  std::size_t stride() const { return stride_; }

 private:
  std::size_t stride_ = 32;
  std::vector<std::uint32_t> index_;
  std::vector<std::uint32_t> count_;
  std::vector<std::uint32_t> early_;
};

}  // namespace duet::sph
