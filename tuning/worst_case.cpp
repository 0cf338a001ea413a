#include "tuning/worst_case.hpp"

#include <cmath>
#include <limits>
#include <random>

#include <yaml-cpp/yaml.h>

#include "core/error.hpp"
#include "core/helicopter/uncertainty.hpp"
#include "core/parallel.hpp"
#include "experiment/flight.hpp"
#include "tuning/search.hpp"

namespace thetad::tuning {

namespace {

constexpr std::size_t kParameters = heli::kParameterUncertaintyCount;

// Thrown by the search's objective at the first flight that does not complete: nothing is worse.
struct NotCompleted {};

// The box's centre, the centres of its 2 x 21 faces, then `corners` corners with seeded signs.
std::vector<std::vector<double>> sampled_design(int corners, std::uint64_t seed) {
  std::vector<std::vector<double>> points{std::vector<double>(kParameters, 0.0)};
  for (std::size_t i = 0; i < kParameters; ++i) {
    for (const double side : {1.0, -1.0}) {
      points.emplace_back(kParameters, 0.0);
      points.back()[i] = side;
    }
  }
  std::mt19937_64 rng(seed);
  for (int c = 0; c < corners; ++c) {
    points.emplace_back(kParameters);
    for (double& x : points.back()) x = (rng() >> 63) != 0 ? 1.0 : -1.0;
  }
  return points;
}

double metric_value(WorstCaseMetric metric, const sim::RunSummary& s) {
  if (s.status != sim::RunStatus::completed) return std::numeric_limits<double>::infinity();
  if (metric == WorstCaseMetric::rms_error) return s.rms_tracking_error.norm();
  if (!s.cost_dev) throw Error("worst case of J_dev: this flight has no J_dev (" + s.cost_dev_weights + ")");
  return *s.cost_dev;
}

class Evaluator {
 public:
  Evaluator(const std::string& scenario, const RunControls& controls, const ControllerSpec& spec, WorstCaseMetric metric)
      : scenario_(scenario), controls_(controls), spec_(spec), metric_(metric) {
    controls_.parameter_uncertainty = true;
    controls_.summary_only = true;
    controls_.timing = false;
  }

  WorstCaseFlight operator()(const std::vector<double>& xi) const {
    RunControls controls = controls_;
    controls.parameter_deviations = xi;
    const Flight flight(scenario_, controls);
    PreparedController prepared = flight.prepare(spec_);
    WorstCaseFlight result{xi, flight.fly(prepared).summary, 0.0};
    result.value = metric_value(metric_, result.summary);
    return result;
  }

 private:
  std::string scenario_;
  RunControls controls_;
  ControllerSpec spec_;
  WorstCaseMetric metric_;
};

WorstCase worst_case_of(const Evaluator& evaluate, const ControllerSpec& spec, const WorstCaseOptions& options) {
  std::vector<std::vector<double>> design = sampled_design(options.corners, options.design_seed);
  if (design.size() > static_cast<std::size_t>(options.max_evaluations)) design.resize(options.max_evaluations);
  std::vector<WorstCaseFlight> flights(design.size());
  for_each_chunk(design.size(), 1, std::max(1, options.threads), [&](int, std::size_t i, std::size_t, std::size_t) {
    flights[i] = evaluate(design[i]);
  });
  WorstCase result{spec, flights.front(), flights.front(), static_cast<int>(flights.size()), {}};
  if (options.progress) options.progress(spec.label, result.evaluations, options.max_evaluations);
  for (const WorstCaseFlight& flight : flights) {
    if (flight.value > result.worst.value) result.worst = flight;
    if (std::isinf(flight.value)) break;  // the first that did not complete, in design order
  }
  if (std::isinf(result.worst.value)) {
    result.stop = "a flight of the sampled design did not complete";
    return result;
  }
  const int remaining = options.max_evaluations - result.evaluations;
  if (remaining < 2) {
    result.stop = "the budget went to the sampled design";
    return result;
  }
  FitOptions search;
  search.algorithm = "LN_COBYLA";
  search.max_local_evaluations = remaining;
  search.seed = options.design_seed;
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(kParameters);
  const SearchBox box{-ones, ones, Eigen::Map<const Eigen::VectorXd>(result.worst.xi.data(), kParameters)};
  const auto objective = [&](const Eigen::VectorXd& x) {
    WorstCaseFlight flight = evaluate(std::vector<double>(x.data(), x.data() + x.size()));
    ++result.evaluations;
    if (options.progress) options.progress(spec.label, result.evaluations, options.max_evaluations);
    const double value = flight.value;
    if (value > result.worst.value) result.worst = std::move(flight);
    if (std::isinf(value)) throw NotCompleted{};
    return -value;  // NLopt minimises
  };
  try {
    result.stop = "NLopt " + search_box(objective, box, search).stop_reason;
  } catch (const NotCompleted&) {
    result.stop = "a flight of the search did not complete";
  }
  return result;
}

nlohmann::ordered_json flight_json(const WorstCaseFlight& flight, WorstCaseMetric metric) {
  const auto names = heli::parameter_uncertainty_names();
  nlohmann::ordered_json deviations, factors;
  for (std::size_t i = 0; i < names.size(); ++i) deviations[std::string(names[i])] = flight.xi[i];
  for (const auto& [name, factor] : flight.summary.parameter_factors) factors[name] = factor;
  nlohmann::ordered_json j = {{"status", sim::status_name(flight.summary.status)},
                              {"end_time_s", flight.summary.end_time},
                              {"reason", flight.summary.reason}};
  j[metric_key(metric)] = std::isinf(flight.value) ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(flight.value);
  j["parameter_deviations"] = deviations;
  j["parameter_factors"] = factors;
  return j;
}

}  // namespace

const char* metric_key(WorstCaseMetric metric) {
  return metric == WorstCaseMetric::rms_error ? "rms_error_m" : "cost_dev";
}

WorstCaseMetric parse_worst_case_metric(const std::string& name) {
  if (name == "rms_error_m") return WorstCaseMetric::rms_error;
  if (name == "cost_dev") return WorstCaseMetric::cost_dev;
  throw Error("worst case: metric '" + name + "' (known: rms_error_m, cost_dev)");
}

WorstCases find_worst_cases(const std::string& scenario, const RunControls& controls,
                            const std::vector<ControllerSpec>& controllers, const WorstCaseOptions& options) {
  if (options.corners < 0 || options.max_evaluations < 1 || options.threads < 1)
    throw Error("worst case: corners must be >= 0, the evaluation budget and the threads >= 1");
  WorstCases cases{scenario, options, {}, {}};
  RunControls nominal = controls;
  nominal.parameter_uncertainty = true;
  const Flight flight(scenario, nominal);
  cases.provenance = flight.provenance();
  for (const ControllerSpec& spec : controllers) flight.prepare(spec);  // bad settings stop it before anything flies
  for (const ControllerSpec& spec : controllers)
    cases.controllers.push_back(worst_case_of(Evaluator(scenario, controls, spec, options.metric), spec, options));
  return cases;
}

nlohmann::ordered_json worst_case_json(const WorstCases& cases) {
  nlohmann::ordered_json j;
  j["format"] = "thetad-worst-case";
  j["format_version"] = 1;
  j["scenario"] = cases.scenario;
  j["metric"] = metric_key(cases.options.metric);
  j["options"] = {{"corners", cases.options.corners},
                  {"max_evaluations", cases.options.max_evaluations},
                  {"design_seed", cases.options.design_seed}};
  j["provenance"] = to_json(cases.provenance);
  j["controllers"] = nlohmann::ordered_json::array();
  for (const WorstCase& c : cases.controllers) {
    j["controllers"].push_back({{"label", c.controller.label},
                                {"controller", c.controller.controller},
                                {"evaluations", c.evaluations},
                                {"stop_reason", c.stop},
                                {"nominal", flight_json(c.nominal, cases.options.metric)},
                                {"worst", flight_json(c.worst, cases.options.metric)}});
  }
  return j;
}

std::string worst_case_scenario(const std::string& scenario_text, const WorstCaseFlight& flight) {
  // Every run control the command offers, as the flight had it, so that the file flies it again.
  const sim::SimulationSettings& s = flight.summary.settings;
  YAML::Node root = YAML::Load(scenario_text);
  YAML::Node simulation = root["simulation"];
  simulation["seed"] = s.seed;
  simulation["duration"] = s.duration;
  simulation["dt"] = s.dt;
  simulation["controller_period_steps"] = s.controller_period_steps;
  simulation["actuator_limits"] = s.actuator_limits.enabled;
  simulation["anti_windup"] = s.actuator_limits.anti_windup;
  YAML::Node disturbances = simulation["disturbances"];
  disturbances["parameter_uncertainty"] = true;
  disturbances["wind_gust"] = s.wind_gust.enabled;
  disturbances["measurement_noise"] = s.noise.measurement;
  disturbances["actuator_noise"] = s.noise.actuator;
  disturbances["wind_noise"] = s.noise.wind_component;
  disturbances["induced_velocity_noise"] = s.noise.induced_velocity;
  const auto names = heli::parameter_uncertainty_names();
  for (std::size_t i = 0; i < names.size(); ++i)
    disturbances["parameter_deviations"][std::string(names[i])] = flight.xi.at(i);
  // --ideal turned docs/model.md §15's blocks off.
  if (!s.turbulence.active() && s.discrete_gusts.empty()) simulation.remove("wind");
  if (!s.sensor_noise.active()) simulation.remove("sensor_noise");
  if (!s.servos.active()) simulation.remove("servos");
  YAML::Emitter out;
  out.SetDoublePrecision(std::numeric_limits<double>::max_digits10);
  out << root;
  return std::string(out.c_str()) + "\n";
}

}  // namespace thetad::tuning
