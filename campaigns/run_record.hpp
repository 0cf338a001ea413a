#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "campaigns/factors.hpp"
#include "campaigns/run_plan.hpp"
#include "experiment/run_result.hpp"

namespace thetad {

// One summary figure of a run as the runs table stores it.
struct MetricColumn {
  std::string_view name;    // the column, unit last ("rms_error_m")
  bool timing;              // wall-clock: 0 under --no-timing and left out when databases are compared
};
// The figures of a run, in column order, named as docs/glossary.md names them: RMS and max position
// error per axis, the 3-D RMS error and the largest per-axis maximum, cost J and J_dev, the RMS
// command per input channel, the in-flight step time and the flight's wall time.
const std::vector<MetricColumn>& metric_columns();

// One row of the runs table: what was flown (the inputs) and what came out (status and figures).
struct RunRecord {
  std::int64_t index = 0;
  int cell = 0;
  int draw = 0;
  std::string scenario;     // the scenario's name
  std::string label;        // the spec's label
  std::string controller;   // the registered name (thetad list)
  std::uint64_t seed = 0;
  FactorValues factors;     // the cell's factors
  std::string status;       // sim::status_name(): completed, diverged or failed (the controller threw or gave NaN)
  std::string reason;       // why it diverged or failed; empty when completed
  std::string information;  // what the controller took from the reference (information_set)
  bool completed() const { return status == "completed"; }
  double end_time_s = 0.0;
  std::int64_t controller_samples = 0;
  std::vector<double> metrics;  // metric_columns() order
};

RunRecord make_record(const PlannedRun& run, const FactorValues& factors, const RunResult& result);

// A record as JSON and back (how an MPI rank sends it to rank 0): numbers round-trip exactly. Both
// ends are one build, so the JSON has no format_version and no reader of older keys.
nlohmann::json to_json(const RunRecord& record);
RunRecord record_from_json(const nlohmann::json& j);

}  // namespace thetad
