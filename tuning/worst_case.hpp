#pragma once

// Worst cases of Table 1's parameter uncertainty (docs/robustness.md): for each controller, the
// deviations xi in [-1, 1]^21 of the 21 parameter entries (docs/model.md §9.1) that make a flight
// track worst, or cost most, where random draws would rarely look: a sampled design over the box
// (its centre, the 42 centres of its faces, random corners) and then a derivative-free NLopt
// maximisation from the worst point of the design, within one evaluation budget per controller.
// Every other disturbance of the scenario is flown as its seed draws it, the same in every flight,
// so the flights differ by the parameters alone. A flight that does not complete is the worst
// outcome there is: the search stops at the first one.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/sim/run_summary.hpp"
#include "experiment/controller_spec.hpp"
#include "experiment/provenance.hpp"
#include "settings/run_controls.hpp"

namespace thetad::tuning {

enum class WorstCaseMetric {
  rms_error,  // the RMS 3-D position error (rms_error_m)
  cost_dev,   // J_dev (docs/model.md §7.2)
};

// "rms_error_m" or "cost_dev" (docs/glossary.md), and back (thetad::Error naming the choices).
const char* metric_key(WorstCaseMetric metric);
WorstCaseMetric parse_worst_case_metric(const std::string& name);

struct WorstCaseOptions {
  WorstCaseMetric metric = WorstCaseMetric::rms_error;
  int corners = 32;             // random corners in the sampled design
  int max_evaluations = 150;    // flights per controller, the design's included
  std::uint64_t design_seed = 1;  // of the corners' signs and of NLopt
  int threads = 1;              // flights of the design at once
  // After every flight: the controller's label, flights so far and the budget.
  std::function<void(const std::string& label, int evaluations, int budget)> progress;
};

struct WorstCaseFlight {
  std::vector<double> xi;   // Table 1's parameter deviations, in table order
  sim::RunSummary summary;  // summary only
  double value = 0.0;       // the metric; +inf when the flight did not complete
};

struct WorstCase {
  ControllerSpec controller;
  WorstCaseFlight nominal;  // xi = 0
  WorstCaseFlight worst;
  int evaluations = 0;
  std::string stop;  // why the search ended
};

struct WorstCases {
  std::string scenario;  // as given
  WorstCaseOptions options;
  Provenance provenance;  // of the nominal flight
  std::vector<WorstCase> controllers;
};

// The worst case of each controller on `scenario` flown with `controls` (the parameter uncertainty
// on, whatever they say). Throws thetad::Error on bad options or files before anything flies.
WorstCases find_worst_cases(const std::string& scenario, const RunControls& controls,
                            const std::vector<ControllerSpec>& controllers, const WorstCaseOptions& options);

// worst_case.json: the options, the provenance, and per controller its nominal and worst flights
// (status, the metric, every deviation and parameter factor by name).
nlohmann::ordered_json worst_case_json(const WorstCases& cases);

// `scenario_text` (the flight's scenario) with simulation.disturbances.parameter_deviations set to
// `flight`'s by name and every run control the flight had (seed, duration, steps, limits, the
// disturbance switches): a scenario file that flies `flight` again (thetad run; its comments are lost).
std::string worst_case_scenario(const std::string& scenario_text, const WorstCaseFlight& flight);

}  // namespace thetad::tuning
