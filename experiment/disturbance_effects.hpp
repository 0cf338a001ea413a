#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/sim/run_summary.hpp"
#include "experiment/controller_spec.hpp"
#include "experiment/progress.hpp"
#include "experiment/provenance.hpp"
#include "settings/run_controls.hpp"

namespace thetad {

// Which disturbance does what (docs/robustness.md): one scenario flown with each of its disturbance
// sources alone, all together, none, and all but one, every controller on the same seed. Each
// source draws from its own stream (docs/model.md §15) and the paper's draws are taken whether its
// sources are on or not, so a source's realization is the same in every flight it is on in. The
// effects are not additive, so no flight's figures are shares of another's.

// One source the scenario has on, and the run control that turns it off.
struct DisturbanceSource {
  std::string name;  // the run control's name: parameter_uncertainty, wind_gust, ..., servos
  bool paper;        // one of the paper's (docs/model.md §9), not of §15
  std::function<void(RunControls&)> turn_off;
};

// The paper's sources: the first ones of active_sources when all are on.
constexpr std::size_t kPaperDisturbanceSources = 6;

// The sources `settings` (a scenario as the controls fly it) has on, in a fixed order: the paper's
// (parameter_uncertainty, wind_gust, measurement_noise, actuator_noise, wind_noise,
// induced_velocity_noise), then §15's (turbulence, discrete_gusts, sensor_noise, servos). The
// actuator limits are not a disturbance: they stay as the scenario has them in every flight.
std::vector<DisturbanceSource> active_sources(const sim::SimulationSettings& settings);

// One flight of the study: its name ("none", "only S", "all", "all but S"), the sources on, and
// the controls that fly it.
struct DisturbanceCase {
  std::string name;
  std::vector<std::string> sources_on;
  RunControls controls;
};

// The cases for `sources` on top of `controls`: none, each alone, all, then all but each (with a
// single source, "all" only once, and no "all but").
std::vector<DisturbanceCase> disturbance_cases(const std::vector<DisturbanceSource>& sources,
                                               const RunControls& controls);

struct DisturbanceRun {
  std::string label;  // the controller's
  std::string case_name;
  sim::RunSummary summary;
};

struct DisturbanceEffects {
  std::string scenario;  // as given (a file or a shipped name)
  std::vector<std::string> sources;
  std::vector<DisturbanceCase> cases;
  std::vector<ControllerSpec> controllers;
  std::vector<DisturbanceRun> runs;  // case-major: every controller of cases[0], then of cases[1] ...
  Provenance provenance;             // of the flight with every source on
};

// Flies every case with every controller (summary only, no timing: the figures are reproducible bit
// for bit) on `workers` threads; `progress` shows each flight. Throws thetad::Error when the
// scenario (with `controls`) has no disturbance on, or on bad files (before anything flies).
DisturbanceEffects fly_disturbance_effects(const std::string& scenario, const RunControls& controls,
                                           const std::vector<ControllerSpec>& controllers, int workers,
                                           Progress* progress = nullptr);

// One block per controller: a row per case with its status, RMS 3-D position error, largest
// per-axis position error, J and J_dev (docs/glossary.md).
std::string disturbance_table(const DisturbanceEffects& effects);

// disturbances.json: the scenario, the sources, the provenance, and per run its controller, case,
// sources on and metrics under the glossary's names.
nlohmann::ordered_json disturbance_json(const DisturbanceEffects& effects);

}  // namespace thetad
