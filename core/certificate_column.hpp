#pragma once

#include <limits>

#include "core/log_column.hpp"

namespace thetad {

// A number a controller reports at every sample on how far its own answer can be trusted (the
// SDRE's CARE condition and stabilizability margin, θ–D's last-term share; docs/model.md §8.4),
// logged as a column after the disturbances' and summarized by its worst value over the run.
struct CertificateColumn {
  enum class Worst { largest, smallest };
  LogColumn column;
  Worst worst;
};

// A certificate's worst value over the controller samples of a run and the time of the first
// sample that had it; NaN for both when no sample had a value that is not NaN.
struct CertificateWorst {
  CertificateColumn certificate;
  double value = std::numeric_limits<double>::quiet_NaN();
  double t = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace thetad
