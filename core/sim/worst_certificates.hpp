#pragma once

#include <cstddef>
#include <vector>

#include "core/controller_column.hpp"

namespace thetad::sim {

// The worst value of each certificate among a law's log columns over the samples of a run, and
// when it came (RunSummary::certificates). NaN values are skipped: a certificate that could not be
// evaluated at a sample says nothing there.
class WorstCertificates {
 public:
  explicit WorstCertificates(const std::vector<ControllerColumn>& columns);

  // The values of one sample at time t, one per column (certificates or not), in their order.
  // Allocates nothing.
  void add(double t, const std::vector<double>& values);
  const std::vector<CertificateWorst>& worst() const { return worst_; }

 private:
  std::vector<CertificateWorst> worst_;
  std::vector<std::size_t> index_;  // of worst_[i]'s column among the law's
};

}  // namespace thetad::sim
