// The exported θ–D and capped SDRE in closed loop (docs/onboard.md, "Fly it"): the paper's θ–D and
// the SDRE of scenarios/sdre-capped.settings.yaml exported at build time (export/CMakeLists.txt),
// each compiled into a plug-in (export/plugin/), their double and float steps flown by the built
// thetad beside the library's controller on the same seed, as a user flies them.

#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/apps/run_thetad.hpp"
#include "tests/scratch_directory.hpp"

namespace {

using thetad::testing::Output;

struct Figures {
  std::string status;
  double cost = 0.0, rms = 0.0;  // J (Eq. 32) and the 3-D RMS position error (m)
};

Figures figures_of(const std::filesystem::path& file) {
  const nlohmann::json run = nlohmann::json::parse(thetad::testing::read_text(file));
  return {run["status"], run["cost"], run["rms_error_m"]};
}

double relative(double value, double reference) { return std::abs(value - reference) / std::abs(reference); }

// `label`'s library controller (flown as `spec`), LABEL-exported and LABEL-float from `plugin` over
// the first `duration` s of scenario I (the paper's disturbances, seed 1): each completes, the
// double step's J and RMS error equal the library's to 1e-9, the float step's to 1e-5.
void expect_exported_flies_as_library(const std::string& plugin, const std::string& label, const std::string& spec,
                                      int duration) {
  const thetad::testing::ScratchDirectory scratch("thetad_exported_closed_loop_test");
  const Output output = thetad::testing::run_thetad(
      scratch.path(), "--plugin " + plugin + " compare --scenario scenario-1 --duration " + std::to_string(duration) +
                          " --controllers " + spec + "," + label + "-exported," + label + "-float" +
                          " --summary-only --no-timing --quiet --out " + (scratch.path() / "out").string());
  ASSERT_EQ(output.status, 0) << output.out << output.err;
  const Figures library = figures_of(scratch.path() / "out" / (label + ".json"));
  const Figures exported = figures_of(scratch.path() / "out" / (label + "-exported.json"));
  const Figures single = figures_of(scratch.path() / "out" / (label + "-float.json"));
  for (const Figures* run : {&library, &exported, &single}) EXPECT_EQ(run->status, "completed");
  EXPECT_LT(relative(exported.cost, library.cost), 1e-9);
  EXPECT_LT(relative(exported.rms, library.rms), 1e-9);
  EXPECT_LT(relative(single.cost, library.cost), 1e-5);
  EXPECT_LT(relative(single.rms, library.rms), 1e-5);
}

// The first 30 s of scenario I (take-off, hover, the figure 8's first half). The double step
// equals the library's to rounding, so its flight does; the float step's u differs by up to ~5e-5
// (R-norm) from step to step, which the closed loop does not amplify: over the whole flight its J
// differed by 9e-10 and its RMS error by 3e-8.
TEST(ExportedClosedLoop, FloatAndDoubleThetaDStepsFlyScenarioOneAsTheLibraryDoes) {
  expect_exported_flies_as_library(THETAD_EXPORTED_PLUGIN, "theta-d", "theta-d", 30);
}

// The first 10 s (take-off and hover; the SDRE step is the costlier, so the flight is shorter):
// from the first sample on, the exported step starts from the same design-point P as the
// library's capped mode.
TEST(ExportedClosedLoop, FloatAndDoubleCappedSdreStepsFlyScenarioOneAsTheLibraryDoes) {
  expect_exported_flies_as_library(THETAD_EXPORTED_SDRE_PLUGIN, "sdre-capped",
                                   "sdre-capped=sdre:" THETAD_SOURCE_DIR "/scenarios/sdre-capped.settings.yaml", 10);
}

}  // namespace
