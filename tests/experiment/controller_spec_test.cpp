#include "experiment/controller_spec.hpp"

#include <filesystem>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "tests/error_message.hpp"
#include "tests/scratch_directory.hpp"

namespace thetad {
namespace {

using testing::error_message;
using ::testing::HasSubstr;

class ControllerSpecs : public ::testing::Test {
 protected:
  void SetUp() override {
    std::ofstream(dir_ / "tuned.yaml") << "theta-d:\n  k: [0.5, 0.25]\n  l: [2, 3]\n";
    std::ofstream(dir_ / "other.yaml") << "sdre:\n  mode: cold\n";
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  testing::ScratchDirectory scratch_{"thetad_controller_spec_test"};
  const std::filesystem::path dir_ = scratch_.path();
};

TEST_F(ControllerSpecs, TheFourFormsNameLabelControllerAndSettings) {
  const ControllerSpec plain = parse_controller_spec("sdre");
  EXPECT_EQ(plain.label, "sdre");
  EXPECT_EQ(plain.controller, "sdre");
  EXPECT_TRUE(plain.settings.IsNull());

  const ControllerSpec labelled = parse_controller_spec("paper=theta-d");
  EXPECT_EQ(labelled.label, "paper");
  EXPECT_EQ(labelled.controller, "theta-d");

  const ControllerSpec filed = parse_controller_spec("theta-d:" + path("tuned.yaml"));
  EXPECT_EQ(filed.label, "theta-d");
  EXPECT_EQ(filed.settings["k"][1].as<double>(), 0.25);
  EXPECT_EQ(filed.settings_source, path("tuned.yaml"));

  const ControllerSpec both = parse_controller_spec("tuned=theta-d:" + path("tuned.yaml"));
  EXPECT_EQ(both.label, "tuned");
  EXPECT_EQ(both.settings["l"][0].as<double>(), 2.0);
}

TEST_F(ControllerSpecs, WithoutAFileTheFallbackBlockOfTheControllerIsUsed) {
  const YAML::Node fallback = load_settings_file(path("other.yaml"));
  const ControllerSpec sdre = parse_controller_spec("cold=sdre", fallback, path("other.yaml"));
  EXPECT_EQ(sdre.settings["mode"].as<std::string>(), "cold");
  EXPECT_EQ(sdre.settings_source, path("other.yaml"));
  EXPECT_TRUE(parse_controller_spec("theta-d", fallback, path("other.yaml")).settings.IsNull());
}

TEST_F(ControllerSpecs, BadSpecsAreErrorsNamingWhatIsWrong) {
  EXPECT_THAT(error_message([] { parse_controller_spec("nope"); }), HasSubstr("unknown controller 'nope' (known: "));
  EXPECT_THAT(error_message([] { parse_controller_spec("a=theta-d:"); }), HasSubstr("no settings file after ':'"));
  EXPECT_THAT(error_message([&] { parse_controller_spec("sdre:" + path("tuned.yaml")); }),
              HasSubstr("has no block for 'sdre'"));
  EXPECT_THAT(error_message([&] { parse_controller_spec("x=theta-d:" + path("missing.yaml")); }),
              HasSubstr("cannot read " + path("missing.yaml") + ": No such file or directory"));
  for (const char* label : {"../up", ".hidden", "-flag", "a b", "tab\t", "x/y"})
    EXPECT_THAT(error_message([&] { parse_controller_spec(std::string(label) + "=sdre"); }), HasSubstr("label '")) << label;
  EXPECT_THAT(error_message([] { parse_controller_spec(std::string(65, 'a') + "=sdre"); }), HasSubstr("1-64 characters"));
  EXPECT_THAT(error_message([] { parse_controller_spec("=sdre"); }),
              HasSubstr("controller '=sdre': an empty label before '='"));
  // Bytes that are not UTF-8 are echoed escaped, so the message is UTF-8.
  EXPECT_THAT(error_message([] { parse_controller_spec("caf\xc3=sdre"); }), HasSubstr("label 'caf\\xC3'"));
  EXPECT_THAT(error_message([] { parse_controller_spec("sd\xffre"); }), HasSubstr("unknown controller 'sd\\xFFre'"));
}

TEST_F(ControllerSpecs, ASettingsBlockThatIsNotAMapIsNamedByItsController) {
  std::ofstream(dir_ / "scalar.yaml") << "theta-d: 5\n";
  EXPECT_THAT(error_message([&] { load_settings_file(dir_ / "scalar.yaml"); }),
              HasSubstr(path("scalar.yaml") + ":1:10: field 'theta-d': expected a map of fields, got '5'"));
}

TEST_F(ControllerSpecs, ALabelMayNotRepeat) {
  const std::vector<ControllerSpec> specs{parse_controller_spec("theta-d"), parse_controller_spec("theta-d")};
  EXPECT_THAT(error_message([&] { check_labels(specs); }), HasSubstr("label 'theta-d' is used twice"));
  check_labels({parse_controller_spec("theta-d"), parse_controller_spec("tuned=theta-d:" + path("tuned.yaml"))});
  EXPECT_THAT(error_message([] { check_labels({parse_controller_spec("A=sdre"), parse_controller_spec("a=lqr")}); }),
              HasSubstr("label 'a' is used twice (as 'A': labels name files)"));
  EXPECT_THAT(error_message([] { parse_controller_spec("Comparison=sdre"); }), HasSubstr("comparison.json"));
}

TEST_F(ControllerSpecs, AYamlListGivesLabelledSpecsWithInlineOrFiledSettings) {
  const std::string source = path("compare.yaml");
  const YAML::Node list = YAML::Load(
      "- {label: paper, controller: theta-d}\n"
      "- {label: tuned, controller: theta-d, settings: tuned.yaml}\n"
      "- {controller: sdre, settings: {mode: cold}}\n");
  const std::vector<ControllerSpec> specs = read_controller_specs(list, source);
  ASSERT_EQ(specs.size(), 3u);
  EXPECT_EQ(specs[0].label, "paper");
  EXPECT_TRUE(specs[0].settings.IsNull());
  EXPECT_EQ(specs[1].settings["k"][0].as<double>(), 0.5);
  EXPECT_EQ(specs[1].settings_source, path("tuned.yaml"));
  EXPECT_EQ(specs[2].label, "sdre");
  EXPECT_EQ(specs[2].settings["mode"].as<std::string>(), "cold");
  EXPECT_EQ(specs[2].settings_source, source);

  EXPECT_THAT(error_message([&] { read_controller_specs(YAML::Load("- {controller: sdre, gain: 1}"), source); }),
              HasSubstr("compare.yaml:1:22: field 'controllers[0].gain': unknown field"));
  EXPECT_THAT(error_message([&] { read_controller_specs(YAML::Load("- {label: a}"), source); }),
              HasSubstr("field 'controllers[0].controller': missing"));
  EXPECT_THAT(error_message([&] { read_controller_specs(YAML::Load("- {controller: sdre}\n- {controller: sdre}"), source); }),
              HasSubstr("used twice"));
  EXPECT_THAT(error_message([&] { read_controller_specs(YAML::Load("[]"), source); }), HasSubstr("non-empty list"));
}

TEST_F(ControllerSpecs, ASettingsFileMayOnlyNameRegisteredControllers) {
  std::ofstream(dir_ / "typo.yaml") << "theta_d:\n  k: [1, 1]\n";
  EXPECT_THAT(error_message([&] { load_settings_file(path("typo.yaml")); }),
              HasSubstr("typo.yaml:1:1: field 'theta_d': unknown controller"));
}

}  // namespace
}  // namespace thetad
