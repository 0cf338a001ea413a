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

ZeroPatternProduct::ZeroPatternProduct(const Eigen::Ref<const Eigen::MatrixXd>& M)
    : rows_(M.rows()), cols_(M.cols()), gathered_(M.cols()) {
  Eigen::Index first = 0;
  while (first < rows_) {
    const std::vector<char> pattern = zero_pattern(M, first);
    Eigen::Index end = first + 1;
    while (end < rows_ && zero_pattern(M, end) == pattern) ++end;
    Block block;
    block.first_row = first;
    for (Eigen::Index j = 0; j < cols_; ++j)
      if (pattern[static_cast<std::size_t>(j)]) block.columns.push_back(j);
    const auto count = static_cast<Eigen::Index>(block.columns.size());
    block.values.resize(end - first, count);
    for (Eigen::Index k = 0; k < count; ++k)
      block.values.col(k) = M.col(block.columns[static_cast<std::size_t>(k)]).segment(first, end - first);
    stored_entries_ += block.values.size();
    blocks_.push_back(std::move(block));
    first = end;
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

void ZeroPatternProduct::apply(double alpha, const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> y) {
  if (x.size() != cols_ || y.size() != rows_)
    throw Error("ZeroPatternProduct: a " + std::to_string(rows_) + "x" + std::to_string(cols_) + " product got x of " +
                std::to_string(x.size()) + " and y of " + std::to_string(y.size()) + " entries");
  for (const Block& block : blocks_) {
    const auto count = static_cast<Eigen::Index>(block.columns.size());
    for (Eigen::Index k = 0; k < count; ++k) gathered_[k] = x[block.columns[static_cast<std::size_t>(k)]];
    y.segment(block.first_row, block.values.rows()).noalias() = alpha * (block.values * gathered_.head(count));
  }
}

}  // namespace thetad
