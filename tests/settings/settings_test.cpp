#include <gtest/gtest.h>
#include <gmock/gmock.h>

#include <string>
#include <vector>

#include "settings/settings.hpp"

namespace thetad {
namespace {

using ::testing::HasSubstr;

// The block sits under `controller:` so that line and column differ from (1, 1).
YAML::Node block(const std::string& text) { return YAML::Load("controller:\n" + text)["controller"]; }

// Runs `read` and returns the SettingsError it must throw.
template <class Read>
SettingsError settings_error_of(Read read) {
  try {
    read();
  } catch (const SettingsError& error) {
    return error;
  }
  ADD_FAILURE() << "no SettingsError";
  return {"", "", YAML::Mark::null_mark()};
}

void expect_error(const SettingsError& error, const std::string& message) {
  EXPECT_EQ(std::string(error.what()), message);
}

TEST(Settings, MissingFieldsTakeTheirDefaults) {
  const Settings fields(block("  mode: warm\n"));
  EXPECT_EQ(fields.number("gain", 2.5), 2.5);
  EXPECT_EQ(fields.integer("count", 3), 3);
  EXPECT_TRUE(fields.boolean("flag", true));
  EXPECT_EQ(fields.string("name", "x"), "x");
  EXPECT_EQ(fields.vector("v", Eigen::Vector2d(1, 2), 2), Eigen::Vector2d(1, 2));
  EXPECT_EQ(fields.diagonal_weight("Q", Eigen::Vector2d(1, 0), Settings::Weight::positive_semidefinite),
            Eigen::Matrix2d(Eigen::Vector2d(1, 0).asDiagonal()));
  // No block at all: every default.
  EXPECT_EQ(Settings(YAML::Node()).number("gain", 1.0), 1.0);
}

TEST(Settings, ReadsPresentFields) {
  const Settings fields(block("  gain: 1e4\n  count: 7\n  flag: false\n  mode: warm\n  v: [1, 2.5]\n  R: [1, 200]\n"));
  fields.allow_only({"gain", "count", "flag", "mode", "v", "R"});
  EXPECT_EQ(fields.number("gain", 0.0), 1e4);
  EXPECT_EQ(fields.integer("count", 0), 7);
  EXPECT_FALSE(fields.boolean("flag", true));
  EXPECT_EQ(fields.choice("mode", "cold", {"cold", "warm"}), "warm");
  EXPECT_EQ(fields.vector("v", Eigen::Vector2d::Zero(), 2), Eigen::Vector2d(1, 2.5));
  EXPECT_EQ(fields.diagonal_weight("R", Eigen::Vector2d::Ones(), Settings::Weight::positive_definite),
            Eigen::Matrix2d(Eigen::Vector2d(1, 200).asDiagonal()));
}

TEST(Settings, UnknownFieldIsNamedWithItsLineAndTheAllowedOnes) {
  const Settings fields(block("  mode: warm\n  Qx: [1]\n"));
  expect_error(settings_error_of([&] { fields.allow_only({"mode", "Q", "R"}); }),
               "3:3: field 'Qx': unknown field (allowed: mode, Q, R)");
}

TEST(Settings, EveryHelperNamesFieldReasonAndLine) {
  const Settings fields(block("  x: abc\n  n: 2.5\n  b: maybe\n  s: [1]\n  m: hot\n  v: [1, 2, 3]\n"
                              "  w: [1, .inf]\n  lo: -3\n  big: 99\n  Q: [1, -1]\n  R: [1, 0]\n  seq: 4\n"));
  expect_error(settings_error_of([&] { fields.number("x", 0); }), "2:6: field 'x': expected a number, got 'abc'");
  expect_error(settings_error_of([&] { fields.integer("n", 0); }), "3:6: field 'n': expected an integer, got '2.5'");
  expect_error(settings_error_of([&] { fields.boolean("b", false); }), "4:6: field 'b': expected true or false, got 'maybe'");
  expect_error(settings_error_of([&] { fields.string("s", ""); }), "5:6: field 's': expected a string, got a sequence");
  expect_error(settings_error_of([&] { fields.choice("m", "cold", {"cold", "warm"}); }),
               "6:6: field 'm': expected one of cold, warm, got 'hot'");
  expect_error(settings_error_of([&] { fields.vector("v", Eigen::Vector2d::Zero(), 2); }),
               "7:6: field 'v': expected 2 entries, got 3");
  expect_error(settings_error_of([&] { fields.vector("w", Eigen::Vector2d::Zero(), 2); }),
               "8:10: field 'w[1]': expected a finite number, got .inf");
  expect_error(settings_error_of([&] { fields.number("lo", 0, 0.0, 1.0); }),
               "9:7: field 'lo': expected a number in [0, 1], got -3");
  expect_error(settings_error_of([&] { fields.integer("big", 0, 1, 10); }),
               "10:8: field 'big': expected an integer in [1, 10], got 99");
  expect_error(settings_error_of([&] { fields.diagonal_weight("Q", Eigen::Vector2d::Ones(), Settings::Weight::positive_semidefinite); }),
               "11:10: field 'Q[1]': expected a number in [0, inf], got -1");
  expect_error(settings_error_of([&] { fields.diagonal_weight("R", Eigen::Vector2d::Ones(), Settings::Weight::positive_definite); }),
               "12:10: field 'R[1]': expected a positive number (the weight must be positive definite), got 0");
  expect_error(settings_error_of([&] { fields.vector("seq", Eigen::Vector2d::Zero(), 2); }),
               "13:8: field 'seq': expected a sequence of 2 numbers, got '4'");
}

TEST(Settings, ErrorOnAMissingFieldPointsAtTheBlock) {
  const Settings fields(block("  a: 1\n"), "controller");
  const SettingsError error = fields.error("b", "required with a");
  EXPECT_EQ(error.field(), "controller.b");
  EXPECT_EQ(error.line(), 2);
  EXPECT_EQ(error.column(), 3);
  EXPECT_EQ(std::string(error.what()), "2:3: field 'controller.b': required with a");
}

TEST(Settings, ABlockThatIsNotAMapIsRejected) {
  expect_error(settings_error_of([] { Settings(block("  - 1\n  - 2\n"), "controller"); }),
               "2:3: field 'controller': expected a map of fields, got a sequence");
}

TEST(Settings, NodesBuiltInCodeHaveNoPosition) {
  YAML::Node node;
  node["gain"] = "high";
  expect_error(settings_error_of([&] { Settings(node).number("gain", 0); }), "field 'gain': expected a number, got 'high'");
}

TEST(Settings, TheCallerAddsTheFileName) {
  const YAML::Node scenario = YAML::Load("name: hover\n\ncontroller:\n  type: sdre\n  settings:\n"
                                         "    Q: [1, 2, 3]\n");
  const auto read = [&] {
    return Settings(scenario["controller"]["settings"]).vector("Q", Eigen::Vector4d::Zero(), 4);
  };
  try {
    with_settings_source("scenario-1.yaml", read);
    FAIL() << "no error";
  } catch (const SettingsError& error) {
    EXPECT_EQ(std::string(error.what()), "scenario-1.yaml:6:8: field 'Q': expected 4 entries, got 3");
    EXPECT_EQ(error.source(), "scenario-1.yaml");
    EXPECT_EQ(error.line(), 6);
    EXPECT_THAT(error.reason(), HasSubstr("expected 4 entries"));
  }
  // A read that succeeds passes its value through.
  const YAML::Node good = YAML::Load("Q: [1, 2, 3, 4]");
  EXPECT_EQ(with_settings_source("f.yaml", [&] { return Settings(good).vector("Q", Eigen::Vector4d::Zero(), 4); }),
            Eigen::Vector4d(1, 2, 3, 4));
}

TEST(Settings, ResolvedHoldsEveryFieldReadWithTheValueUsed) {
  const Settings fields(block("  gain: 0.1\n  grid:\n    speeds: [0, 5]\n"));
  fields.number("gain", 2.5);
  fields.integer("count", 3);
  fields.choice("mode", "warm", {"cold", "warm"});
  fields.vector("v", Eigen::Vector2d(1.0 / 3.0, 2), 2);
  const Settings grid = fields.block("grid");
  grid.vector("speeds", Eigen::Vector2d::Zero(), 2);
  grid.number("altitude", 3.5);
  fields.block("absent").boolean("flag", true);

  const YAML::Node resolved = fields.resolved();
  EXPECT_EQ(resolved["gain"].as<double>(), 0.1);
  EXPECT_EQ(resolved["count"].as<int>(), 3);
  EXPECT_EQ(resolved["mode"].as<std::string>(), "warm");
  // Recorded values round-trip exactly, so a run rebuilt from them is the same run.
  EXPECT_EQ(resolved["v"][0].as<double>(), 1.0 / 3.0);
  EXPECT_EQ(resolved["grid"]["speeds"][1].as<double>(), 5.0);
  EXPECT_EQ(resolved["grid"]["altitude"].as<double>(), 3.5);
  EXPECT_TRUE(resolved["absent"]["flag"].as<bool>());
  EXPECT_EQ(resolved.size(), 6u);
  // A block's own record is its part of the whole.
  EXPECT_EQ(grid.resolved().size(), 6u);
  // A fresh block records nothing it was not asked for.
  EXPECT_EQ(Settings(block("  gain: 1\n")).resolved().size(), 0u);
}

TEST(Settings, AListTakesAnyLengthAndIsRecorded) {
  const Settings fields(block("  speeds: [0, 2.5, 4]\n  none: []\n  bad: [1, x]\n  scalar: 3\n"));
  EXPECT_EQ(fields.list("speeds", {}), (std::vector<double>{0.0, 2.5, 4.0}));
  EXPECT_TRUE(fields.list("none", {1.0}).empty());
  EXPECT_EQ(fields.list("absent", {1.0, 2.0}), (std::vector<double>{1.0, 2.0}));
  const YAML::Node resolved = fields.resolved();
  EXPECT_EQ(resolved["speeds"].as<std::vector<double>>(), (std::vector<double>{0.0, 2.5, 4.0}));
  EXPECT_TRUE(resolved["none"].IsSequence());
  EXPECT_EQ(resolved["none"].size(), 0u);
  EXPECT_EQ(resolved["absent"].as<std::vector<double>>(), (std::vector<double>{1.0, 2.0}));
  expect_error(settings_error_of([&] { fields.list("bad", {}); }), "4:12: field 'bad[1]': expected a number, got 'x'");
  expect_error(settings_error_of([&] { fields.list("scalar", {}); }),
               "5:11: field 'scalar': expected a sequence of numbers, got '3'");
  expect_error(settings_error_of([&] { fields.list("speeds", {}, 0.0, 3.0); }),
               "2:20: field 'speeds[2]': expected a number in [0, 3], got 4");
}

TEST(Settings, ANestedBlockMustBeAMapAndNamesItsPath) {
  const Settings fields(block("  grid: 3\n"));
  expect_error(settings_error_of([&] { fields.block("grid"); }), "2:9: field 'grid': expected a map of fields, got '3'");
}

}  // namespace
}  // namespace thetad
