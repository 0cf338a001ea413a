#include "settings/disturbance_blocks.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "settings/settings.hpp"

namespace thetad {

namespace {

// One value for every entry, or a list of `size` entries; each >= 0.
Eigen::VectorXd per_axis(const Settings& block, const std::string& key, Eigen::Index size) {
  if (block.has(key) && block.node()[key].IsSequence()) return block.vector(key, Eigen::VectorXd::Zero(size), size, 0.0);
  return Eigen::VectorXd::Constant(size, block.number(key, 0.0, 0.0));
}

// A channel group map {position, velocity, attitude, rates, flapping} into the 14 sensed states.
sim::SensedVector sensed_groups(const Settings& block) {
  block.allow_only({"position", "velocity", "attitude", "rates", "flapping"});
  sim::SensedVector values;
  values << per_axis(block, "position", 3), per_axis(block, "velocity", 3), per_axis(block, "attitude", 3),
      per_axis(block, "rates", 3), per_axis(block, "flapping", 2);
  return values;
}

// The position of `name` in `names` (a checked choice: it is there).
int index_of(const std::array<std::string_view, 3>& names, const std::string& name) {
  return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
}

sim::TurbulenceSettings read_turbulence(const Settings& wind) {
  sim::TurbulenceSettings turbulence;
  const auto& models = sim::TurbulenceSettings::kModelNames;
  const auto& intensities = sim::TurbulenceSettings::kIntensityNames;
  const std::string model = wind.choice("model", "paper", {models[0], models[1], models[2]});
  turbulence.model = static_cast<sim::TurbulenceSettings::Model>(index_of(models, model));
  const std::string intensity = wind.choice("intensity", "light", {intensities[0], intensities[1], intensities[2]});
  turbulence.intensity = static_cast<sim::TurbulenceIntensity>(index_of(intensities, intensity));
  turbulence.scale = wind.number("scale", 1.0, 0.0);
  turbulence.airspeed_floor = wind.number("airspeed_floor", turbulence.airspeed_floor, 0.0);
  if (!(turbulence.airspeed_floor > 0.0)) throw wind.error("airspeed_floor", "must be > 0");
  turbulence.sigma = per_axis(wind, "sigma", 3);
  turbulence.correlation_time = wind.number("correlation_time", 1.0, 0.0);
  if (!(turbulence.correlation_time > 0.0)) throw wind.error("correlation_time", "must be > 0");
  if (turbulence.model == sim::TurbulenceSettings::Model::gauss_markov && !wind.has("sigma"))
    throw wind.error("sigma", "missing: the gauss_markov model needs its sigma (m/s, north, east, down)");
  return turbulence;
}

std::vector<sim::DiscreteGust> read_gusts(const Settings& wind) {
  std::vector<sim::DiscreteGust> gusts;
  if (!wind.has("gusts")) return gusts;
  const YAML::Node list = wind.node()["gusts"];
  if (!list.IsSequence()) throw wind.error("gusts", "expected a list of gusts {axis, amplitude, start, duration}");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Settings item(list[i], "simulation.wind.gusts[" + std::to_string(i) + "]");
    item.allow_only({"axis", "amplitude", "start", "duration"});
    for (const char* key : {"axis", "amplitude", "start", "duration"}) {
      if (!item.has(key)) throw item.error(key, "missing (required)");
    }
    sim::DiscreteGust gust;
    const std::string axis = item.choice("axis", "north", {"north", "east", "down"});
    gust.axis = axis == "north" ? 0 : axis == "east" ? 1 : 2;
    gust.amplitude = item.number("amplitude", 0.0);
    gust.start = item.number("start", 0.0, 0.0);
    gust.duration = item.number("duration", 1.0, 0.0);
    if (!(gust.duration > 0.0)) throw item.error("duration", "must be > 0");
    gusts.push_back(gust);
  }
  return gusts;
}

sim::SensorNoiseSettings read_sensor_noise(const Settings& block) {
  block.allow_only({"density", "sigma", "bandwidth", "bias"});
  sim::SensorNoiseSettings noise;
  if (block.has("density") && block.has("sigma"))
    throw block.error("sigma", "give the noise as its density or as sigma with a bandwidth, not both");
  if (block.has("sigma")) {
    if (!block.has("bandwidth"))
      throw block.error("bandwidth", "missing: sigma is the noise's standard deviation in this bandwidth (Hz)");
    const double bandwidth = block.number("bandwidth", 1.0, 0.0);
    if (!(bandwidth > 0.0)) throw block.error("bandwidth", "must be > 0 (Hz)");
    // White to the bandwidth B: σ² = density² B.
    noise.density = sensed_groups(block.block("sigma")) / std::sqrt(bandwidth);
  } else {
    if (block.has("bandwidth")) throw block.error("bandwidth", "only with sigma (a density needs none)");
    noise.density = sensed_groups(block.block("density"));
  }
  noise.bias = sensed_groups(block.block("bias"));
  return noise;
}

sim::ServoSettings read_servos(const Settings& block) {
  block.allow_only({"time_constant", "delay_samples"});
  sim::ServoSettings servos;
  servos.time_constant = per_axis(block, "time_constant", sim::InputVector::RowsAtCompileTime);
  servos.delay_samples = block.integer("delay_samples", 0, 0, sim::ServoSettings::kMaxDelaySamples);
  return servos;
}

// The flight computer (docs/model.md §15.7); its step times from `step_times:` here or a bench file
// (into `file`, read later).
sim::FlightComputerSettings read_computer(const Settings& block, const std::filesystem::path& folder,
                                          std::optional<StepTimeFile>& file) {
  using Computer = sim::FlightComputerSettings;
  block.allow_only({"latency", "fixed", "slowdown", "overrun", "bench", "statistic", "step_times"});
  Computer computer;
  const auto& latencies = Computer::kLatencyNames;
  const std::string latency = block.choice("latency", "none", {latencies[0], latencies[1], latencies[2], latencies[3]});
  computer.latency = static_cast<Computer::Latency>(
      std::find(latencies.begin(), latencies.end(), latency) - latencies.begin());
  const bool fixed = computer.latency == Computer::Latency::fixed;
  const bool scaled = computer.latency == Computer::Latency::measured || computer.latency == Computer::Latency::step_time;
  const bool step_time = computer.latency == Computer::Latency::step_time;
  if (fixed && !block.has("fixed")) throw block.error("fixed", "missing: the fixed latency (s)");
  if (!fixed && block.has("fixed")) throw block.error("fixed", "only with latency: fixed");
  if (!scaled && block.has("slowdown")) throw block.error("slowdown", "only with latency: measured or step-time");
  for (const char* key : {"bench", "statistic", "step_times"})
    if (!step_time && block.has(key)) throw block.error(key, "only with latency: step-time");
  computer.fixed = block.number("fixed", 0.0, 0.0, Computer::kMaxLatency);
  computer.slowdown = block.number("slowdown", 1.0, 0.0, Computer::kMaxSlowdown);
  if (!(computer.slowdown > 0.0)) throw block.error("slowdown", "must be > 0");
  const auto& overruns = Computer::kOverrunNames;
  computer.overrun = block.choice("overrun", overruns[0], {overruns[0], overruns[1]}) == overruns[0]
                         ? Computer::Overrun::skip_next
                         : Computer::Overrun::abort;
  if (step_time) {
    if (block.has("bench") == block.has("step_times"))
      throw block.error("bench", "give the step times as a thetad bench file (bench:) or by label (step_times:), one of them");
    if (block.has("bench")) {
      file = StepTimeFile{folder / block.string("bench", ""), block.choice("statistic", "median", {"median", "p90", "p99", "max"})};
    } else {
      if (block.has("statistic")) throw block.error("statistic", "only with bench:");
      const YAML::Node times = block.node()["step_times"];
      if (!times.IsMap() || times.size() == 0)
        throw block.error("step_times", "expected a map of controller labels to step times (s)");
      const Settings entries = block.block("step_times");
      for (const auto& entry : times) {
        const std::string label = entry.first.as<std::string>();
        computer.step_times.emplace_back(label, entries.number(label, 0.0, 0.0, Computer::kMaxLatency));
      }
      computer.step_time_source = "the scenario's simulation.computer.step_times";
    }
  }
  return computer;
}

}  // namespace

void DisturbanceBlocks::apply(sim::SimulationSettings& settings) const {
  if (turbulence) settings.turbulence = *turbulence;
  if (discrete_gusts) settings.discrete_gusts = *discrete_gusts;
  if (sensor_noise) settings.sensor_noise = *sensor_noise;
  if (servos) settings.servos = *servos;
  if (computer) settings.computer = *computer;
}

DisturbanceBlocks read_disturbance_blocks(const Settings& simulation, const std::filesystem::path& folder) {
  DisturbanceBlocks blocks;
  const YAML::Node& node = simulation.node();
  if (simulation.has("wind")) {
    const Settings wind(node["wind"], "simulation.wind");
    wind.allow_only({"model", "intensity", "scale", "airspeed_floor", "sigma", "correlation_time", "gusts"});
    blocks.turbulence = read_turbulence(wind);
    blocks.discrete_gusts = read_gusts(wind);
  }
  if (simulation.has("sensor_noise"))
    blocks.sensor_noise = read_sensor_noise(Settings(node["sensor_noise"], "simulation.sensor_noise"));
  if (simulation.has("servos")) blocks.servos = read_servos(Settings(node["servos"], "simulation.servos"));
  if (simulation.has("computer"))
    blocks.computer = read_computer(Settings(node["computer"], "simulation.computer"), folder, blocks.step_time_file);
  return blocks;
}

}  // namespace thetad
