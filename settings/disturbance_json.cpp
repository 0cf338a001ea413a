#include "settings/disturbance_json.hpp"

#include <algorithm>
#include <array>
#include <string>

#include "core/error.hpp"

namespace thetad {

namespace {

using Json = nlohmann::ordered_json;

constexpr std::array<const char*, 3> kAxes = {"north", "east", "down"};
constexpr std::array<const char*, 14> kSensedChannels = {"x_p_m",       "y_p_m",       "z_p_m",     "u_m_per_s",
                                                         "v_m_per_s",   "w_m_per_s",   "phi_rad",   "theta_rad",
                                                         "psi_rad",     "p_rad_per_s", "q_rad_per_s", "r_rad_per_s",
                                                         "a1_rad",      "b1_rad"};

template <class Vector>
Json entries(const Vector& v) {
  return std::vector<double>(v.data(), v.data() + v.size());
}

template <class Vector>
Vector vector_of(const Json& json) {
  const std::vector<double> values = json.get<std::vector<double>>();
  if (static_cast<Eigen::Index>(values.size()) != Vector::RowsAtCompileTime)
    throw Error("expected " + std::to_string(Vector::RowsAtCompileTime) + " entries, got " +
                std::to_string(values.size()));
  return Eigen::Map<const Vector>(values.data());
}

// The index of `name` in `names`; throws when it is none of them.
template <class Names>
int index_of(const Names& names, const std::string& name, const char* what) {
  const auto found = std::find(names.begin(), names.end(), name);
  if (found == names.end()) throw Error(std::string("unknown ") + what + " '" + name + "'");
  return static_cast<int>(found - names.begin());
}

}  // namespace

void write_beyond_paper(const sim::SimulationSettings& s, Json& json) {
  const sim::TurbulenceSettings& t = s.turbulence;
  json["turbulence"] = {{"model", sim::TurbulenceSettings::kModelNames[static_cast<std::size_t>(t.model)]},
                        {"intensity", sim::TurbulenceSettings::kIntensityNames[static_cast<std::size_t>(t.intensity)]},
                        {"scale", t.scale},
                        {"airspeed_floor_m_per_s", t.airspeed_floor},
                        {"sigma_ned_m_per_s", entries(t.sigma)},
                        {"correlation_time_s", t.correlation_time}};
  Json gusts = Json::array();
  for (const sim::DiscreteGust& gust : s.discrete_gusts)
    gusts.push_back({{"axis", kAxes[static_cast<std::size_t>(gust.axis)]},
                     {"amplitude_m_per_s", gust.amplitude},
                     {"start_s", gust.start},
                     {"duration_s", gust.duration}});
  json["discrete_gusts"] = gusts;
  json["sensor_noise"] = {{"channels", kSensedChannels},
                          {"density_per_sqrt_hz", entries(s.sensor_noise.density)},
                          {"bias_sigma", entries(s.sensor_noise.bias)}};
  json["servos"] = {{"channels", {"T_mr", "delta_ped", "delta_col", "delta_lon", "delta_lat"}},
                    {"time_constant_s", entries(s.servos.time_constant)},
                    {"delay_samples", s.servos.delay_samples}};
  const sim::FlightComputerSettings& c = s.computer;
  Json step_times = Json::object();
  for (const auto& [label, seconds] : c.step_times) step_times[label] = seconds;
  json["computer"] = {{"latency", sim::FlightComputerSettings::kLatencyNames[static_cast<std::size_t>(c.latency)]},
                      {"fixed_s", c.fixed},
                      {"slowdown", c.slowdown},
                      {"overrun", sim::FlightComputerSettings::kOverrunNames[static_cast<std::size_t>(c.overrun)]},
                      {"step_time_s", c.step_time},
                      {"step_times_s", step_times},
                      {"step_time_source", c.step_time_source}};
}

DisturbanceBlocks read_beyond_paper(const Json& json) {
  DisturbanceBlocks blocks{sim::TurbulenceSettings{}, std::vector<sim::DiscreteGust>{}, sim::SensorNoiseSettings{},
                           sim::ServoSettings{}, sim::FlightComputerSettings{}, std::nullopt};
  if (json.contains("turbulence")) {
    const Json& t = json["turbulence"];
    blocks.turbulence->model = static_cast<sim::TurbulenceSettings::Model>(
        index_of(sim::TurbulenceSettings::kModelNames, t.at("model").get<std::string>(), "turbulence model"));
    blocks.turbulence->intensity = static_cast<sim::TurbulenceIntensity>(
        index_of(sim::TurbulenceSettings::kIntensityNames, t.at("intensity").get<std::string>(), "intensity"));
    blocks.turbulence->scale = t.at("scale").get<double>();
    blocks.turbulence->airspeed_floor = t.at("airspeed_floor_m_per_s").get<double>();
    blocks.turbulence->sigma = vector_of<Eigen::Vector3d>(t.at("sigma_ned_m_per_s"));
    blocks.turbulence->correlation_time = t.at("correlation_time_s").get<double>();
  }
  for (const Json& g : json.value("discrete_gusts", Json::array())) {
    blocks.discrete_gusts->push_back({index_of(kAxes, g.at("axis").get<std::string>(), "gust axis"),
                                      g.at("amplitude_m_per_s").get<double>(), g.at("start_s").get<double>(),
                                      g.at("duration_s").get<double>()});
  }
  if (json.contains("sensor_noise")) {
    blocks.sensor_noise->density = vector_of<sim::SensedVector>(json["sensor_noise"].at("density_per_sqrt_hz"));
    blocks.sensor_noise->bias = vector_of<sim::SensedVector>(json["sensor_noise"].at("bias_sigma"));
  }
  if (json.contains("servos")) {
    blocks.servos->time_constant = vector_of<sim::InputVector>(json["servos"].at("time_constant_s"));
    blocks.servos->delay_samples = json["servos"].at("delay_samples").get<int>();
  }
  if (json.contains("computer")) {
    const Json& c = json["computer"];
    sim::FlightComputerSettings& computer = *blocks.computer;
    computer.latency = static_cast<sim::FlightComputerSettings::Latency>(
        index_of(sim::FlightComputerSettings::kLatencyNames, c.at("latency").get<std::string>(), "latency"));
    computer.fixed = c.at("fixed_s").get<double>();
    computer.slowdown = c.at("slowdown").get<double>();
    computer.overrun = static_cast<sim::FlightComputerSettings::Overrun>(
        index_of(sim::FlightComputerSettings::kOverrunNames, c.at("overrun").get<std::string>(), "overrun"));
    computer.step_time = c.at("step_time_s").get<double>();
    for (const auto& [label, seconds] : c.at("step_times_s").items()) computer.step_times.emplace_back(label, seconds.get<double>());
    computer.step_time_source = c.at("step_time_source").get<std::string>();
  }
  return blocks;
}

}  // namespace thetad
