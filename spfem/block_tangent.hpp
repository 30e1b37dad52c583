#pragma once
// The implicit SPFEM tangent as 2 x 2 node blocks on a pattern fixed for one increment. Every term
// of row k (material and spin, geometric, stiffness stabilisation, layer and wall-strip rows)
// couples two nodes l, m of row k's columns, so the node pattern is the union of the rows' column
// pairs and the block of (l, m) in row k is found by a table built once per increment, not by a
// sort of triplets per Newton iteration (setFromTriplets of about a million triplets was as
// costly as UMFPACK's factorisation of the footing's tangent). Threads add into their own copy
// of the blocks, summed before the free dofs (DofMap's directions) are written into a
// compressed-column matrix whose structure is kept while the DofMap's is unchanged.

#include <cstdint>
#include <vector>

#include <Eigen/Sparse>

#include "common/tensor.hpp"
#include "spfem/node_constraints.hpp"
#include "spfem/smoothing.hpp"

namespace duet::spfem {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

class BlockTangent {
 public:
  /// The node pattern of `cells`' rows (offset/column); `threads` copies of the blocks.
  void build(const SmoothingCells& cells, int threads);
  bool built() const { return !offset_.empty(); }

  /// Sets every thread's blocks to zero.
  void zero();

  /// For row k: the block index of (column[begin + i], column[begin + j]) at [i * length + j].
  const std::int32_t* row_pairs(std::size_t k) const {
    return row_pair_.data() + row_pair_offset_[k];
  }
  /// The blocks thread `t` adds into (dF_l / du_m, 2 x 2).
  Mat2* blocks(int t) { return parts_[std::size_t(t)].data(); }

  /// Adds d[l] times the identity to block (l, l) of every node in some row.
  void add_to_diagonal(const std::vector<double>& d);

  /// Sums the threads' blocks and writes da^T B(l, m) db for the free dofs a of l and b of m.
  void write_free_dofs(const DofMap& dofs, SparseMatrix& out);

 private:
  std::vector<std::int32_t> offset_;           // n_nodes + 1 block-row starts
  std::vector<std::int32_t> column_;           // node m of each block, sorted within a row
  std::vector<std::int32_t> transpose_;        // per block (l, m): the index of block (m, l)
  std::vector<std::int32_t> diagonal_;         // per node: its block (l, l), -1 in no row
  std::vector<std::int32_t> row_pair_offset_;  // n_nodes + 1 starts into row_pair_
  std::vector<std::int32_t> row_pair_;
  std::vector<std::vector<Mat2>> parts_;    // per thread
  std::vector<std::int32_t> csc_first_;     // the DofMap.first the matrix structure was built for
  std::vector<std::int32_t> csc_block_;     // per nonzero: its block (l, m)
  std::vector<std::int32_t> csc_row_node_;  // per nonzero: l (its row dof's node)
};

}  // namespace duet::spfem
