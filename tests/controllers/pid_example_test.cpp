#include <gtest/gtest.h>

#include "controllers/examples/pid.hpp"
#include "controllers/registry.hpp"
#include "controllers/settings.hpp"
#include "tests/controllers/hover_recovery.hpp"

namespace thetad {
namespace {

std::unique_ptr<Controller> make_pid(const heli::Helicopter& model, const YAML::Node& settings = {}) {
  return ControllerRegistry::instance().make("example-pid", settings,
                                             {model, testing::hover_trim_at_3_5_m().state, 0.0});
}

TEST(ExamplePid, HoldsTheTrimExactly) {
  const heli::Helicopter model;
  auto pid = make_pid(model);
  const auto r = testing::recover_hover(*pid, Eigen::Vector3d::Zero(), 2.0);
  EXPECT_EQ(r.status, sim::RunStatus::completed) << r.reason;
  EXPECT_LT(r.max_error, 1e-9);
}

TEST(ExamplePid, ReturnsToHoverFromOneMetreOffsets) {
  const heli::Helicopter model;
  for (const Eigen::Vector3d offset : {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()}) {
    auto pid = make_pid(model);
    const auto r = testing::recover_hover(*pid, offset, 12.0);
    testing::print("example-pid offset " + std::to_string(offset.x()) + "," + std::to_string(offset.y()) + "," +
                       std::to_string(offset.z()), r);
    EXPECT_EQ(r.status, sim::RunStatus::completed) << r.reason;
  }
}

TEST(ExamplePid, RejectsAGainVectorOfTheWrongLength) {
  const heli::Helicopter model;
  const YAML::Node settings = YAML::Load("roll_gains: [0.02]");
  EXPECT_THROW(make_pid(model, settings), SettingsError);
}

}  // namespace
}  // namespace thetad
