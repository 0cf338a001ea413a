#include "campaigns/factors.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "core/error.hpp"

namespace thetad {

const std::vector<Factor>& factors() {
  static const std::vector<Factor> all = [] {
    std::vector<Factor> found;
    for (const RunSetting& setting : run_settings()) {
      if (setting.factor_column > 0) found.push_back(setting);
    }
    std::sort(found.begin(), found.end(),
              [](const Factor& a, const Factor& b) { return a.factor_column < b.factor_column; });
    return found;
  }();
  return all;
}

const Factor* find_factor(std::string_view name) {
  for (const RunSetting& setting : run_settings()) {
    if (setting.is_factor() && setting.names(name)) return &setting;
  }
  return nullptr;
}

std::string factor_names() {
  std::string names;
  for (const Factor& factor : factors()) names += (names.empty() ? "" : ", ") + std::string(factor.name);
  for (const RunSetting& setting : run_settings()) {
    if (setting.is_family()) names += ", " + std::string(setting.name);
  }
  return names;
}

std::optional<double> choice_value(const Factor& factor, std::string_view name) {
  std::string_view rest = factor.choices;
  for (double position = 0.0; !rest.empty(); position += 1.0) {
    const std::size_t space = rest.find(' ');
    if (rest.substr(0, space) == name) return position;
    rest = space == std::string_view::npos ? std::string_view() : rest.substr(space + 1);
  }
  return std::nullopt;
}

double factor_value(const Factor& factor, const std::string& text) {
  char* end = nullptr;
  double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size()) {
    const std::optional<double> chosen = choice_value(factor, text);
    if (!chosen)
      throw Error(factor.choices.empty() ? "expected a number, got '" + text + "'"
                                         : "expected one of " + std::string(factor.choices) + " (or its position), got '" +
                                               text + "'");
    value = *chosen;
  }
  if (!std::isfinite(value) || value < factor.min || value > factor.max) {
    std::ostringstream reason;
    reason << "value " << text << " is outside [" << factor.min << ", " << factor.max << "]";
    throw Error(reason.str());
  }
  return value;
}

void apply(const FactorValues& values, RunControls& controls) {
  for (const auto& [name, value] : values) {
    const Factor* factor = find_factor(name);
    if (factor == nullptr) throw Error("unknown campaign factor '" + name + "' (known: " + factor_names() + ")");
    try {
      factor->set(name, value, controls);
    } catch (const Error& error) {
      throw Error(name + ": " + error.what());
    }
  }
}

}  // namespace thetad
