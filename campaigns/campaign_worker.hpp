#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "campaigns/campaign.hpp"
#include "campaigns/kept_logs.hpp"
#include "campaigns/run_record.hpp"
#include "experiment/flight.hpp"

namespace thetad {

// Flies a campaign's runs by index, one at a time (one worker per thread or MPI rank). The flight
// of a (cell, scenario) and the controllers are built on first use and reused for every draw: a
// run resets its controller and reseeds the flight, so what a run computes depends on its index
// alone, never on which worker flew what before it. A controller is designed from the scenario's
// model and initial state only (ControllerContext), so the cells of a scenario that start from the
// same state (and set the same plant settings) share one (a sweep over disturbances designs the gain-scheduled LQR's table once).
class CampaignWorker {
 public:
  // `timing`: false flies without wall-clock figures (--no-timing). `logs`: the runs whose full log
  // is written (none without).
  CampaignWorker(const Campaign& campaign, bool timing, std::optional<KeptLogs> logs = std::nullopt);

  // Flies run `index` summary-only; a run whose log is kept flies with it and writes its files,
  // and one that did not complete flies again with its log (its seed flies the same run, bit for
  // bit), so that only the few runs kept pay for a log. `observe` (Flight::fly's) may throw to
  // abandon the run.
  RunRecord fly(std::int64_t index, const std::function<void(double t)>& observe = {});

  // Builds every (cell, scenario) flight and every controller once: a bad factor value (a dt that
  // does not divide the controller period) or controller settings fail here, before anything flies.
  void prepare_all();

  // What produces the runs, per scenario (JSON list): the experiment library's provenance of each
  // scenario's flight (build, scenario file and SHA-256, model) without the seed, which is per run.
  std::string provenance();

  // The simulated duration of the runs of `cell` and `scenario` (s).
  double duration(int cell, int scenario);

 private:
  Flight& flight(int cell, int scenario);
  PreparedController& controller(const Flight& flight, int scenario, int index);
  // The run `prepared` flies in `flight`, with its log, written to the folder of run `index`.
  RunResult fly_logged(Flight& flight, PreparedController& prepared, std::int64_t index,
                       const std::function<void(double t)>& observe) const;

  // A controller's design: scenario, initial state, the plant's settings the cell sets (plant.NAME)
  // and controller index.
  using DesignKey = std::tuple<int, std::vector<double>, std::map<std::string, double>, int>;

  const Campaign& campaign_;
  bool timing_;
  std::optional<KeptLogs> logs_;
  std::map<std::pair<int, int>, std::unique_ptr<Flight>> flights_;
  // Each refers to the model of the flight it was designed for (equal in every cell of a scenario
  // that sets the same plant settings).
  std::map<DesignKey, std::unique_ptr<PreparedController>> controllers_;
};

}  // namespace thetad
