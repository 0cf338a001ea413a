// thetad.tune: a tuning run through the tuning library (tuning/tune_run.hpp), with the GIL
// released while it flies and searches.

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "python/bindings.hpp"
#include "python/entries.hpp"
#include "python/task_observer.hpp"
#include "python/values.hpp"
#include "tuning/tune_run.hpp"

namespace thetad::python {

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
        TaskObserver observer(std::move(progress));
        tuning::TuningReport report;
        {
          py::gil_scoped_release unlocked;
          Progress shown(Progress::Mode::quiet, observer.tasks());
          report = tuning::tune(options, &shown, observer.signals("tune"));
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
      "'files'. Run controls as keywords, as for run. progress: True (a bar) or progress(done, total) for each task "
      "(the SDRE record's flight in simulated seconds, the search in evaluations, each validation in flights), at "
      "its start and end and at most 10 times a second between. Ctrl-C stops the run within ~0.1 s of a flight "
      "sample or an evaluation and raises KeyboardInterrupt; the three files are then not written.");
}

}  // namespace thetad::python
