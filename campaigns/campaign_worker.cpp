#include "campaigns/campaign_worker.hpp"

#include <nlohmann/json.hpp>

#include "core/error.hpp"

namespace thetad {

CampaignWorker::CampaignWorker(const Campaign& campaign, bool timing) : campaign_(campaign), timing_(timing) {}

CampaignWorker::CellFlight& CampaignWorker::cell_flight(int cell, int scenario) {
  CellFlight& entry = flights_[{cell, scenario}];
  if (entry.flight) return entry;
  RunControls controls;
  controls.summary_only = campaign_.summary_only;
  controls.timing = timing_;
  const FactorValues& factors = campaign_.cells[static_cast<std::size_t>(cell)];
  try {
    apply(factors, controls);
    entry.flight = std::make_unique<Flight>(campaign_.scenarios[static_cast<std::size_t>(scenario)], controls);
  } catch (const Error& error) {
    std::string where;
    for (const auto& [name, value] : factors) where += " " + name + "=" + std::to_string(value);
    throw Error(campaign_.file.string() + ": sweep cell " + std::to_string(cell) + " (" +
                (where.empty() ? std::string("no factors") : where.substr(1)) + "): " + error.what());
  }
  entry.controllers.resize(campaign_.controllers.size());
  return entry;
}

PreparedController& CampaignWorker::controller(CellFlight& flight, int index) {
  auto& prepared = flight.controllers[static_cast<std::size_t>(index)];
  if (!prepared)
    prepared = std::make_unique<PreparedController>(flight.flight->prepare(campaign_.controllers[static_cast<std::size_t>(index)]));
  return *prepared;
}

RunRecord CampaignWorker::fly(std::int64_t index) {
  const PlannedRun run = planned_run(campaign_, index);
  CellFlight& entry = cell_flight(run.cell, run.scenario);
  PreparedController& prepared = controller(entry, run.controller);
  entry.flight->set_seed(run.seed);
  const RunResult result = entry.flight->fly(prepared);
  return make_record(run, campaign_.cells[static_cast<std::size_t>(run.cell)], result);
}

void CampaignWorker::prepare_all() {
  for (int cell = 0; cell < static_cast<int>(campaign_.cells.size()); ++cell) {
    for (int scenario = 0; scenario < static_cast<int>(campaign_.scenarios.size()); ++scenario) {
      CellFlight& entry = cell_flight(cell, scenario);
      for (int c = 0; c < static_cast<int>(campaign_.controllers.size()); ++c) controller(entry, c);
    }
  }
}

std::string CampaignWorker::provenance() {
  nlohmann::ordered_json scenarios = nlohmann::ordered_json::array();
  for (int scenario = 0; scenario < static_cast<int>(campaign_.scenarios.size()); ++scenario) {
    nlohmann::ordered_json j = to_json(cell_flight(0, scenario).flight->provenance());
    j.erase("seed");
    scenarios.push_back(std::move(j));
  }
  return scenarios.dump();
}

double CampaignWorker::duration(int cell, int scenario) { return cell_flight(cell, scenario).flight->settings().duration; }

}  // namespace thetad
