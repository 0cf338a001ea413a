// The RTAC/TORA benchmark (docs/plants.md) through every front end of the command line, as a user
// runs them: the shipped scenario files that name the plant (scenarios/tora/), flown by θ–D, the
// SDRE and the LQR at the plant's design point, on short horizons; the plant's own factors; the
// errors of a plant's scenario file, each naming the file, the field and the reason; and the example
// plant plug-in (experiment/examples/pendulum-plugin) through a campaign.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "campaigns/campaign.hpp"
#include "campaigns/campaign_store.hpp"
#include "experiment/scenario_files.hpp"
#include "tests/apps/run_thetad.hpp"
#include "tests/scratch_directory.hpp"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using thetad::testing::Output;

constexpr const char* kControllers = " --controllers theta-d,sdre,lqr";

class PlantFrontEnds : public ::testing::Test {
 protected:
  Output thetad(const std::string& arguments) const { return thetad::testing::run_thetad(dir_, arguments); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  nlohmann::json read(const std::string& file) const {
    return nlohmann::json::parse(thetad::testing::read_text(dir_ / file));
  }
  // A scenario file `name` in the scratch folder with `text`; returns its path.
  std::string scenario(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
    return path(name);
  }
  // The records of the campaign `text`, written to the file `name` and run into `name`.out.
  std::vector<thetad::RunRecord> campaign(const std::string& name, const std::string& text,
                                          const std::string& plugin = "") const {
    const Output output = thetad(plugin + "campaign run " + scenario(name, text) +
                                 " --jobs 2 --no-timing --quiet --out " + path(name + ".out"));
    EXPECT_EQ(output.status, 0) << output.err;
    return thetad::CampaignStore(dir_ / (name + ".out") / "campaign.sqlite").records();
  }

  thetad::testing::ScratchDirectory scratch_{"thetad_plant_front_ends_test"};
  const fs::path dir_ = scratch_.path();
};

TEST_F(PlantFrontEnds, CompareFliesTheShippedScenarioInThePlantsColumnsAndPlotDrawsThem) {
  const Output output = thetad("compare --scenario tora/regulation" + std::string(kControllers) +
                               " --duration 2 --no-timing --quiet --out " + path("compare"));
  ASSERT_EQ(output.status, 0) << output.err;
  EXPECT_THAT(output.out, HasSubstr("tora-regulation (2 s, seed 1, ideal"));
  for (const std::string label : {"theta-d", "sdre", "lqr"}) {
    const nlohmann::json result = read("compare/" + label + ".json");
    EXPECT_EQ(result["status"], "completed") << label;
    EXPECT_EQ(result["controller_samples"], 2000) << label;
    EXPECT_EQ(result["provenance"]["plant"], "tora") << label;
    EXPECT_EQ(result["provenance"]["scenario"]["name"], "tora-regulation") << label;
    EXPECT_EQ(result["provenance"]["initial_state"], nlohmann::json::array({1.0, 0.0, 0.0, 0.0})) << label;
    const std::string csv = thetad::testing::read_text(dir_ / "compare" / (label + ".csv"));
    EXPECT_EQ(csv.substr(0, csv.find('\n')),
              "t_s,xi,xi_dot,theta_rad,theta_dot_rad_per_s,meas_xi,meas_xi_dot,meas_theta_rad,"
              "meas_theta_dot_rad_per_s,cmd_torque,app_torque");
  }
  // --plant is the shorthand of the same flight: the same run, bit for bit.
  const Output shorthand = thetad("compare --plant tora --initial-state 1,0,0,0 --controllers sdre --duration 2 "
                                  "--no-timing --quiet --out " + path("shorthand"));
  ASSERT_EQ(shorthand.status, 0) << shorthand.err;
  EXPECT_EQ(read("shorthand/sdre.json")["cost"], read("compare/sdre.json")["cost"]);

  const Output plot = thetad("plot --in " + path("compare") + " --out " + path("figures"));
  ASSERT_EQ(plot.status, 0) << plot.err;
  for (const char* figure : {"states.png", "inputs.png", "compute_time.png"})
    EXPECT_TRUE(fs::exists(dir_ / "figures" / figure)) << figure << "\n" << plot.out;
  EXPECT_FALSE(fs::exists(dir_ / "figures" / "trajectory_3d.png"));
}

TEST_F(PlantFrontEnds, ARunOfAPlantsScenarioReplaysBitForBit) {
  const Output run = thetad("run --scenario tora/strong-coupling --controller theta-d --duration 2 --quiet --out " +
                            path("run"));
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("theta-d on tora-strong-coupling (2 s, seed 1, ideal"));
  EXPECT_EQ(read("run/theta-d.json")["provenance"]["initial_state"], nlohmann::json::array({1.5, 0.0, 0.0, 0.0}));
  const Output again = thetad("run --replay " + path("run/theta-d.json"));
  EXPECT_EQ(again.status, 0) << again.err;
  EXPECT_THAT(again.out, HasSubstr("bit for bit"));
}

TEST_F(PlantFrontEnds, BenchTimesTheStepsOnStatesOfThePlant) {
  const Output output = thetad("bench --scenario tora/regulation" + std::string(kControllers) +
                               " --duration 1 --samples 50 --segments 5 --repetitions 2 --warmup 0 --cpu -2 --quiet "
                               "--out " + path("bench.json"));
  ASSERT_EQ(output.status, 0) << output.err;
  EXPECT_THAT(output.out, HasSubstr("tora-regulation: states recorded along 1 s flown by theta-d"));
  EXPECT_TRUE(fs::exists(dir_ / "bench.json"));
}

TEST_F(PlantFrontEnds, ACampaignSweepsBothScenariosAndTheHorizon) {
  const std::vector<thetad::RunRecord> records =
      campaign("tora.yaml", "campaign: tora-short\nscenarios: [tora/regulation, tora/strong-coupling]\n"
                            "controllers:\n  - {controller: theta-d}\n  - {controller: sdre}\n"
                            "  - {controller: lqr}\ndraws: {count: 1, base_seed: 1}\n"
                            "sweep:\n  grid:\n    duration_s: [0.5, 1]\n");
  ASSERT_EQ(records.size(), 12u);
  const auto& columns = thetad::metric_columns();
  for (const auto& record : records) {
    EXPECT_TRUE(record.completed()) << record.label << " " << record.reason;
    for (std::size_t i = 0; i < columns.size(); ++i) {
      // The cost is the plant's; the helicopter's tracking and input columns are empty (NULL).
      if (columns[i].name == "cost") {
        EXPECT_GT(record.metrics[i], 0.0);
      }
      if (columns[i].name == "rms_command_T_mr_N" || columns[i].name == "rms_error_m") {
        EXPECT_TRUE(std::isnan(record.metrics[i]));
      }
    }
  }
  // The shipped campaign reads: both scenarios, three controllers, three horizons.
  EXPECT_EQ(thetad::load_campaign(thetad::find_campaign("plants/tora")).run_count(), 18);
}

TEST_F(PlantFrontEnds, OptimalComparesWithTheOptimumWithThePlantsJacobianOrDifferences) {
  const Output output = thetad("optimal --scenario tora/regulation" + std::string(kControllers) +
                               " --horizon 1 --cost j --control-interval 0.1 --no-timing --quiet --out " +
                               path("optimal"));
  ASSERT_EQ(output.status, 0) << output.err << output.out;
  EXPECT_THAT(output.err, ::testing::Not(HasSubstr("no Jacobian")));
  const nlohmann::json report = read("optimal/optimality.json");
  EXPECT_TRUE(report["converged"].get<bool>());
  for (const auto& controller : report["controllers"])
    EXPECT_GT(controller["gap_percent"].get<double>(), -1e-3) << controller["label"];

  // The companion oscillator of the test plug-in gives no Jacobian: central differences, said.
  const std::string companion =
      scenario("companion.yaml", "plant: companion\ninitial_state: [0.8, 0.2]\nduration: 1\n");
  const Output differences = thetad(std::string("--plugin ") + THETAD_PLANT_PLUGIN + " optimal --scenario " +
                                    companion + " --controllers sdre --horizon 1 --cost j --control-interval 0.1 "
                                    "--no-timing --quiet --out " + path("differences"));
  ASSERT_EQ(differences.status, 0) << differences.err << differences.out;
  EXPECT_THAT(differences.err, HasSubstr("warning: the plant companion gives no Jacobian"));
}

TEST_F(PlantFrontEnds, TuneFitsThetaDsSeriesOnThePlant) {
  const Output output = thetad("tune --scenario tora/regulation --duration 2 --max-evaluations 30 --no-validation "
                               "--quiet --out " + path("tune"));
  ASSERT_EQ(output.status, 0) << output.err;
  ASSERT_TRUE(fs::exists(dir_ / "tune" / "theta-d-tuned.yaml"));
  const Output tuned = thetad("run --scenario tora/regulation --controller theta-d:" + path("tune/theta-d-tuned.yaml") +
                              " --duration 2 --quiet --out " + path("tuned"));
  EXPECT_EQ(tuned.status, 0) << tuned.err;
}

TEST_F(PlantFrontEnds, APlantsScenarioFileSaysWhatDoesNotApplyToAPlant) {
  const std::string head = "plant: tora\nduration: 2\n";
  const struct {
    std::string file, text, where, message;
  } cases[] = {
      {"wind.yaml", head + "simulation:\n  disturbances: {wind_gust: on}\n", "wind.yaml:4:",
       "field 'simulation.disturbances': the helicopter's; the plant tora flies without"},
      {"phases.yaml", head + "phases:\n  - {type: hold, time: [0, 2]}\n", "phases.yaml:4:",
       "field 'phases': the helicopter's"},
      {"size.yaml", head + "initial_state: [1, 0]\n", "size.yaml (plant tora): ",
       "field 'initial_state' has 2 entries, the plant 4 states"},
      {"unknown.yaml", "plant: nowhere\nduration: 2\n", "unknown.yaml: ",
       "field 'plant': unknown plant 'nowhere' (known: "},
      {"epsilon.yaml", head + "plant_settings: {epsilon: 2}\n", "epsilon.yaml: ",
       "field 'plant_settings': tora: epsilon must lie in (0, 1)"},
      {"typo.yaml", head + "plant_settings: {epsilom: 0.2}\n", "typo.yaml:3:18: ", "field 'epsilom': unknown field"},
  };
  for (const auto& c : cases) {
    const Output output =
        thetad("run --scenario " + scenario(c.file, c.text) + " --controller sdre --quiet --out " + path("out"));
    EXPECT_EQ(output.status, 1) << c.file;
    EXPECT_THAT(output.err, ::testing::AllOf(HasSubstr(c.where), HasSubstr(c.message))) << c.file;
  }
  const Output course = thetad("run --scenario tora/regulation --controller sdre --set course=10 --out " + path("out"));
  EXPECT_EQ(course.status, 1);
  EXPECT_THAT(course.err,
              HasSubstr("(plant tora): initial offsets, speed scales and courses apply to the helicopter's"));
}

// A plant's own factors (docs/campaigns.md): its settings (plant.NAME) and its initial state's
// entries (initial_state.I), swept by a campaign and set by `thetad run --set`; refused, naming the
// factor, where they do not apply.
std::map<std::string, double> plant_factor_values(const thetad::RunRecord& record) {
  return {record.factors.begin(), record.factors.end()};
}

double plant_factor_cost(const thetad::RunRecord& record) {
  const auto& columns = thetad::metric_columns();
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (columns[i].name == "cost") return record.metrics[i];
  }
  return 0.0;
}

TEST_F(PlantFrontEnds, ACampaignSweepsTheCouplingAndTheInitialStateIntoColumnsOfTheirOwn) {
  const std::vector<thetad::RunRecord> records =
      campaign("sweep.yaml", "campaign: tora-factors\nscenarios: [tora/regulation]\ncontrollers:\n"
                             "  - {controller: sdre}\ndraws: {count: 1, base_seed: 1}\nfixed: {duration_s: 2}\n"
                             "sweep:\n  grid:\n    plant.epsilon: [0.2, 0.5]\n    initial_state.0: [0.5, 1]\n");
  ASSERT_EQ(records.size(), 4u);
  std::map<std::pair<double, double>, double> cost;
  for (const auto& record : records) {
    EXPECT_TRUE(record.completed()) << record.reason;
    const auto values = plant_factor_values(record);
    ASSERT_TRUE(values.contains("plant.epsilon") && values.contains("initial_state.0")) << record.index;
    cost[{values.at("plant.epsilon"), values.at("initial_state.0")}] = plant_factor_cost(record);
  }
  ASSERT_EQ(cost.size(), 4u);
  // Twice the start, about four times the cost (the closed loop is nearly linear from here); and
  // the coupling changes the run.
  for (const double epsilon : {0.2, 0.5}) {
    const double ratio = cost.at({epsilon, 1.0}) / cost.at({epsilon, 0.5});
    EXPECT_GT(ratio, 3.0) << epsilon;
    EXPECT_LT(ratio, 5.0) << epsilon;
  }
  EXPECT_NE(cost.at({0.2, 1.0}), cost.at({0.5, 1.0}));
  // The cell (0.2, 1) is the shipped scenario as it is: the same run as without the factors.
  const Output plain = thetad("run --scenario tora/regulation --controller sdre --duration 2 --no-timing --quiet --out " +
                              path("plain"));
  ASSERT_EQ(plain.status, 0) << plain.err;
  EXPECT_EQ(read("plain/sdre.json")["cost"].get<double>(), cost.at({0.2, 1.0}));
}

TEST_F(PlantFrontEnds, RunSetsThemAsTheScenarioFileDoesAndTheRunReplays) {
  const Output set = thetad("run --scenario tora/regulation --controller theta-d --duration 2 --set plant.epsilon=0.5 "
                            "--set initial_state.0=1.5 --no-timing --quiet --out " + path("set"));
  ASSERT_EQ(set.status, 0) << set.err;
  const Output file = thetad("run --scenario tora/strong-coupling --controller theta-d --duration 2 --no-timing "
                             "--quiet --out " + path("file"));
  ASSERT_EQ(file.status, 0) << file.err;
  const Output shorthand = thetad("run --plant tora --set plant.epsilon=0.5 --initial-state 1.5,0,0,0 --controller "
                                  "theta-d --duration 2 --no-timing --quiet --out " + path("shorthand"));
  ASSERT_EQ(shorthand.status, 0) << shorthand.err;
  const nlohmann::json result = read("set/theta-d.json");
  EXPECT_EQ(result["cost"], read("file/theta-d.json")["cost"]);
  EXPECT_EQ(read("shorthand/theta-d.json")["cost"], result["cost"]);
  EXPECT_EQ(result["provenance"]["plant_settings"], nlohmann::json({{"epsilon", 0.5}}));
  EXPECT_EQ(result["provenance"]["initial_state"], nlohmann::json::array({1.5, 0.0, 0.0, 0.0}));
  for (const char* run : {"set/theta-d.json", "shorthand/theta-d.json"}) {
    const Output again = thetad("run --replay " + path(run));
    EXPECT_EQ(again.status, 0) << run << again.err;
    EXPECT_THAT(again.out, HasSubstr("bit for bit")) << run;
  }
}

TEST_F(PlantFrontEnds, AFactorThatDoesNotApplyIsRefusedByName) {
  const struct {
    std::string scenario, factor, message;
  } cases[] = {
      {"scenario-1", "plant.epsilon: [0.2]", "plant.epsilon: a plant's settings and initial state"},
      {"scenario-1", "initial_state.0: [1]", "initial_state.0: a plant's settings and initial state"},
      {"tora/regulation", "initial_state.4: [1]", "initial_state.4: the plant has 4 states"},
      {"tora/regulation", "plant.epsilom: [0.2]", "factor 'plant.epsilom': unknown field"},
      {"tora/regulation", "plant.epsilon: [2]", "field 'plant_settings' with the factors plant.NAME: tora: epsilon"},
      {"tora/regulation", "initial_state.x: [1]", "expected initial_state.I with I a state's index"},
  };
  for (const auto& c : cases) {
    const std::string text = "campaign: refused\nscenarios: [" + c.scenario + "]\ncontrollers:\n  - {controller: lqr}\n"
                             "draws: {count: 1, base_seed: 1}\nfixed: {duration_s: 0.1}\nsweep:\n  grid:\n    " +
                             c.factor + "\n";
    const Output output = thetad("campaign run " + scenario("refused.yaml", text) + " --quiet --out " + path("refused"));
    EXPECT_EQ(output.status, 1) << c.factor;
    EXPECT_THAT(output.err, HasSubstr(c.message)) << c.factor;
    fs::remove_all(dir_ / "refused");
  }
}

TEST_F(PlantFrontEnds, TheExamplePlantPluginFliesAndSweepsItsOwnSettings) {
  const std::string plugin = std::string("--plugin ") + THETAD_PENDULUM_PLUGIN + " ";
  scenario("pendulum.yaml", "plant: inverted-pendulum\nplant_settings: {damping: 0.2}\nduration: 2\n");
  const std::vector<thetad::RunRecord> flown =
      campaign("pendulum-sweep.yaml", "campaign: pendulum\nscenarios: [pendulum.yaml]\ncontrollers:\n"
                                      "  - {controller: theta-d}\n  - {controller: lqr}\n"
                                      "draws: {count: 1, base_seed: 1}\nsweep:\n  grid:\n    plant.length: [0.5, 2]\n",
               plugin);
  ASSERT_EQ(flown.size(), 4u);
  for (const auto& record : flown) {
    EXPECT_TRUE(record.completed()) << record.label << " " << record.reason;
    EXPECT_TRUE(plant_factor_values(record).contains("plant.length"));
  }
  const Output bad = thetad(plugin + "run --scenario " +
                            scenario("bad.yaml", "plant: inverted-pendulum\nplant_settings: {length: 0}\nduration: 1\n") +
                            " --controller sdre --quiet --out " + path("bad"));
  EXPECT_EQ(bad.status, 1);
  EXPECT_THAT(bad.err, ::testing::AllOf(HasSubstr("bad.yaml:2:"), HasSubstr("field 'length'")));
}

}  // namespace
