// thetad.tune: a tuning run through the tuning library (tuning/tune_run.hpp), with the GIL
// released while it flies and searches.

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "python/bindings.hpp"
#include "python/flight_observer.hpp"
#include "python/values.hpp"
#include "tuning/tune_run.hpp"

namespace thetad::python {

namespace {

// What watches a tuning run from Python: the caller's progress(task, done, total) for each task
// the run reports (the SDRE record's flight, the search, each validation), and Ctrl-C, checked at
// those reports and in the draws' flights. Both are called with the GIL released, on the thread
// that called tune, and take the GIL only to call Python.
class TuneObserver {
 public:
  explicit TuneObserver(py::object progress)
      : progress_(progress_callback(std::move(progress), "progress(task, done, total)")) {}

  // Progress's listener: a task's start and end reach the callback always, its updates at most
  // every FlightObserver::kProgressPeriod.
  void report(const std::string& label, double done, double total) {
    // The command line's label without its colon: "fit (closed-loop, LN_COBYLA)".
    const std::string task = !label.empty() && label.back() == ':' ? label.substr(0, label.size() - 1) : label;
    const bool edge = task != task_ || done == 0.0 || (done >= total && done_ < total);
    task_ = task;
    done_ = done;
    total_ = total;
    const Clock::time_point now = Clock::now();
    const bool call = !progress_.is_none() && (edge || now - last_report_ >= FlightObserver::kProgressPeriod);
    if (!call && !signals_.due()) return;
    py::gil_scoped_acquire locked;
    raise_pending_signal();
    if (!call) return;
    last_report_ = now;
    progress_(task, done, total);
  }

  // DrawFlights' observer.
  void flying() {
    if (!signals_.due()) return;
    py::gil_scoped_acquire locked;
    raise_pending_signal();
  }

 private:
  using Clock = std::chrono::steady_clock;

  void raise_pending_signal() const {
    SignalCheck::raise_pending([this] {
      char message[240];
      std::snprintf(message, sizeof message, "tune stopped in %s at %g of %g; no tuned settings or tuning.json written",
                    task_.c_str(), done_, total_);
      return std::string(message);
    });
  }

  py::object progress_;
  SignalCheck signals_;
  Clock::time_point last_report_ = Clock::now();
  std::string task_;
  double done_ = 0.0, total_ = 0.0;
};

}  // namespace

void bind_tuning(py::module_& module) {
  const tuning::TuneOptions defaults;
  module.def(
      "tune",
      [](const std::string& scenario, const std::string& controller, const std::string& objective,
         std::optional<std::string> parameters, const std::string& metric, int draws, int holdout_draws, int terms,
         std::optional<std::string> algorithm, std::optional<int> max_evaluations, double max_seconds,
         std::optional<std::uint64_t> seed, std::optional<std::filesystem::path> settings, const std::filesystem::path& out,
         double weight_bounds, std::optional<std::filesystem::path> record, int every, bool relative, double entry_floor,
         bool validation, std::optional<std::uint64_t> holdout_seed, std::optional<std::string> holdout,
         std::vector<double> k_bounds, std::vector<double> l_bounds, int threads, py::object progress,
         const py::kwargs& controls) {
        tuning::TuneOptions options;
        options.scenario = scenario;
        options.settings = settings.value_or(std::filesystem::path());
        options.controls = run_controls(controls);
        if (seed) options.controls.seed = *seed;
        options.out = out;
        options.objective = objective;
        options.controller = controller;
        options.parameters = std::move(parameters);
        options.weight_bounds = weight_bounds;
        options.terms = terms;
        options.algorithm = std::move(algorithm);
        options.max_evaluations = max_evaluations;
        options.max_seconds = max_seconds;
        options.record = record.value_or(std::filesystem::path());
        options.every = every;
        options.relative = relative;
        options.entry_floor = entry_floor;
        options.metric = metric;
        options.draws = draws;
        options.validation = validation;
        options.holdout_draws = holdout_draws;
        options.holdout_seed = holdout_seed;
        options.holdout = holdout.value_or(std::string());
        options.k_bounds = std::move(k_bounds);
        options.l_bounds = std::move(l_bounds);
        options.threads = threads;
        TuneObserver observer(std::move(progress));
        tuning::TuningReport report;
        {
          py::gil_scoped_release unlocked;
          Progress shown(Progress::Mode::quiet,
                         [&observer](const std::string& task, double done, double total) { observer.report(task, done, total); });
          report = tuning::tune(options, &shown, [&observer](double) { observer.flying(); });
        }
        py::dict result = to_python(to_json(report));
        result["tuned_settings"] = report.files.front().string();
        std::vector<std::string> files;
        for (const std::filesystem::path& file : report.files) files.push_back(file.string());
        result["files"] = files;
        return result;
      },
      py::arg("scenario"), py::arg("controller") = defaults.controller, py::kw_only(),
      py::arg("objective") = defaults.objective, py::arg("parameters") = py::none(), py::arg("metric") = defaults.metric,
      py::arg("draws") = defaults.draws, py::arg("holdout_draws") = defaults.holdout_draws,
      py::arg("terms") = defaults.terms, py::arg("algorithm") = py::none(), py::arg("max_evaluations") = py::none(),
      py::arg("max_seconds") = defaults.max_seconds, py::arg("seed") = py::none(), py::arg("settings") = py::none(),
      py::arg("out"), py::arg("weight_bounds") = defaults.weight_bounds, py::arg("record") = py::none(),
      py::arg("every") = defaults.every, py::arg("relative") = defaults.relative,
      py::arg("entry_floor") = defaults.entry_floor, py::arg("validation") = defaults.validation,
      py::arg("holdout_seed") = py::none(), py::arg("holdout") = py::none(), py::arg("k_bounds") = defaults.k_bounds,
      py::arg("l_bounds") = defaults.l_bounds, py::arg("threads") = defaults.threads, py::arg("progress") = py::none(),
      "Tunes `controller` on `scenario` as `thetad tune` does (docs/tuning.md; the keywords are its options, "
      "--no-validation is validation=False) and writes the same files into `out`: CONTROLLER-tuned.yaml, "
      "tuning.json and, for objective='sigma', sigma-curves.csv. Returns tuning.json's content as a dict, with "
      "'tuned_settings' (the settings file's path, for thetad.controller('tuned=NAME:FILE') or thetad.run) and "
      "'files'. Run controls as keywords, as for run. progress: None or progress(task, done, total) for each task "
      "(the SDRE record's flight in simulated seconds, the search in evaluations, each validation in flights), at "
      "its start and end and at most 10 times a second between. Ctrl-C stops the run within ~0.1 s of a flight "
      "sample or an evaluation and raises KeyboardInterrupt; the three files are then not written.");
}

}  // namespace thetad::python
