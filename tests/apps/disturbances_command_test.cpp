// thetad disturbances as a user runs it: the table and disturbances.json; a scenario flown without
// any disturbance is refused with one clear line and nothing written.

#include <filesystem>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/apps/run_thetad.hpp"
#include "tests/scratch_directory.hpp"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using thetad::testing::Output;

class DisturbancesCommand : public ::testing::Test {
 protected:
  Output thetad(const std::string& arguments) const { return thetad::testing::run_thetad(dir_, arguments); }
  std::string out() const { return (dir_ / "out").string(); }

  thetad::testing::ScratchDirectory scratch_{"thetad_disturbances_test"};
  const fs::path dir_ = scratch_.path();
};

TEST_F(DisturbancesCommand, PrintsEachCasePerControllerAndWritesTheJson) {
  const Output output = thetad("disturbances --scenario " THETAD_SOURCE_DIR
                               "/scenarios/hover-hold.yaml --controllers lqr,theta-d --duration 0.5 --quiet --out " + out());
  ASSERT_EQ(output.status, 0) << output.err;
  EXPECT_THAT(output.out, HasSubstr("lqr\n  disturbances"));
  EXPECT_THAT(output.out, HasSubstr("only wind_gust"));
  EXPECT_THAT(output.out, HasSubstr("all but induced_velocity_noise"));
  const nlohmann::json result = nlohmann::json::parse(thetad::testing::read_text(dir_ / "out" / "disturbances.json"));
  EXPECT_EQ(result["sources"].size(), 6u);
  EXPECT_EQ(result["runs"].size(), 2u * (1 + 6 + 1 + 6));
}

TEST_F(DisturbancesCommand, AnIdealFlightIsRefusedAndNothingIsWritten) {
  const Output output = thetad("disturbances --scenario hover-step --controllers lqr --ideal --out " + out());
  EXPECT_EQ(output.status, 1);
  EXPECT_THAT(output.err, HasSubstr("flies no disturbance"));
  EXPECT_FALSE(fs::exists(dir_ / "out" / "disturbances.json"));
}

}  // namespace
