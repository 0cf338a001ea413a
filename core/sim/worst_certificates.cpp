#include "core/sim/worst_certificates.hpp"

#include <cmath>

namespace thetad::sim {

WorstCertificates::WorstCertificates(const std::vector<ControllerColumn>& columns) {
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (!columns[i].certificate()) continue;
    worst_.push_back({columns[i]});
    index_.push_back(i);
  }
}

void WorstCertificates::add(double t, const std::vector<double>& values) {
  for (std::size_t i = 0; i < worst_.size(); ++i) {
    const double value = values[index_[i]];
    CertificateWorst& worst = worst_[i];
    if (std::isnan(value)) continue;
    const bool worse = worst.certificate.worst == ControllerColumn::Worst::largest ? value > worst.value
                                                                                    : value < worst.value;
    if (std::isnan(worst.value) || worse) {
      worst.value = value;
      worst.t = t;
    }
  }
}

}  // namespace thetad::sim
