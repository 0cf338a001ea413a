// J_dev's weights (core/helicopter/designed_weights.hpp) are the shipped designed set, every
// controller's block of scenarios/designed.settings.yaml and of the fair study's designed settings
// (scenarios/campaigns/fair): regenerated together or not at all.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/helicopter/designed_weights.hpp"
#include "experiment/controller_spec.hpp"

namespace thetad {
namespace {

TEST(DesignedWeights, AreThoseOfTheShippedSettingsFiles) {
  const Eigen::VectorXd q = heli::designed_state_weights(), r = heli::designed_input_weights();
  const std::string scenarios = std::string(THETAD_SOURCE_DIR) + "/scenarios/";
  for (const std::string name : {"designed.settings.yaml", "campaigns/fair/designed-none.settings.yaml",
                                 "campaigns/fair/designed-velocity.settings.yaml",
                                 "campaigns/fair/designed-velocity-trim.settings.yaml"}) {
    const YAML::Node file = load_settings_file(scenarios + name);
    for (const char* controller : {"theta-d", "sdre", "lqr", "lqr-scheduled"}) {
      EXPECT_EQ(file[controller]["Q"].as<std::vector<double>>(), std::vector<double>(q.begin(), q.end()))
          << name << ": " << controller;
      EXPECT_EQ(file[controller]["R"].as<std::vector<double>>(), std::vector<double>(r.begin(), r.end()))
          << name << ": " << controller;
    }
  }
}

}  // namespace
}  // namespace thetad
