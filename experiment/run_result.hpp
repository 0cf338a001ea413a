#pragma once

#include <string>

#include <yaml-cpp/yaml.h>

#include "core/sim/simulator.hpp"
#include "experiment/controller_spec.hpp"
#include "experiment/provenance.hpp"

namespace thetad {

// One flight as every front end reports it: the controller as asked for (spec) and as built
// (every setting with the value used), the summary, the log unless the run was summary-only, and
// what produced it.
struct RunResult {
  ControllerSpec spec;
  YAML::Node settings;  // resolved: every field of the controller's settings, defaults included
  std::string controller_origin;  // "built-in", or the plug-in (path and SHA-256) it came from
  sim::RunSummary summary;
  sim::RunLog log;      // empty when summary-only
  Provenance provenance;
  double wall_time_s = 0.0;  // of the flight; 0 without timing

  bool completed() const { return summary.status == sim::RunStatus::completed; }
};

// What the controller took from the reference (docs/model.md §7.1): its `feedforward` setting as
// flown (none, velocity, velocity+trim) for the built-in controllers, "own" for a controller
// without that setting (a plug-in, a Python controller: what it uses is its own).
std::string information_set(const RunResult& result);

// "completed", "diverged at 16.200 s" or "failed at 3.000 s".
std::string status_text(const sim::RunSummary& summary);

}  // namespace thetad
