// J_dev's weights (core/helicopter/designed_weights.hpp) are the shipped designed set, every
// controller's block of scenarios/designed.settings.yaml: regenerated together or not at all.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/helicopter/designed_weights.hpp"
#include "experiment/controller_spec.hpp"

namespace thetad {
namespace {

TEST(DesignedWeights, AreThoseOfTheShippedSettingsFile) {
  const YAML::Node file = load_settings_file(std::string(THETAD_SOURCE_DIR) + "/scenarios/designed.settings.yaml");
  const Eigen::VectorXd q = heli::designed_state_weights(), r = heli::designed_input_weights();
  for (const char* controller : {"theta-d", "sdre", "lqr", "lqr-scheduled"}) {
    EXPECT_EQ(file[controller]["Q"].as<std::vector<double>>(), std::vector<double>(q.begin(), q.end())) << controller;
    EXPECT_EQ(file[controller]["R"].as<std::vector<double>>(), std::vector<double>(r.begin(), r.end())) << controller;
  }
}

}  // namespace
}  // namespace thetad
