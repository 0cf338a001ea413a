#include "apps/thetad/tune_command.hpp"

#include <cstdio>

namespace thetad::app {

namespace {

std::string numbers(const Eigen::VectorXd& v) {
  std::string text;
  char number[32];
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    std::snprintf(number, sizeof number, "%.17g", v[i]);
    text += (i ? ", " : "") + std::string(number);
  }
  return "[" + text + "]";
}

void print_comparison(const std::string& scenario, const tuning::PairedComparison& c) {
  std::printf("validation scenario=%s metric=%s default_median=%.8g tuned_median=%.8g difference_median=%.6g "
              "difference_ci95=[%.6g,%.6g]\n",
              scenario.c_str(), tuning::metric_name(c.metric), c.default_median, c.tuned_median, c.difference.median,
              c.difference.low, c.difference.high);
}

// Quiet and parseable: one key=value line per figure.
void print_report(const tuning::TuningReport& r) {
  const tuning::FitResult& fit = r.fit;
  std::printf("scenario=%s controller=%s parameters=%s objective=%s terms=%d algorithm=%s", r.scenario.c_str(),
              r.controller.c_str(), r.parameters.c_str(), tuning::objective_name(r.objective.objective), r.terms,
              r.options.algorithm.c_str());
  switch (r.objective.objective) {
    case tuning::Objective::sigma:
      std::printf(" record_samples=%lld weighting=%s\n", static_cast<long long>(r.samples),
                  r.objective.weighting == tuning::Weighting::relative ? "relative" : "absolute");
      break;
    case tuning::Objective::entries:
      std::printf(" record_samples=%lld entry_floor=%g\n", static_cast<long long>(r.samples), r.objective.entry_floor);
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
  std::printf("default_objective=%.10g tuned_objective=%.10g default_%s=%.6g tuned_%s=%.6g\n", fit.start_residual,
              fit.residual, r.figure.c_str(), r.figure_default, r.figure.c_str(), r.figure_tuned);
  std::printf("evaluations=%d setup_time_s=%.3f fit_time_s=%.3f stop_reason=\"%s\"\n", fit.evaluations, r.setup_seconds,
              fit.seconds, fit.stop_reason.c_str());
  for (const tuning::HeldOutValidation& v : r.validations) {
    std::printf("validation scenario=%s role=%s draws=%zu first_seed=%llu pairs=%d default_not_completed=%d "
                "tuned_not_completed=%d\n",
                v.scenario.c_str(), v.scenario == r.scenario ? "tuning_scenario" : "held_out_scenario", v.seeds.size(),
                static_cast<unsigned long long>(v.seeds.front()), v.pairs(), v.default_not_completed(), v.tuned_not_completed());
    print_comparison(v.scenario, v.cost);
    if (v.cost_dev) print_comparison(v.scenario, *v.cost_dev);
    print_comparison(v.scenario, v.rms_error);
  }
  std::string files;
  for (const std::filesystem::path& file : r.files) files += (files.empty() ? "" : ",") + file.string();
  std::printf("wrote=%s\n", files.c_str());
  for (const std::string& warning : r.warnings) std::printf("warning=\"%s\"\n", warning.c_str());
}

}  // namespace

CLI::App* add_tune_command(CLI::App& app, TuneArguments& a) {
  auto* tune = app.add_subcommand(
      "tune", "Fit theta-D's k_i, l_i by an objective (sigma: the paper's sigma_max match to an SDRE flight, "
              "docs/model.md §8.1; entries: a per-entry match; closed-loop: mean cost, J_dev or RMS error over seeded "
              "draws), or any controller's weights Q, R by the closed loop; compare default and tuned on held-out draws");
  add_flight_options(*tune, a.flight);
  tune->get_option("--out")->required();
  tune->add_option("--objective", a.tune.objective, "sigma, entries or closed-loop")
      ->check(CLI::IsMember({"sigma", "entries", "closed-loop"}))
      ->capture_default_str();
  tune->add_option("--controller", a.tune.controller, "The controller tuned (its block of --settings is the start)")
      ->capture_default_str();
  tune->add_option("--parameters", a.tune.parameters,
                   "series (theta-d's k_i, l_i) or weights (log10 factors on the controller's Q and R by group, "
                   "closed-loop only; docs/tuning.md); default: series for theta-d, weights otherwise")
      ->check(CLI::IsMember({"series", "weights"}));
  tune->add_option("--weight-bounds", a.tune.weight_bounds, "weights: each log10 factor lies in [-B, B]")
      ->check(CLI::Range(1e-3, 10.0))
      ->capture_default_str();
  // The expansion's pieces grow fast with N (5, 11, 29 for N = 3, 4, 5; 516 for N = 8), and every
  // sample stores all of them: N = 5 already needs ~340 MB for scenario I's 8500 samples.
  tune->add_option("--terms", a.tune.terms, "N: the theta-D series T0 + ... + T_{N-1} (tunes N-1 pairs k_i, l_i)")
      ->check(CLI::Range(2, 5))
      ->capture_default_str();
  tune->add_option("--algorithm", a.tune.algorithm,
                   "NLopt algorithm: LN_BOBYQA (default), LN_COBYLA (default for closed-loop), LN_SBPLX, "
                   "LN_NELDERMEAD (local from k = l = 1) or GN_DIRECT_L, GN_ISRES (global, then LN_BOBYQA)");
  tune->add_option("--max-evaluations", a.tune.max_evaluations,
                   "Evaluation budget of the (local) search (default: 1500; 40 for closed-loop)")
      ->check(CLI::Range(1, 1000000));
  tune->add_option("--max-seconds", a.tune.max_seconds, "Time budget of the search in seconds (0: none)")
      ->check(CLI::Range(0.0, 1e7))
      ->capture_default_str();
  tune->add_option("--record", a.tune.record,
                   "sigma, entries: SDRE record (CSV), reused if the file exists, else the flight is recorded into it "
                   "(default: <out>/sdre-record.csv, always re-flown)");
  tune->add_option("--every", a.tune.every, "sigma, entries: keep every N-th controller sample in the record")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  tune->add_flag("--relative", a.tune.relative, "sigma: fit relative errors (sigma_theta-D - sigma_SDRE) / sigma_SDRE");
  tune->add_option("--entry-floor", a.tune.entry_floor,
                   "entries: an entry P_rc is scaled by max(|P_rc|, floor * sqrt(P_rr P_cc))")
      ->capture_default_str();
  tune->add_option("--metric", a.tune.metric,
                   "closed-loop, and the figure of merit: cost (J), rms_error_m (the RMS 3-D position error; "
                   "rms-error, its former name, is accepted) or cost_dev (J_dev, docs/model.md §7.2; cost-dev accepted)")
      ->check(CLI::IsMember({"cost", "rms_error_m", "rms-error", "cost_dev", "cost-dev"}))
      ->capture_default_str();
  tune->add_option("--draws", a.tune.draws, "closed-loop: training draws, seeds S ... S+draws-1 (S: --seed or the scenario's)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  tune->add_option("--holdout-draws", a.tune.holdout_draws, "Held-out draws of the validation")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  tune->add_option_function<std::string>(
      "--holdout-seed", [&a](const std::string& text) { a.tune.holdout_seed = parse_seed(text, "--holdout-seed"); },
      "First seed of the held-out draws (default: the seed after the training draws); must not overlap them");
  tune->add_option("--k-bounds", a.tune.k_bounds, "Lower and upper bound of every k_i")->expected(2)->capture_default_str();
  tune->add_option("--l-bounds", a.tune.l_bounds, "Lower and upper bound of every l_i")->expected(2)->capture_default_str();
  tune->add_option("--holdout", a.tune.holdout,
                   "Held-out scenario, validated on the held-out draws too (default: the other paper scenario, when "
                   "tuning on one)");
  tune->add_flag_callback("--no-validation", [&a] { a.tune.validation = false; }, "Skip the held-out validation");
  tune->add_option("--threads", a.tune.threads, "Threads of the fit and of the flights")->check(CLI::Range(1, 64))->capture_default_str();
  return tune;
}

int run_tune(const TuneArguments& a) {
  tuning::TuneOptions options = a.tune;
  options.scenario = a.flight.scenario;
  options.settings = a.flight.settings;
  options.controls = a.flight.controls;
  options.out = a.flight.out;
  Progress progress(Progress::mode_for_stderr(a.flight.quiet));
  const tuning::TuningReport report = tuning::tune(options, &progress);
  print_report(report);
  return report.any_not_completed() ? kExitDiverged : kExitCompleted;
}

}  // namespace thetad::app
