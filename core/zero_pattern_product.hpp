#pragma once

// y = α M x for a dense matrix M with many entries that are exactly zero in a few recurring row
// patterns, as the packed inverse of a Lyapunov operator whose Ac is reducible (whole blocks of
// the inverse are zero; θ–D's rows of it for the helicopter, docs/performance.md). Rows that share
// a pattern form one dense block over their nonzero columns, so a product reads and multiplies
// only those. For finite x the result is the dense product's up to the order of the sums: only
// entries that are exactly 0.0 are left out (0 · Inf would be NaN). Without zeros: one block.

#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace thetad {

class ZeroPatternProduct {
 public:
  ZeroPatternProduct() = default;
  // Blocks of consecutive rows of M with the same zero pattern (sort the rows with
  // group_rows_by_pattern() first, so that each pattern is one block).
  explicit ZeroPatternProduct(const Eigen::Ref<const Eigen::MatrixXd>& M);

  // A stable order of M's rows that brings the rows of each zero pattern together, the patterns
  // in the order of their first row: order[k] is the row of M that goes k-th.
  static std::vector<Eigen::Index> group_rows_by_pattern(const Eigen::Ref<const Eigen::MatrixXd>& M);

  // y = alpha M x. Allocates nothing (not thread-safe per object: a gather buffer).
  void apply(double alpha, const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> y);

  Eigen::Index rows() const { return rows_; }
  Eigen::Index cols() const { return cols_; }
  // Entries a product multiplies: the sum over blocks of rows × nonzero columns.
  Eigen::Index stored_entries() const { return stored_entries_; }

 private:
  struct Block {
    Eigen::Index first_row = 0;
    std::vector<Eigen::Index> columns;  // the nonzero columns of its rows, ascending
    Eigen::MatrixXd values;             // M(rows, columns)
  };
  std::vector<Block> blocks_;
  Eigen::Index rows_ = 0, cols_ = 0, stored_entries_ = 0;
  Eigen::VectorXd gathered_;  // x on a block's columns
};

}  // namespace thetad
