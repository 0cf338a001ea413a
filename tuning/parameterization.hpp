#pragma once

// What a closed-loop search tunes, the same way for every controller: a box of parameters and the
// controller each point of it flies. θ–D's series parameters k_i, l_i; or any controller's weights
// Q and R (docs/tuning.md "Tuning any controller's weights"), so that every controller of a
// comparison can be given the same objective and the same evaluation budget.

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <yaml-cpp/yaml.h>

#include "core/sdc_plant.hpp"
#include "experiment/controller_spec.hpp"
#include "tuning/search.hpp"

namespace thetad::tuning {

struct Parameterization {
  std::string controller;          // the registry name of the controller tuned
  std::string kind;                // "series" or "weights"
  std::vector<std::string> names;  // one per parameter, for the reports
  SearchBox box;
  // The controller at x, labelled `label`.
  std::function<ControllerSpec(const Eigen::VectorXd& x, const std::string& label)> spec;
  // The controller as given (its block's own settings): what the tuned one is validated against.
  ControllerSpec given;

  ControllerSpec default_spec(const std::string& label) const {
    ControllerSpec labelled = given;
    labelled.label = label;
    return labelled;
  }
};

// θ–D's k_1 … k_{N−1}, l_1 … l_{N−1} in the box and from the start of `options`, on the settings
// block `base` (null: every default) with `terms` terms.
Parameterization series_parameters(const YAML::Node& base, int terms, const FitOptions& options);

// The weights of `controller` (any controller whose settings take the diagonals `Q` and `R`):
// Q_j = Q0_j 10^{x_g(j)}, R_i = R0_i 10^{x_i}, Q0, R0 the block's `Q`, `R` (else the plant's design
// weights), x in [−log10_bound, log10_bound], starting at 0. The states are grouped by their unit
// (velocities, angles, rates, integrals, ...: one factor per group), each input is a group of its
// own; the group of the first tracked state (the positions) keeps factor 1, because a common
// factor on Q and R leaves a Riccati gain as it is; groups whose weights are all 0 are left out.
// Throws thetad::Error for a bound that is not positive and finite, or base weights of the wrong size.
Parameterization weight_parameters(const std::string& controller, const YAML::Node& base, const SdcPlant& plant,
                                   double log10_bound = 2.0);

}  // namespace thetad::tuning
