#include "core/trim_sweep.hpp"

#include <numbers>
#include <optional>
#include <sstream>
#include <string>

#include "core/error.hpp"

namespace thetad {

namespace {

using RotorSpeedModel = heli::ModelOptions::RotorSpeedModel;

heli::ModelOptions governor_options(const heli::Helicopter& model) {
  heli::ModelOptions options = model.options();
  options.rotor_speed_model = RotorSpeedModel::governor;
  return options;
}

struct Sweep {
  std::optional<Trim> guess;
  const heli::Helicopter* plant = nullptr;  // the model of the last trim
};

std::string condition_text(double speed, double course, double climb_rate) {
  std::ostringstream text;
  text << "speed " << speed << " m/s, course " << course * 180.0 / std::numbers::pi << " deg, climb " << climb_rate
       << " m/s";
  return text.str();
}

}  // namespace

std::vector<double> envelope_speeds() { return {0.0, 1.0, 2.0, 3.0, 4.0, 6.0, 8.0, 10.0, 12.5, 15.0, 17.5, 20.0}; }

void sweep_trims(const heli::Helicopter& model, const TrimGridAxes& axes,
                 const std::function<void(std::size_t, std::size_t, std::size_t, const GridTrim&)>& visit) {
  const heli::Helicopter governor(model.parameters(), governor_options(model));
  for (std::size_t k = 0; k < axes.climb_rates.size(); ++k) {
    Sweep zero_speed;  // the first course's sweep at speed 0
    for (std::size_t j = 0; j < axes.courses.size(); ++j) {
      Sweep sweep{{}, &model};
      for (std::size_t i = 0; i < axes.speeds.size(); ++i) {
        const double speed = axes.speeds[i], course = axes.courses[j], climb = axes.climb_rates[k];
        if (speed == 0.0 && j > 0) {
          sweep = zero_speed;
          visit(i, j, k, GridTrim{*sweep.guess, *sweep.plant});
          continue;
        }
        const TrimCondition condition = TrimCondition::straight(speed, course, climb, axes.altitude);
        std::optional<Trim> trim;
        if (sweep.plant == &model && model.options().rotor_speed_model != RotorSpeedModel::governor) {
          try {
            trim = find_trim(model, condition, TrimOptions{.initial_guess = sweep.guess});
          } catch (const Error&) {
            sweep.plant = &governor;
          }
        } else {
          sweep.plant = &governor;
        }
        if (!trim) {
          try {
            trim = find_trim(governor, condition, TrimOptions{.initial_guess = sweep.guess});
          } catch (const Error& error) {
            throw Error("no trim at " + condition_text(speed, course, climb) + ": " + error.what());
          }
        }
        sweep.guess = std::move(trim);
        if (speed == 0.0) zero_speed = sweep;
        visit(i, j, k, GridTrim{*sweep.guess, *sweep.plant});
      }
    }
  }
}

}  // namespace thetad
