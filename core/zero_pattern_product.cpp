#include "core/zero_pattern_product.hpp"

#include <algorithm>
#include <map>
#include <string>
#include <utility>

#include "core/error.hpp"

namespace thetad {

namespace {

std::vector<char> zero_pattern(const Eigen::Ref<const Eigen::MatrixXd>& M, Eigen::Index row) {
  std::vector<char> nonzero(static_cast<std::size_t>(M.cols()));
  for (Eigen::Index j = 0; j < M.cols(); ++j) nonzero[static_cast<std::size_t>(j)] = M(row, j) != 0.0;
  return nonzero;
}

}  // namespace

ZeroPatternProduct::ZeroPatternProduct(const Eigen::Ref<const Eigen::MatrixXd>& M, Kernel kernel)
    : kernel_(kernel), rows_(M.rows()), cols_(M.cols()), gathered_(M.cols()) {
  Eigen::Index first = 0, size = 0;
  while (first < rows_) {
    const std::vector<char> pattern = zero_pattern(M, first);
    Eigen::Index end = first + 1;
    while (end < rows_ && zero_pattern(M, end) == pattern) ++end;
    Block block;
    block.first_row = first;
    block.rows = end - first;
    block.padded_rows = kernel == Kernel::eigen ? block.rows : (block.rows + kPanel - 1) / kPanel * kPanel;
    block.offset = size;
    for (Eigen::Index j = 0; j < cols_; ++j)
      if (pattern[static_cast<std::size_t>(j)]) block.columns.push_back(j);
    const auto count = static_cast<Eigen::Index>(block.columns.size());
    // Each block starts a whole number of panels from the first (64-byte aligned where Eigen
    // allocates so: AVX-512).
    size += (block.padded_rows * count + kPanel - 1) / kPanel * kPanel;
    stored_entries_ += block.rows * count;
    blocks_.push_back(std::move(block));
    first = end;
  }
  values_ = Eigen::VectorXd::Zero(size);
  for (const Block& block : blocks_) {
    const auto count = static_cast<Eigen::Index>(block.columns.size());
    for (Eigen::Index row = 0; row < block.padded_rows;) {
      // Eigen's product reads the block as one column-major matrix: one panel the height of it.
      const Eigen::Index height = kernel == Kernel::eigen ? block.rows : panel_height(block, row);
      const Eigen::Index kept = std::min(height, block.rows - row);
      for (Eigen::Index k = 0; k < count; ++k)
        values_.segment(block.offset + row * count + k * height, kept) =
            M.col(block.columns[static_cast<std::size_t>(k)]).segment(block.first_row + row, kept);
      row += height;
    }
  }
}

std::vector<Eigen::Index> ZeroPatternProduct::group_rows_by_pattern(const Eigen::Ref<const Eigen::MatrixXd>& M) {
  std::map<std::vector<char>, Eigen::Index> class_of;  // pattern -> rank of its first appearance
  std::vector<std::pair<Eigen::Index, Eigen::Index>> keyed;  // (class, row)
  for (Eigen::Index i = 0; i < M.rows(); ++i) {
    const auto found = class_of.emplace(zero_pattern(M, i), static_cast<Eigen::Index>(class_of.size())).first;
    keyed.emplace_back(found->second, i);
  }
  std::stable_sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Eigen::Index> order;
  for (const auto& [pattern_class, row] : keyed) order.push_back(row);
  return order;
}

template <Eigen::Index Rows>
void ZeroPatternProduct::apply_panel(const Block& block, Eigen::Index row, double alpha,
                                     Eigen::Ref<Eigen::VectorXd> y) const {
  using Panel = Eigen::Matrix<double, Rows, 1>;
  // Two sums over alternate columns: one alone would wait on the latency of each multiply-add.
  Panel even = Panel::Zero(), odd = Panel::Zero();
  const Eigen::Index count = static_cast<Eigen::Index>(block.columns.size());
  const double* column = values_.data() + block.offset + row * count;
  Eigen::Index k = 0;
  for (; k + 1 < count; k += 2, column += 2 * Rows) {
    even.noalias() += Eigen::Map<const Panel>(column) * gathered_[k];
    odd.noalias() += Eigen::Map<const Panel>(column + Rows) * gathered_[k + 1];
  }
  if (k < count) even.noalias() += Eigen::Map<const Panel>(column) * gathered_[k];
  even += odd;
  const Eigen::Index kept = std::min(Rows, block.rows - row);  // the padding stays out of y
  y.segment(block.first_row + row, kept) = alpha * even.head(kept);
}

void ZeroPatternProduct::apply(double alpha, const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> y) {
  if (x.size() != cols_ || y.size() != rows_)
    throw Error("ZeroPatternProduct: a " + std::to_string(rows_) + "x" + std::to_string(cols_) + " product got x of " +
                std::to_string(x.size()) + " and y of " + std::to_string(y.size()) + " entries");
  for (const Block& block : blocks_) {
    const auto count = static_cast<Eigen::Index>(block.columns.size());
    if (count == 0) {  // rows that are all zero: nothing stored to read
      y.segment(block.first_row, block.rows).setZero();
      continue;
    }
    for (Eigen::Index k = 0; k < count; ++k) gathered_[k] = x[block.columns[static_cast<std::size_t>(k)]];
    if (kernel_ == Kernel::eigen) {
      const Eigen::Map<const Eigen::MatrixXd> values(values_.data() + block.offset, block.rows, count);
      y.segment(block.first_row, block.rows).noalias() = alpha * (values * gathered_.head(count));
      continue;
    }
    for (Eigen::Index row = 0; row < block.padded_rows; row += panel_height(block, row)) {
      if (panel_height(block, row) == 2 * kPanel) apply_panel<2 * kPanel>(block, row, alpha, y);
      else apply_panel<kPanel>(block, row, alpha, y);
    }
  }
}

}  // namespace thetad
