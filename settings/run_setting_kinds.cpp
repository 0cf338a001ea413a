#include "settings/run_setting_kinds.hpp"

#include <algorithm>
#include <limits>
#include <sstream>
#include <vector>

#include "core/helicopter/uncertainty.hpp"

namespace thetad {

bool switch_value(double value) {
  if (value != 0.0 && value != 1.0) throw Error("a switch: 0 (off) or 1 (on), got " + std::to_string(value));
  return value == 1.0;
}

int whole(double value) {
  if (value != std::floor(value)) throw Error("takes whole numbers, got " + std::to_string(value));
  return static_cast<int>(value);
}

void read_dt(const FileField& field, RunControls& controls) {
  read_positive<&RunControls::dt>(field, controls);
  if (!controls.dt || field.block.has("controller_period_steps")) return;
  const double dt = *controls.dt, period = sim::SimulationSettings{}.controller_period(),
               steps = std::round(period / dt);
  std::ostringstream reason;
  if (steps > std::numeric_limits<int>::max()) {
    reason << dt << " s: more than 2^31 - 1 plant steps per controller period " << period << " s";
    throw field.block.error(field.key, reason.str());
  }
  if (steps < 1.0 || std::abs(steps * dt - period) > 1e-9 * period) {
    reason << dt << " s does not divide the controller period " << period
           << " s (the controller samples at 1 kHz with zero-order hold; or give controller_period_steps)";
    throw field.block.error(field.key, reason.str());
  }
  controls.controller_period_steps = static_cast<int>(steps);
}

void read_parameter_deviations(const FileField& field, RunControls& controls) {
  if (!field.block.has(field.key)) return;
  const auto deviations = field.block.block(field.key);
  const auto names = heli::parameter_uncertainty_names();
  std::string allowed;
  for (const auto name : names) allowed += (allowed.empty() ? "" : ", ") + std::string(name);
  for (const auto& item : deviations.node()) {
    const std::string key = item.first.as<std::string>();
    if (std::find(names.begin(), names.end(), key) == names.end())
      throw deviations.error(key, "not a parameter of Table 1 (docs/model.md §9.1; allowed: " + allowed + ")");
  }
  std::vector<double> xi(names.size(), 0.0);
  for (std::size_t i = 0; i < names.size(); ++i) xi[i] = deviations.number(std::string(names[i]), 0.0, -1.0, 1.0);
  controls.parameter_deviations = std::move(xi);
}

void read_duration(const FileField& field, RunControls& controls) {
  read_positive<&RunControls::duration>(field, controls);
  if (controls.duration && *controls.duration > sim::SimulationSettings::kMaxDuration)
    throw field.block.error(field.key, "at most 86400 s (one simulated day)");
}

void read_measurement_noise_on(const FileField& field, RunControls& controls) {
  if (!field.block.has(field.key)) return;
  controls.measurement_noise_on =
      field.block.choice(field.key, "", {"feedback_signal", "absolute_state"}) == "feedback_signal"
          ? sim::MeasurementNoiseOn::feedback_signal
          : sim::MeasurementNoiseOn::absolute_state;
}

}  // namespace thetad
