// Controllers from plug-ins, loaded by the built thetad as a user loads them: --plugin (before or
// after the command), THETAD_PLUGIN_PATH, the origin shown by `thetad list`, and clear errors.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/registry.hpp"
#include "tests/apps/run_thetad.hpp"
#include "tests/scratch_directory.hpp"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using thetad::testing::Output;

class Plugins : public ::testing::Test {
 protected:
  void SetUp() override {
    std::ofstream(dir_ / "hover.yaml") << "name: hover\nduration: 3\ninitial_state:\n  position: [0, 0, 2]\n"
                                          "phases:\n  - name: hold\n    type: hold\n    time: [0, 3]\n";
  }
  Output thetad(const std::string& arguments, const std::string& environment = "") const {
    return thetad::testing::run_thetad(dir_, arguments, environment);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  thetad::testing::ScratchDirectory scratch_{"thetad_plugin_test"};
  const fs::path dir_ = scratch_.path();
};

TEST_F(Plugins, ListShowsWhereEachControllerComesFrom) {
  const Output output = thetad(std::string("--plugin ") + THETAD_EXAMPLE_PLUGIN + " list");
  ASSERT_EQ(output.status, 0) << output.err;
  EXPECT_THAT(output.out, HasSubstr("[plug-in " + fs::canonical(THETAD_EXAMPLE_PLUGIN).string() + " (sha256 "));
  EXPECT_THAT(output.out, HasSubstr("\nexample-pid-plugin "));
  EXPECT_THAT(output.out, HasSubstr("[built-in]"));
}

TEST_F(Plugins, APluginControllerFliesLikeABuiltInOne) {
  const Output output = thetad("compare --scenario " + path("hover.yaml") + " --controllers built-in=example-pid," +
                               "plugged=example-pid-plugin --ideal --out " + path("out") + " --plugin " +
                               THETAD_EXAMPLE_PLUGIN);
  ASSERT_EQ(output.status, 0) << output.err;
  const auto read = [&](const std::string& label) {
    return nlohmann::json::parse(thetad::testing::read_text(dir_ / "out" / (label + ".json")));
  };
  // The same source compiled twice: the same flight, to the last bit.
  EXPECT_EQ(read("plugged")["cost"], read("built-in")["cost"]);
  EXPECT_EQ(read("plugged")["controller"], "example-pid-plugin");
  EXPECT_THAT(read("plugged")["controller_origin"].get<std::string>(),
              HasSubstr("plug-in " + fs::canonical(THETAD_EXAMPLE_PLUGIN).string() + " (sha256 "));
  EXPECT_EQ(read("built-in")["controller_origin"], "built-in");
  EXPECT_LT(read("plugged")["max_error_z_m"].get<double>(), 0.05);
  // A replay without the plug-in says which one flew it.
  const Output without = thetad("run --replay " + path("out/plugged.json"));
  EXPECT_EQ(without.status, 1);
  EXPECT_THAT(without.err, HasSubstr("the run flew the controller 'example-pid-plugin' (plug-in " +
                                     fs::canonical(THETAD_EXAMPLE_PLUGIN).string() + " (sha256 "));
  EXPECT_THAT(without.err, HasSubstr("load the plug-in that has it (--plugin PATH or THETAD_PLUGIN_PATH)"));
}

TEST_F(Plugins, ThePluginPathLoadsFilesAndFolders) {
  const std::string folder = fs::path(THETAD_EXAMPLE_PLUGIN).parent_path().string();
  for (const std::string& entry : {std::string(THETAD_EXAMPLE_PLUGIN), folder}) {
    const Output output = thetad("list", "THETAD_PLUGIN_PATH=" + entry);
    ASSERT_EQ(output.status, 0) << output.err;
    EXPECT_THAT(output.out, HasSubstr("example-pid-plugin"));
  }
  const Output missing = thetad("list", "THETAD_PLUGIN_PATH=" + path("nowhere"));
  EXPECT_EQ(missing.status, 1);
  EXPECT_THAT(missing.err, HasSubstr("THETAD_PLUGIN_PATH: " + path("nowhere") + " does not exist"));
}

// A user's plant from a plug-in, flown by θ–D, the SDRE and the LQR from the command line.
TEST_F(Plugins, APluginPlantFliesThetaDSdreAndLqrFromTheCommandLine) {
  const std::string plugin = std::string("--plugin ") + THETAD_PLANT_PLUGIN;
  const Output list = thetad(plugin + " list");
  ASSERT_EQ(list.status, 0) << list.err;
  EXPECT_THAT(list.out, HasSubstr("plant companion  Duffing-type oscillator"));
  for (const char* controller : {"theta-d", "sdre", "lqr"}) {
    const Output output = thetad(plugin + " run --plant companion --controller " + controller +
                                 " --duration 10 --initial-state 0.8,0.2 --out " + path("plant"));
    ASSERT_EQ(output.status, 0) << output.err;
    EXPECT_THAT(output.out, HasSubstr(std::string(controller) + " on companion (10 s, seed 1, ideal"));
    EXPECT_THAT(output.out, HasSubstr("completed"));
    const auto result =
        nlohmann::json::parse(thetad::testing::read_text(dir_ / "plant" / (std::string(controller) + ".json")));
    EXPECT_EQ(result["format"], "thetad-run-1");  // the result of every plant's flight
    EXPECT_EQ(result["provenance"]["plant"], "companion");
    EXPECT_EQ(result["provenance"]["initial_state"], nlohmann::json::array({0.8, 0.2}));
    EXPECT_EQ(result["controller_samples"], 10000);
    // At rest at the end: the last logged state.
    const std::string csv = thetad::testing::read_text(dir_ / "plant" / (std::string(controller) + ".csv"));
    EXPECT_EQ(csv.substr(0, csv.find('\n')), "t_s,x_0,x_1,meas_x_0,meas_x_1,cmd_u_0,app_u_0,in_flight_step_time_ns");
    const std::string last = csv.substr(csv.rfind('\n', csv.size() - 2) + 1);
    EXPECT_LT(std::abs(std::stod(last.substr(last.find(',') + 1))), 1e-3) << last;
  }
  // The plant's runs replay, with the plug-in that has the plant.
  const Output again = thetad(plugin + " run --replay " + path("plant/sdre.json"));
  EXPECT_EQ(again.status, 0) << again.err;
  EXPECT_THAT(again.out, HasSubstr("agrees with the recorded run"));
  const Output without = thetad("run --replay " + path("plant/sdre.json"));
  EXPECT_EQ(without.status, 1);
  EXPECT_THAT(without.err, HasSubstr("the plant 'companion', which no loaded plug-in registers"));
  // The LQR designs at the plant's design point; the scheduled one needs the helicopter's trims.
  const Output bad =
      thetad(plugin + " run --plant companion --controller lqr-scheduled --duration 1 --out " + path("plant"));
  EXPECT_EQ(bad.status, 1);
  EXPECT_THAT(bad.err, HasSubstr("lqr-scheduled: flies only the X-Cell helicopter"));
  const Output unknown = thetad("run --plant nowhere --controller theta-d --duration 1 --out " + path("plant"));
  EXPECT_EQ(unknown.status, 1);
  EXPECT_THAT(unknown.err, HasSubstr("unknown plant 'nowhere'"));
}

TEST_F(Plugins, APluginBuiltAgainstAnotherInterfaceIsRefused) {
  const Output output = thetad(std::string("--plugin ") + THETAD_OLD_INTERFACE_PLUGIN + " list");
  EXPECT_EQ(output.status, 1);
  EXPECT_THAT(output.err, HasSubstr("plant 'companion' was built against plug-in interface version 1; this thetad has "
                                    "version " + std::to_string(thetad::kPluginInterfaceVersion) +
                                    ": rebuild the plug-in against this thetad"));
}

TEST_F(Plugins, BadPluginsAreOneClearLine) {
  Output output = thetad(std::string("--plugin ") + THETAD_DUPLICATE_PLUGIN + " list");
  EXPECT_EQ(output.status, 1);
  EXPECT_THAT(output.err, HasSubstr("the name 'lqr' is registered twice (built-in and plug-in "));

  output = thetad("--plugin " + path("missing.so") + " list");
  EXPECT_EQ(output.status, 1);
  EXPECT_THAT(output.err, HasSubstr("plug-in " + path("missing.so")));

  std::ofstream(dir_ / "not-a-library.so") << "text";
  output = thetad("--plugin " + path("not-a-library.so") + " list");
  EXPECT_EQ(output.status, 1);
  EXPECT_THAT(output.err, HasSubstr("cannot load plug-in"));
}

}  // namespace
