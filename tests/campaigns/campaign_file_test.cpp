#include "campaigns/campaign.hpp"

#include <filesystem>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "core/error.hpp"
#include "scenarios/scenario.hpp"

namespace thetad {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

const std::filesystem::path kFile = THETAD_SOURCE_DIR "/scenarios/campaigns/test.yaml";

// The message of the error parsing `text` throws (as if it were kFile).
std::string error_of(const std::string& text) {
  try {
    parse_campaign(text, kFile);
  } catch (const Error& error) {
    return error.what();
  }
  return "no error";
}

const std::string kHead = R"(campaign: tiny
scenarios: [scenario-1]
controllers:
  - {label: td, controller: theta-d}
  - {controller: lqr}
draws: {count: 3, base_seed: 7}
)";

TEST(CampaignFile, AGridIsEveryCombinationWithTheFirstFactorSlowest) {
  const Campaign campaign = parse_campaign(kHead + R"(fixed: {duration_s: 0.5}
sweep:
  grid:
    uncertainty_scale: [0, 1, 2]
    gust_scale: [0.5, 1.5]
)",
                                           kFile);
  EXPECT_EQ(campaign.name, "tiny");
  ASSERT_EQ(campaign.controllers.size(), 2u);
  EXPECT_EQ(campaign.controllers[0].label, "td");
  EXPECT_EQ(campaign.controllers[1].label, "lqr");
  EXPECT_EQ(campaign.draws, 3);
  EXPECT_EQ(campaign.base_seed, 7u);
  EXPECT_EQ(campaign.swept, (std::vector<std::string>{"uncertainty_scale", "gust_scale"}));
  ASSERT_EQ(campaign.cells.size(), 6u);
  const FactorValues second{{"duration_s", 0.5}, {"uncertainty_scale", 0.0}, {"gust_scale", 1.5}};
  EXPECT_EQ(campaign.cells[1], second);
  const FactorValues last{{"duration_s", 0.5}, {"uncertainty_scale", 2.0}, {"gust_scale", 1.5}};
  EXPECT_EQ(campaign.cells[5], last);
  EXPECT_EQ(campaign.run_count(), 6 * 2 * 3);
  EXPECT_EQ(campaign.sha256.size(), 64u);
  EXPECT_TRUE(campaign.summary_only);
}

TEST(CampaignFile, AListGivesItsCellsAndNoSweepGivesOneCell) {
  const Campaign listed = parse_campaign(kHead + R"(sweep:
  list:
    - {noise_scale: 0, initial_offset_x_m: 1}
    - {noise_scale: 2, initial_offset_x_m: -1}
)",
                                         kFile);
  ASSERT_EQ(listed.cells.size(), 2u);
  EXPECT_EQ(listed.cells[1], (FactorValues{{"noise_scale", 2.0}, {"initial_offset_x_m", -1.0}}));
  const Campaign single = parse_campaign(kHead, kFile);
  ASSERT_EQ(single.cells.size(), 1u);
  EXPECT_TRUE(single.cells[0].empty());
  EXPECT_EQ(single.run_count(), 6);
}

// Campaign files written before docs/glossary.md put the unit last keep their meaning: the old
// factor keys read as the new ones, and a factor given under both names is an error.
TEST(CampaignFile, TheFactorsOldNamesStillReadAsTheNewOnes) {
  const Campaign old = parse_campaign(kHead + R"(fixed: {duration: 0.5, dt: 0.0005, gust_onset: 1, servo_delay: 2}
sweep:
  grid:
    initial_offset_z: [0, -1]
    initial_offset_pitch: [3]
    servo_time_constant: [0.02]
)",
                                     kFile);
  EXPECT_EQ(old.swept,
            (std::vector<std::string>{"initial_offset_z_m", "initial_offset_pitch_deg", "servo_time_constant_s"}));
  ASSERT_EQ(old.cells.size(), 2u);
  EXPECT_EQ(old.cells[1], (FactorValues{{"duration_s", 0.5},
                                        {"dt_s", 0.0005},
                                        {"gust_onset_s", 1.0},
                                        {"servo_delay_samples", 2.0},
                                        {"initial_offset_z_m", -1.0},
                                        {"initial_offset_pitch_deg", 3.0},
                                        {"servo_time_constant_s", 0.02}}));
  const Campaign listed = parse_campaign(kHead + "sweep:\n  list:\n    - {initial_offset_x: 1, initial_offset_roll: 2}\n"
                                                 "    - {initial_offset_x_m: 3, initial_offset_roll_deg: 4}\n",
                                         kFile);
  EXPECT_EQ(listed.swept, (std::vector<std::string>{"initial_offset_x_m", "initial_offset_roll_deg"}));
  EXPECT_EQ(listed.cells[0], (FactorValues{{"initial_offset_x_m", 1.0}, {"initial_offset_roll_deg", 2.0}}));
  EXPECT_EQ(listed.cells[1], (FactorValues{{"initial_offset_x_m", 3.0}, {"initial_offset_roll_deg", 4.0}}));
  EXPECT_THAT(error_of(kHead + "fixed: {duration: 1, duration_s: 2}\n"),
              HasSubstr("field 'fixed.duration_s': factor 'duration_s' is given twice"));
  EXPECT_THAT(error_of(kHead + "sweep: {grid: {initial_offset_yaw: [1], initial_offset_yaw_deg: [2]}}\n"),
              HasSubstr("field 'sweep.grid.initial_offset_yaw_deg': factor 'initial_offset_yaw_deg' is given twice"));
  EXPECT_THAT(error_of(kHead + "fixed: {dt: 0.001}\nsweep: {grid: {dt_s: [0.001]}}\n"),
              HasSubstr("field 'sweep.grid.dt_s': factor 'dt_s' is also fixed"));
}

// base_seed is an unsigned 64-bit number like --seed: all of it is read, and what is not a whole
// number in range is an error (not wrapped, not saturated, not cut to an int).
TEST(CampaignFile, TheBaseSeedIsAnyUnsigned64BitNumberAndNothingElse) {
  const auto with_seed = [](const std::string& seed) {
    return "campaign: x\nscenarios: [scenario-1]\ncontrollers: [{controller: lqr}]\ndraws: {count: 1, base_seed: " +
           seed + "}\n";
  };
  EXPECT_EQ(parse_campaign(with_seed("18446744073709551615"), kFile).base_seed, 18446744073709551615u);
  EXPECT_EQ(parse_campaign(with_seed("4294967296"), kFile).base_seed, 4294967296u);
  EXPECT_EQ(parse_campaign(with_seed("0"), kFile).base_seed, 0u);
  for (const std::string seed : {"-1", "18446744073709551616", "''", "1.5", "0x10", "[1]"}) {
    EXPECT_THAT(error_of(with_seed(seed)), AllOf(HasSubstr(kFile.string() + ":4:30: field 'draws.base_seed'"),
                                                 HasSubstr("expected a whole number from 0 to 18446744073709551615")))
        << seed;
  }
}

TEST(CampaignFile, ErrorsNameTheFileTheLineAndTheField) {
  const std::string file = kFile.string();
  EXPECT_THAT(error_of(kHead + "drwas: 3\n"),
              AllOf(HasSubstr(file + ":7:1: field 'drwas'"), HasSubstr("unknown")));
  EXPECT_THAT(error_of(kHead + "sweep:\n  grid:\n    gust_scael: [1, 2]\n"),
              AllOf(HasSubstr(file + ":9:5: field 'sweep.grid.gust_scael'"), HasSubstr("unknown factor"),
                    HasSubstr("gust_scale")));
  EXPECT_THAT(error_of(kHead + "sweep:\n  grid:\n    uncertainty_scale: [1, -2]\n"),
              AllOf(HasSubstr(file + ":9:28: field 'sweep.grid.uncertainty_scale[1]'"), HasSubstr("outside")));
  EXPECT_THAT(error_of(kHead + "fixed: {noise_scale: loud}\n"),
              AllOf(HasSubstr(file + ":7:22: field 'fixed.noise_scale'"), HasSubstr("expected a number")));
  EXPECT_THAT(error_of(kHead + "fixed: {gust_scale: 1}\nsweep: {grid: {gust_scale: [1, 2]}}\n"),
              HasSubstr("field 'sweep.grid.gust_scale': factor 'gust_scale' is also fixed"));
  EXPECT_THAT(error_of(kHead + "sweep:\n  list:\n    - {noise_scale: 1}\n    - {gust_scale: 1}\n"),
              AllOf(HasSubstr(file + ":10:7: field 'sweep.list[1]'"), HasSubstr("same factors")));
  EXPECT_THAT(error_of("campaign: x\nscenarios: [no-such-scenario]\ncontrollers: [{controller: lqr}]\ndraws: {count: 1}\n"),
              AllOf(HasSubstr(file + ":2:13: field 'scenarios[0]'"), HasSubstr("no-such-scenario")));
  EXPECT_THAT(error_of("campaign: x\nscenarios: [scenario-1]\ncontrollers: [{controller: nope}]\ndraws: {count: 1}\n"),
              AllOf(HasSubstr(file + ":3:"), HasSubstr("field 'controllers[0].controller'"), HasSubstr("unknown controller")));
  EXPECT_THAT(error_of("campaign: x\nscenarios: [scenario-1]\ncontrollers: [{controller: lqr}, {controller: lqr}]\ndraws: {count: 1}\n"),
              HasSubstr("lqr"));
  EXPECT_THAT(error_of("campaign: x\nscenarios: [scenario-1]\ncontrollers: [{controller: lqr}]\ndraws: {count: 0}\n"),
              AllOf(HasSubstr(file + ":4:"), HasSubstr("field 'draws.count'")));
  EXPECT_THAT(error_of("campaign: x\nscenarios: [scenario-1]\ncontrollers: [{controller: lqr}]\n"),
              HasSubstr("field 'draws': missing"));
  EXPECT_THAT(error_of("campaign: [unclosed\n"), HasSubstr(file + ":"));
}

// Caught before the grid is expanded in memory, and before the run count could overflow.
TEST(CampaignFile, AHugeGridOrRunCountIsRefusedUpFront) {
  std::string values = "[0";
  for (int i = 1; i < 101; ++i) values += ", " + std::to_string(i / 100.0);
  values += "]";
  std::string grid = "sweep:\n  grid:\n";
  for (const char* factor : {"uncertainty_scale", "gust_scale", "noise_scale"})
    grid += std::string("    ") + factor + ": " + values + "\n";
  EXPECT_THAT(error_of(kHead + grid),
              AllOf(HasSubstr(kFile.string() + ":11:18: field 'sweep.grid.noise_scale'"),
                    HasSubstr("would have 1030301 cells, more than the 1000000")));
  const std::string many_draws = R"(campaign: x
scenarios: [scenario-1]
controllers: [{controller: lqr}, {controller: theta-d}]
draws: {count: 1000000}
sweep: {grid: {gust_scale: )" + values + ", noise_scale: " + values + "}}\n";
  EXPECT_THAT(error_of(many_draws), AllOf(HasSubstr(kFile.string() + ":4:"), HasSubstr("field 'draws.count'"),
                                          HasSubstr("would fly 2.0402e+10 runs")));
}

TEST(CampaignFile, TheShippedCampaignsAreValid) {
  const std::filesystem::path folder = THETAD_SOURCE_DIR "/scenarios/campaigns";
  const Campaign paired = load_campaign(folder / "scenario-1-paired.yaml");
  EXPECT_EQ(paired.run_count(), 3 * 200);
  const Campaign envelope = load_campaign(folder / "envelope.yaml");
  EXPECT_EQ(envelope.cells.size(), 36u);
  EXPECT_EQ(envelope.run_count(), 36 * 20 * 2);
  EXPECT_EQ(load_campaign(folder / "scenario-1-paired-fast.yaml").base_seed, paired.base_seed);
  EXPECT_EQ(load_campaign(folder / "envelope-sdre.yaml").cells.size(), 9u);
  const Campaign quick = load_campaign(folder / "envelope-quick.yaml");
  ASSERT_EQ(quick.cells.size(), envelope.cells.size());
  for (std::size_t i = 0; i < quick.cells.size(); ++i) {
    FactorValues swept = quick.cells[i];
    swept.erase(swept.begin());  // the fixed duration
    EXPECT_EQ(swept, envelope.cells[i]) << i;
  }
  EXPECT_EQ(load_campaign(folder / "scenario-1-paired-sdre.yaml").controllers.size(), 3u);
  const Campaign wide = load_campaign(folder / "envelope-wide.yaml");
  EXPECT_EQ(wide.run_count(), 4 * 5 * 4 * 2);
  EXPECT_EQ(wide.base_seed, envelope.base_seed);
  // The fair study: 4 controllers x 3 information sets x 2 weight sets, labelled by all three.
  const std::filesystem::path fair = folder / "fair";
  const Campaign scenario_1 = load_campaign(fair / "scenario-1.yaml");
  ASSERT_EQ(scenario_1.controllers.size(), 24u);
  EXPECT_EQ(scenario_1.controllers.front().label, "theta-d.paper.none");
  EXPECT_EQ(scenario_1.controllers.back().label, "lqr-scheduled.designed.velocity+trim");
  EXPECT_EQ(scenario_1.controllers.back().settings["feedforward"].as<std::string>(), "velocity+trim");
  EXPECT_EQ(scenario_1.run_count(), 24 * 10);
  const Campaign legs = load_campaign(fair / "legs.yaml");
  EXPECT_EQ(legs.cells.size(), 4u);  // the courses
  EXPECT_EQ(legs.run_count(), 4 * 4 * 24 * 5);
  EXPECT_EQ(load_campaign(fair / "legs-20.yaml").run_count(), 2 * 24 * 5);
  EXPECT_EQ(load_campaign(fair / "theta-d-ablation.yaml").run_count(), 2 * 10 * 10);
  // The legs in turbulence, and the tuned weights on the same draws (paired with them).
  const Campaign turbulent = load_campaign(fair / "legs-turbulent.yaml");
  const Campaign tuned = load_campaign(fair / "legs-turbulent-tuned.yaml");
  EXPECT_EQ(turbulent.run_count(), 4 * 4 * 24 * 5);
  EXPECT_EQ(tuned.run_count(), 4 * 4 * 12 * 5);
  EXPECT_EQ(tuned.cells, turbulent.cells);
  EXPECT_EQ(tuned.base_seed, turbulent.base_seed);
  EXPECT_EQ(tuned.draws, turbulent.draws);
  EXPECT_EQ(tuned.scenarios, turbulent.scenarios);
  EXPECT_EQ(tuned.controllers.front().label, "theta-d.tuned.none");
  EXPECT_EQ(tuned.controllers.front().settings["feedforward"].as<std::string>(), "none");
  // The computer in the loop and the turbulence study (docs/robustness.md (e), (f)).
  const Campaign slowdown = load_campaign(folder / "computer" / "slowdown.yaml");
  EXPECT_EQ(slowdown.run_count(), 6 * 3 * 2);
  EXPECT_EQ(slowdown.controllers.back().label, "sdre-cold");
  EXPECT_EQ(load_campaign(folder / "robustness" / "turbulence.yaml").run_count(), 2 * 3 * 4 * 3);
}

// Every campaign file shipped reads, with its scenarios and its controllers' settings files; the
// other files beside them are the scenarios they fly, and read as scenarios.
TEST(CampaignFile, EveryShippedCampaignLoads) {
  int campaigns = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(THETAD_SOURCE_DIR "/scenarios/campaigns")) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".yaml" || name.find(".settings.") != std::string::npos) continue;
    if (YAML::LoadFile(entry.path().string())["campaign"]) {
      EXPECT_NO_THROW(load_campaign(entry.path())) << entry.path();
      ++campaigns;
    } else {
      EXPECT_NO_THROW(load_scenario(entry.path())) << entry.path();
    }
  }
  EXPECT_GE(campaigns, 17);
}

}  // namespace
}  // namespace thetad
