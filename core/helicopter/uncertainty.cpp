#include "core/helicopter/uncertainty.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.hpp"

namespace thetad::heli {

namespace {

// The percents of one noise category, placed by channel.
template <std::size_t N>
std::array<double, N> noise_percents(UncertaintyCategory category) {
  std::array<double, N> percents{};
  for (const auto& entry : kUncertaintyTable) {
    if (entry.category == category) percents[static_cast<std::size_t>(entry.channel)] = entry.percent;
  }
  return percents;
}

}  // namespace

void check_uncertainty_scale(double scale) {
  double largest = 0.0;
  for (const auto& entry : kUncertaintyTable) {
    if (entry.parameter != nullptr) largest = std::max(largest, entry.percent);
  }
  if (!(scale >= 0.0) || !(scale * largest < 100.0)) {
    std::ostringstream message;
    message << "uncertainty scale " << scale << ": must be >= 0 and below " << 100.0 / largest
            << " (Table 1's largest parameter bound, " << largest << " %, times the scale must stay below 100 %)";
    throw Error(message.str());
  }
}

std::string_view to_string(UncertaintyCategory category) {
  switch (category) {
    case UncertaintyCategory::measurement: return "measurement";
    case UncertaintyCategory::actuator: return "actuator";
    case UncertaintyCategory::wind_noise: return "wind noise";
    case UncertaintyCategory::model_noise: return "model noise";
    case UncertaintyCategory::parameter: return "parameter";
  }
  return "unknown";  // unreachable: every enumerator is handled above
}

std::array<double, kPhysicalStateDim> measurement_noise_percents() {
  return noise_percents<kPhysicalStateDim>(UncertaintyCategory::measurement);
}
std::array<double, kInputDim> actuator_noise_percents() { return noise_percents<kInputDim>(UncertaintyCategory::actuator); }
std::array<double, 3> wind_noise_percents() { return noise_percents<3>(UncertaintyCategory::wind_noise); }
std::array<double, 2> induced_velocity_noise_percents() { return noise_percents<2>(UncertaintyCategory::model_noise); }

ParameterDraw parameter_draw(const std::vector<double>& xi) {
  ParameterDraw draw{};
  if (xi.size() != draw.size())
    throw Error("parameter deviations: " + std::to_string(xi.size()) + " given, Table 1 has " +
                std::to_string(draw.size()) + " parameter entries");
  std::copy(xi.begin(), xi.end(), draw.begin());
  // perturbed_parameters names an entry outside [-1, 1]; checked here too, before anything flies.
  perturbed_parameters(Parameters{}, draw);
  return draw;
}

std::array<std::string_view, kParameterUncertaintyCount> parameter_uncertainty_names() {
  std::array<std::string_view, kParameterUncertaintyCount> names{};
  std::size_t next = 0;
  for (const auto& entry : kUncertaintyTable)
    if (entry.parameter != nullptr) names[next++] = entry.name;
  return names;
}

PerturbedParameters perturbed_parameters(const Parameters& nominal, const ParameterDraw& xi, double scale) {
  check_uncertainty_scale(scale);
  PerturbedParameters out{nominal, {}};
  out.report.reserve(kUncertaintyCount);
  std::size_t next = 0;
  for (const auto& entry : kUncertaintyTable) {
    UncertaintyReport row{entry.number, std::string(entry.name), entry.percent, entry.category, true, 0.0, 1.0};
    if (entry.parameter != nullptr) {
      const double x = xi[next++];
      if (!(std::abs(x) <= 1.0)) {
        std::ostringstream message;
        message << "uncertainty draw for Table 1 #" << entry.number << " (" << entry.name << "): xi = " << x
                << " is outside [-1, 1]";
        throw Error(message.str());
      }
      row.per_sample = false;
      row.percent = scale * entry.percent;
      row.xi = x;
      row.factor = 1.0 + row.percent / 100.0 * x;
      out.parameters.*entry.parameter = nominal.*entry.parameter * row.factor;
    }
    out.report.push_back(std::move(row));
  }
  return out;
}

PerturbedParameters perturbed_parameters(const Parameters& nominal, std::mt19937_64& rng, double scale) {
  ParameterDraw xi;
  for (double& x : xi) {
    // 53 random bits -> [0, 1) -> [-1, 1): identical on every standard library, unlike
    // std::uniform_real_distribution.
    x = 2.0 * std::ldexp(static_cast<double>(rng() >> 11), -53) - 1.0;
  }
  return perturbed_parameters(nominal, xi, scale);
}

PerturbedParameters worst_case_parameters(const Parameters& nominal) {
  ParameterDraw ones;
  ones.fill(1.0);
  return perturbed_parameters(nominal, ones);
}

}  // namespace thetad::heli
