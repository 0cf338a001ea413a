#include "controllers/lqr_scheduled.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <numbers>
#include <optional>
#include <sstream>
#include <type_traits>
#include <utility>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "controllers/registry.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/settings.hpp"
#include "core/trim.hpp"

namespace thetad {

namespace {

using RotorSpeedModel = heli::ModelOptions::RotorSpeedModel;
constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kDegree = std::numbers::pi / 180.0;
constexpr const char* kFormatName = "thetad-lqr-schedule";

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

constexpr double kMaxGridSpeed = 50.0;  // the simulator's divergence limit on |(u, v, w)|
constexpr double kMaxGridClimb = 10.0;  // beyond it A4 has several roots (A-11) and the flaps saturate

}  // namespace

namespace {

// The envelope's courses as the settings give them, in degrees: every 45°.
std::vector<double> envelope_courses_deg() {
  std::vector<double> courses;
  for (int course = 0; course < 360; course += 45) courses.push_back(course);
  return courses;
}

}  // namespace

LqrScheduleGrid LqrScheduleGrid::envelope() {
  LqrScheduleGrid grid;
  grid.speeds = {0.0, 1.0, 2.0, 3.0, 4.0, 6.0, 8.0, 10.0, 12.5, 15.0, 17.5, 20.0};
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
      {"courses", list_problem(courses, 0.0, kTwoPi, "rad")},
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

LqrScheduleTable design_lqr_schedule(const heli::Helicopter& model, const LqrScheduleGrid& grid,
                                     const Eigen::VectorXd& state_weights, const Eigen::VectorXd& input_weights,
                                     const LqrDesignProgress& progress) {
  grid.validate();
  LqrScheduleTable table;
  table.grid = grid;
  table.state_weights = state_weights;
  table.input_weights = input_weights;
  table.design_states = LqrScheduledController::kDesignStates;
  table.model_options = model.options().to_string();
  table.model_hash = model_hash(model);
  table.points.resize(grid.size());

  // Where A4 has no trim (high speed: Ω collapses, A-11) the point is designed with the governor.
  heli::ModelOptions governor_options = model.options();
  governor_options.rotor_speed_model = RotorSpeedModel::governor;
  const heli::Helicopter governor(model.parameters(), governor_options);
  const Eigen::MatrixXd Q = state_weights.asDiagonal();
  const Eigen::MatrixXd R = input_weights.asDiagonal();

  std::size_t done = 0;
  const auto design = [&](std::size_t i, std::size_t j, std::size_t k, std::optional<Trim>& guess,
                          bool& own_model_has_trims) {
    LqrSchedulePoint& point = table.points[table.index(i, j, k)];
    point.speed = grid.speeds[i];
    point.course = grid.courses[j];
    point.climb_rate = grid.climb_rates[k];
    const TrimCondition condition =
        TrimCondition::straight(point.speed, point.course, point.climb_rate, grid.altitude);
    const heli::Helicopter* plant = &model;
    std::optional<Trim> trim;
    if (own_model_has_trims) {
      try {
        trim = find_trim(model, condition, TrimOptions{.initial_guess = guess});
      } catch (const Error&) {
        // A4's Ω falls monotonically with speed: once it has no trim, faster points have none either.
        own_model_has_trims = false;
      }
    }
    if (!trim) {
      plant = &governor;
      try {
        trim = find_trim(governor, condition, TrimOptions{.initial_guess = guess});
      } catch (const Error& error) {
        std::ostringstream message;
        message << "lqr-scheduled: no trim at speed " << point.speed << " m/s, course " << point.course / kDegree
                << " deg, climb " << point.climb_rate << " m/s: " << error.what();
        throw Error(message.str());
      }
    }
    point.rotor_speed_model = plant->options().rotor_speed_model;
    point.rotor_speed = trim->rotor_speed;
    point.residual = trim->residual;
    point.point = operating_point(*plant, *trim);
    try {
      OperatingPoint linearized_at = point.point;
      linearized_at.state = lqr_linearization_state(point.point.state);
      point.K = design_lqr(*plant, linearized_at, Q, R, table.design_states).K;
    } catch (const Error& error) {
      std::ostringstream message;
      message << "lqr-scheduled: no LQR gain at speed " << point.speed << " m/s, course " << point.course / kDegree
              << " deg, climb " << point.climb_rate << " m/s: " << error.what();
      throw Error(message.str());
    }
    guess = std::move(trim);
    if (progress) progress(++done, table.points.size(), point);
  };

  for (std::size_t k = 0; k < grid.climb_rates.size(); ++k) {
    std::optional<Trim> zero_speed_trim;
    bool zero_speed_has_own_trim = true;
    for (std::size_t j = 0; j < grid.courses.size(); ++j) {
      std::optional<Trim> guess;
      bool own_model_has_trims = model.options().rotor_speed_model != RotorSpeedModel::governor;
      for (std::size_t i = 0; i < grid.speeds.size(); ++i) {
        if (grid.speeds[i] == 0.0 && j > 0) {
          // At zero speed the course means nothing: one trim for every course keeps the blend
          // continuous through the origin (where the course of the commanded velocity jumps).
          LqrSchedulePoint& point = table.points[table.index(i, j, k)];
          point = table.points[table.index(i, 0, k)];
          point.course = grid.courses[j];
          guess = zero_speed_trim;
          own_model_has_trims = own_model_has_trims && zero_speed_has_own_trim;
          if (progress) progress(++done, table.points.size(), point);
          continue;
        }
        design(i, j, k, guess, own_model_has_trims);
        if (grid.speeds[i] == 0.0) {
          zero_speed_trim = guess;
          zero_speed_has_own_trim = own_model_has_trims;
        }
      }
    }
  }
  return table;
}

// ---- the table file ---------------------------------------------------------------------------

namespace {

using nlohmann::json;

std::string rotor_model_name(RotorSpeedModel model) {
  return model == RotorSpeedModel::governor ? "governor" : "thrust_inversion";
}

json to_json(const Eigen::Ref<const Eigen::VectorXd>& v) { return json(std::vector<double>(v.begin(), v.end())); }

std::string hash_text(std::uint64_t hash) {
  std::ostringstream text;
  text << std::hex << std::setw(16) << std::setfill('0') << hash;
  return text.str();
}

// Reads one file's fields with errors that say "<file>: field '<path>': <reason>".
class TableReader {
 public:
  explicit TableReader(std::filesystem::path file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& field, const std::string& reason) const {
    throw Error("lqr-scheduled table " + file_.string() + ": field '" + field + "': " + reason);
  }

  const json& member(const json& object, const std::string& parent, const char* key) const {
    const std::string field = parent.empty() ? key : parent + "." + key;
    if (!object.is_object()) fail(parent, "expected an object");
    const auto it = object.find(key);
    if (it == object.end()) fail(field, "missing");
    return *it;
  }

  double number(const json& value, const std::string& field) const {
    if (!value.is_number() || !std::isfinite(value.get<double>())) fail(field, "expected a finite number");
    return value.get<double>();
  }

  std::string text(const json& value, const std::string& field) const {
    if (!value.is_string()) fail(field, "expected a string");
    return value.get<std::string>();
  }

  // A list of numbers; `size` < 0 accepts any length.
  Eigen::VectorXd vector(const json& value, const std::string& field, Eigen::Index size = -1) const {
    if (!value.is_array()) fail(field, "expected a list of numbers");
    if (size >= 0 && static_cast<Eigen::Index>(value.size()) != size) {
      fail(field, "expected " + std::to_string(size) + " numbers, got " + std::to_string(value.size()));
    }
    Eigen::VectorXd v(static_cast<Eigen::Index>(value.size()));
    for (std::size_t i = 0; i < value.size(); ++i) {
      v(static_cast<Eigen::Index>(i)) = number(value[i], field + "[" + std::to_string(i) + "]");
    }
    return v;
  }

  std::vector<double> list(const json& value, const std::string& field) const {
    const Eigen::VectorXd v = vector(value, field);
    return {v.begin(), v.end()};
  }

 private:
  std::filesystem::path file_;
};

}  // namespace

void save_lqr_schedule(const LqrScheduleTable& table, const std::filesystem::path& file) {
  json points = json::array();
  for (const LqrSchedulePoint& point : table.points) {
    json gain = json::array();
    for (Eigen::Index row = 0; row < point.K.rows(); ++row) gain.push_back(to_json(point.K.row(row).transpose()));
    points.push_back({{"speed", point.speed},
                      {"course_rad", point.course},
                      {"climb_rate", point.climb_rate},
                      {"rotor_speed_model", rotor_model_name(point.rotor_speed_model)},
                      {"rotor_speed", point.rotor_speed},
                      {"residual", point.residual},
                      {"state", to_json(point.point.state)},
                      {"input", to_json(point.point.input)},
                      {"tracking", to_json(point.point.tracking)},
                      {"K", std::move(gain)}});
  }
  const json document = {
      {"format", kFormatName},
      {"version", LqrScheduleTable::kFormatVersion},
      {"model", {{"options", table.model_options}, {"hash", hash_text(table.model_hash)}}},
      {"weights", {{"Q", to_json(table.state_weights)}, {"R", to_json(table.input_weights)}}},
      {"design_states", table.design_states},
      {"grid",
       {{"speeds", table.grid.speeds},
        {"courses_rad", table.grid.courses},
        {"climb_rates", table.grid.climb_rates},
        {"altitude", table.grid.altitude}}},
      {"points", std::move(points)}};
  // Doubles are written with 17 significant digits: the round trip is exact.
  write_file_atomically(file, document.dump(1) + "\n");
}

LqrScheduleTable load_lqr_schedule(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error("lqr-scheduled table " + file.string() + ": cannot read: " + std::strerror(errno));
  const TableReader read(file);
  json document;
  try {
    document = json::parse(in);
  } catch (const json::exception& error) {
    throw Error("lqr-scheduled table " + file.string() + ": invalid JSON: " + error.what());
  }
  if (read.text(read.member(document, "", "format"), "format") != kFormatName) {
    read.fail("format", std::string("expected \"") + kFormatName + "\"");
  }
  const double version = read.number(read.member(document, "", "version"), "version");
  if (version != LqrScheduleTable::kFormatVersion) {
    read.fail("version", "this thetad reads version " + std::to_string(LqrScheduleTable::kFormatVersion) +
                             ", the file has " + read.member(document, "", "version").dump());
  }

  LqrScheduleTable table;
  const json& model = read.member(document, "", "model");
  table.model_options = read.text(read.member(model, "model", "options"), "model.options");
  const std::string hash = read.text(read.member(model, "model", "hash"), "model.hash");
  std::size_t parsed = 0;
  try {
    table.model_hash = std::stoull(hash, &parsed, 16);
  } catch (const std::exception&) {
    parsed = 0;
  }
  if (hash.size() != 16 || parsed != hash.size()) read.fail("model.hash", "expected 16 hexadecimal digits");

  const json& weights = read.member(document, "", "weights");
  table.state_weights = read.vector(read.member(weights, "weights", "Q"), "weights.Q", heli::kStateDim);
  table.input_weights = read.vector(read.member(weights, "weights", "R"), "weights.R", heli::kInputDim);
  const double design_states = read.number(read.member(document, "", "design_states"), "design_states");
  if (design_states != LqrScheduledController::kDesignStates) {
    read.fail("design_states", "expected " + std::to_string(LqrScheduledController::kDesignStates));
  }
  table.design_states = LqrScheduledController::kDesignStates;

  const json& grid = read.member(document, "", "grid");
  table.grid.speeds = read.list(read.member(grid, "grid", "speeds"), "grid.speeds");
  table.grid.courses = read.list(read.member(grid, "grid", "courses_rad"), "grid.courses_rad");
  table.grid.climb_rates = read.list(read.member(grid, "grid", "climb_rates"), "grid.climb_rates");
  table.grid.altitude = read.number(read.member(grid, "grid", "altitude"), "grid.altitude");
  try {
    table.grid.validate();
  } catch (const Error& error) {
    read.fail("grid", error.what());
  }

  const json& points = read.member(document, "", "points");
  if (!points.is_array() || points.size() != table.grid.size()) {
    read.fail("points", "expected " + std::to_string(table.grid.size()) + " points (the grid's size), got " +
                            (points.is_array() ? std::to_string(points.size()) : std::string("no list")));
  }
  table.points.resize(points.size());
  for (std::size_t i = 0; i < table.grid.speeds.size(); ++i) {
    for (std::size_t j = 0; j < table.grid.courses.size(); ++j) {
      for (std::size_t k = 0; k < table.grid.climb_rates.size(); ++k) {
        const std::size_t index = table.index(i, j, k);
        const std::string at = "points[" + std::to_string(index) + "]";
        const json& entry = points[index];
        LqrSchedulePoint& point = table.points[index];
        const auto field = [&](const char* key) -> const json& { return read.member(entry, at, key); };
        point.speed = read.number(field("speed"), at + ".speed");
        point.course = read.number(field("course_rad"), at + ".course_rad");
        point.climb_rate = read.number(field("climb_rate"), at + ".climb_rate");
        if (point.speed != table.grid.speeds[i] || point.course != table.grid.courses[j] ||
            point.climb_rate != table.grid.climb_rates[k]) {
          read.fail(at, "its flight condition is not the grid's (speed, course, climb) at this index");
        }
        const std::string rotor = read.text(field("rotor_speed_model"), at + ".rotor_speed_model");
        if (rotor != "governor" && rotor != "thrust_inversion") {
          read.fail(at + ".rotor_speed_model", "expected governor or thrust_inversion");
        }
        point.rotor_speed_model = rotor == "governor" ? RotorSpeedModel::governor : RotorSpeedModel::thrust_inversion;
        point.rotor_speed = read.number(field("rotor_speed"), at + ".rotor_speed");
        point.residual = read.number(field("residual"), at + ".residual");
        point.point.state = read.vector(field("state"), at + ".state", heli::kStateDim);
        point.point.input = read.vector(field("input"), at + ".input", heli::kInputDim);
        point.point.tracking = read.vector(field("tracking"), at + ".tracking", heli::kStateDim);
        const json& gain = field("K");
        if (!gain.is_array() || gain.size() != heli::kInputDim) {
          read.fail(at + ".K", "expected " + std::to_string(heli::kInputDim) + " rows");
        }
        point.K.resize(heli::kInputDim, table.design_states);
        for (std::size_t row = 0; row < gain.size(); ++row) {
          point.K.row(static_cast<Eigen::Index>(row)) =
              read.vector(gain[row], at + ".K[" + std::to_string(row) + "]", table.design_states).transpose();
        }
      }
    }
  }
  return table;
}

void check_lqr_schedule_model(const LqrScheduleTable& table, const heli::Helicopter& model, const std::string& source) {
  const std::uint64_t hash = model_hash(model);
  if (table.model_hash != hash) {
    throw Error("lqr-scheduled table " + source + ": field 'model.hash': designed on model " +
                hash_text(table.model_hash) + " (" + table.model_options + "), the controller's model is " +
                hash_text(hash) + " (" + model.options().to_string() +
                "); rebuild the table with `thetad design-lqr` for this model");
  }
}

// ---- the controller ---------------------------------------------------------------------------

namespace {

// value ≈ (1 − weight) · grid[low] + weight · grid[high].
struct Bracket {
  std::size_t low = 0, high = 0;
  double weight = 0.0;
};

// Clamped at the ends (no extrapolation of trims and gains beyond the envelope).
Bracket bracket(const std::vector<double>& grid, double value) {
  if (!(value > grid.front())) return {0, 0, 0.0};  // also NaN: the first point
  if (value >= grid.back()) return {grid.size() - 1, grid.size() - 1, 0.0};
  const std::size_t high = static_cast<std::size_t>(std::upper_bound(grid.begin(), grid.end(), value) - grid.begin());
  return {high - 1, high, (value - grid[high - 1]) / (grid[high] - grid[high - 1])};
}

// Courses wrap: between the last course and the first one + 2π.
Bracket periodic_bracket(const std::vector<double>& grid, double course) {
  if (grid.size() == 1) return {0, 0, 0.0};
  double c = std::fmod(course, kTwoPi);
  if (c < 0.0) c += kTwoPi;
  if (c >= grid.front() && c < grid.back()) return bracket(grid, c);
  const double span = grid.front() + kTwoPi - grid.back();
  const double past_last = c >= grid.back() ? c - grid.back() : c + kTwoPi - grid.back();
  return {grid.size() - 1, 0, past_last / span};
}

}  // namespace

LqrScheduledController::LqrScheduledController(const heli::Helicopter& model,
                                               std::shared_ptr<const LqrScheduleTable> table,
                                               double velocity_time_constant)
    : model_(&model),
      table_(std::move(table)),
      velocity_time_constant_(velocity_time_constant),
      v_(Eigen::VectorXd::Zero(heli::kStateDim)) {
  if (!(velocity_time_constant_ >= 0.0) || !std::isfinite(velocity_time_constant_)) {
    throw Error("lqr-scheduled: the velocity time constant must be finite and >= 0");
  }
  if (!table_ || table_->points.empty() || table_->points.size() != table_->grid.size()) {
    throw Error("lqr-scheduled: the table has no points or not one per grid point");
  }
  gains_.reserve(table_->points.size());
  tracking_.reserve(table_->points.size());
  inputs_.reserve(table_->points.size());
  for (const LqrSchedulePoint& point : table_->points) {
    if (point.K.rows() != heli::kInputDim || point.K.cols() != kDesignStates ||
        point.point.tracking.size() != heli::kStateDim || point.point.input.size() != heli::kInputDim) {
      throw Error("lqr-scheduled: a table point's gain, tracking vector or input does not fit the helicopter");
    }
    gains_.push_back(point.K);
    tracking_.push_back(point.point.tracking.head<kDesignStates>());
    inputs_.push_back(point.point.input);
  }
  schedule(0.0, 0.0, 0.0);
}

void LqrScheduledController::reset(const Eigen::VectorXd& x0, double) {
  if (x0.size() != heli::kStateDim) {
    throw Error("lqr-scheduled: initial state has " + std::to_string(x0.size()) + " entries, the model " +
                std::to_string(heli::kStateDim));
  }
  has_previous_ = false;
  velocity_.setZero();
}

void LqrScheduledController::schedule(double speed, double course, double climb_rate) {
  const LqrScheduleGrid& grid = table_->grid;
  const Bracket s = bracket(grid.speeds, speed);
  const Bracket c = periodic_bracket(grid.courses, course);
  const Bracket h = bracket(grid.climb_rates, climb_rate);
  gain_.setZero();
  trim_input_.setZero();
  trim_tracking_.setZero();
  for (int corner = 0; corner < 8; ++corner) {
    const bool hi_s = corner & 1, hi_c = corner & 2, hi_h = corner & 4;
    const double weight = (hi_s ? s.weight : 1.0 - s.weight) * (hi_c ? c.weight : 1.0 - c.weight) *
                          (hi_h ? h.weight : 1.0 - h.weight);
    if (weight == 0.0) continue;
    const std::size_t index =
        table_->index(hi_s ? s.high : s.low, hi_c ? c.high : c.low, hi_h ? h.high : h.low);
    gain_.noalias() += weight * gains_[index];
    trim_input_.noalias() += weight * inputs_[index];
    trim_tracking_.noalias() += weight * tracking_[index];
  }
  // The body velocities of V* are not blended: they are the commanded velocity (clamped to the
  // grid as the trims are) seen from the blended attitude, as at every trim (body = Rᵀ V_ned).
  // Blended linearly in course, the velocity would shrink between courses: at 45° between the 0°
  // and 90° trims, 0.5 of the speed along each body axis instead of 0.71, a velocity error that
  // the gain fights and that costs decimetres of tracking at 3 m/s.
  const double s_value = std::clamp(speed, grid.speeds.front(), grid.speeds.back());
  const double c_value = grid.courses.size() > 1 ? course : grid.courses.front();
  const Eigen::Vector3d velocity_ned(s_value * std::cos(c_value), s_value * std::sin(c_value),
                                     -std::clamp(climb_rate, grid.climb_rates.front(), grid.climb_rates.back()));
  const Eigen::Matrix3d body_to_ned =
      (Eigen::AngleAxisd(trim_tracking_(heli::kTheta), Eigen::Vector3d::UnitY()) *
       Eigen::AngleAxisd(trim_tracking_(heli::kPhi), Eigen::Vector3d::UnitX()))
          .toRotationMatrix();  // R(φ*, θ*, ψ = 0) of Eq. 2
  trim_tracking_.segment<3>(heli::kU).noalias() = body_to_ned.transpose() * velocity_ned;
}

void LqrScheduledController::control(double t, const Eigen::Ref<const Eigen::VectorXd>& measured_state,
                                     const Reference& reference, Eigen::Ref<Eigen::VectorXd> u) {
  // The commanded velocity: backward difference of the (noise-free) reference over the controller
  // period, through a first-order low pass (exact for a held input); zero at the first sample (the
  // scenarios start at rest). Not the measured velocity: V*'s velocity would then follow the
  // measurement and the velocity error, the damping of the loop, would vanish.
  if (has_previous_ && t > previous_time_) {
    const double period = t - previous_time_;
    const double blend = velocity_time_constant_ > 0.0 ? 1.0 - std::exp(-period / velocity_time_constant_) : 1.0;
    velocity_ += blend * ((reference.position - previous_reference_) / period - velocity_);
  }
  previous_reference_ = reference.position;
  previous_time_ = t;
  has_previous_ = true;
  // Trims are at heading 0 = the paper's commanded heading: the heading frame is the NED frame.
  schedule(std::hypot(velocity_.x(), velocity_.y()), std::atan2(velocity_.y(), velocity_.x()), -velocity_.z());

  model_->tracking_vector(measured_state, reference, v_);
  const DesignVector error = v_.head<kDesignStates>() - trim_tracking_;
  u = trim_input_;
  u.noalias() -= gain_ * error;
}

namespace {

std::unique_ptr<Controller> make_lqr_scheduled(const Settings& fields, const ControllerContext& context) {
  const heli::Helicopter& model = helicopter_of(context, "lqr-scheduled");
  fields.allow_only({"table", "grid", "Q", "R", "velocity_time_constant"});
  const double time_constant = fields.number("velocity_time_constant",
                                             LqrScheduledController::kDefaultVelocityTimeConstant, 0.0, 60.0);
  std::shared_ptr<LqrScheduleTable> table;
  if (fields.has("table")) {
    for (const char* designed : {"grid", "Q", "R"}) {
      if (fields.has(designed)) {
        throw fields.error(designed, "the table fixes the grid and the weights; give either a table or these");
      }
    }
    const std::string file = fields.string("table", "");
    table = std::make_shared<LqrScheduleTable>(load_lqr_schedule(file));
    check_lqr_schedule_model(*table, model, file);
  } else {
    const LqrScheduleGrid grid = read_lqr_grid(fields.block("grid"));
    const Eigen::VectorXd q =
        fields.diagonal_weight("Q", context.defaults.state_weights, Settings::Weight::positive_semidefinite).diagonal();
    const Eigen::VectorXd r =
        fields.diagonal_weight("R", context.defaults.input_weights, Settings::Weight::positive_definite).diagonal();
    table = std::make_shared<LqrScheduleTable>(design_lqr_schedule(model, grid, q, r));
  }
  return std::make_unique<LqrScheduledController>(model, std::move(table), time_constant);
}

const ControllerRegistration registration(
    "lqr-scheduled",
    "LQR gain-scheduled over trims 0-20 m/s (course, climb), blended on the commanded velocity; settings: "
    "table (a `thetad design-lqr` file) or grid, Q, R; velocity_time_constant",
    make_lqr_scheduled);

}  // namespace

}  // namespace thetad
