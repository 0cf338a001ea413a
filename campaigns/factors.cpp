#include "campaigns/factors.hpp"

#include <cmath>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <sstream>

#include "core/error.hpp"

namespace thetad {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The initial offset is a vector in RunControls; a campaign sweeps its axes one by one.
void offset_axis(RunControls& controls, int axis, double value) {
  if (!controls.initial_offset) controls.initial_offset = Eigen::Vector3d::Zero();
  (*controls.initial_offset)[axis] = value;
}

// A switch: 0 off, 1 on (a factor is a number, and anything between would be a typo).
bool switch_value(const char* name, double value) {
  if (value != 0.0 && value != 1.0) throw Error(std::string(name) + " is a switch: 0 (off) or 1 (on), got " + std::to_string(value));
  return value == 1.0;
}

// A whole number of `name` (a count or a choice's position), as the int it stands for.
int whole(const char* name, double value) {
  if (value != std::floor(value)) throw Error(std::string(name) + " takes whole numbers, got " + std::to_string(value));
  return static_cast<int>(value);
}

// The attitude offset likewise, read in degrees (as people state angles), flown in radians.
void attitude_axis(RunControls& controls, int axis, double degrees) {
  if (!controls.initial_attitude_offset) controls.initial_attitude_offset = Eigen::Vector3d::Zero();
  (*controls.initial_attitude_offset)[axis] = degrees * std::numbers::pi / 180.0;
}

}  // namespace

const std::vector<Factor>& factors() {
  static const std::vector<Factor> all = {
      {"uncertainty_scale", "", "multiplies Table 1's 21 parameter bounds (0 nominal plant, 1 the paper's, 2 twice)",
       0.0, 9.99, [](double v, RunControls& c) { c.uncertainty_scale = v; }},
      {"gust_scale", "", "multiplies the whole wind, mean and gust (0 calm, 1 the paper's gust)", 0.0, kInf,
       [](double v, RunControls& c) { c.gust_scale = v; }},
      {"gust_onset_s", "s", "time the wind starts blowing (calm air before)", 0.0, kInf,
       [](double v, RunControls& c) { c.gust_onset = v; }},
      {"noise_scale", "", "multiplies every sensor, actuator, wind-component and induced-velocity noise level", 0.0,
       kInf, [](double v, RunControls& c) { c.noise_scale = v; }},
      {"initial_offset_x_m", "m", "added to the initial north position", -kInf, kInf,
       [](double v, RunControls& c) { offset_axis(c, 0, v); }},
      {"initial_offset_y_m", "m", "added to the initial east position", -kInf, kInf,
       [](double v, RunControls& c) { offset_axis(c, 1, v); }},
      {"initial_offset_z_m", "m", "added to the initial down position (negative: higher)", -kInf, kInf,
       [](double v, RunControls& c) { offset_axis(c, 2, v); }},
      {"initial_offset_roll_deg", "deg", "added to the initial roll angle phi", -180.0, 180.0,
       [](double v, RunControls& c) { attitude_axis(c, 0, v); }},
      {"initial_offset_pitch_deg", "deg", "added to the initial pitch angle theta", -180.0, 180.0,
       [](double v, RunControls& c) { attitude_axis(c, 1, v); }},
      {"initial_offset_yaw_deg", "deg", "added to the initial yaw angle psi (heading)", -180.0, 180.0,
       [](double v, RunControls& c) { attitude_axis(c, 2, v); }},
      {"trajectory_speed_scale", "", "flies the same path this many times faster (the scenario's duration / s)",
       0.01, 100.0, [](double v, RunControls& c) { c.speed_scale = v; }},
      {"course", "deg", "turns the scenario's trajectory about its start, north towards east (the heading stays)",
       -360.0, 360.0, [](double v, RunControls& c) { c.course = v * std::numbers::pi / 180.0; }},
      {"actuator_limits", "", "the servo magnitude and rate limits (docs/model.md §12): 1 on, 0 off", 0.0, 1.0,
       [](double v, RunControls& c) { c.actuator_limits = switch_value("actuator_limits", v); }},
      {"turbulence_model", "", "the gust model on the paper's mean wind (docs/model.md §15): paper, dryden, gauss_markov",
       0.0, 2.0,
       [](double v, RunControls& c) {
         c.turbulence_model = static_cast<sim::TurbulenceSettings::Model>(whole("turbulence_model", v));
       },
       "paper dryden gauss_markov"},
      {"turbulence_intensity", "", "the Dryden intensity: light, moderate, severe (W20 = 15, 30, 45 kt)", 0.0, 2.0,
       [](double v, RunControls& c) {
         c.turbulence_intensity = static_cast<sim::TurbulenceIntensity>(whole("turbulence_intensity", v));
       },
       "light moderate severe"},
      {"turbulence_scale", "", "multiplies the Dryden or Gauss-Markov turbulence (0 none, 1 as specified)", 0.0, kInf,
       [](double v, RunControls& c) { c.turbulence_scale = v; }},
      {"servo_delay_samples", "samples", "transport delay of the command, in controller samples", 0.0,
       sim::ServoSettings::kMaxDelaySamples,
       [](double v, RunControls& c) { c.servo_delay_samples = whole("servo_delay_samples", v); }},
      {"servo_time_constant_s", "s", "first-order servo lag of every input", 0.0, 10.0,
       [](double v, RunControls& c) { c.servo_time_constant = v; }},
      {"slowdown", "", "the flight computer this many times slower than its step times (docs/model.md §15.7; the "
       "scenario's computer latency measured or step-time)", 0.0, sim::FlightComputerSettings::kMaxSlowdown,
       [](double v, RunControls& c) { c.slowdown = v; }},
      {"dt_s", "s", "plant (RK4) step; must divide the controller period", 0.0, kInf,
       [](double v, RunControls& c) { c.dt = v; }},
      {"duration_s", "s", "flight duration (shorter than the scenario: the flight stops there)", 0.0,
       sim::SimulationSettings::kMaxDuration, [](double v, RunControls& c) { c.duration = v; }},
  };
  return all;
}

const Factor* find_factor(std::string_view name) {
  // The names before docs/glossary.md put the unit last (campaign files and databases of
  // format_version 4 and earlier): a campaign file may still write them.
  static constexpr std::pair<std::string_view, std::string_view> kOldNames[] = {
      {"gust_onset", "gust_onset_s"},
      {"initial_offset_x", "initial_offset_x_m"},
      {"initial_offset_y", "initial_offset_y_m"},
      {"initial_offset_z", "initial_offset_z_m"},
      {"initial_offset_roll", "initial_offset_roll_deg"},
      {"initial_offset_pitch", "initial_offset_pitch_deg"},
      {"initial_offset_yaw", "initial_offset_yaw_deg"},
      {"servo_delay", "servo_delay_samples"},
      {"servo_time_constant", "servo_time_constant_s"},
      {"dt", "dt_s"},
      {"duration", "duration_s"},
  };
  for (const auto& [old_name, new_name] : kOldNames) {
    if (name == old_name) name = new_name;
  }
  for (const Factor& factor : factors()) {
    if (factor.name == name) return &factor;
  }
  return nullptr;
}

std::string factor_names() {
  std::string names;
  for (const Factor& factor : factors()) {
    if (!names.empty()) names += ", ";
    names += factor.name;
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
    factor->apply(value, controls);
  }
}

}  // namespace thetad
