#include "tuning/packed_series.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "core/parallel.hpp"

namespace thetad::tuning {

namespace {

// Samples per chunk of the parallel loops: small enough to balance two workers, large enough
// that the per-chunk overhead is nothing next to 128 eigenvalue problems.
constexpr std::size_t kChunk = 128;

}  // namespace

void pack_lower(const Eigen::MatrixXd& matrix, double* packed) {
  for (Eigen::Index c = 0; c < matrix.cols(); ++c)
    for (Eigen::Index r = c; r < matrix.rows(); ++r) *packed++ = matrix(r, c);
}

void unpack_lower(const double* packed, Eigen::MatrixXd& matrix) {
  for (Eigen::Index c = 0; c < matrix.cols(); ++c)
    for (Eigen::Index r = c; r < matrix.rows(); ++r) matrix(r, c) = *packed++;
}

PackedSeries::PackedSeries(const ThetaDController& controller, const TuningRecord& record, int threads)
    : terms_(controller.settings().terms), threads_(std::max(1, threads)), n_(controller.T0().rows()) {
  const Eigen::Index m = controller.g0().cols();
  if (record.states.rows() != n_ || record.inputs.rows() != m)
    throw Error("tuning: the record has " + std::to_string(record.states.rows()) + " states and " +
                std::to_string(record.inputs.rows()) + " inputs, the controller's plant " + std::to_string(n_) +
                " and " + std::to_string(m));
  if (record.size() == 0) throw Error("tuning: the record has no samples");
  const auto K = static_cast<std::size_t>(record.size());
  for (double t : record.time) elapsed_.push_back(t - controller.start_time());

  std::vector<ThetaDController> copies(static_cast<std::size_t>(threads_), controller);
  powers_ = copies[0].series_expansion(record.states.col(0), record.inputs.col(0)).powers;
  const std::size_t pieces = powers_.size();
  packed_.resize(K * pieces * packed_size());
  for_each_chunk(K, kChunk, threads_, [&](int worker, std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      const auto column = static_cast<Eigen::Index>(k);
      const SeriesExpansion expansion =
          copies[static_cast<std::size_t>(worker)].series_expansion(record.states.col(column), record.inputs.col(column));
      for (std::size_t j = 0; j < pieces; ++j) pack_lower(expansion.pieces[j], packed_.data() + (k * pieces + j) * packed_size());
    }
  });
}

void PackedSeries::for_each_chunk_sum(
    const Eigen::VectorXd& k, const Eigen::VectorXd& l,
    const std::function<void(int, std::size_t, Eigen::Index, const double*)>& visit) const {
  if (k.size() != parameters() || l.size() != parameters())
    throw Error("tuning: k and l need " + std::to_string(parameters()) + " entries each");
  const std::size_t pieces = powers_.size(), size = packed_size();
  SeriesExpansion monomials;
  monomials.powers = powers_;
  for_each_chunk(elapsed_.size(), kChunk, threads_, [&](int worker, std::size_t chunk, std::size_t begin, std::size_t end) {
    std::vector<double> sum(size);
    Eigen::VectorXd e(parameters());
    std::vector<double> coefficient(pieces);
    for (std::size_t sample = begin; sample < end; ++sample) {
      for (Eigen::Index i = 0; i < e.size(); ++i) e[i] = perturbation_factor(k[i], l[i], elapsed_[sample]);
      for (std::size_t j = 0; j < pieces; ++j) coefficient[j] = monomials.coefficient(j, e);
      const double* piece = packed_.data() + sample * pieces * size;
      for (std::size_t index = 0; index < size; ++index) {
        double value = 0.0;
        for (std::size_t j = 0; j < pieces; ++j) value += coefficient[j] * piece[j * size + index];
        sum[index] = value;
      }
      visit(worker, chunk, static_cast<Eigen::Index>(sample), sum.data());
    }
  });
}

void PackedSeries::for_each_sum(const Eigen::VectorXd& k, const Eigen::VectorXd& l,
                                const std::function<void(int, Eigen::Index, const double*)>& visit) const {
  for_each_chunk_sum(k, l, [&](int worker, std::size_t, Eigen::Index sample, const double* packed) { visit(worker, sample, packed); });
}

double PackedSeries::sum_over_samples(const Eigen::VectorXd& k, const Eigen::VectorXd& l,
                                      const std::function<double(int, Eigen::Index, const double*)>& term) const {
  std::vector<double> partial((elapsed_.size() + kChunk - 1) / kChunk, 0.0);
  for_each_chunk_sum(k, l, [&](int worker, std::size_t chunk, Eigen::Index sample, const double* packed) {
    partial[chunk] += term(worker, sample, packed);
  });
  double sum = 0.0;
  for (double value : partial) sum += value;
  return sum;
}

}  // namespace thetad::tuning
