#include "apps/thetad/tune_command.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "controllers/sdre.hpp"
#include "controllers/theta_d.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "experiment/controller_spec.hpp"
#include "experiment/result_json.hpp"
#include "experiment/run_files.hpp"
#include "experiment/scenario_files.hpp"
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

// The θ–D the command flies and tunes: the settings file's block (or the defaults) with this many
// terms and these k, l (empty: the defaults, all 1), built for `flight`.
PreparedController make_theta_d(const Flight& flight, const YAML::Node& base, const std::string& label, int terms,
                                const Eigen::VectorXd& k, const Eigen::VectorXd& l) {
  YAML::Node block = base ? YAML::Clone(base) : YAML::Node(YAML::NodeType::Map);
  block[theta_d_keys::terms] = terms;
  const auto values = [](const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); };
  if (k.size() > 0) block[theta_d_keys::k] = values(k);
  if (l.size() > 0) block[theta_d_keys::l] = values(l);
  return flight.prepare({label, "theta-d", block, {}, {}});
}

tuning::FitOptions fit_options(const TuneArguments& a, std::uint64_t seed) {
  tuning::FitOptions options;
  options.algorithm = a.algorithm;
  options.weighting = a.relative ? tuning::Weighting::relative : tuning::Weighting::absolute;
  options.k_lower = a.k_bounds[0];
  options.k_upper = a.k_bounds[1];
  options.l_lower = a.l_bounds[0];
  options.l_upper = a.l_bounds[1];
  options.seed = seed;
  tuning::check_fit_options(options, a.terms - 1);
  return options;
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
tuning::TuningRecord fly_record(const TuneArguments& a, const Flight& flight, const YAML::Node& settings,
                                Progress& progress) {
  const PreparedController sdre = flight.prepare(parse_controller_spec("sdre", settings, a.flight.settings.string()));
  const auto start = Clock::now();
  tuning::TuningRecord record = tuning::record_sdre_flight(flight, dynamic_cast<const SdreController&>(*sdre.controller),
                                                           a.every, a.threads, &progress);
  const std::filesystem::path file = a.record.empty() ? a.flight.out / "sdre-record.csv" : a.record;
  tuning::write_record(file, record);
  std::fprintf(stderr, "recorded %lld samples with sigma_max(P) by cold CARE solves (%.1f s): %s\n",
               static_cast<long long>(record.size()), seconds_since(start), file.c_str());
  return record;
}

// The default and the tuned θ–D flown on each validation flight.
std::vector<tuning::Validation> validate(const TuneArguments& a, const std::vector<std::pair<const Flight*, std::string>>& flights,
                                 const YAML::Node& base, const tuning::FitResult& fit, Progress& progress) {
  std::vector<tuning::Validation> validations;
  for (const auto& [flight, role] : flights) {
    for (const bool tuned : {false, true}) {
      const std::string parameters = tuned ? "tuned" : "default";
      PreparedController controller = tuned ? make_theta_d(*flight, base, "theta-d-tuned", a.terms, fit.k, fit.l)
                                            : make_theta_d(*flight, base, "theta-d-default", a.terms, {}, {});
      const RunResult run =
          flight->fly(controller, &progress, "theta-d " + parameters + " on " + flight->scenario().name + ":");
      validations.push_back({flight->scenario().name, role, parameters, run.summary});
    }
  }
  return validations;
}

// Quiet and parseable: one key=value line per figure.
void print_report(const tuning::TuningReport& r, const std::vector<std::filesystem::path>& written) {
  const tuning::FitResult& fit = r.fit;
  std::printf("scenario=%s samples=%lld terms=%d algorithm=%s weighting=%s\n", r.scenario.c_str(),
              static_cast<long long>(r.samples), r.terms, r.options.algorithm.c_str(),
              r.options.weighting == tuning::Weighting::relative ? "relative" : "absolute");
  std::printf("k=%s\nl=%s\n", numbers(fit.k).c_str(), numbers(fit.l).c_str());
  std::printf("residual_default=%.10g residual_tuned=%.10g rms_sigma_error_default=%.6g rms_sigma_error_tuned=%.6g\n",
              fit.start_residual, fit.residual, r.rms_sigma_error_default(), r.rms_sigma_error_tuned());
  std::printf("evaluations=%d expansion_seconds=%.3f fit_seconds=%.3f stop=\"%s\"\n", fit.evaluations,
              r.expansion_seconds, fit.seconds, fit.stop_reason.c_str());
  for (const tuning::Validation& v : r.validations) {
    const sim::RunSummary& s = v.summary;
    std::printf("validation scenario=%s role=%s theta_d=%s status=\"%s\" rms_m=%.5f,%.5f,%.5f max_m=%.5f,%.5f,%.5f "
                "cost=%.8g\n",
                v.scenario.c_str(), v.role.c_str(), v.parameters.c_str(), status_text(s).c_str(),
                s.rms_tracking_error.x(), s.rms_tracking_error.y(), s.rms_tracking_error.z(), s.max_tracking_error.x(),
                s.max_tracking_error.y(), s.max_tracking_error.z(), s.cost);
  }
  std::printf("wrote=%s,%s,%s\n", written[0].c_str(), written[1].c_str(), written[2].c_str());
}

}  // namespace

CLI::App* add_tune_command(CLI::App& app, TuneArguments& a) {
  auto* tune = app.add_subcommand(
      "tune", "Fit theta-D's k_i, l_i so that sigma_max(sum T_i) matches sigma_max(P_SDRE) along an SDRE flight "
              "(paper-spec 7.5); validate on the tuning and a held-out scenario");
  add_flight_options(*tune, a.flight);
  tune->get_option("--out")->required();
  // The expansion's pieces grow fast with N (5, 11, 29 for N = 3, 4, 5; 516 for N = 8), and every
  // sample stores all of them: N = 5 already needs ~340 MB for scenario I's 8500 samples.
  tune->add_option("--terms", a.terms, "N: the theta-D series T0 + ... + T_{N-1} (tunes N-1 pairs k_i, l_i)")
      ->check(CLI::Range(2, 5))
      ->capture_default_str();
  tune->add_option("--algorithm", a.algorithm,
                   "NLopt algorithm: LN_BOBYQA, LN_SBPLX, LN_NELDERMEAD (local from k = l = 1) or GN_DIRECT_L, "
                   "GN_ISRES (global, then LN_BOBYQA)")
      ->capture_default_str();
  tune->add_option("--record", a.record,
                   "SDRE record (CSV): reused if the file exists, else the flight is recorded into it "
                   "(default: <out>/sdre-record.csv, always re-flown)");
  tune->add_option("--every", a.every, "Keep every N-th controller sample in the record")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  tune->add_flag("--relative", a.relative, "Fit relative errors (sigma_theta-D - sigma_SDRE) / sigma_SDRE");
  tune->add_option("--k-bounds", a.k_bounds, "Lower and upper bound of every k_i")->expected(2)->capture_default_str();
  tune->add_option("--l-bounds", a.l_bounds, "Lower and upper bound of every l_i")->expected(2)->capture_default_str();
  tune->add_option("--holdout", a.holdout,
                   "Held-out scenario for validation (default: the other paper scenario, when tuning on one)");
  tune->add_flag("--no-validation", a.no_validation, "Skip the validation flights");
  tune->add_option("--threads", a.threads, "Threads of the fit")->check(CLI::Range(1, 64))->capture_default_str();
  return tune;
}

int run_tune(const TuneArguments& a) {
  // Everything that can be wrong with the inputs fails here, before a flight or a file. The
  // validation flights need their summaries only.
  RunControls controls = run_controls(a.flight);
  controls.summary_only = true;
  const Flight flight(a.flight.scenario, controls);
  const tuning::FitOptions options_without_progress = fit_options(a, flight.settings().seed);
  const YAML::Node settings = a.flight.settings.empty() ? YAML::Node() : load_settings_file(a.flight.settings);
  const YAML::Node base = settings.IsMap() && settings["theta-d"] ? settings["theta-d"] : YAML::Node();
  std::optional<Flight> holdout;
  const std::filesystem::path holdout_file =
      a.holdout.empty() ? default_holdout(find_scenario(a.flight.scenario)) : a.holdout;
  if (!a.no_validation && !holdout_file.empty()) holdout.emplace(holdout_file.string(), controls);
  const std::optional<tuning::TuningRecord> reused = reused_record(a, flight);
  prepare_output_folder(a.flight.out);

  Progress progress(Progress::mode_for_stderr(a.flight.quiet));
  const tuning::TuningRecord record = reused ? *reused : fly_record(a, flight, settings, progress);
  // The θ–D starts where the recorded flight started: A0, g0, T0 at the scenario's x0, t0 = 0.
  PreparedController theta_d = make_theta_d(flight, base, "theta-d", a.terms, {}, {});
  auto& series = dynamic_cast<ThetaDController&>(*theta_d.controller);
  series.reset(flight.scenario().initial_state, 0.0);
  const auto expansion_start = Clock::now();
  const tuning::SigmaMatch match(series, record, a.threads);
  const double expansion_seconds = seconds_since(expansion_start);

  tuning::FitOptions options = options_without_progress;
  const bool live = progress.mode() == Progress::Mode::live;
  auto last_draw = Clock::now();
  options.progress = [&](int evaluations, double best) {
    if (!live || Clock::now() - last_draw < std::chrono::milliseconds(100)) return;
    last_draw = Clock::now();
    std::fprintf(stderr, "\r\033[Kfit (%s): %d evaluations, best residual %.6e", a.algorithm.c_str(), evaluations, best);
  };
  const tuning::FitResult fit = tuning::fit(match, options);
  if (live) std::fprintf(stderr, "\r\033[K");

  tuning::TuningReport report{flight.scenario().name, flight.settings().seed, match.samples(), reused.has_value(),
                              a.terms, options_without_progress, fit, expansion_seconds, a.threads, {},
                              flight.provenance()};
  const std::filesystem::path settings_file = a.flight.out / "theta-d-tuned.yaml";
  write_file_atomically(settings_file, tuned_settings_file(report, make_theta_d(flight, base, "theta-d", a.terms, fit.k,
                                                                                  fit.l).settings));
  write_file_atomically(a.flight.out / "sigma-curves.csv", sigma_curves_csv(match, record, fit));

  std::vector<std::pair<const Flight*, std::string>> validation_flights;
  if (!a.no_validation) validation_flights.emplace_back(&flight, "tuning");
  if (holdout) validation_flights.emplace_back(&*holdout, "held-out");
  report.validations = validate(a, validation_flights, base, fit, progress);
  write_file_atomically(a.flight.out / "tuning.json", to_json(report).dump(2) + "\n");
  print_report(report, {settings_file, a.flight.out / "sigma-curves.csv", a.flight.out / "tuning.json"});
  return report.any_diverged() ? kExitDiverged : kExitCompleted;
}

}  // namespace thetad::app
