#pragma once

#include "settings/run_controls.hpp"

namespace thetad::testing {

// A run of `duration` seconds, every other control as the scenario says.
inline RunControls seconds(double duration) {
  RunControls controls;
  controls.duration = duration;
  return controls;
}

}  // namespace thetad::testing
