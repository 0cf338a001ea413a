#include "scenarios/scenario.hpp"

#include <algorithm>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "settings/run_settings.hpp"
#include "settings/settings.hpp"
#include "settings/yaml_document.hpp"
#include "core/error.hpp"
#include "core/text_file.hpp"
#include "core/helicopter/state.hpp"

namespace thetad {

namespace {

std::string seconds(double t) {
  std::ostringstream text;
  text << t << " s";
  return text.str();
}

// The value of `key` in `map`, or an undefined node (a Settings block with every default) when the
// key is absent: yaml-cpp's const lookup of a missing key gives an invalid node instead.
YAML::Node child(const YAML::Node& map, const char* key) {
  return map.IsMap() && map[key] ? map[key] : YAML::Node();
}

void require(const Settings& block, const std::string& key) {
  if (!block.has(key)) throw block.error(key, "missing (required)");
}

double positive(const Settings& block, const std::string& key) {
  require(block, key);
  const double value = block.number(key, 0.0);
  if (!(value > 0.0)) throw block.error(key, "must be > 0");
  return value;
}

// [x, y, h] with h the altitude (up, >= 0: the ground) as NED [x, y, -h].
Eigen::Vector3d position(const Settings& block, const std::string& key, const Eigen::Vector3d& fallback_ned) {
  const Eigen::Vector3d fallback(fallback_ned.x(), fallback_ned.y(), -fallback_ned.z());
  const Eigen::Vector3d xyh = block.vector(key, fallback, 3);
  if (xyh.z() < 0.0) throw block.error(key, "altitude h (the third entry) must be >= 0: the ground is h = 0");
  return {xyh.x(), xyh.y(), -xyh.z()};
}

Motion read_motion(const Settings& phase, const std::string& type) {
  if (type == "hold") {
    phase.allow_only({"name", "type", "time"});
    return Hold{};
  }
  if (type == "ramp" || type == "step" || type == "blend") {
    phase.allow_only({"name", "type", "time", "to"});
    require(phase, "to");
    const Eigen::Vector3d to = position(phase, "to", Eigen::Vector3d::Zero());
    if (type == "ramp") return Ramp{to};
    if (type == "step") return Step{to};
    return Blend{to};
  }
  if (type == "accelerate") {
    phase.allow_only({"name", "type", "time", "direction", "speed"});
    require(phase, "direction");
    require(phase, "speed");
    const Eigen::Vector3d xyh = phase.vector("direction", Eigen::Vector3d::Zero(), 3);
    if (!(xyh.norm() > 0.0)) throw phase.error("direction", "must not be zero");
    const Eigen::Vector2d speed = phase.vector("speed", Eigen::Vector2d::Zero(), 2, 0.0);
    return Accelerate{Eigen::Vector3d(xyh.x(), xyh.y(), -xyh.z()).normalized(), speed(0), speed(1)};
  }
  if (type == "sinusoid") {
    phase.allow_only({"name", "type", "time", "amplitude", "period"});
    require(phase, "amplitude");
    const Eigen::Vector3d xyh = phase.vector("amplitude", Eigen::Vector3d::Zero(), 3);
    return Sinusoid{{xyh.x(), xyh.y(), -xyh.z()}, positive(phase, "period")};
  }
  if (type == "figure8") {
    phase.allow_only({"name", "type", "time", "amplitude_x", "amplitude_y", "period"});
    return FigureEight{positive(phase, "amplitude_x"), positive(phase, "amplitude_y"), positive(phase, "period")};
  }
  phase.allow_only({"name", "type", "time", "radius", "period", "altitude_change", "direction"});
  const double radius = positive(phase, "radius");
  const double period = positive(phase, "period");
  const double descent = phase.number("altitude_change", 0.0);
  const bool counterclockwise =
      phase.choice("direction", "counterclockwise", {"counterclockwise", "clockwise"}) == "counterclockwise";
  return Circle{radius, period, descent, counterclockwise};
}

// Phases back to back from 0; returns the end of the last one.
double read_phases(const YAML::Node& root, PhasedTrajectory& trajectory) {
  const Settings top(root);
  require(top, "phases");
  const YAML::Node phases = root["phases"];
  if (!phases.IsSequence() || phases.size() == 0) throw top.error("phases", "expected a non-empty list of phases");

  std::string previous;
  for (std::size_t i = 0; i < phases.size(); ++i) {
    const Settings indexed(phases[i], "phases[" + std::to_string(i) + "]");
    require(indexed, "type");
    const std::string type =
        indexed.choice("type", "", {"hold", "ramp", "step", "blend", "accelerate", "sinusoid", "figure8", "circle"});
    const std::string name = indexed.string("name", type);
    const Settings phase(phases[i], "phases." + name);

    require(phase, "time");
    const Eigen::Vector2d time = phase.vector("time", Eigen::Vector2d::Zero(), 2, 0.0);
    const double start = time(0), end = time(1);
    if (!(end > start)) throw phase.error("time", "ends at " + seconds(end) + ", not after its start " + seconds(start));
    const double expected_start = trajectory.end_time();
    if (i == 0 && start != 0.0) throw phase.error("time", "the first phase must start at 0 s, not " + seconds(start));
    if (start < expected_start) {
      throw phase.error("time", "starts at " + seconds(start) + ", before phase '" + previous + "' ends at " +
                                    seconds(expected_start) + " (phases must be in time order and must not overlap)");
    }
    if (start > expected_start) {
      throw phase.error("time", "starts at " + seconds(start) + ", leaving a gap after phase '" + previous +
                                    "' which ends at " + seconds(expected_start) + " (phases must be back to back)");
    }
    trajectory.append(name, end, read_motion(phase, type));
    previous = name;
  }
  return trajectory.end_time();
}

Eigen::VectorXd read_initial_state(const YAML::Node& root) {
  using namespace heli;
  Eigen::VectorXd x0 = Eigen::VectorXd::Zero(kStateDim);
  x0(kS) = 1.0;
  const Settings initial(child(root, "initial_state"), "initial_state");
  initial.allow_only({"position", "velocity", "attitude", "rates", "flapping"});
  x0.segment<3>(kXp) = position(initial, "position", Eigen::Vector3d::Zero());
  x0.segment<3>(kU) = initial.vector("velocity", Eigen::Vector3d::Zero(), 3);
  x0.segment<3>(kPhi) = initial.vector("attitude", Eigen::Vector3d::Zero(), 3);
  x0.segment<3>(kP) = initial.vector("rates", Eigen::Vector3d::Zero(), 3);
  x0.segment<2>(kA1) = initial.vector("flapping", Eigen::Vector2d::Zero(), 2);
  return x0;
}

heli::ModelOptions read_model(const YAML::Node& node, std::string& preset) {
  const Settings model(node, "simulation.model");
  preset = model.choice("preset", "resolved", {"resolved", "paper"});
  heli::ModelOptions options = heli::ModelOptions::preset(preset);
  if (!node.IsMap()) return options;
  for (const auto& item : node) {
    const std::string key = item.first.Scalar();
    if (key == "preset") continue;
    const bool known = std::find(heli::ModelOptions::names.begin(), heli::ModelOptions::names.end(), key) !=
                       heli::ModelOptions::names.end();
    if (!known) {
      std::string allowed = "preset";
      for (const auto name : heli::ModelOptions::names) allowed += ", " + std::string(name);
      throw SettingsError("simulation.model." + key, "unknown field (allowed: " + allowed + ")", item.first.Mark());
    }
    if (!item.second.IsScalar()) throw model.error(key, "expected a value, got a list or a map");
    try {
      options.set(key, item.second.Scalar());
    } catch (const Error& error) {
      throw model.error(key, error.what());
    }
  }
  return options;
}

// The flight loop refuses a flight that is too long or shorter than one controller sample
// (SimulationSettings::validate) without knowing the file or the field: the file's own values (the
// defaults for what it does not say) are checked here, naming the field that sets them.
void check_flight_length(const Settings& top, const Settings& simulation, const Scenario& scenario) {
  const sim::SimulationSettings settings = scenario.simulation_settings({});
  const Settings& says_duration = scenario.simulation.duration ? simulation : top;
  if (settings.duration > sim::SimulationSettings::kMaxDuration)
    throw says_duration.error("duration", "at most 86400 s (one simulated day)");
  const double period = settings.controller_period();
  // Named: the field of the file that sets the controller period, or the duration when the file
  // says neither dt nor controller_period_steps.
  const std::string period_field = simulation.has("dt")                        ? "dt"
                                   : simulation.has("controller_period_steps") ? "controller_period_steps"
                                                                               : "";
  const auto period_error = [&](const std::string& reason) {
    return period_field.empty() ? says_duration.error("duration", reason) : simulation.error(period_field, reason);
  };
  if (settings.duration < period) {
    throw period_error("the flight (" + seconds(settings.duration) + ") is shorter than one controller period (" +
                       seconds(period) + " = dt × controller_period_steps)");
  }
  // SimulationSettings::validate's bound: 1e10 samples are days of computing, not a study.
  if (settings.duration / period > 1e10)
    throw period_error("a controller period of " + seconds(period) + " gives more than 1e10 controller samples over " +
                       seconds(settings.duration));
}

// The `simulation:` block: what the run settings' rows read (settings/run_settings.hpp), and the
// model, which only a scenario says.
void read_simulation(const YAML::Node& root, Scenario& scenario) {
  const Settings simulation(child(root, "simulation"), "simulation");
  scenario.simulation =
      read_simulation_block(simulation, std::filesystem::path(scenario.source).parent_path(), {"model"});
  scenario.model_options = read_model(child(simulation.node(), "model"), scenario.model_preset);
  check_flight_length(Settings(root), simulation, scenario);
}

// Refuses the first key of `block` that is among `helicopter_only`, saying why a plant has no use for it.
void refuse_helicopter_fields(const Settings& block, std::initializer_list<std::string_view> helicopter_only,
                              const std::string& plant) {
  for (const std::string_view key : helicopter_only) {
    if (block.has(std::string(key)))
      throw block.error(std::string(key), "the helicopter's; the plant " + plant +
                                              " flies without disturbances, actuator limits or trajectory, regulated "
                                              "to the origin (docs/plants.md)");
  }
}

// A file that names a plant: its settings, initial state and duration, and the simulation fields
// that mean the same for every plant.
Scenario read_plant_scenario(const YAML::Node& root, const std::string& source) {
  const Settings top(root);
  Scenario scenario;
  scenario.source = source;
  scenario.plant = top.string("plant", "");
  if (scenario.plant.empty()) throw top.error("plant", "must name a registered plant (thetad list)");
  refuse_helicopter_fields(top, {"phases"}, scenario.plant);
  top.allow_only({"name", "description", "plant", "plant_settings", "duration", "initial_state", "simulation"});
  scenario.name = top.string("name", std::filesystem::path(source).stem().string());
  scenario.description = top.string("description", "");
  scenario.duration = positive(top, "duration");
  if (top.has("plant_settings")) {
    if (!root["plant_settings"].IsMap()) throw top.error("plant_settings", "expected a map of the plant's settings");
    scenario.plant_settings = root["plant_settings"];
  }
  if (top.has("initial_state")) {
    const std::vector<double> x0 = top.list("initial_state", {});
    if (x0.empty()) throw top.error("initial_state", "expected the plant's initial state, one number per state");
    scenario.initial_state = Eigen::Map<const Eigen::VectorXd>(x0.data(), static_cast<Eigen::Index>(x0.size()));
  }
  const Settings simulation(child(root, "simulation"), "simulation");
  refuse_helicopter_fields(simulation,
                           {"actuator_limits", "anti_windup", "disturbances", "model", "wind", "sensor_noise", "servos",
                            "computer"},
                           scenario.plant);
  read_simulation(root, scenario);
  return scenario;
}

Scenario read_scenario(const YAML::Node& root, const std::string& source) {
  if (!root.IsMap()) throw SettingsError("scenario", "expected a map of fields", root.Mark());
  const Settings top(root);
  if (top.has("plant")) return read_plant_scenario(root, source);
  top.allow_only({"name", "description", "duration", "initial_state", "phases", "simulation"});

  Scenario scenario;
  scenario.source = source;
  scenario.name = top.string("name", std::filesystem::path(source).stem().string());
  scenario.description = top.string("description", "");
  scenario.duration = positive(top, "duration");
  scenario.initial_state = read_initial_state(root);
  scenario.trajectory = PhasedTrajectory(scenario.initial_state.segment<3>(heli::kXp));
  const double end = read_phases(root, scenario.trajectory);
  if (end != scenario.duration) {
    throw top.error("duration", seconds(scenario.duration) + ", but the phases end at " + seconds(end) +
                                    " (the last phase must end at the duration)");
  }
  read_simulation(root, scenario);
  return scenario;
}

}  // namespace

Scenario Scenario::at_speed(double speed_scale) const {
  Scenario faster = *this;
  faster.trajectory = trajectory.time_scaled(speed_scale);
  faster.duration = duration / speed_scale;
  if (simulation.duration) faster.simulation.duration = *simulation.duration / speed_scale;
  return faster;
}

Scenario Scenario::turned(double course) const {
  Scenario result = *this;
  result.trajectory = trajectory.turned(course);
  return result;
}

sim::SimulationSettings Scenario::simulation_settings() const { return simulation_settings(sim::SimulationSettings()); }

sim::SimulationSettings Scenario::simulation_settings(sim::SimulationSettings base) const {
  base.duration = duration;
  fly(simulation, base);
  // The paper has no actuator limits: its literal preset flies without them unless the file says.
  if (!simulation.actuator_limits && model_preset == "paper") base.actuator_limits.enabled = false;
  return base;
}

Scenario as_flown(const RunControls& controls, const Scenario& scenario) {
  const Scenario faster = controls.speed_scale ? scenario.at_speed(*controls.speed_scale) : scenario;
  return controls.course ? faster.turned(*controls.course) : faster;
}

Scenario parse_scenario(const std::string& text, const std::string& source) {
  const YAML::Node root = parse_yaml(text, source);
  return with_settings_source(source, [&] { return read_scenario(root, source); });
}

Scenario load_scenario(const std::filesystem::path& file) { return parse_scenario(read_text_file(file), file.string()); }

}  // namespace thetad
