#include "controllers/lqr_schedule_design.hpp"

#include <cmath>
#include <numbers>
#include <sstream>
#include <type_traits>
#include <utility>

#include "core/error.hpp"
#include "core/trim.hpp"
#include "core/trim_sweep.hpp"

namespace thetad {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kMaxGridSpeed = 50.0;  // the simulator's divergence limit on |(u, v, w)|
constexpr double kMaxGridClimb = 10.0;  // beyond it A4 has several roots and the flaps saturate

// Why a grid list is unusable, or empty when it is fine.
std::string list_problem(const std::vector<double>& values, double min, double max, const char* unit) {
  if (values.empty()) return "needs at least one value";
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i]) || values[i] < min || values[i] >= max) {
      std::ostringstream reason;
      reason << "value " << values[i] << " " << unit << " is outside [" << min << ", " << max << ")";
      return reason.str();
    }
    if (i > 0 && values[i] <= values[i - 1]) return "values must be strictly ascending";
  }
  return {};
}

// The envelope's courses as the settings give them, in degrees: every 45°.
std::vector<double> envelope_courses_deg() {
  std::vector<double> courses;
  for (int j = 0; j < kEnvelopeCourses; ++j) courses.push_back(360.0 * j / kEnvelopeCourses);
  return courses;
}

}  // namespace

LqrScheduleGrid LqrScheduleGrid::envelope() {
  LqrScheduleGrid grid;
  grid.speeds = envelope_speeds();
  for (const double course : envelope_courses_deg()) grid.courses.push_back(course * kDegree);
  grid.climb_rates = {-1.0, 0.0, 1.0};
  return grid;
}

LqrScheduleGrid LqrScheduleGrid::hover() {
  LqrScheduleGrid grid;
  grid.speeds = {0.0};
  grid.courses = {0.0};
  grid.climb_rates = {0.0};
  return grid;
}

void LqrScheduleGrid::validate() const {
  const std::pair<const char*, std::string> problems[] = {
      {"speeds", list_problem(speeds, 0.0, kMaxGridSpeed, "m/s")},
      {"courses", list_problem(courses, 0.0, 2.0 * std::numbers::pi, "rad")},
      {"climb_rates", list_problem(climb_rates, -kMaxGridClimb, kMaxGridClimb, "m/s")}};
  for (const auto& [list, problem] : problems) {
    if (!problem.empty()) throw Error(std::string("lqr-scheduled grid: ") + list + ": " + problem);
  }
  if (!std::isfinite(altitude)) throw Error("lqr-scheduled grid: altitude must be finite");
}

LqrScheduleGrid read_lqr_grid(const Settings& fields) {
  fields.allow_only({"speeds", "courses_deg", "climb_rates", "altitude"});
  const LqrScheduleGrid envelope = LqrScheduleGrid::envelope();
  // Recorded as given (courses in degrees), so that the settings as used rebuild the same grid.
  const auto list = [&](const char* key, const std::vector<double>& fallback, double min, double max,
                        const char* unit, double scale) {
    std::vector<double> values = fields.list(key, fallback);
    for (double& value : values) value *= scale;
    const std::string problem = list_problem(values, min * scale, max * scale, unit);
    if (!problem.empty()) throw fields.error(key, problem);
    return values;
  };
  LqrScheduleGrid grid;
  grid.speeds = list("speeds", envelope.speeds, 0.0, kMaxGridSpeed, "m/s", 1.0);
  grid.courses = list("courses_deg", envelope_courses_deg(), 0.0, 360.0, "rad", kDegree);
  grid.climb_rates = list("climb_rates", envelope.climb_rates, -kMaxGridClimb, kMaxGridClimb, "m/s", 1.0);
  grid.altitude = fields.number("altitude", envelope.altitude, -1e4, 1e4);
  return grid;
}

std::uint64_t model_hash(const heli::Helicopter& model) {
  // FNV-1a, 64 bit: a fingerprint, not a security measure.
  std::uint64_t hash = 14695981039346656037ull;
  const auto add = [&hash](const void* data, std::size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) hash = (hash ^ bytes[i]) * 1099511628211ull;
  };
  const std::string options = model.options().to_string();
  add(options.data(), options.size());
  // Parameters is a plain struct of doubles (no padding), so its bytes are its values.
  static_assert(std::is_trivially_copyable_v<heli::Parameters> && sizeof(heli::Parameters) % sizeof(double) == 0);
  add(&model.parameters(), sizeof(heli::Parameters));
  return hash;
}

// The flap-inflow sign sign(u_a) of A-7 (in k_z, §2.5) jumps at u_a = 0 whenever the helicopter
// moves sideways (μ ≠ 0), and an exactly sideways trim sits on the jump, where central differences
// return jump/(2h): ∂ȧ1/∂u = −43 1/s at 4 m/s and −2676 1/s at 10 m/s with the default step, a
// step-dependent artefact that moved K by 1–6 %. The model takes the u_a >= 0 branch at u_a = 0
// (sign(0) = +1), so the Jacobians are taken on it, beyond the differencing step (6e-6 m/s).
constexpr double kBranchOffset = 1e-4;  // m/s

Eigen::VectorXd lqr_linearization_state(const Eigen::VectorXd& trim_state) {
  Eigen::VectorXd x = trim_state;
  if (std::abs(x(heli::kU)) < kBranchOffset && std::abs(x(heli::kV)) >= kBranchOffset) x(heli::kU) = kBranchOffset;
  return x;
}

namespace {

// "speed 4 m/s, course 90 deg, climb 0.5 m/s": where a design failed.
std::string condition_text(const LqrSchedulePoint& point) {
  std::ostringstream text;
  text << "speed " << point.speed << " m/s, course " << point.course / kDegree << " deg, climb " << point.climb_rate
       << " m/s";
  return text.str();
}

// One grid point's linearization and gain at its trim.
LqrSchedulePoint design_point(const LqrScheduleTable& table, std::size_t i, std::size_t j, std::size_t k,
                              const GridTrim& found) {
  LqrSchedulePoint point;
  point.speed = table.grid.speeds[i];
  point.course = table.grid.courses[j];
  point.climb_rate = table.grid.climb_rates[k];
  point.rotor_speed_model = found.plant.options().rotor_speed_model;
  point.rotor_speed = found.trim.rotor_speed;
  point.residual = found.trim.residual;
  point.point = operating_point(found.plant, found.trim);
  try {
    OperatingPoint linearized_at = point.point;
    linearized_at.state = lqr_linearization_state(point.point.state);
    point.K = design_lqr(found.plant, linearized_at, table.state_weights.asDiagonal(),
                         table.input_weights.asDiagonal(), table.design_states)
                  .K;
  } catch (const Error& error) {
    throw Error("no LQR gain at " + condition_text(point) + ": " + error.what());
  }
  return point;
}

}  // namespace

LqrScheduleTable design_lqr_schedule(const heli::Helicopter& model, const LqrScheduleGrid& grid,
                                     const Eigen::VectorXd& state_weights, const Eigen::VectorXd& input_weights,
                                     const LqrDesignProgress& progress) {
  grid.validate();
  LqrScheduleTable table;
  table.grid = grid;
  table.state_weights = state_weights;
  table.input_weights = input_weights;
  table.design_states = LqrScheduleTable::kDesignStates;
  table.model_options = model.options().to_string();
  table.model_hash = model_hash(model);
  table.points.resize(grid.size());

  std::size_t done = 0;
  try {
    sweep_trims(model, {grid.speeds, grid.courses, grid.climb_rates, grid.altitude},
                [&](std::size_t i, std::size_t j, std::size_t k, const GridTrim& found) {
                  LqrSchedulePoint& point = table.points[table.index(i, j, k)];
                  point = design_point(table, i, j, k, found);
                  if (progress) progress(++done, table.points.size(), point);
                });
  } catch (const Error& error) {
    throw Error(std::string("lqr-scheduled: ") + error.what());
  }
  return table;
}

}  // namespace thetad
