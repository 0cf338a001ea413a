// Every shipped scenario flies with every built-in helicopter controller, with the settings file
// shipped beside it (scenarios/<name>.settings.yaml) when there is one; and the scheduled LQR's
// envelope check passes on each whole scenario with those settings. The flights are short (the
// SDRE costs ~0.5 ms per step): the whole flights are in docs/scenarios.md, with their commands.

#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "controllers/lqr_scheduled.hpp"
#include "controllers/registry.hpp"
#include "experiment/flight.hpp"
#include "settings/settings.hpp"

namespace thetad {
namespace {

namespace fs = std::filesystem;

const fs::path kScenarios = fs::path(THETAD_SOURCE_DIR) / "scenarios";

std::vector<fs::path> shipped_scenarios() {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(kScenarios)) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() == ".yaml" && name.find(".settings.") == std::string::npos)
      files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// The settings file beside `scenario`, or none.
fs::path settings_beside(const fs::path& scenario) {
  const fs::path file = kScenarios / (scenario.stem().string() + ".settings.yaml");
  return fs::exists(file) ? file : fs::path();
}

ControllerSpec spec_for(const std::string& controller, const fs::path& scenario) {
  const fs::path settings = settings_beside(scenario);
  if (settings.empty()) return {controller, controller, YAML::Node(), ""};
  return parse_controller_spec(controller, load_settings_file(settings), settings.string());
}

TEST(ShippedScenarios, AreTheSixDocumentedOnes) {
  std::vector<std::string> names;
  for (const auto& file : shipped_scenarios()) names.push_back(file.stem().string());
  EXPECT_EQ(names, (std::vector<std::string>{"fast-forward", "hover-hold", "hover-step", "hover-to-hover", "scenario-1",
                                              "scenario-2"}));
}

TEST(ShippedScenarios, EveryControllerFliesTheFirstSeconds) {
  RunControls controls;
  controls.duration = 1.5;
  controls.summary_only = true;
  controls.timing = false;
  for (const auto& file : shipped_scenarios()) {
    const Flight flight(file.string(), controls);
    for (const std::string& controller : ControllerRegistry::instance().names()) {  // every one, a new one too
      PreparedController prepared = flight.prepare(spec_for(controller, file));
      const RunResult result = flight.fly(prepared);
      EXPECT_EQ(result.summary.status, sim::RunStatus::completed)
          << file.stem() << " with " << controller << ": " << result.summary.reason;
      EXPECT_LT(result.summary.max_tracking_error.maxCoeff(), 0.5) << file.stem() << " with " << controller;
    }
  }
}

TEST(ShippedScenarios, TheScheduledLqrEnvelopeHoldsEachWholeScenario) {
  for (const auto& file : shipped_scenarios()) {
    const Flight flight(file.string());
    const ControllerSpec spec = spec_for("lqr-scheduled", file);
    const Settings fields(spec.settings);
    const LqrScheduleGrid grid = read_lqr_grid(fields.block("grid"));
    const double time_constant = fields.number("velocity_time_constant",
                                               LqrScheduledController::kDefaultVelocityTimeConstant, 0.0, 60.0);
    EXPECT_NO_THROW(check_lqr_envelope(grid, time_constant, flight.scenario().trajectory, flight.settings().duration,
                                       flight.settings().controller_period()))
        << file.stem();
  }
}

TEST(ShippedScenarios, TheScheduledLqrRefusesAFlightBeyondItsGridBeforeFlying) {
  const Flight flight((kScenarios / "fast-forward.yaml").string());
  const YAML::Node settings = YAML::Load("grid:\n  speeds: [0, 5, 10]\n  courses_deg: [0]\n");
  try {
    flight.prepare({"lqr-scheduled", "lqr-scheduled", settings, ""});
    ADD_FAILURE() << "no error";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("a horizontal speed outside the grid's speeds [0.000000, 10.000000] m/s"), std::string::npos)
        << message;
    EXPECT_NE(message.find("at t = 22.2"), std::string::npos) << message;  // 10 m/s 0.2 s after 22 s: the filter's lag
  }
}

}  // namespace
}  // namespace thetad
