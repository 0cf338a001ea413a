#include "experiment/provenance.hpp"

#include <unistd.h>

#include <array>
#include <ctime>

namespace thetad {

nlohmann::ordered_json to_json(const BuildInfo& build) {
  nlohmann::ordered_json j;
  j["thetad_version"] = build.version;
  j["git_revision"] = build.git_revision;
  j["build_type"] = build.build_type;
  j["compiler"] = build.compiler;
  j["compiler_flags"] = build.flags;
  j["eigen"] = build.eigen;
  j["lapack_linked"] = build.lapack;
  j["blas_loaded"] = build.blas_loaded;
  j["lapack_loaded"] = build.lapack_loaded;
  return j;
}

nlohmann::ordered_json to_json(const Provenance& p) {
  nlohmann::ordered_json j = to_json(p.build);
  j["plant"] = p.plant;
  j["scenario"] = {{"name", p.scenario_name}, {"file", p.scenario_file}, {"sha256", p.scenario_sha256}};
  if (!p.scenario_text.empty()) j["scenario"]["text"] = p.scenario_text;
  j["model"] = {{"preset", p.model_preset}, {"options", p.model_options}};
  j["seed"] = p.seed;
  j["dt_s"] = p.dt;
  if (p.initial_offset) j["initial_offset_m"] = *p.initial_offset;
  if (p.initial_attitude_offset) j["initial_attitude_offset_rad"] = *p.initial_attitude_offset;
  if (p.speed_scale) j["trajectory_speed_scale"] = *p.speed_scale;
  if (p.course) j["course_rad"] = *p.course;
  if (!p.initial_state.empty()) j["initial_state"] = p.initial_state;
  if (!p.plant_settings.empty()) j["plant_settings"] = p.plant_settings;
  if (!p.host.empty()) j["host"] = p.host;
  if (!p.start_time.empty()) j["start_time_utc"] = p.start_time;
  return j;
}

void stamp_host_and_time(Provenance& provenance) {
  std::array<char, 256> host{};
  if (gethostname(host.data(), host.size() - 1) == 0) provenance.host = host.data();
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  std::array<char, 32> text{};
  std::strftime(text.data(), text.size(), "%Y-%m-%dT%H:%M:%SZ", &utc);
  provenance.start_time = text.data();
}

}  // namespace thetad
