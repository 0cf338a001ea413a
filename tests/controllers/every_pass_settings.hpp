#pragma once

// θ–D or SDRE settings with the model's design defaults (the paper's weights, u0 = hover thrust,
// docs/model.md §8.1, §6.2), and the same with every one of `passes` fixed-point passes run (tolerance 0),
// so that "3 passes" always means 3. Shared by the controller tests and the benchmarks.

#include "core/sdc_plant.hpp"

namespace thetad::testing {

template <class Settings>
Settings design_settings(const SdcPlant& model) {
  const DesignDefaults defaults = model.design_defaults();
  Settings s;
  s.Q = defaults.state_weights.asDiagonal();
  s.R = defaults.input_weights.asDiagonal();
  s.initial_input = defaults.input;
  return s;
}

template <class Settings>
Settings every_pass_settings(const SdcPlant& model, int passes) {
  Settings s = design_settings<Settings>(model);
  s.fixed_point_iterations = passes;
  s.fixed_point_tolerance = 0.0;
  return s;
}

}  // namespace thetad::testing
