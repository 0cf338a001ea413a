#pragma once

// The input fixed point of the θ–D and SDRE steps, whose F and B depend on the input (the rotor
// speed follows T_mr). Standard C++ only; `thetad export` copies this file, after
// helicopter_sdc.hpp (Status, kInputs), into the header it writes.

#ifndef THETAD_ONBOARD_FIXED_POINT
#define THETAD_ONBOARD_FIXED_POINT

#include <cmath>

namespace thetad_onboard {

// The fixed point u → F(x; u), B(x; u) → u' of docs/model.md §6.2 from the applied input: `pass`
// (guess, update) → Status computes one pass's update; at most `passes` passes, stopping early when
// max|Δu| < tolerance (the library's controllers' rule). On Status::ok `guess` holds u, finite.
template <class T, class Pass>
Status fixed_point(const T* applied, int passes, T tolerance, int& iterations, T& input_change, T* guess, Pass pass) {
  T update[kInputs];
  for (int k = 0; k < kInputs; ++k) guess[k] = applied[k];
  for (iterations = 1;; ++iterations) {
    const Status status = pass(guess, update);
    if (status != Status::ok) return status;
    T change = T(0);
    for (int k = 0; k < kInputs; ++k) {
      const T difference = std::abs(update[k] - guess[k]);
      if (!(difference <= change)) change = difference;  // a NaN is the largest change
      guess[k] = update[k];
    }
    input_change = change;
    if (iterations >= passes || change < tolerance) break;
  }
  for (int k = 0; k < kInputs; ++k)
    if (!std::isfinite(guess[k])) return Status::not_finite;
  return Status::ok;
}

}  // namespace thetad_onboard

#endif  // THETAD_ONBOARD_FIXED_POINT
