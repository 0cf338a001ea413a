#pragma once

// What a tuning run is on disk (`thetad tune`): the tuned settings file, the σ_max curves and
// tuning.json, defined here for every front end.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "core/sim/simulator.hpp"
#include "experiment/provenance.hpp"
#include "tuning/record.hpp"
#include "tuning/sigma_fit.hpp"

namespace thetad::tuning {

// One validation flight of a θ–D (the default or the tuned k_i, l_i) on a scenario, in a role
// ("tuning": the scenario tuned on; "held-out").
struct Validation {
  std::string scenario, role, parameters;
  sim::RunSummary summary;
};

struct TuningReport {
  std::string scenario;
  std::uint64_t seed = 0;
  Eigen::Index samples = 0;
  bool record_reused = false;
  int terms = 0;
  FitOptions options;
  FitResult fit;
  double expansion_seconds = 0.0;
  int threads = 0;
  std::vector<Validation> validations;
  Provenance provenance;

  // RMS of the σ_max error per sample, with the default k_i = l_i = 1 and tuned.
  double rms_sigma_error_default() const;
  double rms_sigma_error_tuned() const;
  bool any_diverged() const;
};

nlohmann::ordered_json to_json(const TuningReport& report);

// The settings file of the tuned θ–D: `theta-d:` with every field as the tuned controller uses it
// (`settings`, resolved), so that the spec `tuned=theta-d:FILE` flies exactly what was tuned.
std::string tuned_settings_file(const TuningReport& report, const YAML::Node& settings);

// t_s, σ_max of the SDRE's P, and of ΣT_i with the default and the tuned k_i, l_i, per sample.
std::string sigma_curves_csv(const SigmaMatch& match, const TuningRecord& record, const FitResult& fit);

}  // namespace thetad::tuning
