#include "campaigns/campaign.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "experiment/scenario_files.hpp"
#include "experiment/sha256.hpp"
#include "core/text_file.hpp"
#include "settings/settings.hpp"
#include "settings/yaml_document.hpp"

namespace thetad {

namespace {

namespace fs = std::filesystem;

// Caps that keep a typo from asking for the impossible (docs/campaigns.md): a grid is expanded in
// memory, and a billion runs is decades of flights at a second each.
constexpr std::size_t kMaxCells = 1000000;
constexpr double kMaxRuns = 1e9;

// A scenario as the campaign names it: a file relative to the campaign file's folder, or a shipped
// name. Resolved to what find_scenario accepts, so the campaign flies the same file from any folder.
std::string resolve_scenario(const std::string& given, const fs::path& campaign_file) {
  const fs::path beside = campaign_file.parent_path() / given;
  if (fs::is_regular_file(beside)) return fs::absolute(beside).lexically_normal().string();
  return find_scenario(given).string();
}

std::vector<std::string> read_scenarios(const YAML::Node& node, const fs::path& file) {
  const Settings root(node);
  const YAML::Node list = node["scenarios"];
  if (!list || !list.IsSequence() || list.size() == 0)
    throw root.error("scenarios", "expected a non-empty list of scenario files or shipped names");
  std::vector<std::string> scenarios;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string field = "scenarios[" + std::to_string(i) + "]";
    if (!list[i].IsScalar()) throw SettingsError(field, "expected a scenario file or name", list[i].Mark());
    try {
      scenarios.push_back(resolve_scenario(list[i].Scalar(), file));
    } catch (const Error& error) {
      throw SettingsError(field, error.what(), list[i].Mark());
    }
  }
  return scenarios;
}

// One factor's value, checked against the factor's range.
double factor_value(const YAML::Node& node, const std::string& field, const Factor& factor) {
  if (!node.IsScalar()) throw SettingsError(field, "expected a number", node.Mark());
  try {
    return factor_value(factor, node.Scalar());
  } catch (const Error& error) {
    throw SettingsError(field, error.what(), node.Mark());
  }
}

const Factor& known_factor(const std::string& name, const std::string& field, const YAML::Mark& mark) {
  const Factor* factor = find_factor(name);
  if (factor == nullptr)
    throw SettingsError(field, "unknown factor '" + name + "' (known: " + factor_names() + ")", mark);
  return *factor;
}

// A factor given twice in one map, once by its old name (`duration` and `duration_s`).
void check_once(const FactorValues& values, const std::string& factor, const std::string& field,
                const YAML::Mark& mark) {
  for (const auto& [name, value] : values) {
    if (name == factor) throw SettingsError(field, "factor '" + name + "' is given twice", mark);
  }
}

// `fixed:` — factors every run shares.
FactorValues read_fixed(const YAML::Node& node) {
  FactorValues fixed;
  if (!node) return fixed;
  if (!node.IsMap()) throw SettingsError("fixed", "expected a map from factor to value", node.Mark());
  for (const auto& entry : node) {
    const std::string field = "fixed." + entry.first.Scalar();
    const Factor& factor = known_factor(entry.first.Scalar(), field, entry.first.Mark());
    const std::string name = factor.current_name(entry.first.Scalar());
    check_once(fixed, name, field, entry.first.Mark());
    fixed.emplace_back(name, factor_value(entry.second, field, factor));
  }
  return fixed;
}

// `sweep: {grid: {factor: [values]}}` (every combination, the first factor slowest) or
// `sweep: {list: [{factor: value, ...}, ...]}` (those cells; every item names the same factors).
std::vector<FactorValues> read_sweep(const YAML::Node& node, const FactorValues& fixed, std::vector<std::string>& swept) {
  std::vector<FactorValues> cells{fixed};
  if (!node) return cells;
  const Settings sweep(node, "sweep");
  sweep.allow_only({"grid", "list"});
  if (sweep.has("grid") == sweep.has("list")) throw sweep.error("grid", "give exactly one of 'grid' or 'list'");
  const auto check_not_fixed = [&](const std::string& name, const std::string& field, const YAML::Mark& mark) {
    for (const auto& [fixed_name, value] : fixed) {
      if (fixed_name == name) throw SettingsError(field, "factor '" + name + "' is also fixed", mark);
    }
  };
  if (sweep.has("grid")) {
    const YAML::Node grid = node["grid"];
    if (!grid.IsMap() || grid.size() == 0) throw sweep.error("grid", "expected a map from factor to a list of values");
    for (const auto& axis : grid) {
      const std::string field = "sweep.grid." + axis.first.Scalar();
      const Factor& factor = known_factor(axis.first.Scalar(), field, axis.first.Mark());
      const std::string name = factor.current_name(axis.first.Scalar());
      check_not_fixed(name, field, axis.first.Mark());
      if (std::find(swept.begin(), swept.end(), name) != swept.end())
        throw SettingsError(field, "factor '" + name + "' is given twice", axis.first.Mark());
      if (!axis.second.IsSequence() || axis.second.size() == 0)
        throw SettingsError(field, "expected a non-empty list of values", axis.second.Mark());
      if (cells.size() * axis.second.size() > kMaxCells)
        throw SettingsError(field, "the grid would have " + std::to_string(cells.size() * axis.second.size()) +
                                       " cells, more than the " + std::to_string(kMaxCells) + " a campaign may have",
                            axis.second.Mark());
      std::vector<FactorValues> next;
      for (const FactorValues& cell : cells) {
        for (std::size_t i = 0; i < axis.second.size(); ++i) {
          FactorValues extended = cell;
          extended.emplace_back(name, factor_value(axis.second[i], field + "[" + std::to_string(i) + "]", factor));
          next.push_back(std::move(extended));
        }
      }
      cells = std::move(next);
      swept.push_back(name);
    }
    return cells;
  }
  const YAML::Node list = node["list"];
  if (!list.IsSequence() || list.size() == 0) throw sweep.error("list", "expected a non-empty list of cells");
  std::vector<FactorValues> listed;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string item = "sweep.list[" + std::to_string(i) + "]";
    if (!list[i].IsMap() || list[i].size() == 0) throw SettingsError(item, "expected a map from factor to value", list[i].Mark());
    FactorValues cell = fixed;
    std::vector<std::string> names;
    for (const auto& entry : list[i]) {
      const std::string field = item + "." + entry.first.Scalar();
      const Factor& factor = known_factor(entry.first.Scalar(), field, entry.first.Mark());
      const std::string name = factor.current_name(entry.first.Scalar());
      check_not_fixed(name, field, entry.first.Mark());
      check_once(cell, name, field, entry.first.Mark());
      cell.emplace_back(name, factor_value(entry.second, field, factor));
      names.push_back(name);
    }
    if (i == 0) swept = names;
    if (names != swept) throw SettingsError(item, "every cell of the list must set the same factors, in the same order, as the first", list[i].Mark());
    listed.push_back(std::move(cell));
  }
  return listed;
}

}  // namespace

Campaign parse_campaign(const std::string& text, const fs::path& file) {
  const YAML::Node node = parse_yaml(text, file.string());
  return with_settings_source(file.string(), [&] {
    if (!node.IsMap()) throw SettingsError("(file)", "expected a map (docs/campaigns.md)", node.Mark());
    const Settings root(node);
    root.allow_only({"campaign", "scenarios", "controllers", "draws", "fixed", "sweep", "summary_only"});
    Campaign campaign;
    campaign.file = file;
    campaign.text = text;
    campaign.sha256 = sha256_hex(text);
    if (!root.has("campaign")) throw root.error("campaign", "missing (required): the campaign's name");
    campaign.name = root.string("campaign", "");
    if (campaign.name.empty()) throw root.error("campaign", "must not be empty");
    campaign.scenarios = read_scenarios(node, file);
    if (!root.has("controllers")) throw root.error("controllers", "missing (required)");
    campaign.controllers = read_controller_specs(node["controllers"], file.string());
    if (!root.has("draws")) throw root.error("draws", "missing (required): {count, base_seed}");
    const Settings draws = root.block("draws");
    draws.allow_only({"count", "base_seed"});
    if (!draws.has("count")) throw draws.error("count", "missing (required)");
    campaign.draws = draws.integer("count", 0, 1, 1000000);
    campaign.base_seed = draws.seed("base_seed", 1);
    campaign.summary_only = root.boolean("summary_only", true);
    campaign.cells = read_sweep(node["sweep"], read_fixed(node["fixed"]), campaign.swept);
    // In floating point: the product of four counts read from the file may not fit in 64 bits.
    const double runs = static_cast<double>(campaign.cells.size()) * static_cast<double>(campaign.scenarios.size()) *
                        static_cast<double>(campaign.controllers.size()) * campaign.draws;
    if (runs > kMaxRuns) {
      std::ostringstream reason;
      reason << "the campaign would fly " << runs << " runs (cells x scenarios x controllers x draws), more than "
             << kMaxRuns;
      throw draws.error("count", reason.str());
    }
    return campaign;
  });
}

Campaign load_campaign(const fs::path& file) { return parse_campaign(read_text_file(file), file); }

}  // namespace thetad
