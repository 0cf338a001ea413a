#include "core/zero_pattern_product.hpp"

#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "tests/heap_counter.hpp"

namespace thetad {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

// 40 rows in 4 interleaved zero patterns over 30 columns (one of them: the whole row zero), the
// nonzeros drawn at random: the shape of the rows of a reducible Lyapunov inverse.
MatrixXd patterned_matrix() {
  std::mt19937_64 generator(3);
  std::normal_distribution<double> normal;
  MatrixXd M = MatrixXd::Zero(40, 30);
  for (Eigen::Index i = 0; i < M.rows(); ++i)
    for (Eigen::Index j = 0; j < M.cols(); ++j) {
      const bool nonzero = i % 4 == 0 ? j < 20 : i % 4 == 1 ? j % 3 == 0 : i % 4 == 2 ? j >= 12 : false;
      if (nonzero) M(i, j) = normal(generator);
    }
  return M;
}

MatrixXd rows_in_order(const MatrixXd& M, const std::vector<Eigen::Index>& order) {
  MatrixXd sorted(M.rows(), M.cols());
  for (std::size_t k = 0; k < order.size(); ++k) sorted.row(static_cast<Eigen::Index>(k)) = M.row(order[k]);
  return sorted;
}

TEST(ZeroPatternProduct, GroupsTheRowsOfAPatternInTheOrderOfTheirFirstRow) {
  const std::vector<Eigen::Index> order = ZeroPatternProduct::group_rows_by_pattern(patterned_matrix());
  ASSERT_EQ(order.size(), 40u);
  for (std::size_t k = 0; k < order.size(); ++k) {
    EXPECT_EQ(order[k] % 4, static_cast<Eigen::Index>(k / 10)) << k;           // pattern by pattern
    EXPECT_EQ(order[k] / 4, static_cast<Eigen::Index>(k % 10)) << k;           // stable within one
  }
}

// Each test runs with both kernels, whichever this build picks by default.
class ZeroPatternKernels : public ::testing::TestWithParam<ZeroPatternProduct::Kernel> {};

TEST_P(ZeroPatternKernels, MultipliesOnlyTheNonzerosAndGivesTheDenseProduct) {
  const MatrixXd M = patterned_matrix();
  const MatrixXd sorted = rows_in_order(M, ZeroPatternProduct::group_rows_by_pattern(M));
  ZeroPatternProduct product(sorted, GetParam());
  EXPECT_EQ(product.rows(), 40);
  EXPECT_EQ(product.cols(), 30);
  EXPECT_EQ(product.stored_entries(), 10 * 20 + 10 * 10 + 10 * 18);  // the zero rows store nothing
  const VectorXd x = VectorXd::LinSpaced(30, -1.0, 2.0);
  VectorXd y = VectorXd::Constant(40, 7.0);  // every entry written, the zero rows too
  product.apply(-0.5, x, y);
  const VectorXd expected = -0.5 * (sorted * x);
  EXPECT_LE((y - expected).cwiseAbs().maxCoeff(), 1e-15 * expected.cwiseAbs().maxCoeff());
  EXPECT_EQ(y.tail(10), VectorXd::Zero(10));
}

TEST_P(ZeroPatternKernels, AMatrixWithoutZerosIsOneDenseBlock) {
  const MatrixXd M = MatrixXd::Random(7, 5);
  ZeroPatternProduct product(M, GetParam());
  EXPECT_EQ(product.stored_entries(), 35);
  const VectorXd x = VectorXd::Random(5);
  VectorXd y(7);
  product.apply(2.0, x, y);
  EXPECT_LE((y - 2.0 * M * x).norm(), 1e-14 * (M * x).norm());
}

// Blocks of 37 rows (two 16-row panels and an 8-row one, the last clipped), 1 row, 16 and 8 rows
// (whole panels) and 17 rows, over odd and even numbers of columns (the panels take columns two
// at a time), one a single column. y is a segment between guard entries that must stay as they
// were: padding written out of a block would show there or in the next block.
TEST_P(ZeroPatternKernels, BlocksOfAnyHeightAndWidthGiveTheDenseProduct) {
  std::mt19937_64 generator(5);
  std::normal_distribution<double> normal;
  MatrixXd M = MatrixXd::Zero(79, 15);
  for (Eigen::Index i = 0; i < M.rows(); ++i)
    for (Eigen::Index j = 0; j < M.cols(); ++j) {
      const bool nonzero = i < 37   ? j % 2 == 1
                           : i == 37 ? j == 4
                           : i < 54  ? j < 14
                           : i < 62  ? j % 3 == 0
                                     : true;
      if (nonzero) M(i, j) = normal(generator);
    }
  ZeroPatternProduct product(M, GetParam());
  EXPECT_EQ(product.stored_entries(), 37 * 7 + 1 + 16 * 14 + 8 * 5 + 17 * 15);
  const VectorXd x = VectorXd::LinSpaced(15, 3.0, -2.0);
  VectorXd guarded = VectorXd::Constant(79 + 16, 7.0);
  product.apply(1.5, x, guarded.segment(8, 79));
  const VectorXd expected = 1.5 * (M * x);
  EXPECT_LE((guarded.segment(8, 79) - expected).cwiseAbs().maxCoeff(), 1e-14 * expected.cwiseAbs().maxCoeff());
  EXPECT_EQ(guarded.head(8), VectorXd::Constant(8, 7.0));
  EXPECT_EQ(guarded.tail(8), VectorXd::Constant(8, 7.0));
}

// No nonzero column at all (T1's basis when no coefficient varies has none): zeros.
TEST_P(ZeroPatternKernels, AMatrixOfZerosOrWithoutColumnsGivesZeros) {
  for (const MatrixXd& M : {MatrixXd(MatrixXd::Zero(40, 5)), MatrixXd(171, 0)}) {
    ZeroPatternProduct product(M, GetParam());
    EXPECT_EQ(product.stored_entries(), 0);
    VectorXd y = VectorXd::Constant(M.rows(), 7.0);
    product.apply(1.0, VectorXd::Ones(M.cols()), y);
    EXPECT_EQ(y, VectorXd::Zero(M.rows()));
  }
}

TEST_P(ZeroPatternKernels, AllocatesNothingPerProductAndRefusesWrongSizes) {
  const MatrixXd M = patterned_matrix();
  ZeroPatternProduct product(rows_in_order(M, ZeroPatternProduct::group_rows_by_pattern(M)), GetParam());
  const VectorXd x = VectorXd::Ones(30);
  VectorXd y(40);
  const long allocations = testing::heap_allocations_during([&] { product.apply(1.0, x, y); });
  if (allocations < 0) GTEST_SKIP() << "malloc cannot be interposed in this build (AddressSanitizer)";
  EXPECT_EQ(allocations, 0);
  VectorXd short_y(39);
  EXPECT_THROW(product.apply(1.0, x, short_y), Error);
}

INSTANTIATE_TEST_SUITE_P(Kernels, ZeroPatternKernels,
                         ::testing::Values(ZeroPatternProduct::Kernel::eigen, ZeroPatternProduct::Kernel::register_panels),
                         [](const ::testing::TestParamInfo<ZeroPatternProduct::Kernel>& info) {
                           return info.param == ZeroPatternProduct::Kernel::eigen ? std::string("eigen")
                                                                                   : std::string("register_panels");
                         });

}  // namespace
}  // namespace thetad
