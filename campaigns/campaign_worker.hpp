#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "campaigns/campaign.hpp"
#include "campaigns/run_record.hpp"
#include "experiment/flight.hpp"

namespace thetad {

// Flies a campaign's runs by index, one at a time (one worker per thread or MPI rank). The flight
// of a (cell, scenario) and its controllers are built on first use and reused for every draw: a
// run resets its controller and reseeds the flight, so what a run computes depends on its index
// alone, never on which worker flew what before it.
class CampaignWorker {
 public:
  // `timing`: false flies without wall-clock figures (--no-timing).
  CampaignWorker(const Campaign& campaign, bool timing);

  RunRecord fly(std::int64_t index);

  // Builds every (cell, scenario) flight and every controller once: a bad factor value (a dt that
  // does not divide the controller period) or controller settings fail here, before anything flies.
  void prepare_all();

  // What produces the runs, per scenario (JSON list): the experiment library's provenance of each
  // scenario's flight (build, scenario file and SHA-256, model) without the seed, which is per run.
  std::string provenance();

  // The simulated duration of the runs of `cell` and `scenario` (s).
  double duration(int cell, int scenario);

 private:
  struct CellFlight {
    std::unique_ptr<Flight> flight;
    std::vector<std::unique_ptr<PreparedController>> controllers;  // built on first use
  };
  CellFlight& cell_flight(int cell, int scenario);
  PreparedController& controller(CellFlight& flight, int index);

  const Campaign& campaign_;
  bool timing_;
  std::map<std::pair<int, int>, CellFlight> flights_;
};

}  // namespace thetad
