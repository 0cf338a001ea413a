#include <gtest/gtest.h>
#include <gmock/gmock.h>

#include <string>

#include "controllers/registry.hpp"
#include "core/settings.hpp"
#include "core/test_plants.hpp"
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

// u = −R⁻¹ B(x)ᵀ P x on the companion oscillator, with P the closed-form SDRE solution.
double companion_input(const CompanionPlant& plant, const Eigen::Vector2d& x, double q1, double q2, double r) {
  const SdcPlant::Coefficients sdc = plant.sdc(x, Eigen::VectorXd::Zero(1));
  return -(sdc.B.transpose() * CompanionPlant::sdre_solution(x, q1, q2, r) * x)(0) / r;
}

TEST(ControllerRegistry, ThetaDAndSdreFlyAPlantThatIsNotTheHelicopter) {
  const CompanionPlant plant;
  const Eigen::Vector2d x0(0.4, -0.3), x(-0.7, 0.5);
  const ControllerContext context{plant, x0};
  // The plant says nothing of its design: Q = I, R = 1, u0 = 0.
  EXPECT_EQ(context.defaults.state_weights, Eigen::VectorXd::Ones(2));
  EXPECT_EQ(context.defaults.input_weights, Eigen::VectorXd::Ones(1));
  EXPECT_EQ(context.defaults.input, Eigen::VectorXd::Zero(1));
  Eigen::VectorXd u(1);

  // θ–D at its initial state is T0 = P(x0) (Ã = 0, g̃ = 0: every later term vanishes).
  auto theta_d = ControllerRegistry::instance().make("theta-d", {}, context);
  theta_d->reset(x0, 0.0);
  theta_d->control(0.0, x0, Reference{}, u);
  EXPECT_NEAR(u(0), companion_input(plant, x0, 1.0, 1.0, 1.0), 1e-12);

  // SDRE with the caller's own defaults solves the CARE of those weights at every state.
  const ControllerContext weighted{plant, DesignDefaults{Eigen::Vector2d(2.0, 0.5), Eigen::VectorXd::Constant(1, 3.0),
                                                         Eigen::VectorXd::Zero(1)}, x0};
  for (const std::string mode : {"cold", "warm"}) {
    auto sdre = ControllerRegistry::instance().make("sdre", YAML::Load("mode: " + mode), weighted);
    sdre->reset(x0, 0.0);
    sdre->control(0.0, x0, Reference{}, u);
    EXPECT_NEAR(u(0), companion_input(plant, x0, 2.0, 0.5, 3.0), 1e-12) << mode;
    sdre->control(1e-3, x, Reference{}, u);
    EXPECT_NEAR(u(0), companion_input(plant, x, 2.0, 0.5, 3.0), 1e-12) << mode;
  }
}

TEST(ControllerRegistry, ControllersThatTrimTheHelicopterRefuseAnotherPlant) {
  const CompanionPlant plant;
  const ControllerContext context{plant, Eigen::Vector2d(0.4, -0.3)};
  for (const std::string name : {"lqr", "lqr-scheduled", "example-pid"}) {
    EXPECT_THAT([&] { ControllerRegistry::instance().make(name, {}, context); },
                ::testing::ThrowsMessage<Error>(HasSubstr(
                    name + ": flies only the X-Cell helicopter (heli::Helicopter), whose trims it is designed at; "
                           "this plant is another SdcPlant (n = 2, m = 1)")))
        << name;
  }
}

}  // namespace
}  // namespace thetad
