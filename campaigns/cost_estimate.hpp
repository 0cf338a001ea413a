#pragma once

#include <string>
#include <vector>

#include "campaigns/campaign.hpp"

namespace thetad {

// What a campaign will cost, from a short timed pilot: each controller flies the first cell of the
// first scenario for `pilot_seconds` of simulated time (draw 0), and the wall time per simulated
// second is extrapolated to every run. An upper bound: a run that diverges ends early.
struct CostEstimate {
  struct Pilot {
    std::string label;
    double wall_per_simulated_second = 0.0;
  };
  std::vector<Pilot> pilots;
  double core_seconds = 0.0;  // every run, one after the other

  double wall_seconds(int workers) const { return core_seconds / workers; }
};

CostEstimate estimate_cost(const Campaign& campaign, double pilot_seconds = 1.0);

}  // namespace thetad
