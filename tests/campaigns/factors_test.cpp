#include "campaigns/factors.hpp"

#include <numbers>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "campaigns/campaign.hpp"
#include "core/error.hpp"

namespace thetad {
namespace {

using ::testing::HasSubstr;

TEST(Factors, EachSetsItsOverride) {
  RunControls controls;
  apply({{"uncertainty_scale", 2.0}, {"gust_scale", 1.5}, {"gust_onset_s", 3.0}, {"noise_scale", 0.5},
         {"initial_offset_y_m", -1.0}, {"initial_offset_z_m", 0.5}, {"trajectory_speed_scale", 1.25}, {"course", 90.0},
         {"dt_s", 5e-4}, {"duration_s", 7.0}},
        controls);
  EXPECT_EQ(controls.uncertainty_scale, 2.0);
  EXPECT_EQ(controls.gust_scale, 1.5);
  EXPECT_EQ(controls.gust_onset, 3.0);
  EXPECT_EQ(controls.noise_scale, 0.5);
  EXPECT_EQ(controls.initial_offset, Eigen::Vector3d(0.0, -1.0, 0.5));
  EXPECT_FALSE(controls.initial_attitude_offset);
  EXPECT_EQ(controls.speed_scale, 1.25);
  EXPECT_DOUBLE_EQ(*controls.course, std::numbers::pi / 2.0);
  EXPECT_EQ(controls.dt, 5e-4);
  EXPECT_EQ(controls.duration, 7.0);
  EXPECT_THROW(apply({{"speed_scale", 2.0}}, controls), Error);
}

TEST(Factors, TheAttitudeOffsetIsInDegreesInTheFileAndInRadiansInTheRun) {
  RunControls controls;
  apply({{"initial_offset_roll_deg", 10.0}, {"initial_offset_yaw_deg", -90.0}}, controls);
  ASSERT_TRUE(controls.initial_attitude_offset);
  EXPECT_DOUBLE_EQ((*controls.initial_attitude_offset)[0], std::numbers::pi / 18.0);
  EXPECT_EQ((*controls.initial_attitude_offset)[1], 0.0);
  EXPECT_DOUBLE_EQ((*controls.initial_attitude_offset)[2], -std::numbers::pi / 2.0);
  EXPECT_EQ(find_factor("initial_offset_pitch_deg")->unit, "deg");
}

TEST(Factors, TurbulenceAndServosSetTheirFields) {
  RunControls controls;
  apply({{"turbulence_model", 1.0}, {"turbulence_intensity", 2.0}, {"turbulence_scale", 0.5},
         {"servo_delay_samples", 3.0}, {"servo_time_constant_s", 0.02}},
        controls);
  EXPECT_EQ(controls.turbulence_model, sim::TurbulenceSettings::Model::dryden);
  EXPECT_EQ(controls.turbulence_intensity, sim::TurbulenceIntensity::severe);
  EXPECT_EQ(controls.turbulence_scale, 0.5);
  EXPECT_EQ(controls.servo_delay_samples, 3);
  EXPECT_EQ(controls.servo_time_constant, 0.02);
  sim::SimulationSettings settings;
  thetad::apply(controls, settings);
  EXPECT_EQ(settings.turbulence.model, sim::TurbulenceSettings::Model::dryden);
  EXPECT_EQ(settings.servos.time_constant, sim::InputVector::Constant(0.02));
  EXPECT_THROW(apply({{"servo_delay_samples", 1.5}}, controls), Error);
}

TEST(Factors, ACampaignFileMayNameAChoice) {
  const std::string head = "campaign: x\nscenarios: [scenario-1]\ncontrollers: [{controller: lqr}]\ndraws: {count: 1}\n";
  const Campaign campaign =
      parse_campaign(head + "fixed: {turbulence_model: dryden}\nsweep: {grid: {turbulence_intensity: [light, 1, severe]}}\n",
                     "factors.yaml");
  ASSERT_EQ(campaign.cells.size(), 3u);
  EXPECT_EQ(campaign.cells[2].back(), (std::pair<std::string, double>("turbulence_intensity", 2.0)));
  EXPECT_EQ(campaign.cells[2].front(), (std::pair<std::string, double>("turbulence_model", 1.0)));
  try {
    parse_campaign(head + "fixed: {turbulence_model: karman}\n", "factors.yaml");
    ADD_FAILURE() << "no error";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("field 'fixed.turbulence_model': expected one of paper dryden gauss_markov"));
  }
}

TEST(Factors, ACampaignFileRefusesValuesOutsideTheirRange) {
  const std::string head = "campaign: x\nscenarios: [scenario-1]\ncontrollers: [{controller: lqr}]\ndraws: {count: 1}\n";
  const auto error_of = [&](const std::string& sweep) {
    try {
      parse_campaign(head + sweep, "factors.yaml");
    } catch (const Error& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(error_of("sweep: {grid: {trajectory_speed_scale: [1, 0]}}\n"),
              HasSubstr("field 'sweep.grid.trajectory_speed_scale[1]': value 0 is outside [0.01, 100]"));
  EXPECT_THAT(error_of("fixed: {initial_offset_pitch_deg: 200}\n"),
              HasSubstr("field 'fixed.initial_offset_pitch_deg': value 200 is outside [-180, 180]"));
  EXPECT_EQ(parse_campaign(head + "sweep: {grid: {trajectory_speed_scale: [0.5, 2], initial_offset_roll_deg: [-5, 5]}}\n",
                           "factors.yaml")
                .cells.size(),
            4u);
}

}  // namespace
}  // namespace thetad
