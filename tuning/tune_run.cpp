#include "tuning/tune_run.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <tuple>
#include <utility>

#include "controllers/feedforward_controller.hpp"
#include "controllers/sdre.hpp"
#include "controllers/theta_d.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "experiment/controller_spec.hpp"
#include "experiment/run_files.hpp"
#include "experiment/scenario_files.hpp"
#include "tuning/entry_fit.hpp"

namespace thetad::tuning {

namespace {

// Whether two flights start in the same state and command the same positions over the time flown
// (sampled every controller period): then a validation on the second adds no new scenario.
bool same_commands(const Flight& a, const Flight& b) {
  if (a.settings().duration != b.settings().duration || a.scenario().initial_state != b.scenario().initial_state)
    return false;
  const double period = a.settings().controller_period();
  for (double t = 0.0; t <= a.settings().duration; t += period) {
    if (a.scenario().trajectory.position(t) != b.scenario().trajectory.position(t)) return false;
  }
  return true;
}

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// The paper's two scenarios validate each other: tuning on one holds the other out.
std::string default_holdout(const std::filesystem::path& scenario) {
  const std::string name = scenario.filename().string();
  const char* other = name == "scenario-1.yaml" ? "scenario-2.yaml" : name == "scenario-2.yaml" ? "scenario-1.yaml" : nullptr;
  if (other == nullptr) return {};
  const std::filesystem::path sibling = scenario.parent_path() / other;
  return std::filesystem::exists(sibling) ? sibling.string() : std::string();
}

ObjectiveSettings objective_settings(const TuneOptions& a) {
  ObjectiveSettings o;
  o.objective = parse_objective(a.objective);
  o.weighting = a.relative ? Weighting::relative : Weighting::absolute;
  o.every = a.every;
  o.metric = parse_metric(a.metric);
  if (!(a.entry_floor > 0.0 && a.entry_floor <= 1.0))
    throw Error("--entry-floor must lie in (0, 1], got " + std::to_string(a.entry_floor));
  o.entry_floor = a.entry_floor;
  if (o.objective == Objective::closed_loop && a.draws < 1)
    throw Error("--draws: the closed-loop objective needs at least 1 training draw");
  return o;
}

// A bound pair of `name` ("--k-bounds"): its lower and upper value.
std::pair<double, double> bounds(const std::vector<double>& pair, const char* name) {
  if (pair.size() != 2)
    throw Error(std::string(name) + ": expected a lower and an upper bound, got " + std::to_string(pair.size()) + " values");
  return {pair[0], pair[1]};
}

FitOptions fit_options(const TuneOptions& a, const ObjectiveSettings& objective, std::uint64_t seed) {
  FitOptions options;
  // A diverged draw is +∞ to the closed loop, which BOBYQA's quadratic model cannot step around.
  options.algorithm = a.algorithm.value_or(objective.objective == Objective::closed_loop ? "LN_COBYLA" : "LN_BOBYQA");
  std::tie(options.k_lower, options.k_upper) = bounds(a.k_bounds, "--k-bounds");
  std::tie(options.l_lower, options.l_upper) = bounds(a.l_bounds, "--l-bounds");
  options.max_local_evaluations = a.max_evaluations.value_or(objective.objective == Objective::closed_loop ? 40 : 1500);
  options.max_seconds = a.max_seconds;
  options.seed = seed;
  check_fit_options(options, a.terms - 1);
  return options;
}

// What the search moves: θ–D's series or the controller's weights; only the closed loop can tune
// weights, and only θ–D has a series.
Parameterization parameterization(const TuneOptions& a, const TuningReport& report, const YAML::Node& base,
                                  const Flight& flight) {
  const std::string kind = a.parameters.value_or(a.controller == "theta-d" ? "series" : "weights");
  if (kind == "series") {
    if (a.controller != "theta-d")
      throw Error("--parameters series: only theta-d has a series (k_i, l_i); tune " + a.controller +
                  "'s weights with --parameters weights");
    return series_parameters(base, a.terms, report.options);
  }
  if (kind != "weights") throw Error("--parameters: unknown kind '" + kind + "' (known: series, weights)");
  if (report.objective.objective != Objective::closed_loop)
    throw Error("--parameters weights: the weights are tuned by the closed loop only (--objective closed-loop)");
  flight.prepare(parse_controller_spec(a.controller));  // an unknown controller fails here, by name
  return weight_parameters(a.controller, base, flight.plant(), a.weight_bounds);
}

// The record of --record when that file exists (it must be of this scenario); nothing otherwise.
std::optional<TuningRecord> reused_record(const TuneOptions& a, const Flight& flight) {
  if (a.record.empty() || !std::filesystem::exists(a.record)) return std::nullopt;
  TuningRecord record = read_record(a.record, flight.plant().state_dim(), flight.plant().input_dim());
  if (record.scenario != flight.scenario().name)
    throw Error(a.record.string() + ": recorded on scenario '" + record.scenario + "', not '" + flight.scenario().name +
                "' (delete it or name another --record file to re-fly)");
  return record;
}

// The SDRE flight recorded now and saved (to --record, else <out>/sdre-record.csv).
TuningRecord fly_record(const TuneOptions& a, const Flight& flight, const SdreController& sdre, Progress& progress) {
  const auto start = Clock::now();
  TuningRecord record = record_sdre_flight(flight, sdre, a.every, a.threads, &progress);
  const std::filesystem::path file = a.record.empty() ? a.out / "sdre-record.csv" : a.record;
  write_record(file, record);
  char line[160];
  std::snprintf(line, sizeof line, "recorded %lld samples with sigma_max(P) by cold CARE solves (%.1f s): ",
                static_cast<long long>(record.size()), seconds_since(start));
  progress.note(line + file.string());
  return record;
}

// `options` reporting each evaluation to `progress` as a task of its evaluation budget.
FitOptions with_progress(FitOptions options, bool global, Progress& progress, const std::string& label) {
  progress.start(label, options.max_local_evaluations + (global ? options.max_global_evaluations : 0), "evaluations");
  options.progress = [&progress](int evaluations, double best) {
    char note[48];
    std::snprintf(note, sizeof note, "best %.6e", best);
    progress.update(evaluations, note);
  };
  return options;
}

struct Searched {
  FitResult fit;
  std::string sigma_curves;  // the sigma objective's sigma-curves.csv
};

// The search of the chosen objective; fills the record-based fields and the figure of `report`.
Searched search(const TuneOptions& a, const Flight& flight, const YAML::Node& settings, const YAML::Node& base,
                const std::optional<TuningRecord>& reused, DrawFlights& draws, TuningReport& report, Progress& progress) {
  // Started once the record and the expansion are ready: one progress task at a time.
  const auto options = [&] {
    const std::string& algorithm = report.options.algorithm;
    return with_progress(report.options, algorithm.rfind("GN_", 0) == 0, progress, "fit (" + a.objective + ", " + algorithm + "):");
  };
  if (report.objective.objective == Objective::closed_loop) {
    const FitResult fit = tuning::fit(draws, report.objective.training_seeds, report.objective.metric, options());
    const Metric metric = report.objective.metric;
    report.figure = std::string("mean_") +
                    (metric == Metric::cost ? "cost" : metric == Metric::rms_error ? "rms_error_m" : "cost_dev");
    report.figure_default = fit.start_residual;
    report.figure_tuned = fit.residual;
    return {fit, {}};
  }
  const PreparedController sdre = flight.prepare(parse_controller_spec("sdre", settings, a.settings.string()));
  const auto& sdre_controller = paper_form<SdreController>(*sdre.controller, "thetad tune");
  const TuningRecord record = reused ? *reused : fly_record(a, flight, sdre_controller, progress);
  report.samples = record.size();
  report.record_reused = reused.has_value();
  // The θ–D starts where the recorded flight started: A0, g0, T0 at the scenario's x0, t0 = 0.
  PreparedController theta_d = flight.prepare(theta_d_spec(base, "theta-d", a.terms, {}, {}));
  auto& series = paper_form<ThetaDController>(*theta_d.controller, "thetad tune");
  series.reset(flight.scenario().initial_state, 0.0);
  const auto setup = Clock::now();
  const auto samples = static_cast<double>(record.size());
  if (report.objective.objective == Objective::sigma) {
    const SigmaMatch match(series, record, a.threads);
    report.setup_seconds = seconds_since(setup);
    const FitResult fit = tuning::fit(match, report.objective.weighting, options());
    report.figure = "rms_sigma_error";
    report.figure_default = std::sqrt(fit.start_residual / samples);
    report.figure_tuned = std::sqrt(fit.residual / samples);
    return {fit, sigma_curves_csv(match, record, fit)};
  }
  const EntryMatch match(series, record, sdre_value_matrices(sdre_controller, record, a.threads),
                         report.objective.entry_floor, a.threads);
  report.setup_seconds = seconds_since(setup);
  const FitResult fit = tuning::fit(match, options());
  const double entries = samples * static_cast<double>(series.T0().size());
  report.figure = "rms_relative_entry_error";
  report.figure_default = std::sqrt(fit.start_residual / entries);
  report.figure_tuned = std::sqrt(fit.residual / entries);
  return {fit, {}};
}

}  // namespace

TuningReport tune(const TuneOptions& a, Progress* shown, const std::function<void(double t)>& observe) {
  // Everything that can be wrong with the inputs fails here, before a flight or a file. Every
  // flight but the SDRE record needs its summary only.
  RunControls controls = a.controls;
  controls.summary_only = true;
  const Flight flight(a.scenario, controls);
  const std::uint64_t seed = flight.settings().seed;
  TuningReport report;
  report.scenario = flight.scenario().name;
  report.seed = seed;
  report.objective = objective_settings(a);
  report.terms = a.terms;
  report.options = fit_options(a, report.objective, seed);
  report.threads = a.threads;
  report.provenance = flight.provenance();
  const bool closed_loop = report.objective.objective == Objective::closed_loop;
  // The record objectives train on the record's one flight, of seed S; the closed loop on S … S+draws−1.
  const int training = closed_loop ? a.draws : 1;
  const DrawSeeds seeds = draw_seeds(seed, training, a.holdout_seed.value_or(seed + static_cast<std::uint64_t>(training)),
                                     a.validation ? a.holdout_draws : 0);
  if (closed_loop) report.objective.training_seeds = seeds.training;

  const YAML::Node settings = a.settings.empty() ? YAML::Node() : load_settings_file(a.settings);
  const YAML::Node base = settings.IsMap() && settings[a.controller] ? settings[a.controller] : YAML::Node();
  const Parameterization parameters = parameterization(a, report, base, flight);
  report.controller = parameters.controller;
  report.parameters = parameters.kind;
  report.parameter_names = parameters.names;
  report.box = parameters.box;
  DrawFlights draws(a.scenario, controls, parameters, a.threads);
  std::optional<DrawFlights> holdout;
  const std::string holdout_scenario = a.holdout.empty() ? default_holdout(find_scenario(a.scenario)) : a.holdout;
  if (a.validation && !holdout_scenario.empty()) holdout.emplace(holdout_scenario, controls, parameters, a.threads);
  if (holdout && same_commands(draws.flight(), holdout->flight())) {
    char warning[320];
    std::snprintf(warning, sizeof warning,
                  "the held-out scenario %s commands the same motion as %s over the %g s flown: its validation is "
                  "no test on another scenario (fly longer or name another holdout)",
                  holdout->flight().scenario().name.c_str(), flight.scenario().name.c_str(), flight.settings().duration);
    report.warnings.push_back(warning);
  }
  const std::optional<TuningRecord> reused = closed_loop ? std::nullopt : reused_record(a, flight);
  prepare_output_folder(a.out);

  Progress quiet(Progress::Mode::quiet);
  Progress& progress = shown ? *shown : quiet;
  std::vector<DrawFlights*> validation{&draws};
  if (holdout) validation.push_back(&*holdout);
  for (DrawFlights* flights : validation) flights->set_observer(observe);
  const Searched searched = search(a, flight, settings, base, reused, draws, report, progress);
  report.fit = searched.fit;
  progress.finish("done: " + std::to_string(report.fit.evaluations) + " evaluations, " + report.fit.stop_reason);
  const std::string tuned_settings =
      tuned_settings_file(report, flight.prepare(parameters.spec(report.fit.x, report.controller)).settings);

  for (DrawFlights* flights : validation) {
    if (!a.validation) break;
    progress.start("validation on " + flights->flight().scenario().name + ":", 2.0 * static_cast<double>(seeds.held_out.size()),
                   "flights");
    report.validations.push_back(validate_held_out(*flights, report.fit.x, seeds.held_out, seed));
    progress.finish("done");
  }
  // Written together at the end, so that a run stopped on its way leaves none of them.
  report.files = {a.out / (report.controller + "-tuned.yaml"), a.out / "tuning.json"};
  if (!searched.sigma_curves.empty()) report.files.push_back(a.out / "sigma-curves.csv");
  write_file_atomically(report.files[0], tuned_settings);
  write_file_atomically(report.files[1], to_json(report).dump(2) + "\n");
  if (!searched.sigma_curves.empty()) write_file_atomically(report.files[2], searched.sigma_curves);
  return report;
}

}  // namespace thetad::tuning
