#include "apps/thetad/compare_command.hpp"

#include <algorithm>
#include <cstdio>
#include <memory>

#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/error.hpp"

namespace thetad::app {

namespace {

struct Row {
  std::string name;  // as registered; summary.controller is the law's own, more specific name
  sim::RunSummary summary;
  sim::RunFiles files;
};

// The four cyclic/pedal/collective commands are angles (rad): one number for the table, the
// root-sum-square of their RMS values; the JSON files keep every channel.
double angle_effort(const sim::RunSummary& s) { return s.command_rms.tail<4>().norm(); }

void print_table(const std::vector<Row>& rows) {
  std::size_t width = std::string("controller").size();
  for (const Row& row : rows) width = std::max(width, row.summary.controller.size());
  const int w = static_cast<int>(width);
  std::printf("%-*s  %-22s %27s %27s %9s %9s %11s %17s\n", w, "", "", "RMS position error (m)", "max position error (m)",
              "RMS T_mr", "RMS angle", "", "compute/step (us)");
  std::printf("%-*s  %-22s %9s%9s%9s %9s%9s%9s %9s %9s %11s %8s %8s\n", w, "controller", "status", "x", "y", "z", "x",
              "y", "z", "(N)", "cmd (rad)", "cost J", "median", "p99");
  for (const Row& row : rows) {
    const sim::RunSummary& s = row.summary;
    std::printf("%-*s  %-22s %9.4f%9.4f%9.4f %9.4f%9.4f%9.4f %9.3f %9.4f %11.4g %8.1f %8.1f\n", w,
                s.controller.c_str(), status_text(s).c_str(), s.rms_tracking_error.x(), s.rms_tracking_error.y(),
                s.rms_tracking_error.z(), s.max_tracking_error.x(), s.max_tracking_error.y(),
                s.max_tracking_error.z(), s.command_rms[0], angle_effort(s), s.cost, s.compute_ns_median * 1e-3,
                s.compute_ns_p99 * 1e-3);
  }
  for (const Row& row : rows) {
    if (!row.summary.reason.empty()) std::printf("%s: %s\n", row.summary.controller.c_str(), row.summary.reason.c_str());
  }
}

std::string comparison_json(const Flight& flight, const std::vector<Row>& rows) {
  nlohmann::ordered_json j;
  const Scenario& scenario = flight.scenario();
  j["scenario"] = {{"name", scenario.name},
                   {"file", scenario.source},
                   {"description", scenario.description},
                   {"duration_s", scenario.duration}};
  j["seed"] = flight.settings().seed;
  j["disturbances"] = flight.disturbances();
  j["runs"] = nlohmann::ordered_json::array();
  for (const Row& row : rows) {
    j["runs"].push_back({{"controller", row.name},
                         {"csv", row.files.csv.filename().string()},
                         {"json", row.files.json.filename().string()},
                         {"summary", nlohmann::ordered_json::parse(sim::summary_json(row.summary))}});
  }
  return j.dump(2) + "\n";
}

}  // namespace

CLI::App* add_compare_command(CLI::App& app, CompareArguments& arguments) {
  auto* compare = app.add_subcommand(
      "compare", "Fly several controllers through a scenario on the same seed; print a table, write <out>/comparison.json");
  add_flight_options(*compare, arguments.flight);
  compare->add_option("--controllers", arguments.controllers, "Comma-separated controller names (see thetad list)")
      ->required()
      ->delimiter(',');
  return compare;
}

int run_compare(const CompareArguments& arguments) {
  const auto& names = arguments.controllers;
  for (auto it = names.begin(); it != names.end(); ++it) {
    if (std::find(names.begin(), it, *it) != it) throw Error("--controllers: '" + *it + "' is listed twice");
  }
  const Flight flight(arguments.flight);
  std::vector<std::unique_ptr<Controller>> controllers;
  for (const auto& name : names) controllers.push_back(flight.make_controller(name));

  const auto& out = arguments.flight.out;
  std::error_code error;
  std::filesystem::create_directories(out, error);
  if (error) throw Error("cannot create directory " + out.string() + ": " + error.message());

  std::vector<Row> rows;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string label = "[" + std::to_string(i + 1) + "/" + std::to_string(names.size()) + "] " + names[i] + ":";
    const sim::RunResult result = flight.fly(*controllers[i], label);
    rows.push_back({names[i], result.summary, sim::write_run(result, out, names[i])});
  }

  std::printf("%s (%g s, seed %llu, %s)\n", flight.scenario().name.c_str(), flight.scenario().duration,
              static_cast<unsigned long long>(flight.settings().seed), flight.disturbances().c_str());
  print_table(rows);
  const auto path = out / "comparison.json";
  write_file_atomically(path, comparison_json(flight, rows));
  std::printf("Wrote %s and one .csv/.json pair per controller in %s.\n", path.c_str(), out.c_str());
  return 0;
}

}  // namespace thetad::app
