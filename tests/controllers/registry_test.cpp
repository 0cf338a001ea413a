#include <gtest/gtest.h>
#include <gmock/gmock.h>

#include <string>

#include "controllers/registry.hpp"
#include "core/settings.hpp"
#include "tests/controllers/hover_recovery.hpp"

namespace thetad {
namespace {

using ::testing::HasSubstr;
using ::testing::IsSupersetOf;

ControllerContext hover_context(const heli::Helicopter& model) {
  return {model, testing::hover_trim_at_3_5_m().state, 0.0};
}

TEST(ControllerRegistry, KnowsEveryBuiltInControllerAndTheExample) {
  EXPECT_THAT(ControllerRegistry::instance().names(), IsSupersetOf({"sdre", "lqr", "example-pid", "theta-d"}));
  for (const auto& name : ControllerRegistry::instance().names()) {
    EXPECT_FALSE(ControllerRegistry::instance().description(name).empty()) << name;
  }
}

TEST(ControllerRegistry, AnUnknownNameListsTheKnownOnes) {
  const heli::Helicopter model;
  try {
    ControllerRegistry::instance().make("sdre2", {}, hover_context(model));
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("unknown controller 'sdre2'"));
    EXPECT_THAT(error.what(), HasSubstr("example-pid, lqr, lqr-scheduled, sdre"));
  }
}

TEST(ControllerRegistry, AnUnknownSettingIsNamedWithItsLine) {
  const heli::Helicopter model;
  const YAML::Node settings = YAML::Load("# a typo of fixed_point_iterations:\nfixed_point_iteration: 2\n");
  for (const std::string name : {"sdre", "lqr", "example-pid", "theta-d"}) {
    try {
      ControllerRegistry::instance().make(name, settings, hover_context(model));
      ADD_FAILURE() << name << ": no error";
    } catch (const SettingsError& error) {
      EXPECT_EQ(error.field(), "fixed_point_iteration") << name;
      EXPECT_EQ(error.line(), 2) << name;
      EXPECT_THAT(error.what(), HasSubstr("2:1: field 'fixed_point_iteration': unknown field (allowed: ")) << name;
    }
  }
}

TEST(ControllerRegistry, AWrongWeightLengthReadsLikeTheCommandLineMessage) {
  const heli::Helicopter model;
  const YAML::Node scenario = YAML::Load("controller: sdre\nsettings:\n  mode: warm\n  Q: [1, 2]\n");
  try {
    with_settings_source("scenario-1.yaml", [&] {
      return ControllerRegistry::instance().make("sdre", scenario["settings"], hover_context(model));
    });
    FAIL() << "no error";
  } catch (const SettingsError& error) {
    EXPECT_EQ(std::string(error.what()), "scenario-1.yaml:4:6: field 'Q': expected 18 entries, got 2");
  }
}

TEST(ControllerRegistry, ClonesFlyLikeTheOriginal) {
  const heli::Helicopter model;
  const Trim& hover = testing::hover_trim_at_3_5_m();
  Eigen::VectorXd x = hover.state;
  x(heli::kXp) += 0.3;
  x(heli::kV) = 0.2;
  Reference reference;
  reference.position = hover.state.segment<3>(heli::kXp);
  for (const std::string name : {"sdre", "lqr", "example-pid"}) {
    auto original = ControllerRegistry::instance().make(name, {}, hover_context(model));
    auto copy = original->clone();
    Eigen::VectorXd a(heli::kInputDim), b(heli::kInputDim);
    original->reset(hover.state, 0.0);
    copy->reset(hover.state, 0.0);
    original->control(0.0, x, reference, a);
    copy->control(0.0, x, reference, b);
    EXPECT_EQ(a, b) << name;
    EXPECT_EQ(copy->name(), original->name());
  }
}

}  // namespace
}  // namespace thetad
