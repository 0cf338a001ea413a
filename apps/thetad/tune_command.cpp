#include "apps/thetad/tune_command.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>

#include "controllers/feedforward_controller.hpp"
#include "controllers/sdre.hpp"
#include "controllers/theta_d.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "experiment/controller_spec.hpp"
#include "experiment/run_files.hpp"
#include "experiment/scenario_files.hpp"
#include "tuning/closed_loop.hpp"
#include "tuning/entry_fit.hpp"
#include "tuning/held_out.hpp"
#include "tuning/record.hpp"
#include "tuning/sigma_fit.hpp"
#include "tuning/tuning_report.hpp"

namespace thetad::app {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

std::string numbers(const Eigen::VectorXd& v) {
  std::string text;
  char number[32];
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    std::snprintf(number, sizeof number, "%.17g", v[i]);
    text += (i ? ", " : "") + std::string(number);
  }
  return "[" + text + "]";
}

// The paper's two scenarios validate each other: tuning on one holds the other out.
std::filesystem::path default_holdout(const std::filesystem::path& scenario) {
  const std::string name = scenario.filename().string();
  const char* other = name == "scenario-1.yaml" ? "scenario-2.yaml" : name == "scenario-2.yaml" ? "scenario-1.yaml" : nullptr;
  if (other == nullptr) return {};
  const std::filesystem::path sibling = scenario.parent_path() / other;
  return std::filesystem::exists(sibling) ? sibling : std::filesystem::path();
}

tuning::ObjectiveSettings objective_settings(const TuneArguments& a) {
  tuning::ObjectiveSettings o;
  o.objective = tuning::parse_objective(a.objective);
  o.weighting = a.relative ? tuning::Weighting::relative : tuning::Weighting::absolute;
  o.every = a.every;
  o.metric = tuning::parse_metric(a.metric);
  if (!(a.entry_floor > 0.0 && a.entry_floor <= 1.0))
    throw Error("--entry-floor must lie in (0, 1], got " + std::to_string(a.entry_floor));
  o.entry_floor = a.entry_floor;
  if (o.objective == tuning::Objective::closed_loop && a.draws < 1)
    throw Error("--draws: the closed-loop objective needs at least 1 training draw");
  return o;
}

tuning::FitOptions fit_options(const TuneArguments& a, const tuning::ObjectiveSettings& objective, std::uint64_t seed) {
  tuning::FitOptions options;
  // A diverged draw is +∞ to the closed loop, which BOBYQA's quadratic model cannot step around.
  options.algorithm = a.algorithm.value_or(objective.objective == tuning::Objective::closed_loop ? "LN_COBYLA" : "LN_BOBYQA");
  options.k_lower = a.k_bounds[0];
  options.k_upper = a.k_bounds[1];
  options.l_lower = a.l_bounds[0];
  options.l_upper = a.l_bounds[1];
  options.max_local_evaluations =
      a.max_evaluations.value_or(objective.objective == tuning::Objective::closed_loop ? 40 : 1500);
  options.max_seconds = a.max_seconds;
  options.seed = seed;
  tuning::check_fit_options(options, a.terms - 1);
  return options;
}

// What the search moves: θ–D's series or the controller's weights; only the closed loop can tune
// weights, and only θ–D has a series.
tuning::Parameterization parameterization(const TuneArguments& a, const tuning::TuningReport& report,
                                          const YAML::Node& base, const Flight& flight) {
  const std::string kind = a.parameters.value_or(a.controller == "theta-d" ? "series" : "weights");
  if (kind == "series") {
    if (a.controller != "theta-d")
      throw Error("--parameters series: only theta-d has a series (k_i, l_i); tune " + a.controller +
                  "'s weights with --parameters weights");
    return tuning::series_parameters(base, a.terms, report.options);
  }
  if (report.objective.objective != tuning::Objective::closed_loop)
    throw Error("--parameters weights: the weights are tuned by the closed loop only (--objective closed-loop)");
  flight.prepare(parse_controller_spec(a.controller));  // an unknown controller fails here, by name
  return tuning::weight_parameters(a.controller, base, flight.plant(), a.weight_bounds);
}

// The record of --record when that file exists (it must be of this scenario); nothing otherwise.
std::optional<tuning::TuningRecord> reused_record(const TuneArguments& a, const Flight& flight) {
  if (a.record.empty() || !std::filesystem::exists(a.record)) return std::nullopt;
  const heli::Helicopter& model = flight.model();
  tuning::TuningRecord record = tuning::read_record(a.record, model.state_dim(), model.input_dim());
  if (record.scenario != flight.scenario().name)
    throw Error(a.record.string() + ": recorded on scenario '" + record.scenario + "', not '" + flight.scenario().name +
                "' (delete it or name another --record file to re-fly)");
  return record;
}

// The SDRE flight recorded now and saved (to --record, else <out>/sdre-record.csv).
tuning::TuningRecord fly_record(const TuneArguments& a, const Flight& flight, const SdreController& sdre,
                                Progress& progress) {
  const auto start = Clock::now();
  tuning::TuningRecord record = tuning::record_sdre_flight(flight, sdre, a.every, a.threads, &progress);
  const std::filesystem::path file = a.record.empty() ? a.flight.out / "sdre-record.csv" : a.record;
  tuning::write_record(file, record);
  std::fprintf(stderr, "recorded %lld samples with sigma_max(P) by cold CARE solves (%.1f s): %s\n",
               static_cast<long long>(record.size()), seconds_since(start), file.c_str());
  return record;
}

// `options` reporting each evaluation to `progress` as a task of its evaluation budget.
tuning::FitOptions with_progress(tuning::FitOptions options, bool global, Progress& progress, const std::string& label) {
  progress.start(label, options.max_local_evaluations + (global ? options.max_global_evaluations : 0), "evaluations");
  options.progress = [&progress](int evaluations, double best) {
    char note[48];
    std::snprintf(note, sizeof note, "best %.6e", best);
    progress.update(evaluations, note);
  };
  return options;
}

// The search of the chosen objective; fills the record-based fields and the figure of `report`
// and writes <out>/sigma-curves.csv for the sigma objective.
tuning::FitResult search(const TuneArguments& a, const Flight& flight, const YAML::Node& settings, const YAML::Node& base,
                         const std::optional<tuning::TuningRecord>& reused, tuning::DrawFlights& draws,
                         tuning::TuningReport& report, Progress& progress) {
  // Started once the record and the expansion are ready: one progress task at a time.
  const auto options = [&] {
    const std::string& algorithm = report.options.algorithm;
    return with_progress(report.options, algorithm.rfind("GN_", 0) == 0, progress, "fit (" + a.objective + ", " + algorithm + "):");
  };
  if (report.objective.objective == tuning::Objective::closed_loop) {
    const tuning::FitResult fit = tuning::fit(draws, report.objective.training_seeds, report.objective.metric, options());
    const tuning::Metric metric = report.objective.metric;
    report.figure = std::string("mean_") +
                    (metric == tuning::Metric::cost ? "cost" : metric == tuning::Metric::rms_error ? "rms_error_m" : "cost_dev");
    report.figure_default = fit.start_residual;
    report.figure_tuned = fit.residual;
    return fit;
  }
  const PreparedController sdre = flight.prepare(parse_controller_spec("sdre", settings, a.flight.settings.string()));
  const auto& sdre_controller = paper_form<SdreController>(*sdre.controller, "thetad tune");
  const tuning::TuningRecord record = reused ? *reused : fly_record(a, flight, sdre_controller, progress);
  report.samples = record.size();
  report.record_reused = reused.has_value();
  // The θ–D starts where the recorded flight started: A0, g0, T0 at the scenario's x0, t0 = 0.
  PreparedController theta_d = flight.prepare(tuning::theta_d_spec(base, "theta-d", a.terms, {}, {}));
  auto& series = paper_form<ThetaDController>(*theta_d.controller, "thetad tune");
  series.reset(flight.scenario().initial_state, 0.0);
  const auto setup = Clock::now();
  const auto samples = static_cast<double>(record.size());
  if (report.objective.objective == tuning::Objective::sigma) {
    const tuning::SigmaMatch match(series, record, a.threads);
    report.setup_seconds = seconds_since(setup);
    const tuning::FitResult fit = tuning::fit(match, report.objective.weighting, options());
    report.figure = "rms_sigma_error";
    report.figure_default = std::sqrt(fit.start_residual / samples);
    report.figure_tuned = std::sqrt(fit.residual / samples);
    write_file_atomically(a.flight.out / "sigma-curves.csv", sigma_curves_csv(match, record, fit));
    return fit;
  }
  const tuning::EntryMatch match(series, record, tuning::sdre_value_matrices(sdre_controller, record, a.threads),
                                 report.objective.entry_floor, a.threads);
  report.setup_seconds = seconds_since(setup);
  const tuning::FitResult fit = tuning::fit(match, options());
  const double entries = samples * static_cast<double>(series.T0().size());
  report.figure = "rms_relative_entry_error";
  report.figure_default = std::sqrt(fit.start_residual / entries);
  report.figure_tuned = std::sqrt(fit.residual / entries);
  return fit;
}

void print_comparison(const std::string& scenario, const tuning::PairedComparison& c) {
  std::printf("validation scenario=%s metric=%s default_median=%.8g tuned_median=%.8g difference_median=%.6g "
              "difference_95=[%.6g,%.6g]\n",
              scenario.c_str(), tuning::metric_name(c.metric), c.default_median, c.tuned_median, c.difference.median,
              c.difference.low, c.difference.high);
}

// Quiet and parseable: one key=value line per figure.
void print_report(const tuning::TuningReport& r, const std::vector<std::filesystem::path>& written) {
  const tuning::FitResult& fit = r.fit;
  std::printf("scenario=%s controller=%s parameters=%s objective=%s terms=%d algorithm=%s", r.scenario.c_str(),
              r.controller.c_str(), r.parameters.c_str(), tuning::objective_name(r.objective.objective), r.terms,
              r.options.algorithm.c_str());
  switch (r.objective.objective) {
    case tuning::Objective::sigma:
      std::printf(" samples=%lld weighting=%s\n", static_cast<long long>(r.samples),
                  r.objective.weighting == tuning::Weighting::relative ? "relative" : "absolute");
      break;
    case tuning::Objective::entries:
      std::printf(" samples=%lld entry_floor=%g\n", static_cast<long long>(r.samples), r.objective.entry_floor);
      break;
    case tuning::Objective::closed_loop:
      std::printf(" metric=%s training_draws=%zu\n", tuning::metric_name(r.objective.metric), r.objective.training_seeds.size());
      break;
  }
  if (r.parameters == "series") {
    std::printf("k=%s\nl=%s\n", numbers(fit.k).c_str(), numbers(fit.l).c_str());
  } else {
    for (std::size_t i = 0; i < r.parameter_names.size(); ++i)
      std::printf("%s=%.10g\n", r.parameter_names[i].c_str(), fit.x[static_cast<Eigen::Index>(i)]);
  }
  std::printf("residual_default=%.10g residual_tuned=%.10g %s_default=%.6g %s_tuned=%.6g\n", fit.start_residual,
              fit.residual, r.figure.c_str(), r.figure_default, r.figure.c_str(), r.figure_tuned);
  std::printf("evaluations=%d setup_seconds=%.3f fit_seconds=%.3f stop=\"%s\"\n", fit.evaluations, r.setup_seconds,
              fit.seconds, fit.stop_reason.c_str());
  for (const tuning::HeldOutValidation& v : r.validations) {
    std::printf("validation scenario=%s role=%s draws=%zu first_seed=%llu pairs=%d diverged_default=%d diverged_tuned=%d\n",
                v.scenario.c_str(), v.scenario == r.scenario ? "tuning-scenario" : "held-out-scenario", v.seeds.size(),
                static_cast<unsigned long long>(v.seeds.front()), v.pairs(), v.diverged_default(), v.diverged_tuned());
    print_comparison(v.scenario, v.cost);
    if (v.cost_dev) print_comparison(v.scenario, *v.cost_dev);
    print_comparison(v.scenario, v.rms_error);
  }
  std::string files;
  for (const std::filesystem::path& file : written) files += (files.empty() ? "" : ",") + file.string();
  std::printf("wrote=%s\n", files.c_str());
}

}  // namespace

CLI::App* add_tune_command(CLI::App& app, TuneArguments& a) {
  auto* tune = app.add_subcommand(
      "tune", "Fit theta-D's k_i, l_i by an objective (sigma: the paper's sigma_max match to an SDRE flight, "
              "docs/model.md §8.1; entries: a per-entry match; closed-loop: mean cost, J_dev or RMS error over seeded "
              "draws), or any controller's weights Q, R by the closed loop; compare default and tuned on held-out draws");
  add_flight_options(*tune, a.flight);
  tune->get_option("--out")->required();
  tune->add_option("--objective", a.objective, "sigma, entries or closed-loop")
      ->check(CLI::IsMember({"sigma", "entries", "closed-loop"}))
      ->capture_default_str();
  tune->add_option("--controller", a.controller, "The controller tuned (its block of --settings is the start)")
      ->capture_default_str();
  tune->add_option("--parameters", a.parameters,
                   "series (theta-d's k_i, l_i) or weights (log10 factors on the controller's Q and R by group, "
                   "closed-loop only; docs/tuning.md); default: series for theta-d, weights otherwise")
      ->check(CLI::IsMember({"series", "weights"}));
  tune->add_option("--weight-bounds", a.weight_bounds, "weights: each log10 factor lies in [-B, B]")
      ->check(CLI::Range(1e-3, 10.0))
      ->capture_default_str();
  // The expansion's pieces grow fast with N (5, 11, 29 for N = 3, 4, 5; 516 for N = 8), and every
  // sample stores all of them: N = 5 already needs ~340 MB for scenario I's 8500 samples.
  tune->add_option("--terms", a.terms, "N: the theta-D series T0 + ... + T_{N-1} (tunes N-1 pairs k_i, l_i)")
      ->check(CLI::Range(2, 5))
      ->capture_default_str();
  tune->add_option("--algorithm", a.algorithm,
                   "NLopt algorithm: LN_BOBYQA (default), LN_COBYLA (default for closed-loop), LN_SBPLX, "
                   "LN_NELDERMEAD (local from k = l = 1) or GN_DIRECT_L, GN_ISRES (global, then LN_BOBYQA)");
  tune->add_option("--max-evaluations", a.max_evaluations,
                   "Evaluation budget of the (local) search (default: 1500; 40 for closed-loop)")
      ->check(CLI::Range(1, 1000000));
  tune->add_option("--max-seconds", a.max_seconds, "Time budget of the search in seconds (0: none)")
      ->check(CLI::Range(0.0, 1e7))
      ->capture_default_str();
  tune->add_option("--record", a.record,
                   "sigma, entries: SDRE record (CSV), reused if the file exists, else the flight is recorded into it "
                   "(default: <out>/sdre-record.csv, always re-flown)");
  tune->add_option("--every", a.every, "sigma, entries: keep every N-th controller sample in the record")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  tune->add_flag("--relative", a.relative, "sigma: fit relative errors (sigma_theta-D - sigma_SDRE) / sigma_SDRE");
  tune->add_option("--entry-floor", a.entry_floor,
                   "entries: an entry P_rc is scaled by max(|P_rc|, floor * sqrt(P_rr P_cc))")
      ->capture_default_str();
  tune->add_option("--metric", a.metric,
                   "closed-loop, and the figure of merit: cost (J), rms-error (m) or cost-dev (J_dev, docs/model.md §7.2)")
      ->check(CLI::IsMember({"cost", "rms-error", "cost-dev"}))
      ->capture_default_str();
  tune->add_option("--draws", a.draws, "closed-loop: training draws, seeds S ... S+draws-1 (S: --seed or the scenario's)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  tune->add_option("--holdout-draws", a.holdout_draws, "Held-out draws of the validation")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  tune->add_option_function<std::string>(
      "--holdout-seed", [&a](const std::string& text) { a.holdout_seed = parse_seed(text, "--holdout-seed"); },
      "First seed of the held-out draws (default: the seed after the training draws); must not overlap them");
  tune->add_option("--k-bounds", a.k_bounds, "Lower and upper bound of every k_i")->expected(2)->capture_default_str();
  tune->add_option("--l-bounds", a.l_bounds, "Lower and upper bound of every l_i")->expected(2)->capture_default_str();
  tune->add_option("--holdout", a.holdout,
                   "Held-out scenario, validated on the held-out draws too (default: the other paper scenario, when "
                   "tuning on one)");
  tune->add_flag("--no-validation", a.no_validation, "Skip the held-out validation");
  tune->add_option("--threads", a.threads, "Threads of the fit and of the flights")->check(CLI::Range(1, 64))->capture_default_str();
  return tune;
}

int run_tune(const TuneArguments& a) {
  // Everything that can be wrong with the inputs fails here, before a flight or a file. Every
  // flight but the SDRE record needs its summary only.
  RunControls controls = run_controls(a.flight);
  controls.summary_only = true;
  const Flight flight(a.flight.scenario, controls);
  const std::uint64_t seed = flight.settings().seed;
  tuning::TuningReport report;
  report.scenario = flight.scenario().name;
  report.seed = seed;
  report.objective = objective_settings(a);
  report.terms = a.terms;
  report.options = fit_options(a, report.objective, seed);
  report.threads = a.threads;
  report.provenance = flight.provenance();
  const bool closed_loop = report.objective.objective == tuning::Objective::closed_loop;
  // The record objectives train on the record's one flight, of seed S; the closed loop on S … S+draws−1.
  const int training = closed_loop ? a.draws : 1;
  const tuning::DrawSeeds seeds = tuning::draw_seeds(
      seed, training, a.holdout_seed.value_or(seed + static_cast<std::uint64_t>(training)), a.no_validation ? 0 : a.holdout_draws);
  if (closed_loop) report.objective.training_seeds = seeds.training;

  const YAML::Node settings = a.flight.settings.empty() ? YAML::Node() : load_settings_file(a.flight.settings);
  const YAML::Node base = settings.IsMap() && settings[a.controller] ? settings[a.controller] : YAML::Node();
  const tuning::Parameterization parameters = parameterization(a, report, base, flight);
  report.controller = parameters.controller;
  report.parameters = parameters.kind;
  report.parameter_names = parameters.names;
  report.box = parameters.box;
  tuning::DrawFlights draws(a.flight.scenario, controls, parameters, a.threads);
  std::optional<tuning::DrawFlights> holdout;
  const std::filesystem::path holdout_file =
      a.holdout.empty() ? default_holdout(find_scenario(a.flight.scenario)) : a.holdout;
  if (!a.no_validation && !holdout_file.empty()) holdout.emplace(holdout_file.string(), controls, parameters, a.threads);
  const std::optional<tuning::TuningRecord> reused = closed_loop ? std::nullopt : reused_record(a, flight);
  prepare_output_folder(a.flight.out);

  Progress progress(Progress::mode_for_stderr(a.flight.quiet));
  report.fit = search(a, flight, settings, base, reused, draws, report, progress);
  progress.finish("done: " + std::to_string(report.fit.evaluations) + " evaluations, " + report.fit.stop_reason);
  std::vector<std::filesystem::path> written{a.flight.out / (report.controller + "-tuned.yaml"),
                                             a.flight.out / "tuning.json"};
  if (report.objective.objective == tuning::Objective::sigma) written.push_back(a.flight.out / "sigma-curves.csv");
  write_file_atomically(written[0],
                        tuned_settings_file(report, flight.prepare(parameters.spec(report.fit.x, report.controller)).settings));

  std::vector<tuning::DrawFlights*> validation{&draws};
  if (holdout) validation.push_back(&*holdout);
  for (tuning::DrawFlights* flights : validation) {
    if (a.no_validation) break;
    progress.start("validation on " + flights->flight().scenario().name + ":", 2.0 * static_cast<double>(seeds.held_out.size()),
                   "flights");
    report.validations.push_back(tuning::validate_held_out(*flights, report.fit.x, seeds.held_out, seed));
    progress.finish("done");
  }
  write_file_atomically(written[1], to_json(report).dump(2) + "\n");
  print_report(report, written);
  return report.any_diverged() ? kExitDiverged : kExitCompleted;
}

}  // namespace thetad::app
