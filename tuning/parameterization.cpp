#include "tuning/parameterization.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "tuning/closed_loop.hpp"

namespace thetad::tuning {

namespace {

std::vector<double> values(const Eigen::VectorXd& v) { return {v.data(), v.data() + v.size()}; }

// The block's diagonal `key`, else `fallback`.
Eigen::VectorXd base_weights(const YAML::Node& base, const char* key, const Eigen::VectorXd& fallback,
                             const std::string& controller) {
  if (!base || !base.IsMap() || !base[key]) return fallback;
  const auto given = base[key].as<std::vector<double>>();
  if (static_cast<Eigen::Index>(given.size()) != fallback.size())
    throw Error("tuning: " + controller + "'s " + key + " has " + std::to_string(given.size()) + " entries, the plant needs " +
                std::to_string(fallback.size()));
  return Eigen::Map<const Eigen::VectorXd>(given.data(), fallback.size());
}

}  // namespace

Parameterization series_parameters(const YAML::Node& base, int terms, const FitOptions& options) {
  const int p = terms - 1;
  Parameterization series;
  series.controller = "theta-d";
  series.kind = "series";
  for (const char* name : {"k", "l"})
    for (int i = 1; i <= p; ++i) series.names.push_back(name + std::to_string(i));
  series.box = series_box(options, p);
  series.spec = [base, terms, p](const Eigen::VectorXd& x, const std::string& label) {
    return theta_d_spec(base, label, terms, x.head(p), x.tail(p));
  };
  series.given = theta_d_spec(base, "theta-d", terms, {}, {});
  return series;
}

Parameterization weight_parameters(const std::string& controller, const YAML::Node& base, const SdcPlant& plant,
                                   double log10_bound) {
  if (!(log10_bound > 0.0) || !std::isfinite(log10_bound))
    throw Error("tuning: the weights' log10 bound must be positive and finite, got " + std::to_string(log10_bound));
  const DesignDefaults defaults = plant.design_defaults();
  const Eigen::VectorXd Q0 = base_weights(base, "Q", defaults.state_weights, controller),
                        R0 = base_weights(base, "R", defaults.input_weights, controller);
  const std::vector<LogColumn> states = plant.state_columns(), inputs = plant.input_columns();
  const std::vector<TrackedState> tracked = plant.tracked_states();
  const std::string reference_unit = tracked.empty() ? states.front().unit : states[static_cast<std::size_t>(tracked.front().index)].unit;

  Parameterization weights;
  weights.controller = controller;
  weights.kind = "weights";
  // state_parameter[j]: the factor state j takes, one per unit; none for the reference group and
  // for zero weights, which no factor changes.
  std::vector<int> state_parameter(states.size(), -1);
  std::vector<std::string> units;
  for (std::size_t j = 0; j < states.size(); ++j) {
    const std::string& unit = states[j].unit;
    if (unit == reference_unit || !(Q0[static_cast<Eigen::Index>(j)] > 0.0)) continue;
    const auto found = std::find(units.begin(), units.end(), unit);
    state_parameter[j] = static_cast<int>(found - units.begin());
    if (found == units.end()) {
      units.push_back(unit);
      weights.names.push_back("log10 Q[" + unit + "]");
    }
  }
  const auto state_groups = static_cast<int>(weights.names.size());
  for (const LogColumn& input : inputs) weights.names.push_back("log10 R[" + input.name + "]");
  const auto size = static_cast<Eigen::Index>(weights.names.size());
  weights.box = {Eigen::VectorXd::Constant(size, -log10_bound), Eigen::VectorXd::Constant(size, log10_bound),
                 Eigen::VectorXd::Zero(size)};
  weights.spec = [base, controller, Q0, R0, state_parameter, state_groups](const Eigen::VectorXd& x,
                                                                          const std::string& label) {
    Eigen::VectorXd Q = Q0, R = R0;
    for (std::size_t j = 0; j < state_parameter.size(); ++j)
      if (state_parameter[j] >= 0) Q[static_cast<Eigen::Index>(j)] *= std::pow(10.0, x[state_parameter[j]]);
    for (Eigen::Index i = 0; i < R.size(); ++i) R[i] *= std::pow(10.0, x[state_groups + i]);
    YAML::Node block = base ? YAML::Clone(base) : YAML::Node(YAML::NodeType::Map);
    block["Q"] = values(Q);
    block["R"] = values(R);
    return ControllerSpec{label, controller, block, {}, {}};
  };
  weights.given = weights.spec(weights.box.start, controller);
  return weights;
}

}  // namespace thetad::tuning
