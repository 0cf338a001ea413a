// thetad.run and thetad.compare: flights through the experiment library (experiment/flight.hpp),
// with the GIL released while the simulator flies.

#include <optional>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "experiment/comparison.hpp"
#include "experiment/run_files.hpp"
#include "python/bindings.hpp"
#include "python/entries.hpp"
#include "python/python_controller.hpp"
#include "python/task_observer.hpp"
#include "python/values.hpp"

namespace thetad::python {

namespace {

// The log as a (rows, columns) view of the result's memory, without the wall-clock column when
// the run measured no time (the columns of the CSV).
py::array log_array(py::object self) {
  const RunResult& result = self.cast<const RunResult&>();
  const auto schema = static_cast<py::ssize_t>(result.log.columns.size());
  const auto columns =
      static_cast<py::ssize_t>(log_columns(result.log.columns, result.summary.settings.measure_compute_time).size());
  const auto rows = static_cast<py::ssize_t>(result.log.rows());
  const auto item = static_cast<py::ssize_t>(sizeof(double));
  py::array view(py::dtype::of<double>(), {rows, columns}, {schema * item, item}, result.log.values.data(), self);
  py::detail::array_proxy(view.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return view;
}

std::vector<std::string> column_headers(const RunResult& result) {
  std::vector<std::string> headers;
  for (const auto& column : log_columns(result.log.columns, result.summary.settings.measure_compute_time))
    headers.push_back(column.header());
  return headers;
}

}  // namespace

void bind_flights(py::module_& module) {
  py::class_<RunResult>(module, "RunResult",
                        "One flight: summary, settings, provenance and (unless summary_only) the log")
      .def_property_readonly("label", [](const RunResult& r) { return r.spec.label; })
      .def_property_readonly("controller", [](const RunResult& r) { return r.spec.controller; })
      .def_property_readonly("controller_origin", [](const RunResult& r) { return r.controller_origin; })
      .def_property_readonly("completed", &RunResult::completed)
      .def_property_readonly("status", [](const RunResult& r) { return sim::status_name(r.summary.status); },
                             "completed, diverged or failed, as the result file says")
      .def_property_readonly("status_text", [](const RunResult& r) { return status_text(r.summary); },
                             "'completed', or 'diverged at T s' / 'failed at T s', for display")
      .def_property_readonly("reason", [](const RunResult& r) { return r.summary.reason; })
      .def_property_readonly("summary", [](const RunResult& r) { return to_python(summary_json(r.summary)); })
      .def_property_readonly("settings", [](const RunResult& r) { return to_python(yaml_to_json(r.settings)); })
      .def_property_readonly("provenance", [](const RunResult& r) { return to_python(to_json(r.provenance)); })
      .def_property_readonly("wall_time_s", [](const RunResult& r) { return r.wall_time_s; })
      .def_property_readonly("columns", &column_headers, "the log's columns, NAME_UNIT as in the CSV header")
      .def_property_readonly("log", &log_array, "the log, (rows, columns), read-only, no copy; empty when summary_only")
      .def(
          "frame",
          [](py::object self) {
            // A copy: a frame is for editing, and pandas would otherwise share the read-only log.
            return py::module_::import("pandas").attr("DataFrame")(
                log_array(self), py::arg("columns") = column_headers(self.cast<const RunResult&>()), py::arg("copy") = true);
          },
          "the log as a pandas.DataFrame (a copy), columns as in the CSV (NAME_UNIT)")
      .def(
          "json", [](const RunResult& r) { return to_python(result_json(r, nullptr)); },
          "the result file's content (format thetad-run-1) without the log's file")
      .def(
          "write",
          [](const RunResult& r, const std::string& folder) {
            const RunFiles files = write_run_files(r, folder);
            return py::make_tuple(files.json.string(), files.csv.empty() ? py::object(py::none()) : py::str(files.csv.string()));
          },
          py::arg("folder"), "writes LABEL.json and LABEL.csv as `thetad run` does; returns their paths")
      .def("__repr__", [](const RunResult& r) { return "RunResult(" + r.spec.label + ": " + status_text(r.summary) + ")"; });

  module.def(
      "run",
      [](const std::optional<std::string>& scenario, py::handle controller, py::handle plant,
         const std::optional<std::vector<double>>& initial_state, std::optional<std::string> label, py::object progress,
         const py::kwargs& controls) {
        if (controller.is_none()) throw py::type_error("run: give the controller to fly");
        const RunControls parsed = run_controls(controls);
        const PlantArgument flown = plant_argument(plant);
        Entry entry = entry_of(controller);
        if (label) spec_of(entry).label = *label;
        check_label(spec_of(entry).label);
        PreparedController prepared;  // released with the GIL held (a Python controller's reference)
        TaskObserver observer(std::move(progress));
        RunResult result;
        {
          py::gil_scoped_release unlocked;
          const Flight flight = flight_of(scenario, flown, initial_state, parsed);
          prepared = prepare(flight, entry);
          result = flight.fly(prepared, nullptr, {}, observer.hook(spec_of(entry).label, flight.settings().duration));
        }
        observer.finished(result.spec.label, result.summary.end_time);
        return result;
      },
      py::arg("scenario") = py::none(), py::arg("controller") = py::none(), py::kw_only(),
      py::arg("plant") = py::none(), py::arg("initial_state") = py::none(), py::arg("label") = py::none(),
      py::arg("progress") = py::none(),
      "Flies `controller` (a registered name or spec string, thetad.controller(...), or a thetad.Controller "
      "subclass instance) through `scenario` (a file or a shipped scenario's name; a file may name a plant, "
      "docs/plants.md), or regulates `plant` (a registered plant's name, thetad.plants(), or a thetad.Plant subclass "
      "instance) from `initial_state` (its own when None; then duration_s is needed). Run controls as keywords: "
      "seed, duration_s, dt_s, log_every, summary_only, timing, ideal, the disturbance switches, actuator_limits and "
      "anti_windup (duration and dt, the earlier names, still work). progress: None or progress(t, duration), "
      "called with the simulated seconds at most 10 times a second and once at the end. Ctrl-C stops the flight "
      "within ~0.1 s and raises KeyboardInterrupt.");

  module.def(
      "compare",
      [](const std::optional<std::string>& scenario, const std::optional<py::sequence>& controllers, py::handle plant,
         const std::optional<std::vector<double>>& initial_state, py::object progress, const py::kwargs& controls) {
        if (!controllers) throw py::type_error("compare: give the controllers to fly");
        const RunControls parsed = run_controls(controls);
        const PlantArgument flown = plant_argument(plant);
        std::vector<Entry> entries = entries_of(*controllers);
        std::vector<PreparedController> prepared;
        TaskObserver observer(std::move(progress));
        std::vector<RunResult> results;
        py::gil_scoped_release unlocked;
        const Flight flight = flight_of(scenario, flown, initial_state, parsed);
        for (Entry& entry : entries) prepared.push_back(prepare(flight, entry));
        for (PreparedController& controller : prepared) {
          const auto observe = observer.hook(controller.spec.label, flight.settings().duration);
          results.push_back(flight.fly(controller, nullptr, {}, observe));
          py::gil_scoped_acquire locked;
          observer.finished(controller.spec.label, results.back().summary.end_time);
        }
        return results;
      },
      py::arg("scenario") = py::none(), py::arg("controllers") = py::none(), py::kw_only(),
      py::arg("plant") = py::none(), py::arg("initial_state") = py::none(), py::arg("progress") = py::none(),
      "The same flight (same seed: same perturbed plant and noise; `scenario`, or `plant` and `initial_state` as "
      "for run) for each controller, in order: a list of "
      "RunResult. Labels must differ ('paper=theta-d', thetad.controller(..., label=...)). progress and Ctrl-C "
      "as for run, progress starting anew for each controller.");

  module.def("comparison_table", &comparison_table, py::arg("results"),
             "The table `thetad compare` prints, for a list of RunResult");
}

}  // namespace thetad::python
