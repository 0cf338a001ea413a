// The exported θ–D in closed loop (docs/onboard.md, "Fly it"): the paper's θ–D exported at build
// time (tests/CMakeLists.txt), compiled into a plug-in (export/plugin/), its double and float steps
// flown by the built thetad beside the library's θ–D on the same seed, as a user flies them.

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

// The first 30 s of scenario I (take-off, hover, the figure 8's first half; the paper's
// disturbances, seed 1). The double step equals the library's to rounding, so its flight does;
// the float step's u differs by up to ~5e-5 (R-norm) from step to step, which the closed loop does
// not amplify: over the whole flight its J differed by 9e-10 and its RMS error by 3e-8.
TEST(ExportedClosedLoop, FloatAndDoubleStepsFlyScenarioOneAsTheLibraryDoes) {
  const thetad::testing::ScratchDirectory scratch("thetad_exported_closed_loop_test");
  const Output output = thetad::testing::run_thetad(
      scratch.path(), std::string("--plugin ") + THETAD_EXPORTED_PLUGIN +
                          " compare --scenario scenario-1 --duration 30 --controllers theta-d,theta-d-exported,theta-d-float"
                          " --summary-only --no-timing --quiet --out " + (scratch.path() / "out").string());
  ASSERT_EQ(output.status, 0) << output.out << output.err;
  const Figures library = figures_of(scratch.path() / "out" / "theta-d.json");
  const Figures exported = figures_of(scratch.path() / "out" / "theta-d-exported.json");
  const Figures single = figures_of(scratch.path() / "out" / "theta-d-float.json");
  for (const Figures* run : {&library, &exported, &single}) EXPECT_EQ(run->status, "completed");
  EXPECT_LT(relative(exported.cost, library.cost), 1e-9);
  EXPECT_LT(relative(exported.rms, library.rms), 1e-9);
  EXPECT_LT(relative(single.cost, library.cost), 1e-5);
  EXPECT_LT(relative(single.rms, library.rms), 1e-5);
}

}  // namespace
