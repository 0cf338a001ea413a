#include "core/sim/worst_certificates.hpp"

#include <cmath>

namespace thetad::sim {

WorstCertificates::WorstCertificates(const std::vector<CertificateColumn>& columns) {
  worst_.reserve(columns.size());
  for (const CertificateColumn& column : columns) worst_.push_back({column});
}

void WorstCertificates::add(double t, const std::vector<double>& values) {
  for (std::size_t i = 0; i < worst_.size(); ++i) {
    const double value = values[i];
    CertificateWorst& worst = worst_[i];
    if (std::isnan(value)) continue;
    const bool worse = worst.certificate.worst == CertificateColumn::Worst::largest ? value > worst.value
                                                                                     : value < worst.value;
    if (std::isnan(worst.value) || worse) {
      worst.value = value;
      worst.t = t;
    }
  }
}

}  // namespace thetad::sim
