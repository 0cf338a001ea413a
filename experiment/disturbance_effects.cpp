#include "experiment/disturbance_effects.hpp"

#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "experiment/flight.hpp"
#include "experiment/result_json.hpp"

namespace thetad {

namespace {

// A source is on when its switch is on and its strength is not zero.
bool on(bool enabled, double scale) { return enabled && scale > 0.0; }

// The RMS 3-D position error: the norm of the per-axis RMS errors (docs/glossary.md rms_error_m).
double rms_error(const sim::RunSummary& s) { return s.rms_tracking_error.norm(); }

double max_axis_error(const sim::RunSummary& s) {
  return s.max_tracking_error.size() > 0 ? s.max_tracking_error.maxCoeff() : 0.0;
}

std::string format(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

}  // namespace

std::vector<DisturbanceSource> active_sources(const sim::SimulationSettings& s) {
  std::vector<DisturbanceSource> sources;
  bool paper = true;  // the paper's sources are added first
  const auto add = [&](bool active, const char* name, std::function<void(RunControls&)> turn_off) {
    if (active) sources.push_back({name, paper, std::move(turn_off)});
  };
  const double noise = s.noise.scale;
  add(on(s.parameter_uncertainty, s.uncertainty_scale), "parameter_uncertainty",
      [](RunControls& c) { c.parameter_uncertainty = false; });
  add(on(s.wind_gust.enabled, s.wind_gust.amplitude_scale), "wind_gust", [](RunControls& c) { c.wind_gust = false; });
  add(on(s.noise.measurement, noise), "measurement_noise", [](RunControls& c) { c.measurement_noise = false; });
  add(on(s.noise.actuator, noise), "actuator_noise", [](RunControls& c) { c.actuator_noise = false; });
  add(on(s.noise.wind_component, noise), "wind_noise", [](RunControls& c) { c.wind_noise = false; });
  add(on(s.noise.induced_velocity, noise), "induced_velocity_noise",
      [](RunControls& c) { c.induced_velocity_noise = false; });
  paper = false;
  add(on(s.turbulence.active(), s.turbulence.scale), "turbulence",
      [](RunControls& c) { c.turbulence_model = sim::TurbulenceSettings::Model::paper; });
  add(!s.discrete_gusts.empty(), "discrete_gusts",
      [](RunControls& c) { c.beyond_paper.discrete_gusts = std::vector<sim::DiscreteGust>{}; });
  add(s.sensor_noise.active(), "sensor_noise",
      [](RunControls& c) { c.beyond_paper.sensor_noise = sim::SensorNoiseSettings{}; });
  // The single-field controls act after the blocks (RunControls), so they are zeroed as well.
  add(s.servos.active(), "servos", [](RunControls& c) {
    c.beyond_paper.servos = sim::ServoSettings{};
    c.servo_delay_samples = 0;
    c.servo_time_constant = 0.0;
  });
  return sources;
}

std::vector<DisturbanceCase> disturbance_cases(const std::vector<DisturbanceSource>& sources,
                                               const RunControls& controls) {
  const auto only = [&](const std::vector<bool>& keep, std::string name) {
    DisturbanceCase c{std::move(name), {}, controls};
    for (std::size_t i = 0; i < sources.size(); ++i) {
      if (keep[i]) {
        c.sources_on.push_back(sources[i].name);
      } else {
        sources[i].turn_off(c.controls);
      }
    }
    return c;
  };
  const std::size_t n = sources.size();
  std::vector<DisturbanceCase> cases{only(std::vector<bool>(n, false), "none")};
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<bool> keep(n, false);
    keep[i] = true;
    cases.push_back(only(keep, n == 1 ? "all" : "only " + sources[i].name));
  }
  if (n < 2) return cases;
  cases.push_back(only(std::vector<bool>(n, true), "all"));
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<bool> keep(n, true);
    keep[i] = false;
    cases.push_back(only(keep, "all but " + sources[i].name));
  }
  return cases;
}

DisturbanceEffects fly_disturbance_effects(const std::string& scenario, const RunControls& controls,
                                           const std::vector<ControllerSpec>& controllers, int workers,
                                           Progress* progress) {
  RunControls quiet = controls;
  quiet.summary_only = true;
  quiet.timing = false;
  const Flight all(scenario, quiet);
  DisturbanceEffects effects;
  effects.scenario = scenario;
  effects.controllers = controllers;
  effects.provenance = all.provenance();
  const std::vector<DisturbanceSource> sources = active_sources(all.settings());
  if (sources.empty())
    throw Error("thetad disturbances: " + scenario + " flies no disturbance (with these options: --ideal "
                "turns every one off), so there is nothing to tell apart");
  for (const auto& source : sources) effects.sources.push_back(source.name);
  effects.cases = disturbance_cases(sources, quiet);

  // Every flight and controller is built before anything flies, so that a bad settings file stops
  // the study at once; a Flight per case keeps each case's controllers on its own model.
  std::vector<std::unique_ptr<Flight>> flights;
  std::vector<PreparedController> prepared;
  for (const auto& c : effects.cases) {
    flights.push_back(std::make_unique<Flight>(scenario, c.controls));
    for (const auto& spec : controllers) prepared.push_back(flights.back()->prepare(spec));
  }
  effects.runs.resize(prepared.size());
  for_each_chunk(prepared.size(), 1, std::max(1, workers), [&](int worker, std::size_t i, std::size_t, std::size_t) {
    const DisturbanceCase& c = effects.cases[i / controllers.size()];
    const std::string heading = c.name + ", " + prepared[i].spec.label + ":";
    // One display shows one flight at a time: the calling thread's; the other workers fly unseen.
    RunResult result = flights[i / controllers.size()]->fly(prepared[i], worker == 0 ? progress : nullptr, heading);
    effects.runs[i] = {prepared[i].spec.label, c.name, std::move(result.summary)};
  });
  return effects;
}

std::string disturbance_table(const DisturbanceEffects& effects) {
  std::string text;
  char line[256];
  for (std::size_t k = 0; k < effects.controllers.size(); ++k) {
    text += effects.controllers[k].label + "\n";
    std::snprintf(line, sizeof line, "  %-34s %-22s %12s %12s %12s %12s\n", "disturbances", "status", "RMS 3-D (m)",
                  "max axis (m)", "J", "J_dev");
    text += line;
    for (std::size_t c = 0; c < effects.cases.size(); ++c) {
      const sim::RunSummary& s = effects.runs[c * effects.controllers.size() + k].summary;
      const std::string cost_dev = s.cost_dev ? format("%12.5g", *s.cost_dev) : std::string(11, ' ') + "-";
      std::snprintf(line, sizeof line, "  %-34s %-22s %12.4g %12.4g %12.5g %s\n", effects.cases[c].name.c_str(),
                    status_text(s).c_str(), rms_error(s), max_axis_error(s), s.cost, cost_dev.c_str());
      text += line;
    }
  }
  return text + "Each source draws from its own stream: a source's realization is the same in every flight it is on in. "
                "The effects are not additive.\n";
}

nlohmann::ordered_json disturbance_json(const DisturbanceEffects& effects) {
  nlohmann::ordered_json j;
  j["format"] = "thetad-disturbances";
  j["format_version"] = 1;
  j["scenario"] = effects.scenario;
  j["seed"] = effects.provenance.seed;
  j["sources"] = effects.sources;
  j["provenance"] = to_json(effects.provenance);
  j["runs"] = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < effects.runs.size(); ++i) {
    const DisturbanceRun& run = effects.runs[i];
    const sim::RunSummary& s = run.summary;
    const DisturbanceCase& c = effects.cases[i / effects.controllers.size()];
    nlohmann::ordered_json r = {{"label", run.label},
                                {"controller", effects.controllers[i % effects.controllers.size()].controller},
                                {"case", c.name},
                                {"sources_on", c.sources_on},
                                {"status", sim::status_name(s.status)},
                                {"end_time_s", s.end_time},
                                {"rms_error_m", rms_error(s)},
                                {"max_axis_error_m", max_axis_error(s)},
                                {"cost", s.cost}};
    r["cost_dev"] = s.cost_dev ? nlohmann::ordered_json(*s.cost_dev) : nlohmann::ordered_json(nullptr);
    r["reason"] = s.reason;
    // Every setting the flight had, so that a case can be flown again by hand (thetad run).
    r["settings"] = summary_json(s)["settings"];
    j["runs"].push_back(std::move(r));
  }
  return j;
}

}  // namespace thetad
