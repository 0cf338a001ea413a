#include "settings/settings.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <span>

#include "core/sim/seed.hpp"
#include "core/text_file.hpp"

namespace thetad {

namespace {

std::string where(const YAML::Mark& mark, const std::string& source) {
  std::ostringstream prefix;
  prefix << escaped_utf8(source);
  if (!mark.is_null()) prefix << (source.empty() ? "" : ":") << mark.line + 1 << ":" << mark.column + 1;
  if (prefix.tellp() > 0) prefix << ": ";
  return prefix.str();
}

std::string kind_of(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Null: return "null";
    case YAML::NodeType::Sequence: return "a sequence";
    case YAML::NodeType::Map: return "a map";
    case YAML::NodeType::Scalar: return "'" + escaped_utf8(node.Scalar()) + "'";
    case YAML::NodeType::Undefined: break;
  }
  return "nothing";
}

std::string joined(std::span<const std::string_view> names) {
  std::string result;
  for (const auto name : names) result += (result.empty() ? "" : ", ") + std::string(name);
  return result;
}

std::string text(double value) {
  std::ostringstream stream;
  stream << value;
  return stream.str();
}

std::string interval(double min, double max) { return "[" + text(min) + ", " + text(max) + "]"; }

}  // namespace

SettingsError::SettingsError(std::string field, std::string reason, const YAML::Mark& mark, std::string source)
    : Error(where(mark, source) + "field '" + field + "': " + reason),
      field_(std::move(field)),
      reason_(std::move(reason)),
      mark_(mark),
      source_(std::move(source)) {}

void check_block(const YAML::Node& node, const std::string& name, const std::string& source) {
  if (node.IsDefined() && !node.IsNull() && !node.IsMap())
    throw SettingsError(name, "expected a map of fields, got " + kind_of(node), node.Mark(), source);
}

Settings::Settings(const YAML::Node& node, std::string path)
    : Settings(node, std::move(path), std::make_shared<Record>(), {}) {}

Settings::Settings(const YAML::Node& node, std::string path, std::shared_ptr<Record> record,
                   std::vector<std::string> keys)
    : node_(node), path_(std::move(path)), record_(std::move(record)), keys_(std::move(keys)) {
  // A top-level block's name is its caller's to give (check_block): "settings" stands in for it.
  check_block(node_, path_.empty() ? "settings" : path_);
}

std::string Settings::field_name(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

SettingsError Settings::error(const std::string& key, const std::string& reason) const {
  // A missing key's node has no position (and an undefined node throws on Mark()): point at the
  // enclosing block instead.
  const YAML::Node value = node_.IsMap() ? node_[key] : YAML::Node();
  const YAML::Mark mark = value.IsDefined() ? value.Mark() : (node_.IsDefined() ? node_.Mark() : YAML::Mark::null_mark());
  return {field_name(key), reason, mark};
}

void Settings::allow_only(std::initializer_list<std::string_view> allowed) const {
  allow_only(std::span<const std::string_view>(allowed.begin(), allowed.size()));
}

void Settings::allow_only(std::span<const std::string_view> allowed) const {
  if (!node_.IsMap()) return;
  for (const auto& item : node_) {
    const std::string key = item.first.Scalar();
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
      throw SettingsError(field_name(escaped_utf8(key)), "unknown field (allowed: " + joined(allowed) + ")",
                          item.first.Mark());
    }
  }
}

bool Settings::has(const std::string& key) const { return node_.IsMap() && node_[key].IsDefined(); }

Settings Settings::block(const std::string& key) const {
  std::vector<std::string> keys = keys_;
  keys.push_back(key);
  Settings nested(has(key) ? node_[key] : YAML::Node(), field_name(key), record_, std::move(keys));
  nested.recorded<YAML::Node>("", YAML::Node(YAML::NodeType::Map));
  return nested;
}

// yaml-cpp nodes are handles: reset() rebinds one, while assignment would overwrite the node it
// refers to. An empty key records the block itself (an empty map where nothing is read from it).
template <class Value>
Value Settings::recorded(const std::string& key, Value value) const {
  YAML::Node at;
  at.reset(record_->root);
  const std::size_t depth = key.empty() ? keys_.size() - 1 : keys_.size();
  for (std::size_t i = 0; i < depth; ++i) {
    if (!at[keys_[i]].IsMap()) at[keys_[i]] = YAML::Node(YAML::NodeType::Map);
    const YAML::Node next = at[keys_[i]];
    at.reset(next);
  }
  const std::string& field = key.empty() ? keys_.back() : key;
  if constexpr (std::is_same_v<Value, YAML::Node>) {
    if (!at[field].IsMap()) at[field] = value;
  } else if constexpr (std::is_same_v<Value, Eigen::VectorXd>) {
    at[field] = std::vector<double>(value.data(), value.data() + value.size());
  } else {
    at[field] = value;
  }
  return value;
}

double Settings::entry(const YAML::Node& node, const std::string& field, double min, double max) const {
  double value = 0.0;
  if (!node.IsScalar() || !YAML::convert<double>::decode(node, value)) {
    throw SettingsError(field, "expected a number, got " + kind_of(node), node.Mark());
  }
  if (!std::isfinite(value)) throw SettingsError(field, "expected a finite number, got " + node.Scalar(), node.Mark());
  if (value < min || value > max) {
    throw SettingsError(field, "expected a number in " + interval(min, max) + ", got " + node.Scalar(), node.Mark());
  }
  return value;
}

double Settings::number(const std::string& key, double fallback, double min, double max) const {
  return recorded(key, has(key) ? entry(node_[key], field_name(key), min, max) : fallback);
}

int Settings::integer(const std::string& key, int fallback, int min, int max) const {
  if (!has(key)) return recorded(key, fallback);
  const YAML::Node node = node_[key];
  int value = 0;
  if (!node.IsScalar() || !YAML::convert<int>::decode(node, value)) {
    throw error(key, "expected an integer, got " + kind_of(node));
  }
  if (value < min || value > max) {
    throw error(key, "expected an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "], got " +
                         std::to_string(value));
  }
  return recorded(key, value);
}

std::uint64_t Settings::seed(const std::string& key, std::uint64_t fallback) const {
  if (!has(key)) return recorded(key, fallback);
  const YAML::Node node = node_[key];
  const std::optional<std::uint64_t> value = node.IsScalar() ? sim::parse_seed(node.Scalar()) : std::nullopt;
  if (!value) throw error(key, std::string(sim::kSeedExpected) + ", got " + kind_of(node));
  return recorded(key, *value);
}

bool Settings::boolean(const std::string& key, bool fallback) const {
  if (!has(key)) return recorded(key, fallback);
  const YAML::Node node = node_[key];
  bool value = false;
  if (!node.IsScalar() || !YAML::convert<bool>::decode(node, value)) {
    throw error(key, "expected true or false, got " + kind_of(node));
  }
  return recorded(key, value);
}

std::string Settings::string(const std::string& key, const std::string& fallback) const {
  if (!has(key)) return recorded(key, fallback);
  const YAML::Node node = node_[key];
  if (!node.IsScalar()) throw error(key, "expected a string, got " + kind_of(node));
  return recorded(key, node.Scalar());
}

std::string Settings::choice(const std::string& key, const std::string& fallback,
                             std::initializer_list<std::string_view> choices) const {
  const std::string value = string(key, fallback);
  if (std::find(choices.begin(), choices.end(), value) == choices.end()) {
    throw error(key, "expected one of " + joined(choices) + ", got '" + escaped_utf8(value) + "'");
  }
  return value;
}

Eigen::VectorXd Settings::vector(const std::string& key, const Eigen::VectorXd& fallback, Eigen::Index size,
                                 double min, double max) const {
  if (!has(key)) return recorded(key, fallback);
  const YAML::Node node = node_[key];
  if (!node.IsSequence()) {
    throw error(key, "expected a sequence of " + std::to_string(size) + " numbers, got " + kind_of(node));
  }
  if (static_cast<Eigen::Index>(node.size()) != size) {
    throw error(key, "expected " + std::to_string(size) + " entries, got " + std::to_string(node.size()));
  }
  const std::vector<double> values = entries(key, min, max);
  return recorded(key, Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(values.data(), size)));
}

std::vector<double> Settings::list(const std::string& key, const std::vector<double>& fallback, double min,
                                   double max) const {
  if (!has(key)) return recorded(key, fallback);
  const YAML::Node node = node_[key];
  if (!node.IsSequence()) throw error(key, "expected a sequence of numbers, got " + kind_of(node));
  return recorded(key, entries(key, min, max));
}

std::vector<double> Settings::entries(const std::string& key, double min, double max) const {
  const YAML::Node node = node_[key];
  std::vector<double> values(node.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    values[i] = entry(node[i], field_name(key) + "[" + std::to_string(i) + "]", min, max);
  }
  return values;
}

Eigen::MatrixXd Settings::diagonal_weight(const std::string& key, const Eigen::VectorXd& fallback_diagonal,
                                          Weight kind) const {
  const Eigen::Index size = fallback_diagonal.size();
  const Eigen::VectorXd diagonal = vector(key, fallback_diagonal, size, 0.0);
  if (kind == Weight::positive_definite) {
    for (Eigen::Index i = 0; i < size; ++i) {
      if (!(diagonal(i) > 0.0)) {
        const YAML::Node node = has(key) ? node_[key][static_cast<std::size_t>(i)] : YAML::Node();
        throw SettingsError(field_name(key) + "[" + std::to_string(i) + "]",
                            "expected a positive number (the weight must be positive definite), got " +
                                text(diagonal(i)),
                            node.Mark());
      }
    }
  }
  return diagonal.asDiagonal();
}

}  // namespace thetad
