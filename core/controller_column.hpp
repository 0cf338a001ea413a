#pragma once

#include <cstddef>
#include <limits>

#include "core/log_column.hpp"

namespace thetad {

// A column that a controller writes into the run log at every sample, after the disturbances'
// (ControlLaw::log_columns): a number of its own state or work (an integrator, a gain, a count), or
// a certificate of how far its answer can be trusted (the SDRE's CARE condition and
// stabilizability margin, θ–D's last-term share; docs/model.md §8.4), which the run also
// summarizes by its worst value.
struct ControllerColumn {
  enum class Worst { none, largest, smallest };
  LogColumn column;
  Worst worst = Worst::none;  // none: logged only, not a certificate
  bool certificate() const { return worst != Worst::none; }
};

// A certificate's worst value over the controller samples of a run and the time of the first
// sample that had it; NaN for both when no sample had a value that is not NaN.
struct CertificateWorst {
  ControllerColumn certificate;
  double value = std::numeric_limits<double>::quiet_NaN();
  double t = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace thetad
