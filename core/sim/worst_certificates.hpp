#pragma once

#include <vector>

#include "core/certificate_column.hpp"

namespace thetad::sim {

// The worst value of each certificate of a law over the samples of a run, and when it came
// (RunSummary::certificates). NaN values are skipped: a certificate that could not be evaluated
// at a sample says nothing there.
class WorstCertificates {
 public:
  explicit WorstCertificates(const std::vector<CertificateColumn>& columns);

  // The values of one sample at time t, in the order of the columns. Allocates nothing.
  void add(double t, const std::vector<double>& values);
  const std::vector<CertificateWorst>& worst() const { return worst_; }

 private:
  std::vector<CertificateWorst> worst_;
};

}  // namespace thetad::sim
