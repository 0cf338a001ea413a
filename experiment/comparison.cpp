#include "experiment/comparison.hpp"

#include <algorithm>
#include <cstdio>

#include "experiment/result_json.hpp"
#include "experiment/sha256.hpp"

namespace thetad {

namespace {

// The four cyclic/pedal/collective commands are angles (rad): one number for the table, the
// root-sum-square of their RMS values; the result files keep every channel.
double angle_effort(const sim::RunSummary& s) { return s.command_rms.tail<4>().norm(); }

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
  std::string text;
  append(text, "%-*s  %-22s %27s %27s %9s %9s %11s %17s\n", w, "", "", "RMS position error (m)",
         "max position error (m)", "RMS T_mr", "RMS angle", "", timing ? "in-flight us/step" : "");
  append(text, "%-*s  %-22s %9s%9s%9s %9s%9s%9s %9s %9s %11s %8s %8s\n", w, "controller", "status", "x", "y", "z", "x",
         "y", "z", "(N)", "cmd (rad)", "cost J", timing ? "median" : "", timing ? "p99" : "");
  for (const RunResult& run : runs) {
    const sim::RunSummary& s = run.summary;
    append(text, "%-*s  %-22s %9.4f%9.4f%9.4f %9.4f%9.4f%9.4f %9.3f %9.4f %11.4g", w, run.spec.label.c_str(),
           status_text(s).c_str(), s.rms_tracking_error.x(), s.rms_tracking_error.y(), s.rms_tracking_error.z(),
           s.max_tracking_error.x(), s.max_tracking_error.y(), s.max_tracking_error.z(), s.command_rms[0],
           angle_effort(s), s.cost);
    if (timing) append(text, " %8.1f %8.1f", s.compute_ns_median * 1e-3, s.compute_ns_p99 * 1e-3);
    text += "\n";
  }
  for (const RunResult& run : runs) {
    if (!run.summary.reason.empty()) text += run.spec.label + ": " + run.summary.reason + "\n";
  }
  if (timing)
    text += "In-flight compute times include the simulation's noise around each step; `thetad bench` measures the "
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
                         {"json", files[i].json.filename().string()},
                         {"json_sha256", sha256_of_file(files[i].json)}});
  }
  return j;
}

}  // namespace thetad
