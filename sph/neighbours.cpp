#include "sph/neighbours.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace duet::sph {

namespace {
// A runaway particle must not make the grid explode; the driver stops such runs anyway.
constexpr double kMaxCells = 5.0e7;
}  // namespace

int CellList::cell_x(const Vec2& x) const {
  const int c = static_cast<int>(std::floor((x.x() - origin_.x()) / cell_size_));
  return std::clamp(c, 0, nx_ - 1);
}

int CellList::cell_y(const Vec2& x) const {
  const int c = static_cast<int>(std::floor((x.y() - origin_.y()) / cell_size_));
  return std::clamp(c, 0, ny_ - 1);
}

void CellList::build(std::span<const Vec2> positions, double cell_size) {
  if (!(cell_size > 0.0)) throw std::invalid_argument("CellList: cell size must be > 0");
  cell_size_ = cell_size;
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::max());
  Vec2 hi = Vec2::Constant(std::numeric_limits<double>::lowest());
  bool finite = true;
  for (const Vec2& x : positions) {
    finite = finite && x.allFinite();
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  if (positions.empty()) lo = hi = Vec2::Zero();
  if (!finite || !lo.allFinite() || !hi.allFinite()) {
    throw std::domain_error("CellList: non-finite particle position");
  }
  origin_ = lo;
  const double ex = std::floor((hi.x() - lo.x()) / cell_size) + 1.0;
  const double ey = std::floor((hi.y() - lo.y()) / cell_size) + 1.0;
  if (ex * ey > kMaxCells) throw std::domain_error("CellList: particles spread too far apart");
  nx_ = static_cast<int>(ex);
  ny_ = static_cast<int>(ey);
  const std::size_t n_cells = static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_);

  // Counting sort of particle indices by cell.
  start_.assign(n_cells + 1, 0);
  cell_of_.resize(positions.size());
  sorted_.resize(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const std::uint32_t c =
        static_cast<std::uint32_t>(cell_y(positions[i])) * static_cast<std::uint32_t>(nx_) +
        static_cast<std::uint32_t>(cell_x(positions[i]));
    cell_of_[i] = c;
    ++start_[c + 1];
  }
  for (std::size_t c = 0; c < n_cells; ++c) start_[c + 1] += start_[c];
  // Fill in reverse with a running end pointer, so indices stay ascending within a cell.
  for (std::size_t i = positions.size(); i-- > 0;) {
    const std::uint32_t c = cell_of_[i];
    sorted_[--start_[c + 1]] = static_cast<std::uint32_t>(i);
  }
  // After the reverse fill start_[c + 1] holds the first slot of cell c; shift back.
  for (std::size_t c = 0; c < n_cells; ++c) start_[c] = start_[c + 1];
  start_[n_cells] = static_cast<std::uint32_t>(positions.size());
}

void NeighbourLists::build(const CellList& cells, std::span<const Vec2> positions,
                           std::size_t n_query, double radius, std::size_t late_from) {
  if (cells.cell_size() < radius) {
    throw std::invalid_argument("NeighbourLists: cell size smaller than the search radius");
  }
  const double radius2 = radius * radius;
  count_.resize(n_query);
  early_.resize(n_query);
  for (;;) {
    index_.resize(n_query * stride_);
    std::size_t longest = 0;
    const std::size_t stride = stride_;
#pragma omp parallel for schedule(static) reduction(max : longest) if (n_query >= 2048)
    for (std::size_t i = 0; i < n_query; ++i) {
      const Vec2 xi = positions[i];
      const int cx = cells.cell_x(xi);
      const int cy = cells.cell_y(xi);
      const int y0 = std::max(cy - 1, 0), y1 = std::min(cy + 1, cells.n_cells_y() - 1);
      const int x0 = std::max(cx - 1, 0), x1 = std::min(cx + 1, cells.n_cells_x() - 1);
      std::uint32_t* row = index_.data() + i * stride;
      std::size_t n = 0;
      std::size_t n_early = 0;
      // Two sweeps over the 3 x 3 cells: indices below late_from first, then the rest.
      for (int part = 0; part < 2; ++part) {
        for (int y = y0; y <= y1; ++y) {
          for (int x = x0; x <= x1; ++x) {
            for (const std::uint32_t j : cells.in_cell(x, y)) {
              if (j == i || (j >= late_from) != (part == 1)) continue;
              if ((positions[j] - xi).squaredNorm() >= radius2) continue;
              if (n < stride) row[n] = j;
              ++n;
            }
          }
        }
        if (part == 0) n_early = n;
      }
      count_[i] = static_cast<std::uint32_t>(std::min(n, stride));
      early_[i] = static_cast<std::uint32_t>(std::min(n_early, stride));
      longest = std::max(longest, n);
    }
    if (longest <= stride_) return;
    stride_ = longest + longest / 4 + 4;  // rare: grow and search again
  }
}

void NeighbourLists::drop_lower_pairs(std::size_t below) {
  const std::size_t n_rows = count_.size();
  const std::size_t stride = stride_;
#pragma omp parallel for schedule(static) if (n_rows >= 2048)
  for (std::size_t i = 0; i < n_rows; ++i) {
    std::uint32_t* row = index_.data() + i * stride;
    std::size_t kept = 0;
    for (std::size_t e = 0; e < early_[i]; ++e) {
      const std::uint32_t j = row[e];
      if (j < below && j < i) continue;
      row[kept++] = j;
    }
    const std::size_t dropped = early_[i] - kept;
    for (std::size_t e = early_[i]; e < count_[i]; ++e) row[e - dropped] = row[e];
    early_[i] = static_cast<std::uint32_t>(kept);
    count_[i] -= static_cast<std::uint32_t>(dropped);
  }
}

std::size_t NeighbourLists::max_count() const {
  std::uint32_t m = 0;
  for (const auto c : count_) m = std::max(m, c);
  return m;
}

}  // namespace duet::sph
