#pragma once

// What a tuning run is on disk (`thetad tune`): the objective and its settings, the tuned settings
// file, the σ_max curves (σ objective) and tuning.json, defined here for every front end.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "experiment/provenance.hpp"
#include "tuning/closed_loop.hpp"
#include "tuning/parameterization.hpp"
#include "tuning/held_out.hpp"
#include "tuning/record.hpp"
#include "tuning/search.hpp"
#include "tuning/sigma_fit.hpp"

namespace thetad::tuning {

enum class Objective {
  sigma,        // the paper's least squares on σ_max (sigma_fit)
  entries,      // the per-entry relative fit of ΣT_i to P (entry_fit)
  closed_loop,  // the mean cost or RMS error over training draws (closed_loop)
};
const char* objective_name(Objective objective);  // "sigma", "entries", "closed-loop"
// Throws thetad::Error naming the known objectives.
Objective parse_objective(const std::string& name);

// The objective and the settings that only it reads.
struct ObjectiveSettings {
  Objective objective = Objective::sigma;
  Weighting weighting = Weighting::absolute;  // sigma
  double entry_floor = 1e-3;                  // entries: see entry_fit.hpp
  int every = 10;                             // sigma, entries: the record keeps every N-th sample
  Metric metric = Metric::cost;               // closed-loop
  std::vector<std::uint64_t> training_seeds;  // closed-loop
};

struct TuningReport {
  std::string scenario;
  std::string controller = "theta-d";
  std::string parameters = "series";        // Parameterization::kind
  std::vector<std::string> parameter_names;  // Parameterization::names
  SearchBox box;
  std::uint64_t seed = 0;
  ObjectiveSettings objective;
  Eigen::Index samples = 0;    // of the record (sigma, entries)
  bool record_reused = false;
  // What the caller should know about how the run was set up (a held-out scenario that commands
  // the training scenario's motion over the flown time).
  std::vector<std::string> warnings;
  int terms = 0;
  FitOptions options;
  FitResult fit;
  // What the objective's value means in words ("rms_sigma_error", "mean_cost", ...), at the
  // default and the tuned k, l.
  std::string figure;
  double figure_default = 0.0, figure_tuned = 0.0;
  double setup_seconds = 0.0;  // before the search: the series expansion and target matrices
  int threads = 0;
  std::vector<HeldOutValidation> validations;  // the tuning scenario first, then a held-out scenario
  Provenance provenance;
  // What the run wrote (tune_run.hpp): the tuned settings file first, then tuning.json and the
  // σ_max curves; not in tuning.json.
  std::vector<std::filesystem::path> files;

  // Whether a held-out draw diverged or failed, for either controller (the exit code says so).
  bool any_not_completed() const;
};

// tuning.json: {"format", "format_version", the report's fields, "validation", "provenance"}.
// Its "format_version" says which names it uses:
//   1 (no "format" or "format_version"): the names before docs/glossary.md. "residual_default",
//     "residual_tuned", "<figure>_default", "<figure>_tuned", "diverged_default", "diverged_tuned",
//     "difference_interval", the comparison "rms_error", the metric "rms-error", "record.samples",
//     "record.reused", "setup_seconds", "fit_seconds", the roles "tuning scenario" and "held-out
//     scenario", and a run's "status" as status_text ("diverged at 1.234 s").
//   2: the glossary's names ("θ–D settings and tuning"): "default_objective", "tuned_objective",
//     "default_<figure>", "tuned_<figure>", "default_not_completed", "tuned_not_completed",
//     "difference_ci95", "rms_error_m", "record_samples", "record_reused", "setup_time_s",
//     "fit_time_s", the roles "tuning_scenario" and "held_out_scenario", and a run's bare "status"
//     (completed, diverged, failed) with its "end_time_s".
inline constexpr const char* kTuningFormat = "thetad-tuning-1";
inline constexpr int kTuningFormatVersion = 2;
nlohmann::ordered_json to_json(const TuningReport& report);

// The settings file of the tuned controller: `CONTROLLER:` with every field as the tuned controller
// uses it (`settings`, resolved), so that the spec `tuned=CONTROLLER:FILE` flies exactly what was tuned.
std::string tuned_settings_file(const TuningReport& report, const YAML::Node& settings);

// t_s, σ_max of the SDRE's P, and of ΣT_i with the default and the tuned k_i, l_i, per sample.
std::string sigma_curves_csv(const SigmaMatch& match, const TuningRecord& record, const FitResult& fit);

}  // namespace thetad::tuning
