#include "campaigns/cost_estimate.hpp"

#include <algorithm>
#include <chrono>

#include "campaigns/campaign_worker.hpp"
#include "campaigns/run_plan.hpp"

namespace thetad {

CostEstimate estimate_cost(const Campaign& campaign, double pilot_seconds) {
  RunControls controls;
  controls.summary_only = campaign.summary_only;
  apply(campaign.cells.front(), controls);
  CostEstimate estimate;
  {
    Flight probe(campaign.scenarios.front(), controls);
    controls.duration = std::min(pilot_seconds, probe.settings().duration);
  }
  controls.seed = draw_seed(campaign.base_seed, 0);
  const Flight pilot(campaign.scenarios.front(), controls);
  for (const ControllerSpec& spec : campaign.controllers) {
    PreparedController prepared = pilot.prepare(spec);
    const auto start = std::chrono::steady_clock::now();
    pilot.fly(prepared);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    estimate.pilots.push_back({spec.label, wall / *controls.duration});
  }
  CampaignWorker worker(campaign, false);
  for (int cell = 0; cell < static_cast<int>(campaign.cells.size()); ++cell) {
    for (int scenario = 0; scenario < static_cast<int>(campaign.scenarios.size()); ++scenario) {
      const double duration = worker.duration(cell, scenario);
      for (const auto& pilot_run : estimate.pilots)
        estimate.core_seconds += campaign.draws * duration * pilot_run.wall_per_simulated_second;
    }
  }
  return estimate;
}

}  // namespace thetad
