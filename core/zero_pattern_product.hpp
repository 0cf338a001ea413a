#pragma once

// y = α M x for a dense matrix M with many entries that are exactly zero in a few recurring row
// patterns, as the packed inverse of a Lyapunov operator whose Ac is reducible (whole blocks of
// the inverse are zero; θ–D's rows of it for the helicopter, docs/performance.md). Rows that share
// a pattern form one dense block over their nonzero columns, so a product reads and multiplies
// only those (and, with the register panels, the zeros that pad a block to whole panels). For
// finite x the result is the dense product's up to the order of the sums: only entries that are
// exactly 0.0 are left out (0 · Inf would be NaN). Without zeros: one block.

#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace thetad {

class ZeroPatternProduct {
 public:
  // How a block is multiplied: by Eigen's matrix–vector product, or a panel of rows at a time,
  // accumulated in registers over two streams of columns. Same products, summed in another order.
  enum class Kernel { eigen, register_panels };
  // The faster for this build, as measured on the θ–D step (docs/performance.md): the panels
  // where Eigen vectorises with AVX-512, Eigen's product with SSE2 (where 16-row panels run out of
  // registers). AVX2 was not measured and keeps Eigen's.
#ifdef EIGEN_VECTORIZE_AVX512
  static constexpr Kernel kFastest = Kernel::register_panels;
#else
  static constexpr Kernel kFastest = Kernel::eigen;
#endif

  ZeroPatternProduct() = default;
  // Blocks of consecutive rows of M with the same zero pattern (sort the rows with
  // group_rows_by_pattern() first, so that each pattern is one block).
  explicit ZeroPatternProduct(const Eigen::Ref<const Eigen::MatrixXd>& M, Kernel kernel = kFastest);

  // A stable order of M's rows that brings the rows of each zero pattern together, the patterns
  // in the order of their first row: order[k] is the row of M that goes k-th.
  static std::vector<Eigen::Index> group_rows_by_pattern(const Eigen::Ref<const Eigen::MatrixXd>& M);

  // y = alpha M x. Allocates nothing (not thread-safe per object: a gather buffer).
  void apply(double alpha, const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> y);

  Eigen::Index rows() const { return rows_; }
  Eigen::Index cols() const { return cols_; }
  // The entries of M's blocks: the sum over blocks of rows × nonzero columns (the panels also
  // multiply the padding, up to 7 rows a block).
  Eigen::Index stored_entries() const { return stored_entries_; }

 private:
  // For Eigen's product a block's values are stored column by column. For the panels its rows are
  // padded by zeros to a multiple of kPanel and cut into panels of 2·kPanel rows (the last one
  // kPanel if that is what is left), each stored column by column after the one above it, so
  // that a panel's product reads one contiguous stream however tall the block.
  static constexpr Eigen::Index kPanel = 8;
  struct Block {
    Eigen::Index first_row = 0, rows = 0, padded_rows = 0, offset = 0;  // offset into values_
    std::vector<Eigen::Index> columns;  // the nonzero columns of its rows, ascending
  };
  // The height of the panel at `row` of a block: 2·kPanel while that much is left, then kPanel.
  static Eigen::Index panel_height(const Block& block, Eigen::Index row) {
    return block.padded_rows - row >= 2 * kPanel ? 2 * kPanel : kPanel;
  }
  // y on rows [row, row + Rows) of a block (clipped to it) from gathered_.
  template <Eigen::Index Rows>
  void apply_panel(const Block& block, Eigen::Index row, double alpha, Eigen::Ref<Eigen::VectorXd> y) const;
  Kernel kernel_ = kFastest;
  std::vector<Block> blocks_;
  Eigen::VectorXd values_;  // the blocks' M(rows, columns), padded, one after the other
  Eigen::Index rows_ = 0, cols_ = 0, stored_entries_ = 0;
  Eigen::VectorXd gathered_;  // x on a block's columns
};

}  // namespace thetad
