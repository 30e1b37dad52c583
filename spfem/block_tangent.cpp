#include "spfem/block_tangent.hpp"

#include <algorithm>

namespace duet::spfem {

namespace {

std::int32_t find_block(const std::vector<std::int32_t>& offset,
                        const std::vector<std::int32_t>& column, std::int32_t l, std::int32_t m) {
  const auto begin = column.begin() + offset[std::size_t(l)];
  const auto end = column.begin() + offset[std::size_t(l) + 1];
  return static_cast<std::int32_t>(std::lower_bound(begin, end, m) - column.begin());
}

}  // namespace

void BlockTangent::build(const SmoothingCells& cells, int threads) {
  const std::size_t n = cells.area.size();
  std::vector<std::vector<std::int32_t>> coupled(n);
  for (std::size_t k = 0; k < n; ++k) {
    if (!(cells.area[k] > 0.0)) continue;
    const std::int32_t begin = cells.offset[k];
    const std::int32_t end = cells.offset[k + 1];
    for (std::int32_t i = begin; i < end; ++i) {
      std::vector<std::int32_t>& row = coupled[std::size_t(cells.column[std::size_t(i)])];
      for (std::int32_t j = begin; j < end; ++j) row.push_back(cells.column[std::size_t(j)]);
    }
  }
  offset_.assign(n + 1, 0);
  column_.clear();
  for (std::size_t l = 0; l < n; ++l) {
    std::vector<std::int32_t>& row = coupled[l];
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    column_.insert(column_.end(), row.begin(), row.end());
    offset_[l + 1] = static_cast<std::int32_t>(column_.size());
  }
  transpose_.resize(column_.size());
  for (std::size_t l = 0; l < n; ++l) {
    for (std::int32_t p = offset_[l]; p < offset_[l + 1]; ++p) {
      transpose_[std::size_t(p)] =
          find_block(offset_, column_, column_[std::size_t(p)], static_cast<std::int32_t>(l));
    }
  }
  diagonal_.assign(n, -1);
  for (std::size_t l = 0; l < n; ++l) {
    const auto l32 = static_cast<std::int32_t>(l);
    const std::int32_t p = find_block(offset_, column_, l32, l32);
    if (p < offset_[l + 1] && column_[std::size_t(p)] == l32) diagonal_[l] = p;
  }
  row_pair_offset_.assign(n + 1, 0);
  row_pair_.clear();
  for (std::size_t k = 0; k < n; ++k) {
    if (cells.area[k] > 0.0) {
      const std::int32_t begin = cells.offset[k];
      const std::int32_t end = cells.offset[k + 1];
      for (std::int32_t i = begin; i < end; ++i) {
        for (std::int32_t j = begin; j < end; ++j) {
          row_pair_.push_back(find_block(offset_, column_, cells.column[std::size_t(i)],
                                         cells.column[std::size_t(j)]));
        }
      }
    }
    row_pair_offset_[k + 1] = static_cast<std::int32_t>(row_pair_.size());
  }
  parts_.assign(std::size_t(std::max(threads, 1)), std::vector<Mat2>(column_.size()));
  csc_first_.clear();  // a new pattern: the matrix structure is rebuilt
}

void BlockTangent::zero() {
  for (std::vector<Mat2>& part : parts_) std::fill(part.begin(), part.end(), Mat2::Zero());
}

void BlockTangent::add_to_diagonal(const std::vector<double>& d) {
  for (std::size_t l = 0; l < diagonal_.size() && l < d.size(); ++l) {
    if (diagonal_[l] >= 0) parts_[0][std::size_t(diagonal_[l])].diagonal().array() += d[l];
  }
}

void BlockTangent::write_free_dofs(const DofMap& dofs, SparseMatrix& out) {
  std::vector<Mat2>& sum = parts_[0];
  for (std::size_t t = 1; t < parts_.size(); ++t) {
    for (std::size_t p = 0; p < sum.size(); ++p) sum[p] += parts_[t][p];
  }
  const std::size_t n = offset_.size() - 1;
  const auto n_free = static_cast<int>(dofs.n_free());
  if (csc_first_ != dofs.first || out.rows() != n_free || out.cols() != n_free) {
    // Column b (node m, in node order) holds the free dofs a of every l coupled to m, in node
    // order: row indices ascend as compressed-column storage requires.
    std::vector<int> outer(std::size_t(n_free) + 1, 0);
    std::vector<int> inner;
    csc_block_.clear();
    for (std::size_t m = 0; m < n; ++m) {
      for (std::int32_t b = dofs.first[m]; b < dofs.first[m + 1]; ++b) {
        for (std::int32_t p = offset_[m]; p < offset_[m + 1]; ++p) {
          const auto l = std::size_t(column_[std::size_t(p)]);
          for (std::int32_t a = dofs.first[l]; a < dofs.first[l + 1]; ++a) {
            inner.push_back(a);
            csc_block_.push_back(transpose_[std::size_t(p)]);  // block (l, m)
          }
        }
        outer[std::size_t(b) + 1] = static_cast<int>(inner.size());
      }
    }
    out.resize(n_free, n_free);
    out.resizeNonZeros(static_cast<Eigen::Index>(inner.size()));
    std::copy(outer.begin(), outer.end(), out.outerIndexPtr());
    std::copy(inner.begin(), inner.end(), out.innerIndexPtr());
    csc_first_ = dofs.first;
  }
  double* value = out.valuePtr();
  const int* outer = out.outerIndexPtr();
  const int* inner = out.innerIndexPtr();
  for (int b = 0; b < n_free; ++b) {
    const Vec2& db = dofs.direction[std::size_t(b)];
    for (int p = outer[b]; p < outer[b + 1]; ++p) {
      const Vec2 column = sum[std::size_t(csc_block_[std::size_t(p)])] * db;
      value[p] = dofs.direction[std::size_t(inner[p])].dot(column);
    }
  }
}

}  // namespace duet::spfem
