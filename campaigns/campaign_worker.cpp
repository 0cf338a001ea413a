#include "campaigns/campaign_worker.hpp"

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "experiment/run_files.hpp"

namespace thetad {

CampaignWorker::CampaignWorker(const Campaign& campaign, bool timing, std::optional<KeptLogs> logs)
    : campaign_(campaign), timing_(timing), logs_(std::move(logs)) {}

Flight& CampaignWorker::flight(int cell, int scenario) {
  std::unique_ptr<Flight>& entry = flights_[{cell, scenario}];
  if (entry) return *entry;
  RunControls controls;
  controls.summary_only = campaign_.summary_only;
  controls.timing = timing_;
  const FactorValues& factors = campaign_.cells[static_cast<std::size_t>(cell)];
  try {
    apply(factors, controls);
    entry = std::make_unique<Flight>(campaign_.scenarios[static_cast<std::size_t>(scenario)], controls);
  } catch (const Error& error) {
    std::string where;
    for (const auto& [name, value] : factors) where += " " + name + "=" + std::to_string(value);
    throw Error(campaign_.file.string() + ": sweep cell " + std::to_string(cell) + " (" +
                (where.empty() ? std::string("no factors") : where.substr(1)) + "): " + error.what());
  }
  return *entry;
}

PreparedController& CampaignWorker::controller(const Flight& flight, int scenario, int index) {
  const Eigen::VectorXd& x0 = flight.initial_state();
  DesignKey key{scenario, std::vector<double>(x0.data(), x0.data() + x0.size()), flight.provenance().plant_settings,
                index};
  std::unique_ptr<PreparedController>& prepared = controllers_[key];
  if (!prepared)
    prepared = std::make_unique<PreparedController>(flight.prepare(campaign_.controllers[static_cast<std::size_t>(index)]));
  return *prepared;
}

RunRecord CampaignWorker::fly(std::int64_t index, const std::function<void(double t)>& observe) {
  const PlannedRun run = planned_run(campaign_, index);
  Flight& cell = flight(run.cell, run.scenario);
  PreparedController& prepared = controller(cell, run.scenario, run.controller);
  cell.set_seed(run.seed);
  const bool kept = logs_ && logs_->keeps(run);
  const RunResult result = kept ? fly_logged(cell, prepared, index, observe) : cell.fly(prepared, nullptr, {}, observe);
  if (logs_ && !kept && !result.completed()) fly_logged(cell, prepared, index, observe);
  return make_record(run, campaign_.cells[static_cast<std::size_t>(run.cell)], result);
}

RunResult CampaignWorker::fly_logged(Flight& flight, PreparedController& prepared, std::int64_t index,
                                     const std::function<void(double t)>& observe) const {
  const bool keep_log = flight.settings().keep_log;
  flight.set_keep_log(true);
  RunResult result = flight.fly(prepared, nullptr, {}, observe);
  flight.set_keep_log(keep_log);
  write_run_files(result, logs_->run_folder(index));
  return result;
}

void CampaignWorker::prepare_all() {
  for (int cell = 0; cell < static_cast<int>(campaign_.cells.size()); ++cell) {
    for (int scenario = 0; scenario < static_cast<int>(campaign_.scenarios.size()); ++scenario) {
      const Flight& entry = flight(cell, scenario);
      for (int c = 0; c < static_cast<int>(campaign_.controllers.size()); ++c) controller(entry, scenario, c);
    }
  }
}

std::string CampaignWorker::provenance() {
  nlohmann::ordered_json scenarios = nlohmann::ordered_json::array();
  for (int scenario = 0; scenario < static_cast<int>(campaign_.scenarios.size()); ++scenario) {
    // What differs from run to run is in the runs table, not here.
    Provenance shared = flight(0, scenario).provenance();
    shared.initial_offset.reset();
    shared.initial_attitude_offset.reset();
    shared.speed_scale.reset();
    shared.course.reset();
    shared.plant_settings.clear();
    nlohmann::ordered_json j = to_json(shared);
    j.erase("seed");
    scenarios.push_back(std::move(j));
  }
  return scenarios.dump();
}

double CampaignWorker::duration(int cell, int scenario) { return flight(cell, scenario).settings().duration; }

}  // namespace thetad
