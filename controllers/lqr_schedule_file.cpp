#include "controllers/lqr_schedule_file.hpp"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <utility>

#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/text_file.hpp"

namespace thetad {

namespace {

using nlohmann::json;
using RotorSpeedModel = heli::ModelOptions::RotorSpeedModel;
constexpr const char* kFormatName = "thetad-lqr-schedule";

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
      {"format_version", LqrScheduleTable::kFormatVersion},
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

namespace {

// Everything of the table but its points: the model, the weights, the design states and the grid.
LqrScheduleTable read_header(const TableReader& read, const json& document) {
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
  if (design_states != LqrScheduleTable::kDesignStates) {
    read.fail("design_states", "expected " + std::to_string(LqrScheduleTable::kDesignStates));
  }
  table.design_states = LqrScheduleTable::kDesignStates;

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
  return table;
}

// The point `at` ("points[7]"), which must be the one of the flight condition its index stands for.
LqrSchedulePoint read_point(const TableReader& read, const json& entry, const std::string& at, double speed,
                            double course, double climb_rate, Eigen::Index design_states) {
  LqrSchedulePoint point;
  const auto field = [&](const char* key) -> const json& { return read.member(entry, at, key); };
  point.speed = read.number(field("speed"), at + ".speed");
  point.course = read.number(field("course_rad"), at + ".course_rad");
  point.climb_rate = read.number(field("climb_rate"), at + ".climb_rate");
  if (point.speed != speed || point.course != course || point.climb_rate != climb_rate) {
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
  point.K.resize(heli::kInputDim, design_states);
  for (std::size_t row = 0; row < gain.size(); ++row) {
    point.K.row(static_cast<Eigen::Index>(row)) =
        read.vector(gain[row], at + ".K[" + std::to_string(row) + "]", design_states).transpose();
  }
  return point;
}

}  // namespace

LqrScheduleTable load_lqr_schedule(const std::filesystem::path& file) {
  const std::string text = read_text_file(file);
  const TableReader read(file);
  json document;
  try {
    document = json::parse(text);
  } catch (const json::exception& error) {
    throw Error("lqr-scheduled table " + file.string() + ": invalid JSON: " + error.what());
  }
  if (read.text(read.member(document, "", "format"), "format") != kFormatName) {
    read.fail("format", std::string("expected \"") + kFormatName + "\"");
  }
  // Tables of version 1 said "version"; their content is that of version 2.
  const char* key = document.is_object() && !document.contains("format_version") ? "version" : "format_version";
  const json& given = read.member(document, "", key);
  const double version = read.number(given, key);
  if (version > LqrScheduleTable::kFormatVersion)
    read.fail(key, "written by a newer thetad (format_version " + given.dump() + "; this one reads up to " +
                       std::to_string(LqrScheduleTable::kFormatVersion) + ")");
  if (version != std::floor(version) || version < 1 || (std::string(key) == "version" && version != 1))
    read.fail(key, "expected a format_version from 1 to " + std::to_string(LqrScheduleTable::kFormatVersion) +
                       ", the file has " + given.dump());

  LqrScheduleTable table = read_header(read, document);
  const json& points = read.member(document, "", "points");
  if (!points.is_array() || points.size() != table.grid.size()) {
    read.fail("points", "expected " + std::to_string(table.grid.size()) + " points (the grid's size), got " +
                            (points.is_array() ? std::to_string(points.size()) : std::string("no list")));
  }
  table.points.resize(points.size());
  const LqrScheduleGrid& grid = table.grid;
  for (std::size_t i = 0; i < grid.speeds.size(); ++i) {
    for (std::size_t j = 0; j < grid.courses.size(); ++j) {
      for (std::size_t k = 0; k < grid.climb_rates.size(); ++k) {
        const std::size_t index = table.index(i, j, k);
        table.points[index] = read_point(read, points[index], "points[" + std::to_string(index) + "]", grid.speeds[i],
                                         grid.courses[j], grid.climb_rates[k], table.design_states);
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

}  // namespace thetad
