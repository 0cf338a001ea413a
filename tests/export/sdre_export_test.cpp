// `thetad export` of the SDRE (export/sdre_export.cpp): only the capped mode, given by a spec's own
// settings or by the settings every spec reads; the header carries the design point's P, which is
// the library's cold solve there, and the check data the P each run resumes from.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "controllers/sdre.hpp"
#include "experiment/controller_spec.hpp"
#include "export/controller_export.hpp"
#include "tests/error_message.hpp"
#include "tests/scratch_directory.hpp"

#include <fstream>

namespace thetad {
namespace {

using ::testing::HasSubstr;

Flight short_flight() {
  RunControls controls;
  controls.duration = 0.05;
  controls.summary_only = true;
  return Flight("scenario-1", controls);
}

// `spec` with a settings file (read by every spec without its own) that holds `settings`.
ExportedController export_spec(const Flight& flight, const std::string& spec, const std::string& settings) {
  const testing::ScratchDirectory scratch("thetad_sdre_export_test");
  const std::filesystem::path file = scratch.path() / "sdre.yaml";
  std::ofstream(file) << settings << "\n";
  PreparedController prepared = flight.prepare(parse_controller_specs({spec}, file).front());
  return export_controller(flight, prepared, ExportCheckOptions{2, 10});
}

TEST(SdreExport, WritesTheCappedStepWithTheDesignPointsValueMatrix) {
  const Flight flight = short_flight();
  const ExportedController exported = export_spec(flight, "sdre", "sdre: {mode: capped, newton_iterations: 3}");
  EXPECT_EQ(exported.label, "sdre");
  EXPECT_THAT(exported.header, HasSubstr("THETAD_ONBOARD_LYAPUNOV_SCHUR"));
  EXPECT_THAT(exported.header, HasSubstr("thetad_onboard::sdre_step<T, Design<T>>"));
  EXPECT_THAT(exported.header, HasSubstr("static constexpr int newton_iterations = 3;"));
  EXPECT_THAT(exported.check_data, HasSubstr("kCarriedBefore[2][324]"));
  EXPECT_EQ(exported.check_samples, 20);

  // P0 is the library's cold solution at the initial state with the initial input: what the
  // capped controller starts from after reset().
  PreparedController prepared = flight.prepare(
      parse_controller_specs({"capped=sdre:" + std::string(THETAD_SOURCE_DIR) + "/scenarios/sdre-capped.settings.yaml"})
          .front());
  prepared.controller->reset(flight.initial_state(), 0.0);
  const auto& sdre = dynamic_cast<const SdreController&>(*prepared.controller);
  const SdcPlant::Coefficients sdc = flight.model().sdc(flight.initial_state(), sdre.settings().initial_input);
  EXPECT_EQ(sdre.last_value_matrix(), solve_care(sdc.F, sdc.B, sdre.settings().Q, sdre.settings().R).P);
}

TEST(SdreExport, RefusesTheWarmAndColdModesByName) {
  const Flight flight = short_flight();
  for (const char* mode : {"warm", "cold"}) {
    EXPECT_THAT(testing::error_message([&] {
                  export_spec(flight, "sdre", std::string("sdre: {mode: ") + mode + "}");
                }),
                HasSubstr(std::string("sdre is exportable in mode capped only") + " (a fixed number")) << mode;
  }
}

}  // namespace
}  // namespace thetad
