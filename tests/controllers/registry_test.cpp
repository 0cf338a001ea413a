#include <gtest/gtest.h>
#include <gmock/gmock.h>

#include <cstring>
#include <string>
#include <vector>

#include "controllers/lqr_scheduled.hpp"
#include "controllers/registry.hpp"
#include "settings/settings.hpp"
#include "tests/controllers/hover_recovery.hpp"
#include "tests/test_plants.hpp"

namespace thetad {
namespace {

using ::testing::HasSubstr;
using ::testing::IsSupersetOf;

ControllerContext hover_context(const heli::Helicopter& model) {
  return {model, testing::hover_trim_at_3_5_m().state, 0.0};
}

// The tests below go through every name the registry knows, so that a controller added to it is
// held to the same rules without an edit here; this one checks that the built-ins are there.
TEST(ControllerRegistry, KnowsEveryBuiltInControllerAndTheExample) {
  EXPECT_THAT(ControllerRegistry::instance().names(),
              IsSupersetOf({"sdre", "lqr", "lqr-scheduled", "example-pid", "theta-d"}));
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
    std::string known;
    for (const std::string& name : ControllerRegistry::instance().names()) known += (known.empty() ? "" : ", ") + name;
    EXPECT_EQ(std::string(error.what()), "unknown controller 'sdre2' (known: " + known + ")");
  }
}

TEST(ControllerRegistry, AnUnknownSettingIsNamedWithItsLine) {
  const heli::Helicopter model;
  const YAML::Node settings = YAML::Load("# a typo of fixed_point_iterations:\nfixed_point_iteration: 2\n");
  for (const std::string& name : ControllerRegistry::instance().names()) {
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

// lqr-scheduled designs its table when it is built: a few seconds for the envelope, ~0.1 s here.
YAML::Node quick_settings(const std::string& name) {
  return name == "lqr-scheduled" ? YAML::Load("grid: {speeds: [0, 2], courses_deg: [0, 90], climb_rates: [0]}")
                                 : YAML::Node();
}

// One control step from the hover trim displaced by 0.3 m, after reset.
Eigen::VectorXd first_step(Controller& controller) {
  const Trim& hover = testing::hover_trim_at_3_5_m();
  Eigen::VectorXd x = hover.state;
  x(heli::kXp) += 0.3;
  x(heli::kV) = 0.2;
  Reference reference;
  reference.position = hover.state.segment<3>(heli::kXp);
  Eigen::VectorXd u(heli::kInputDim);
  controller.reset(hover.state, 0.0);
  controller.control(0.0, x, reference, u);
  return u;
}

TEST(ControllerRegistry, ClonesFlyLikeTheOriginal) {
  const heli::Helicopter model;
  for (const std::string& name : ControllerRegistry::instance().names()) {
    auto original = ControllerRegistry::instance().make(name, quick_settings(name), hover_context(model));
    auto copy = original->clone();
    EXPECT_EQ(first_step(*original), first_step(*copy)) << name;
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

TEST(ControllerRegistry, EveryControllerFliesAnotherPlantOrRefusesItByName) {
  const CompanionPlant plant;
  const ControllerContext context{plant, Eigen::Vector2d(0.4, -0.3)};
  std::vector<std::string> refused;
  for (const std::string& name : ControllerRegistry::instance().names()) {
    try {
      ControllerRegistry::instance().make(name, {}, context);
    } catch (const Error& error) {
      EXPECT_EQ(std::string(error.what()),
                name + ": flies only the X-Cell helicopter (heli::Helicopter), whose trims it is designed at; "
                       "this plant is another SdcPlant (n = 2, m = 1)");
      refused.push_back(name);
    }
  }
  // The ones that trim the X-Cell; θ–D and SDRE fly the plant (above), the LQR at its design point.
  EXPECT_THAT(refused, IsSupersetOf({"lqr-scheduled", "example-pid"}));
  EXPECT_THAT(refused, ::testing::Not(::testing::Contains("theta-d")));
  EXPECT_THAT(refused, ::testing::Not(::testing::Contains("sdre")));
  EXPECT_THAT(refused, ::testing::Not(::testing::Contains("lqr")));
}

TEST(ControllerRegistry, TheSettingsAsUsedRebuildTheSameController) {
  const heli::Helicopter model;
  const ControllerRegistry& registry = ControllerRegistry::instance();
  for (const std::string& name : registry.names()) {
    const BuiltController built = registry.build(name, quick_settings(name), hover_context(model));
    const BuiltController rebuilt = registry.build(name, built.settings, hover_context(model));
    EXPECT_GT(built.settings.size(), 0u) << name;
    EXPECT_EQ(YAML::Dump(rebuilt.settings), YAML::Dump(built.settings)) << name;
    const Eigen::VectorXd u = first_step(*built.controller), again = first_step(*rebuilt.controller);
    ASSERT_EQ(u.size(), again.size()) << name;
    EXPECT_EQ(std::memcmp(u.data(), again.data(), sizeof(double) * static_cast<std::size_t>(u.size())), 0)
        << name << ": " << u.transpose() << " rebuilt: " << again.transpose();
  }
}

TEST(ControllerRegistry, TheSettingsAsUsedHoldEveryFieldGivenOrDefault) {
  const heli::Helicopter model;
  const ControllerRegistry& registry = ControllerRegistry::instance();
  const YAML::Node theta_d = registry.build("theta-d", YAML::Load("{terms: 2, k: [0.5]}"), hover_context(model)).settings;
  EXPECT_EQ(theta_d["terms"].as<int>(), 2);
  EXPECT_EQ(theta_d["k"].as<std::vector<double>>(), std::vector<double>{0.5});
  EXPECT_EQ(theta_d["l"].as<std::vector<double>>(), std::vector<double>{1.0});
  EXPECT_EQ(theta_d["fixed_point_iterations"].as<int>(), 3);
  EXPECT_EQ(theta_d["fixed_point_tolerance"].as<double>(), 1e-6);
  const DesignDefaults defaults = model.design_defaults();
  EXPECT_EQ(theta_d["Q"].as<std::vector<double>>(),
            std::vector<double>(defaults.state_weights.begin(), defaults.state_weights.end()));
  EXPECT_EQ(theta_d["R"].as<std::vector<double>>(),
            std::vector<double>(defaults.input_weights.begin(), defaults.input_weights.end()));
  EXPECT_EQ(theta_d["feedforward"].as<std::string>(), "none");
  EXPECT_FALSE(theta_d["certificates"].as<bool>());
  EXPECT_EQ(theta_d.size(), 9u);

  const YAML::Node scheduled =
      registry.build("lqr-scheduled", YAML::Load("grid: {speeds: [0, 2], courses_deg: [90]}"), hover_context(model))
          .settings;
  EXPECT_EQ(scheduled["grid"]["speeds"].as<std::vector<double>>(), (std::vector<double>{0.0, 2.0}));
  EXPECT_EQ(scheduled["grid"]["courses_deg"].as<std::vector<double>>(), std::vector<double>{90.0});
  EXPECT_EQ(scheduled["grid"]["climb_rates"].as<std::vector<double>>(), (std::vector<double>{-1.0, 0.0, 1.0}));
  EXPECT_EQ(scheduled["grid"]["altitude"].as<double>(), 3.5);
  EXPECT_EQ(scheduled["velocity_time_constant"].as<double>(), LqrScheduledController::kDefaultVelocityTimeConstant);
  EXPECT_EQ(scheduled["Q"].size(), 18u);
  EXPECT_EQ(scheduled["R"].size(), 5u);
  EXPECT_FALSE(scheduled["table"]) << "a designed schedule has no table file";
}

// u = −gain · (the first m states): a controller as small as a plug-in's, to register from a test
// under names chosen at run time.
class ProportionalController final : public Controller {
 public:
  ProportionalController(std::string name, double gain, Eigen::Index inputs)
      : name_(std::move(name)), gain_(gain), inputs_(inputs) {}
  std::string name() const override { return name_; }
  std::unique_ptr<Controller> clone() const override { return std::make_unique<ProportionalController>(*this); }
  void reset(const Eigen::VectorXd&, double) override {}
  void control(double, const Eigen::Ref<const Eigen::VectorXd>& x, const Reference&,
               Eigen::Ref<Eigen::VectorXd> u) override {
    u = -gain_ * x.head(inputs_);
  }

 private:
  std::string name_;
  double gain_;
  Eigen::Index inputs_;
};

// Registered as `name`, it calls itself that unless its settings say otherwise (calls_itself).
ControllerFactory proportional(const std::string& name) {
  return [name](const Settings& settings, const ControllerContext& context) -> std::unique_ptr<Controller> {
    settings.allow_only({"gain", "calls_itself"});
    return std::make_unique<ProportionalController>(settings.string("calls_itself", name), settings.number("gain", 1.0),
                                                    context.plant.input_dim());
  };
}

// A plug-in built against another interface version, an empty name or a taken one is refused, by
// every registry alike: inside a plug-in's scope the refusal waits for the loader, outside it throws.
TEST(Registry, RefusesOtherInterfaceVersionsEmptyAndTakenNames) {
  Registry<int> registry("widget");
  registry.add("a", "the first", 1, kPluginInterfaceVersion);
  EXPECT_THAT([&] { registry.add("a", "again", 2, kPluginInterfaceVersion); },
              ::testing::ThrowsMessage<Error>(HasSubstr("widget registry: the name 'a' is registered twice (built-in and built-in)")));
  EXPECT_THAT([&] { registry.add("", "nameless", 3, kPluginInterfaceVersion); },
              ::testing::ThrowsMessage<Error>(HasSubstr("widget registry: an empty name")));
  {
    const RegistrationOrigin plugin("plug-in /old/libold.so");
    registry.add("b", "built against the first interface", 4, 1);
    registry.add("a", "taken", 5, kPluginInterfaceVersion);
  }
  const std::vector<std::string> refused = registry.take_refusals();
  ASSERT_EQ(refused.size(), 2u);
  EXPECT_THAT(refused[0], HasSubstr("widget 'b' was built against plug-in interface version 1; this thetad has version " +
                                    std::to_string(kPluginInterfaceVersion) + ": rebuild the plug-in"));
  EXPECT_THAT(refused[1], HasSubstr("(built-in and plug-in /old/libold.so)"));
  EXPECT_TRUE(registry.take_refusals().empty());
  EXPECT_EQ(registry.names(), std::vector<std::string>{"a"});
  EXPECT_THAT([&] { registry.entry("c"); }, ::testing::ThrowsMessage<Error>(HasSubstr("unknown widget 'c' (known: a)")));
}

// Last in this file: it adds controllers to the registry for good (well-behaved ones, should the
// tests run in another order; named anew on each repetition).
TEST(ControllerRegistry, ARegistrationRecordsTheOriginItWasMadeIn) {
  ControllerRegistry& registry = ControllerRegistry::instance();
  for (const std::string& name : registry.names()) {
    if (name.rfind("origin-", 0) != 0) {
      EXPECT_EQ(registry.origin(name), "built-in") << name;
    }
  }
  static int repetition = 0;
  const std::string run = std::to_string(++repetition);
  {
    const RegistrationOrigin outer("plugin /path/to/libouter.so");
    registry.add("origin-outer-" + run, "registered in a scope", proportional("origin-outer-" + run),
                 kPluginInterfaceVersion);
    {
      const RegistrationOrigin inner("plugin /path/to/libinner.so");
      const ControllerRegistration registration("origin-inner-" + run, "registered in a nested scope",
                                                proportional("origin-inner-" + run));
    }
    registry.add("origin-outer-again-" + run, "registered after the nested scope ended",
                 proportional("origin-outer-again-" + run), kPluginInterfaceVersion);
  }
  registry.add("origin-after-" + run, "registered after every scope ended", proportional("origin-after-" + run),
               kPluginInterfaceVersion);
  EXPECT_EQ(registry.origin("origin-outer-" + run), "plugin /path/to/libouter.so");
  EXPECT_EQ(registry.origin("origin-inner-" + run), "plugin /path/to/libinner.so");
  EXPECT_EQ(registry.origin("origin-outer-again-" + run), "plugin /path/to/libouter.so");
  EXPECT_EQ(registry.origin("origin-after-" + run), "built-in");
  EXPECT_THAT([&] { registry.origin("nonesuch"); },
              ::testing::ThrowsMessage<Error>(HasSubstr("unknown controller 'nonesuch' (known: ")));

  // What a run records (name()) is what the user asked for, or it plus a variant's suffix.
  const heli::Helicopter model;
  const std::string name = "origin-after-" + run;
  EXPECT_EQ(registry.make(name, {}, hover_context(model))->name(), name);
  EXPECT_EQ(registry.make(name, YAML::Load("calls_itself: " + name + "-fast"), hover_context(model))->name(),
            name + "-fast");
  for (const std::string& other : {std::string("proportional"), name + "fast", std::string("origin-after")}) {
    EXPECT_THAT([&] { registry.make(name, YAML::Load("calls_itself: " + other), hover_context(model)); },
                ::testing::ThrowsMessage<Error>(HasSubstr("controller '" + name + "' (built-in) built a controller "
                                                          "that calls itself '" + other + "': derive it from "
                                                          "NamedController<\"" + name + "\">")))
        << other;
  }
}

}  // namespace
}  // namespace thetad
