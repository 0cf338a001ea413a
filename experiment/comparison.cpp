#include "experiment/comparison.hpp"

#include <algorithm>
#include <cstdio>

#include "experiment/result_json.hpp"
#include "experiment/sha256.hpp"

namespace thetad {

namespace {

// The inputs after the first (the helicopter's pedal, collective and cyclics, all angles) in one
// number for the table: the root-sum-square of their RMS values; the result files keep every channel.
double other_inputs_effort(const sim::RunSummary& s) { return s.command_rms.tail(s.command_rms.size() - 1).norm(); }

void append(std::string& text, const char* pattern, auto... values) {
  char line[512];
  std::snprintf(line, sizeof line, pattern, values...);
  text += line;
}

}  // namespace

std::string comparison_table(const std::vector<RunResult>& runs) {
  std::size_t width = std::string("controller").size();
  for (const RunResult& run : runs) width = std::max(width, run.spec.label.size());
  const int w = static_cast<int>(width);
  const bool timing = !runs.empty() && runs.front().summary.settings.measure_compute_time;
  // The columns are the plant's: one per tracked state, the 3-D RMS error (rms_error_m), the first
  // input and the others together. The runs of one table flew one plant.
  const sim::RunSummary none;
  const sim::RunSummary& shape = runs.empty() ? none : runs.front().summary;
  const auto axes = static_cast<int>(shape.tracked.size());
  const std::string unit = shape.tracked.empty() || shape.tracked.front().command.unit.empty()
                               ? ""
                               : " (" + shape.tracked.front().command.unit + ")";
  const std::string first = shape.inputs.empty() ? "" : "RMS " + shape.inputs.front().name;
  const std::string first_unit =
      shape.inputs.empty() || shape.inputs.front().unit.empty() ? "" : "(" + shape.inputs.front().unit + ")";
  std::string text;
  append(text, "%-*s  %-22s %-13s", w, "", "", "");
  if (axes > 0)
    append(text, " %*s %18s  %*s", 9 * axes, ("RMS tracking error" + unit).c_str(), "", 9 * axes,
           ("max tracking error" + unit).c_str());
  append(text, " %9s %9s %11s %11s %17s\n", first.c_str(), shape.inputs.size() > 1 ? "RMS other" : "", "", "",
         timing ? "in-flight us/step" : "");
  append(text, "%-*s  %-22s %-13s", w, "controller", "status", "information");
  if (axes > 0) {
    text += " ";
    for (const auto& tracked : shape.tracked) append(text, "%9s", tracked.axis.c_str());
    append(text, " %18s  ", ("RMS 3-D error" + unit).c_str());
    for (const auto& tracked : shape.tracked) append(text, "%9s", tracked.axis.c_str());
  }
  append(text, " %9s %9s %11s %11s %8s %8s\n", first_unit.c_str(), shape.inputs.size() > 1 ? "inputs" : "", "J_dev",
         "cost J", timing ? "median" : "", timing ? "p99" : "");
  for (const RunResult& run : runs) {
    const sim::RunSummary& s = run.summary;
    append(text, "%-*s  %-22s %-13s", w, run.spec.label.c_str(), status_text(s).c_str(),
           information_set(run).c_str());
    if (axes > 0) {
      text += " ";
      for (Eigen::Index k = 0; k < s.rms_tracking_error.size(); ++k) append(text, "%9.4f", s.rms_tracking_error[k]);
      append(text, " %18.4f  ", s.rms_tracking_error.norm());
      for (Eigen::Index k = 0; k < s.max_tracking_error.size(); ++k) append(text, "%9.4f", s.max_tracking_error[k]);
    }
    append(text, " %9.4g", s.command_rms.size() > 0 ? s.command_rms[0] : 0.0);
    if (s.command_rms.size() > 1) append(text, " %9.4f", other_inputs_effort(s));
    else append(text, " %9s", "");
    if (s.cost_dev) append(text, " %11.4g", *s.cost_dev);
    else append(text, " %11s", "-");
    append(text, " %11.4g", s.cost);
    if (timing) append(text, " %8.1f %8.1f", s.compute_ns_median * 1e-3, s.compute_ns_p99 * 1e-3);
    text += "\n";
  }
  for (const RunResult& run : runs) {
    if (!run.summary.reason.empty()) text += run.spec.label + ": " + run.summary.reason + "\n";
  }
  if (timing)
    text += "In-flight step times include the simulation's noise around each step; `thetad bench` measures the "
            "per-step cost.\n";
  return text;
}

nlohmann::ordered_json comparison_json(const Flight& flight, const std::vector<RunResult>& runs,
                                       const std::vector<RunFiles>& files) {
  nlohmann::ordered_json j;
  const Scenario& scenario = flight.scenario();
  j["format"] = "thetad-comparison-1";
  j["scenario"] = {{"name", scenario.name},
                   {"file", scenario.source},
                   {"description", scenario.description},
                   {"duration_s", flight.settings().duration}};
  j["seed"] = flight.settings().seed;
  j["disturbances"] = flight.disturbances();
  j["provenance"] = to_json(flight.provenance());
  j["runs"] = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < runs.size(); ++i) {
    j["runs"].push_back({{"label", runs[i].spec.label},
                         {"controller", runs[i].spec.controller},
                         {"status", sim::status_name(runs[i].summary.status)},
                         {"information", information_set(runs[i])},
                         {"json", files[i].json.filename().string()},
                         {"json_sha256", sha256_of_file(files[i].json)}});
  }
  return j;
}

}  // namespace thetad
