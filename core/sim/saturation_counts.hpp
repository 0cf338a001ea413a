#pragma once

#include <cstdint>
#include <vector>

namespace thetad::sim {

// How often the actuator limits changed the input of a run, per input channel, in controller
// samples (zeros for a plant without limits).
struct SaturationCounts {
  std::vector<std::int64_t> magnitude;  // held at lower or upper
  std::vector<std::int64_t> rate;       // slowed by the rate limit
  std::int64_t samples_limited = 0;     // samples where any channel was changed

  static SaturationCounts none(int inputs) {
    return {std::vector<std::int64_t>(static_cast<std::size_t>(inputs)),
            std::vector<std::int64_t>(static_cast<std::size_t>(inputs)), 0};
  }
};

}  // namespace thetad::sim
