#include "experiment/flight.hpp"

#include <chrono>
#include <cstdio>

#include "controllers/registry.hpp"
#include "core/error.hpp"
#include "core/helicopter/designed_weights.hpp"
#include "core/text_file.hpp"
#include "experiment/disturbance_effects.hpp"
#include "settings/settings.hpp"
#include "experiment/build_info.hpp"
#include "experiment/controller_build.hpp"
#include "experiment/plant_registry.hpp"
#include "experiment/scenario_files.hpp"
#include "experiment/sha256.hpp"
#include "experiment/step_time_file.hpp"

namespace thetad {

namespace {

// The plant `name` built from its settings block with the run's plant.NAME factors over it; errors
// name the file (`source`) and the field, or the factor.
NamedPlant registered_plant(const std::string& name, const YAML::Node& block, const RunControls& controls,
                            const std::string& source) {
  const PlantRegistry& registry = PlantRegistry::instance();
  if (!registry.contains(name))
    throw Error(source + ": field 'plant': unknown plant '" + name + "' (known: " + registry.known_names() +
                "; a plug-in's plant needs --plugin or THETAD_PLUGIN_PATH)");
  YAML::Node settings = block;
  if (!controls.plant_settings.empty()) {
    settings = block ? YAML::Clone(block) : YAML::Node(YAML::NodeType::Map);
    for (const auto& [key, value] : controls.plant_settings) settings[key] = value;
  }
  const auto factor = [&](const std::string& key) {
    return controls.plant_settings.contains(key) ? "factor 'plant." + key + "'" : std::string();
  };
  try {
    return with_settings_source(source, [&] { return registry.make(name, settings); });
  } catch (const SettingsError& error) {
    if (factor(error.field()).empty()) throw;
    throw Error(source + ": " + factor(error.field()) + ": " + error.reason() + " (a setting of the plant " + name + ")");
  } catch (const Error& error) {
    const std::string given = controls.plant_settings.empty() ? "" : " with the factors plant.NAME";
    throw Error(source + ": field 'plant_settings'" + given + ": " + error.what());
  }
}

// "plant.epsilon, initial_state.0": the plant's factors among `controls`, for messages.
std::string plant_factors(const RunControls& controls) {
  std::string names;
  for (const auto& [key, value] : controls.plant_settings) names += (names.empty() ? "" : ", ") + ("plant." + key);
  for (const auto& [index, value] : controls.initial_state_entries)
    names += (names.empty() ? "" : ", ") + ("initial_state." + std::to_string(index));
  return names;
}

}  // namespace

Flight::Flight(const std::string& scenario, const RunControls& controls)
    : Flight(from_text(read_text_file(find_scenario(scenario)), find_scenario(scenario).string(), controls)) {}

Flight Flight::from_text(const std::string& text, const std::string& file, const RunControls& controls) {
  Scenario parsed = parse_scenario(text, file);
  Flight flight;
  if (parsed.plant.empty()) {
    flight = Flight(parsed, controls);
  } else {
    NamedPlant named = registered_plant(parsed.plant, parsed.plant_settings, controls, parsed.source);
    if (parsed.initial_state.size() == 0) parsed.initial_state = named.initial_state;
    flight = plant_flight(std::move(named.plant), std::move(parsed), controls);
  }
  // The very bytes it was parsed from, so that a replay needs no file that may have changed.
  flight.provenance_.scenario_text = text;
  flight.provenance_.scenario_sha256 = sha256_hex(text);
  // Absolute, so that a replay from another folder finds it.
  flight.provenance_.scenario_file = std::filesystem::absolute(file).lexically_normal().string();
  return flight;
}

Flight::Flight(const Scenario& parsed, const RunControls& controls)
    : scenario_(as_flown(controls, parsed)),
      settings_(scenario_.simulation_settings()),
      initial_state_(offset_initial_state(controls, scenario_.initial_state)) {
  if (!plant_factors(controls).empty())
    throw Error(scenario_.source + ": " + plant_factors(controls) + ": a plant's settings and initial state (docs/plants.md); "
                "the helicopter's scenario has neither (its initial offsets move its start)");
  const auto helicopter = std::make_shared<const heli::Helicopter>(heli::Parameters::nominal(), scenario_.model_options);
  helicopter_ = helicopter.get();
  plant_ = helicopter;
  // A replay gives the computer as recorded, step times included: the bench file is not read again.
  if (scenario_.simulation.beyond_paper.step_time_file && !controls.beyond_paper.computer)
    load_step_times(*scenario_.simulation.beyond_paper.step_time_file, settings_.computer);
  apply(controls, settings_);
  provenance_.build = build_info();
  provenance_.plant = "helicopter";
  provenance_.scenario_name = scenario_.name;
  provenance_.model_preset = scenario_.model_preset;
  provenance_.model_options = scenario_.model_options.to_string();
  provenance_.seed = settings_.seed;
  provenance_.dt = settings_.dt;
  const auto entries = [](const Eigen::Vector3d& v) { return std::array<double, 3>{v.x(), v.y(), v.z()}; };
  if (controls.initial_offset) provenance_.initial_offset = entries(*controls.initial_offset);
  if (controls.initial_attitude_offset) provenance_.initial_attitude_offset = entries(*controls.initial_attitude_offset);
  provenance_.speed_scale = controls.speed_scale;
  provenance_.course = controls.course;
  settings_.check_memory(log_width());
}

Flight Flight::plant_flight(std::shared_ptr<const SdcPlant> plant, Scenario scenario, const RunControls& controls) {
  const std::string& name = scenario.plant;
  const std::string where = scenario.source.empty() ? "plant " + name : scenario.source + " (plant " + name + ")";
  if (scenario.initial_state.size() != plant->state_dim())
    throw Error(where + ": " + (scenario.source.empty() ? "the initial state" : "field 'initial_state'") + " has " +
                std::to_string(scenario.initial_state.size()) + " entries, the plant " +
                std::to_string(plant->state_dim()) + " states");
  if (controls.initial_offset || controls.initial_attitude_offset || controls.speed_scale || controls.course)
    throw Error(where + ": initial offsets, speed scales and courses apply to the helicopter's scenarios");
  for (const auto& [index, value] : controls.initial_state_entries) {
    if (index >= plant->state_dim())
      throw Error(where + ": initial_state." + std::to_string(index) + ": the plant has " +
                  std::to_string(plant->state_dim()) + " states (initial_state.0 to initial_state." +
                  std::to_string(plant->state_dim() - 1) + ")");
    scenario.initial_state[index] = value;
  }
  // It flies as it is (sim::NoDisturbances): a switch that turns a disturbance on would be recorded
  // as on and have no effect.
  for (const auto& asked : {controls.parameter_uncertainty, controls.wind_gust, controls.measurement_noise,
                            controls.actuator_noise, controls.wind_noise, controls.induced_velocity_noise,
                            controls.actuator_limits}) {
    if (asked.value_or(false))
      throw Error(where + ": it flies without disturbances or actuator limits (those are the helicopter's)");
  }
  Flight flight;
  flight.settings_ = scenario.simulation_settings(sim::SimulationSettings::ideal());
  apply(controls, flight.settings_);
  flight.settings_.actuator_limits.enabled = false;  // the helicopter's servos, nothing to do with this plant
  scenario.duration = flight.settings_.duration;
  if (scenario.description.empty()) scenario.description = "the plant " + name + " regulated to the origin";
  flight.initial_state_ = scenario.initial_state;
  flight.provenance_.build = build_info();
  flight.provenance_.plant = name;
  flight.provenance_.scenario_name = scenario.name;
  flight.provenance_.initial_state.assign(scenario.initial_state.data(),
                                          scenario.initial_state.data() + scenario.initial_state.size());
  flight.provenance_.plant_settings = controls.plant_settings;
  flight.provenance_.seed = flight.settings_.seed;
  flight.provenance_.dt = flight.settings_.dt;
  flight.scenario_ = std::move(scenario);
  flight.plant_ = std::move(plant);
  flight.settings_.check_memory(flight.log_width());
  return flight;
}

Flight Flight::of_plant(std::shared_ptr<const SdcPlant> plant, const std::string& name,
                        const Eigen::VectorXd& initial_state, const RunControls& controls) {
  if (!controls.duration) throw Error("plant " + name + ": its flight needs a duration (it has no scenario to say it)");
  if (!controls.plant_settings.empty())
    throw Error("plant " + name + ": the factors plant.NAME set a registered plant's settings (flown by its name); "
                "this plant object is built with its own");
  Scenario scenario;
  scenario.name = name;
  scenario.plant = name;
  scenario.initial_state = initial_state;
  scenario.duration = *controls.duration;
  return plant_flight(std::move(plant), std::move(scenario), controls);
}

Flight Flight::of_plant(const std::string& name, const std::optional<Eigen::VectorXd>& initial_state,
                        const RunControls& controls) {
  PlantRegistry::instance().entry(name);  // an unknown name: the registry's message, listing the known ones
  NamedPlant named = registered_plant(name, YAML::Node(), controls, "plant " + name);
  RunControls built = controls;  // the plant settings are in the plant built
  built.plant_settings.clear();
  Flight flight = of_plant(std::move(named.plant), name, initial_state ? *initial_state : named.initial_state, built);
  flight.provenance_.plant_settings = controls.plant_settings;
  return flight;
}

Flight Flight::of_scenario_or_plant(const std::string& scenario, const std::string& plant,
                                   const std::optional<Eigen::VectorXd>& initial_state, const RunControls& controls) {
  if (scenario.empty() == plant.empty())
    throw Error("a flight needs a scenario or a registered plant: one of them" +
                std::string(scenario.empty() ? "" : " (a scenario file may name a plant: docs/plants.md)"));
  if (!plant.empty()) return of_plant(plant, initial_state, controls);
  if (initial_state) throw Error("an initial state is given for a plant; a scenario file says its own");
  return Flight(scenario, controls);
}

const heli::Helicopter& Flight::model() const {
  if (!helicopter_) throw Error("the flight of plant " + scenario_.name + " has no helicopter to give this command");
  return *helicopter_;
}

std::unique_ptr<sim::Disturbances> Flight::make_disturbances() const {
  if (helicopter_)
    return std::make_unique<sim::HelicopterDisturbances>(settings_, helicopter_->parameters(), helicopter_->options());
  return std::make_unique<sim::NoDisturbances>(*plant_);
}

std::string Flight::disturbances() const {
  std::vector<std::string> paper, beyond;
  for (const DisturbanceSource& source : active_sources(settings_)) (source.paper ? paper : beyond).push_back(source.name);
  const char* limits = settings_.actuator_limits.enabled ? "; actuator limits on" : "; no actuator limits";
  const auto listed = [](const std::vector<std::string>& names) {
    std::string text;
    for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
    return text;
  };
  if (paper.empty() && beyond.empty())
    return settings_.actuator_limits.enabled ? std::string("no uncertainty, noise or wind") + limits
                                             : "ideal (no uncertainty, noise, wind or actuator limits)";
  const std::string papers = paper.size() == kPaperDisturbanceSources ? "all disturbances (the paper's)"
                             : paper.empty()                ? "none of the paper's disturbances"
                                                            : "of the paper's disturbances " + listed(paper);
  return papers + (beyond.empty() ? "" : "; beyond them " + listed(beyond)) + limits;
}

void Flight::set_keep_log(bool keep) {
  sim::SimulationSettings settings = settings_;
  settings.keep_log = keep;
  settings.validate();
  settings.check_memory(log_width());
  settings_ = settings;
}

std::size_t Flight::log_width() const { return sim::log_schema(*plant_, *make_disturbances()).size(); }

std::optional<sim::DeviationCost> Flight::deviation_cost(std::string& why_not) const {
  if (plant_->bias_state() < 0) {
    why_not = "none: the plant has no bias state (SdcPlant::bias_state)";
    return std::nullopt;
  }
  std::shared_ptr<const TrimSource> trims;
  try {
    trims = trims_->get(*plant_, scenario_.trajectory, settings_.duration, settings_.controller_period());
  } catch (const Error& error) {
    // The run flies all the same: only its score cannot be had.
    why_not = std::string("none: ") + error.what();
    return std::nullopt;
  }
  if (!trims) {
    why_not = "none: the plant has no trims (SdcPlant::trim_source)";
    return std::nullopt;
  }
  // One Q, R for every controller: the helicopter's designed set, another plant's design weights.
  const DesignDefaults defaults = plant_->design_defaults();
  const sim::DeviationWeights weights =
      helicopter_ ? sim::DeviationWeights{heli::designed_state_weights(), heli::designed_input_weights(),
                                          "the designed weights of scenarios/designed.settings.yaml (docs/weights.md)"}
                  : sim::DeviationWeights{defaults.state_weights, defaults.input_weights, "the plant's design weights"};
  return sim::DeviationCost(*plant_, trims, weights, settings_.controller_period());
}

sim::SimulationSettings Flight::flown_settings(const std::string& label) const {
  sim::SimulationSettings settings = settings_;
  sim::FlightComputerSettings& computer = settings.computer;
  if (computer.latency == sim::FlightComputerSettings::Latency::step_time && !computer.step_times.empty())
    computer.step_time = computer.step_time_of(label);
  return settings;
}

PreparedController Flight::prepare(const ControllerSpec& spec) const {
  flown_settings(spec.label);  // fails here, before any flight, when the flight computer has no step time for it
  ControllerContext context(*plant_, initial_state_, 0.0);
  context.reference = &scenario_.trajectory;
  context.duration = settings_.duration;
  context.controller_period = settings_.controller_period();
  context.shared_trims = trims_;
  BuiltController built = build_controller(spec, context);
  return {spec, std::move(built.controller), built.settings, {}};
}

RunResult Flight::fly(PreparedController& prepared, Progress* progress, const std::string& heading,
                      const std::function<void(double t)>& observe) const {
  RunResult result;
  result.spec = prepared.spec;
  result.settings = prepared.settings;
  result.controller_origin =
      prepared.origin.empty() ? ControllerRegistry::instance().origin(prepared.spec.controller) : prepared.origin;
  result.provenance = provenance_;
  if (settings_.measure_compute_time) stamp_host_and_time(result.provenance);
  std::string no_deviation;
  std::optional<sim::DeviationCost> deviation = deviation_cost(no_deviation);
  if (progress) progress->start(heading.empty() ? prepared.spec.label + ":" : heading, settings_.duration);
  const auto start = std::chrono::steady_clock::now();
  const auto report = [progress, &observe](double t) {
    if (progress) progress->update(t);
    if (observe) observe(t);
  };
  const std::unique_ptr<sim::Disturbances> disturbances = make_disturbances();
  sim::RunResult flown = sim::simulate(*prepared.controller, *disturbances, scenario_.trajectory, initial_state_,
                                       flown_settings(prepared.spec.label),
                                       progress || observe ? std::function<void(double)>(report) : std::function<void(double)>(),
                                       deviation ? &*deviation : nullptr);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.summary = std::move(flown.summary);
  if (!deviation) result.summary.cost_dev_weights = no_deviation;
  result.log = std::move(flown.log);
  if (settings_.measure_compute_time) result.wall_time_s = wall;
  if (progress) {
    char outcome[160];
    std::snprintf(outcome, sizeof outcome, "%s (%.1f s wall)", status_text(result.summary).c_str(), wall);
    progress->finish(outcome);
  }
  return result;
}

}  // namespace thetad
