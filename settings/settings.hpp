#pragma once

// Reading a controller's settings block (a YAML map) with one set of rules and one error format,
// so that every controller accepts and rejects its settings the same way:
//  - a missing field takes its default; a field that is present must be valid (no silent fallback);
//  - an unknown field is an error that lists the allowed ones (a typo never goes unnoticed);
//  - every error is a SettingsError: "<file>:<line>:<column>: field '<name>': <reason>", with the
//    1-based position of the offending node (of the enclosing map when the field is missing).
//
//  - every value a reader takes, given or default, is recorded: resolved() is the block as it was
//    used, every field included, so a result can say exactly what was flown and a run can be
//    rebuilt from it.
//
// A factory does not know which file its block came from; the caller that does (the command line)
// adds it with with_settings_source().

#include <cstdint>
#include <initializer_list>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <yaml-cpp/yaml.h>

#include "core/error.hpp"

namespace thetad {

class SettingsError : public Error {
 public:
  // `mark` is yaml-cpp's 0-based position; a null mark (a node not loaded from text) prints none.
  SettingsError(std::string field, std::string reason, const YAML::Mark& mark, std::string source = {});

  const std::string& field() const { return field_; }
  const std::string& reason() const { return reason_; }
  // 1-based line and column, 0 when unknown.
  int line() const { return mark_.is_null() ? 0 : mark_.line + 1; }
  int column() const { return mark_.is_null() ? 0 : mark_.column + 1; }
  const std::string& source() const { return source_; }

  // The same error, located in the file `source`.
  SettingsError in_source(std::string source) const { return {field_, reason_, mark_, std::move(source)}; }

 private:
  std::string field_;
  std::string reason_;
  YAML::Mark mark_;
  std::string source_;
};

// Runs `read` (e.g. a ControllerRegistry::make on a block of `source`) and rethrows a SettingsError
// escaping it with `source` as its file name, so the message reads
// "scenario-1.yaml:12:5: field 'Q': expected 18 entries, got 17".
template <class Read>
decltype(auto) with_settings_source(const std::string& source, Read&& read) {
  try {
    return std::forward<Read>(read)();
  } catch (const SettingsError& error) {
    // An error that already names its file (a file read inside `read`) keeps it.
    if (!error.source().empty()) throw;
    throw error.in_source(source);
  }
}

// Throws a SettingsError for the field `name` unless `node` is a map, null or undefined (a block
// with every default). For the callers that know a block's name (a settings file's `theta-d:`, a
// registry's controller), so that a block of the wrong type is reported under that name.
void check_block(const YAML::Node& node, const std::string& name, const std::string& source = {});

// One settings block. Getters take the field's key and its default; the node must be a map or
// null/undefined (no settings: every default).
class Settings {
 public:
  // `path` prefixes field names in messages ("controller.Q"); empty for a top-level block.
  explicit Settings(const YAML::Node& node, std::string path = {});

  // Throws on the first key of the map that is not in `allowed`, naming it and listing `allowed`.
  void allow_only(std::initializer_list<std::string_view> allowed) const;
  void allow_only(std::span<const std::string_view> allowed) const;

  bool has(const std::string& key) const;

  // The nested map under `key` (absent: every default), read with the same rules; its fields are
  // recorded under `key` in this block's resolved().
  Settings block(const std::string& key) const;
  const YAML::Node& node() const { return node_; }

  // A finite number in [min, max].
  double number(const std::string& key, double fallback, double min = -inf(), double max = inf()) const;
  // An integer in [min, max] ("3.0" is not an integer).
  int integer(const std::string& key, int fallback, int min = std::numeric_limits<int>::min(),
              int max = std::numeric_limits<int>::max()) const;
  // A seed: a whole decimal number from 0 to 2^64 - 1 (sim::parse_seed), never wrapped or saturated.
  std::uint64_t seed(const std::string& key, std::uint64_t fallback) const;
  // true/false (also yes/no, on/off as YAML 1.1 reads them).
  bool boolean(const std::string& key, bool fallback) const;
  std::string string(const std::string& key, const std::string& fallback) const;
  // A string that must be one of `choices` (listed in the message otherwise).
  std::string choice(const std::string& key, const std::string& fallback,
                     std::initializer_list<std::string_view> choices) const;
  // A sequence of exactly `size` finite numbers, each in [min, max].
  Eigen::VectorXd vector(const std::string& key, const Eigen::VectorXd& fallback, Eigen::Index size,
                         double min = -inf(), double max = inf()) const;
  // A sequence of any length (empty too) of finite numbers, each in [min, max].
  std::vector<double> list(const std::string& key, const std::vector<double>& fallback, double min = -inf(),
                           double max = inf()) const;

  // A diagonal weight matrix given by its diagonal (`Q: [1e4, 2e4, ...]`) of fallback.size()
  // entries: every entry >= 0 for a state weight (Q), > 0 for an input weight (R) so that R is
  // positive definite.
  enum class Weight { positive_semidefinite, positive_definite };
  Eigen::MatrixXd diagonal_weight(const std::string& key, const Eigen::VectorXd& fallback_diagonal,
                                  Weight kind) const;

  // The error for `key`, positioned at its node (or at the block when the key is missing); for
  // checks only the caller can make (e.g. between fields).
  SettingsError error(const std::string& key, const std::string& reason) const;

  // Every field read so far through this block and the blocks made from it, with the value used
  // (the default when the field was absent), as a YAML map.
  YAML::Node resolved() const { return record_->root; }

 private:
  struct Record {
    YAML::Node root{YAML::NodeType::Map};
  };
  Settings(const YAML::Node& node, std::string path, std::shared_ptr<Record> record, std::vector<std::string> keys);
  template <class Value>
  Value recorded(const std::string& key, Value value) const;

  static constexpr double inf() { return std::numeric_limits<double>::infinity(); }
  std::string field_name(const std::string& key) const;
  double entry(const YAML::Node& node, const std::string& field, double min, double max) const;
  // The entries of the sequence under `key`, each checked by entry().
  std::vector<double> entries(const std::string& key, double min, double max) const;

  YAML::Node node_;
  std::string path_;
  std::shared_ptr<Record> record_;
  std::vector<std::string> keys_;  // where this block's fields go in record_->root
};

}  // namespace thetad
