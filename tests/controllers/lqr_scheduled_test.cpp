#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "controllers/linearization.hpp"
#include "controllers/lqr.hpp"
#include "controllers/lqr_scheduled.hpp"
#include "controllers/registry.hpp"
#include "core/error.hpp"
#include "settings/settings.hpp"
#include "tests/controllers/hover_recovery.hpp"
#include "tests/heap_counter.hpp"

namespace thetad {
namespace {

constexpr double kPi = std::numbers::pi;

// A CI-sized grid (36 points, ~0.4 s to design): three speeds, the four directions, three climb
// rates; 3 m/s and 45° courses fall between its points.
const char* const kTestGrid = "{speeds: [0, 2, 4], courses_deg: [0, 90, 180, 270], climb_rates: [-0.5, 0, 0.5]}";

const heli::Helicopter& model() {
  static const heli::Helicopter helicopter;
  return helicopter;
}

const std::shared_ptr<const LqrScheduleTable>& test_table() {
  static const auto table = std::make_shared<const LqrScheduleTable>(
      design_lqr_schedule(model(), read_lqr_grid(Settings(YAML::Load(kTestGrid))),
                          model().design_defaults().state_weights, model().design_defaults().input_weights));
  return table;
}

std::filesystem::path temporary_file(const std::string& name) {
  return std::filesystem::path(::testing::TempDir()) / ("lqr_scheduled_test_" + name);
}

TEST(LqrScheduled, GainAtAGridPointIsThePlainLqrDesignedThere) {
  LqrScheduledController controller(model(), test_table());
  const LqrScheduleTable& table = *test_table();
  const DesignDefaults defaults = model().design_defaults();
  LqrSettings settings{defaults.state_weights.asDiagonal(), defaults.input_weights.asDiagonal(), 17};
  for (const std::size_t index : {std::size_t{4}, table.index(1, 1, 2), table.index(2, 2, 0), table.index(2, 3, 1)}) {
    const LqrSchedulePoint& point = table.points[index];
    SCOPED_TRACE("speed " + std::to_string(point.speed) + ", course " + std::to_string(point.course) + ", climb " +
                 std::to_string(point.climb_rate));
    controller.schedule(point.speed, point.course, point.climb_rate);
    OperatingPoint linearized_at = point.point;
    linearized_at.state = lqr_linearization_state(point.point.state);
    const LqrController plain(model(), linearized_at, settings);
    EXPECT_EQ(controller.gain(), plain.design().K);
    EXPECT_EQ(controller.trim_input(), point.point.input);
    EXPECT_EQ(controller.trim_tracking(), point.point.tracking.head<17>());
    // And the stored trim is the trim solver's for that flight condition, from the hover guess.
    const Trim fresh = find_trim(model(), TrimCondition::straight(point.speed, point.course, point.climb_rate, 3.5));
    EXPECT_LE((fresh.state - point.point.state).cwiseAbs().maxCoeff(), 1e-7);
    EXPECT_LE((fresh.input - point.point.input).cwiseAbs().maxCoeff(), 1e-6);
  }
  // The one-point schedule is the hover LQR of the "lqr" controller.
  LqrScheduledController hover(
      model(), std::make_shared<LqrScheduleTable>(design_lqr_schedule(model(), LqrScheduleGrid::hover(),
                                                                      defaults.state_weights, defaults.input_weights)));
  const LqrController plain(model(), operating_point(model(), testing::hover_trim_at_3_5_m()), settings);
  EXPECT_LE((hover.gain() - plain.design().K).cwiseAbs().maxCoeff(), 1e-6 * plain.design().K.cwiseAbs().maxCoeff());
}

// The largest change of the blended gain over a step of `delta` in one scheduling variable.
double largest_jump(LqrScheduledController& controller, double speed, double course, double climb, int variable,
                    double delta) {
  controller.schedule(speed, course, climb);
  const LqrScheduledController::Gain before = controller.gain();
  controller.schedule(speed + (variable == 0 ? delta : 0.0), course + (variable == 1 ? delta : 0.0),
                      climb + (variable == 2 ? delta : 0.0));
  return (controller.gain() - before).cwiseAbs().maxCoeff();
}

TEST(LqrScheduled, InterpolationIsContinuousAcrossGridPointsTheCourseWrapAndTheOrigin) {
  LqrScheduledController controller(model(), test_table());
  // Across a speed grid line (2 m/s), the course wrap (360° = 0°), a course grid line (90°) and a
  // climb grid line (0): the jump shrinks with the step (Lipschitz), no step change anywhere.
  struct Case {
    double speed, course, climb;
    int variable;
  };
  for (const Case& c : {Case{2.0, 0.3, 0.1, 0}, Case{3.0, -1e-3 / 2, 0.2, 1}, Case{3.0, kPi / 2, 0.2, 1},
                        Case{3.0, 1.0, 0.0, 2}, Case{0.0, 2.0, 0.3, 0}}) {
    const double coarse = largest_jump(controller, c.speed, c.course, c.climb, c.variable, 1e-3);
    const double fine = largest_jump(controller, c.speed, c.course, c.climb, c.variable, 1e-6);
    EXPECT_LE(fine, 2e-3 * coarse + 1e-9) << "variable " << c.variable;
    EXPECT_LE(coarse, 1.0) << "variable " << c.variable;
  }
  // Through the origin the course of the commanded velocity jumps by π: the gain does not.
  controller.schedule(1e-9, 0.0, 0.0);
  const LqrScheduledController::Gain forward = controller.gain();
  controller.schedule(1e-9, kPi, 0.0);
  EXPECT_LE((controller.gain() - forward).cwiseAbs().maxCoeff(), 1e-6);
  // Halfway between two speeds the blend is the mean of the two points' gains.
  const LqrScheduleTable& table = *test_table();
  controller.schedule(3.0, 0.0, 0.0);
  const Eigen::MatrixXd mean = 0.5 * (table.points[table.index(1, 0, 1)].K + table.points[table.index(2, 0, 1)].K);
  EXPECT_LE((controller.gain() - mean).cwiseAbs().maxCoeff(), 1e-9 * mean.cwiseAbs().maxCoeff());
  // Clamped beyond the grid.
  controller.schedule(50.0, 0.0, 5.0);
  EXPECT_EQ(controller.gain(), table.points[table.index(2, 0, 2)].K);
}

TEST(LqrScheduled, TrimsAreEquilibriaAndLinearizationsMatchASecondStepSize) {
  const LqrScheduleTable& table = *test_table();
  for (const LqrSchedulePoint& point : table.points) {
    // The body rows are at rest and the position rows move with the commanded velocity.
    const Eigen::VectorXd f = model().f(point.point.state, point.point.input);
    const Eigen::Vector3d velocity(point.speed * std::cos(point.course), point.speed * std::sin(point.course),
                                   -point.climb_rate);
    EXPECT_LE(f.segment<11>(heli::kU).norm(), 1e-8);
    EXPECT_LE((f.segment<3>(heli::kXp) - velocity).norm(), 1e-8);
    EXPECT_LE(point.residual, 1e-8);
    EXPECT_EQ(point.rotor_speed_model, heli::ModelOptions::RotorSpeedModel::thrust_inversion);
  }
  // Central differences at two step sizes agree to 1e-6 (relative to the entry, or absolute for
  // entries below 1) where the design takes them: truncation and rounding are both below that at
  // the default step. Forward, sideways (on the jump of sign(u_a)) and rearward, climbing and not.
  for (const std::size_t index : {table.index(1, 0, 1), table.index(2, 1, 2), table.index(2, 2, 0),
                                  table.index(1, 3, 1)}) {
    const OperatingPoint& point = table.points[index].point;
    const Eigen::VectorXd x = lqr_linearization_state(point.state);
    const Linearization fine = linearize(model(), x, point.input);
    const Linearization coarse = linearize(model(), x, point.input, 4 * 6e-6);
    const auto scale = [](const Eigen::MatrixXd& m) { return m.cwiseAbs().cwiseMax(1.0); };
    EXPECT_LE(((fine.A - coarse.A).cwiseAbs().cwiseQuotient(scale(fine.A))).maxCoeff(), 1e-6) << index;
    EXPECT_LE(((fine.B - coarse.B).cwiseAbs().cwiseQuotient(scale(fine.B))).maxCoeff(), 1e-6) << index;
  }
}

// CI-sized closed loop (ideal, 1 kHz). Measured: from 1 m in x or y the error is below 0.1 m after
// < 3 s and below 0.03 m after 6 s, as the hover LQR (the blend at hover is its gain).
TEST(LqrScheduled, ReturnsToHoverFromOffsets) {
  for (const Eigen::Vector3d& offset : {Eigen::Vector3d(1.0, 0.0, 0.0), Eigen::Vector3d(0.0, 1.0, 0.0)}) {
    LqrScheduledController controller(model(), test_table());
    const auto r = testing::recover_hover(controller, offset, 6.0, 0.1);
    testing::print("lqr-scheduled from (" + std::to_string(offset.x()) + ", " + std::to_string(offset.y()) + ", 0)",
                   r);
    ASSERT_EQ(r.status, sim::RunStatus::completed) << r.reason;
    EXPECT_LT(r.settling_time, 3.0);
    EXPECT_LT(r.final_error, 0.03);
  }
}

TEST(LqrScheduled, AControlStepAllocatesNothing) {
  LqrScheduledController controller(model(), test_table());
  const Trim& hover = testing::hover_trim_at_3_5_m();
  controller.reset(hover.state, 0.0);
  Reference reference;
  reference.position = hover.state.segment<3>(heli::kXp);
  Eigen::VectorXd u(heli::kInputDim);
  const long allocations = testing::heap_allocations_during([&] {
    for (int k = 0; k < 100; ++k) {
      reference.position += Eigen::Vector3d(3e-3, 1e-3, -2e-4);  // between grid points in all variables
      controller.control(1e-3 * k, hover.state, reference, u);
    }
  });
  if (allocations < 0) GTEST_SKIP() << "heap allocations cannot be counted in this build";
  EXPECT_EQ(allocations, 0);
  EXPECT_TRUE(u.allFinite());
  // The counter counts: a clone copies the controller's buffers.
  EXPECT_GT(testing::heap_allocations_during([&] { EXPECT_NE(controller.clone(), nullptr); }), 0);
}

// A straight line at constant velocity from the origin at 3.5 m.
class StraightLine final : public ReferenceTrajectory {
 public:
  explicit StraightLine(const Eigen::Vector3d& velocity) : velocity_(velocity) {}
  Eigen::Vector3d position(double t) const override { return Eigen::Vector3d(0.0, 0.0, -3.5) + velocity_ * t; }
  Eigen::Vector3d velocity(double) const override { return velocity_; }
  Eigen::Vector3d acceleration(double) const override { return Eigen::Vector3d::Zero(); }

 private:
  Eigen::Vector3d velocity_;
};

// 3 m/s forward and 3 m/s along 45° while climbing 0.25 m/s (all between grid points), from the
// trim of that flight, for 6 s. Measured: max error 3 mm (forward) and 3 mm (diagonal climb),
// final error < 1 mm.
TEST(LqrScheduled, TracksStraightFlightBetweenGridPoints) {
  struct Case {
    double course, climb, max_error;
  };
  for (const Case& c : {Case{0.0, 0.0, 0.02}, Case{kPi / 4, 0.25, 0.02}}) {
    const Trim trim = find_trim(model(), TrimCondition::straight(3.0, c.course, c.climb, 3.5));
    const Eigen::Vector3d velocity(3.0 * std::cos(c.course), 3.0 * std::sin(c.course), -c.climb);
    const StraightLine line(velocity);
    sim::SimulationSettings settings = sim::SimulationSettings::ideal();
    settings.duration = 6.0;
    settings.measure_compute_time = false;
    // No low pass on the scheduling velocity: the run starts in steady flight (no velocity jump to
    // smooth), and the filter's start from rest would be what the errors measure.
    LqrScheduledController controller(model(), test_table(), 0.0);
    const sim::RunResult run = sim::simulate(controller, line, trim.state, settings);
    ASSERT_EQ(run.summary.status, sim::RunStatus::completed) << run.summary.reason;
    const std::size_t xc = testing::log_column("x_c"), xp = testing::log_column("x_p");
    double max_error = 0.0, final_error = 0.0;
    for (Eigen::Index i = 0; i < run.log.rows(); ++i) {
      const auto row = run.log.row(i);
      final_error = (row.segment<3>(static_cast<Eigen::Index>(xp)) - row.segment<3>(static_cast<Eigen::Index>(xc))).norm();
      max_error = std::max(max_error, final_error);
    }
    std::printf("lqr-scheduled at 3 m/s, course %.0f deg, climb %.2f m/s: max error %.3f m, final error %.2e m\n",
                c.course * 180 / kPi, c.climb, max_error, final_error);
    EXPECT_LT(max_error, c.max_error);
    EXPECT_LT(final_error, 0.01);
    EXPECT_LE((controller.scheduled_velocity() - velocity).norm(), 1e-9);
  }
}

TEST(LqrScheduled, TableRoundTripsThroughItsFile) {
  const LqrScheduleTable& table = *test_table();
  const auto file = temporary_file("round_trip.json");
  save_lqr_schedule(table, file);
  const LqrScheduleTable loaded = load_lqr_schedule(file);
  EXPECT_EQ(loaded.grid.speeds, table.grid.speeds);
  EXPECT_EQ(loaded.grid.courses, table.grid.courses);
  EXPECT_EQ(loaded.grid.climb_rates, table.grid.climb_rates);
  EXPECT_EQ(loaded.grid.altitude, table.grid.altitude);
  EXPECT_EQ(loaded.state_weights, table.state_weights);
  EXPECT_EQ(loaded.input_weights, table.input_weights);
  EXPECT_EQ(loaded.model_hash, table.model_hash);
  EXPECT_EQ(loaded.model_options, table.model_options);
  ASSERT_EQ(loaded.points.size(), table.points.size());
  for (std::size_t i = 0; i < table.points.size(); ++i) {
    EXPECT_EQ(loaded.points[i].K, table.points[i].K);
    EXPECT_EQ(loaded.points[i].point.state, table.points[i].point.state);
    EXPECT_EQ(loaded.points[i].point.input, table.points[i].point.input);
    EXPECT_EQ(loaded.points[i].point.tracking, table.points[i].point.tracking);
    EXPECT_EQ(loaded.points[i].rotor_speed, table.points[i].rotor_speed);
    EXPECT_EQ(loaded.points[i].rotor_speed_model, table.points[i].rotor_speed_model);
  }
  EXPECT_NO_THROW(check_lqr_schedule_model(loaded, model(), file.string()));

  // The registry's controller loads it by path.
  auto controller = ControllerRegistry::instance().make("lqr-scheduled", YAML::Load("table: " + file.string()),
                                                        {model(), testing::hover_trim_at_3_5_m().state, 0.0});
  EXPECT_EQ(controller->name(), "lqr-scheduled");
  EXPECT_EQ(dynamic_cast<LqrScheduledController&>(*controller).table().points.size(), table.points.size());
}

// A table of format_version 1 named its version "version"; it loads as it did.
TEST(LqrScheduled, ATableOfFormatVersion1StillLoads) {
  const auto file = temporary_file("version_1.json");
  save_lqr_schedule(*test_table(), file);
  nlohmann::ordered_json document = nlohmann::ordered_json::parse(std::ifstream(file));
  EXPECT_EQ(document["format_version"], LqrScheduleTable::kFormatVersion);
  document.erase("format_version");
  document["version"] = 1;
  std::ofstream(file, std::ios::trunc) << document.dump(1);
  const LqrScheduleTable loaded = load_lqr_schedule(file);
  ASSERT_EQ(loaded.points.size(), test_table()->points.size());
  for (std::size_t i = 0; i < loaded.points.size(); ++i) EXPECT_EQ(loaded.points[i].K, test_table()->points[i].K);
  EXPECT_EQ(loaded.model_hash, test_table()->model_hash);
}

// Runs `action` and returns the thetad::Error's message ("" when nothing was thrown).
template <class Action>
std::string error_of(Action action) {
  try {
    action();
  } catch (const Error& error) {
    return error.what();
  }
  return {};
}

TEST(LqrScheduled, CorruptOrMismatchedTablesAreClearErrors) {
  const auto file = temporary_file("corrupt.json");
  save_lqr_schedule(*test_table(), file);
  std::ifstream in(file);
  const nlohmann::json good = nlohmann::json::parse(in);
  const auto write = [&](const std::string& text) { std::ofstream(file, std::ios::trunc) << text; };
  const auto load_error = [&] { return error_of([&] { load_lqr_schedule(file); }); };

  write(good.dump().substr(0, 1000));
  EXPECT_NE(load_error().find("invalid JSON"), std::string::npos) << load_error();
  EXPECT_NE(load_error().find(file.string()), std::string::npos) << load_error();

  nlohmann::json changed = good;
  changed["format_version"] = LqrScheduleTable::kFormatVersion + 1;
  write(changed.dump());
  EXPECT_NE(load_error().find("field 'format_version': written by a newer thetad"), std::string::npos) << load_error();
  changed = good;
  changed.erase("format_version");
  changed["version"] = 2;
  write(changed.dump());
  EXPECT_NE(load_error().find("field 'version'"), std::string::npos) << load_error();

  changed = good;
  changed["points"][3]["K"][2].erase(0);
  write(changed.dump());
  EXPECT_NE(load_error().find("field 'points[3].K[2]': expected 17 numbers, got 16"), std::string::npos)
      << load_error();

  changed = good;
  changed["points"][5]["state"][7] = "pitch";
  write(changed.dump());
  EXPECT_NE(load_error().find("field 'points[5].state[7]': expected a finite number"), std::string::npos)
      << load_error();

  changed = good;
  changed["points"].erase(1);
  write(changed.dump());
  EXPECT_NE(load_error().find("field 'points': expected 36 points"), std::string::npos) << load_error();

  changed = good;
  changed["grid"]["speeds"] = {0, 4, 2};
  write(changed.dump());
  EXPECT_NE(load_error().find("strictly ascending"), std::string::npos) << load_error();

  changed = good;
  changed["model"].erase("hash");
  write(changed.dump());
  EXPECT_NE(load_error().find("field 'model.hash': missing"), std::string::npos) << load_error();

  // A table designed on another model: the governor rotor model, or another parameter set.
  heli::ModelOptions options;
  options.rotor_speed_model = heli::ModelOptions::RotorSpeedModel::governor;
  const heli::Helicopter governor(heli::Parameters::nominal(), options);
  const std::string mismatch = error_of([&] { check_lqr_schedule_model(*test_table(), governor, "t.json"); });
  EXPECT_NE(mismatch.find("t.json: field 'model.hash'"), std::string::npos) << mismatch;
  EXPECT_NE(mismatch.find("rotor_speed_model=governor"), std::string::npos) << mismatch;
  heli::Parameters heavier = heli::Parameters::nominal();
  heavier.mass *= 1.01;
  EXPECT_NE(model_hash(heli::Helicopter(heavier)), model_hash(model()));

  write(good.dump());
  auto make = [&](const std::string& settings) {
    return error_of([&] {
      ControllerRegistry::instance().make("lqr-scheduled", YAML::Load(settings), {governor, Eigen::VectorXd::Zero(18), 0.0});
    });
  };
  EXPECT_NE(make("table: " + file.string()).find("field 'model.hash'"), std::string::npos);
  EXPECT_NE(make("table: " + file.string() + "\nQ: [1]").find("field 'Q'"), std::string::npos);
  EXPECT_NE(make("gain: 3").find("field 'gain'"), std::string::npos);
  EXPECT_NE(make("grid: {speeds: [0, -1]}").find("field 'grid.speeds'"), std::string::npos);
  EXPECT_NE(make("table: /nonexistent/table.json").find("cannot read"), std::string::npos);
}

}  // namespace
}  // namespace thetad
