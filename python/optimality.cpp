// thetad.optimal: `thetad optimal` from Python (optimal/optimality_report.hpp), the GIL released
// while the controllers fly and Ipopt solves.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/stl.h>

#include "experiment/run_files.hpp"
#include "optimal/optimality_report.hpp"
#include "python/bindings.hpp"
#include "python/entries.hpp"
#include "python/task_observer.hpp"
#include "python/values.hpp"

namespace thetad::python {

namespace {

// What thetad.optimal returns: named fields, not a tuple.
struct Optimality {
  nlohmann::ordered_json report;  // optimality.json's content
  std::vector<RunResult> runs;    // the flights, then each optimum (and its unbounded solve)
  bool converged = false;         // every solve converged and no unbounded optimum costs more than its bounded one
};

OptimalCost cost_of(const std::string& name) {
  if (name == "j-dev") return OptimalCost::deviation;
  if (name == "j") return OptimalCost::paper;
  throw py::value_error("optimal: cost must be 'j-dev' (the comparison's score) or 'j' (Eq. 32), got '" + name + "'");
}

}  // namespace

void bind_optimal(py::module_& module) {
  py::class_<Optimality>(module, "Optimality", "What thetad.optimal found: the report, the runs, whether it converged")
      .def_property_readonly("report", [](const Optimality& o) { return to_python(o.report); },
                             "optimality.json's content: the segment, the solves, each controller's cost and gap")
      .def_readonly("runs", &Optimality::runs, "the flights, then the optima, as RunResult")
      .def_readonly("converged", &Optimality::converged)
      .def("__repr__", [](const Optimality& o) {
        std::string text = "Optimality(" + o.report["cost"]["name"].get<std::string>() + ":";
        for (const auto& c : o.report["controllers"]) {
          // Appended piece by piece: GCC 12 warns (-Wrestrict, a false positive) on " " + std::string&&.
          text.append(" ").append(c["label"].get<std::string>()).append(" gap ");
          text += c["gap_percent"].is_number() ? std::to_string(c["gap_percent"].get<double>()) + " %" : "-";
        }
        return text + (o.converged ? ")" : "; NOT converged)");
      });

  module.def(
      "optimal",
      [](const std::optional<std::string>& scenario, const std::optional<py::sequence>& controllers, py::handle plant,
         const std::optional<std::vector<double>>& initial_state, double horizon, double start, const std::string& cost,
         bool actuator_limits, double control_interval, std::optional<std::string> warm_start, int max_iterations,
         double tolerance, std::optional<std::string> out, bool timing, py::object progress) {
        if (!controllers) throw py::type_error("optimal: give the controllers to fly");
        const PlantArgument flown = plant_argument(plant);
        RunControls controls;
        controls.duration = start + horizon;
        controls.ideal = true;  // the optimum is that of the nominal plant with ideal sensors
        controls.actuator_limits = actuator_limits;
        controls.log_every = 1;
        controls.summary_only = false;
        controls.timing = timing;
        OptimalityOptions options;
        options.cost = cost_of(cost);
        options.control_interval = control_interval;
        options.start = start;
        options.warm_start = warm_start.value_or("");
        options.solver.ipopt.max_iterations = max_iterations;
        options.solver.ipopt.tolerance = tolerance;
        std::vector<Entry> entries = entries_of(*controllers);
        TaskObserver observer(std::move(progress));
        Optimality result;
        {
          py::gil_scoped_release unlocked;
          const Flight flight = flight_of(scenario, flown, initial_state, controls);
          // A segment off the grid fails before the controllers are built.
          if (optimality_problem(flight, options).finite_differences) {
            py::gil_scoped_acquire locked;
            const std::string warning = "the plant " + flight.provenance().plant +
                                        " gives no Jacobian (SdcPlant::jacobian): the optimum's derivatives are "
                                        "central differences of f";
            if (PyErr_WarnEx(PyExc_RuntimeWarning, warning.c_str(), 1) < 0) throw py::error_already_set();
          }
          std::vector<PreparedController> prepared;
          for (Entry& entry : entries) prepared.push_back(prepare(flight, entry));
          if (out) prepare_output_folder(*out);
          Progress watched(Progress::Mode::quiet, observer.tasks());
          const OptimalityGap gap = optimality_gap(flight, prepared, options, &watched);
          result.report = out ? write_optimality(flight, gap, options, *out) : optimality_json(flight, gap, options, {});
          result.runs = optimality_runs(gap);
          result.converged = optimality_converged(gap) && unbounded_at_most_bounded(gap);
        }
        return result;
      },
      py::arg("scenario") = py::none(), py::arg("controllers") = py::none(), py::kw_only(), py::arg("plant") = py::none(),
      py::arg("initial_state") = py::none(), py::arg("horizon"), py::arg("start") = 0.0,
      py::arg("cost") = "j-dev", py::arg("actuator_limits") = false, py::arg("control_interval") = 0.05,
      py::arg("warm_start") = py::none(), py::arg("max_iterations") = 1000, py::arg("tolerance") = 1e-6,
      py::arg("out") = py::none(), py::arg("timing") = true, py::arg("progress") = py::none(),
      "`thetad optimal`: each controller's cost (cost='j-dev' or 'j') over `horizon` seconds from `start`, flown "
      "ideal through `scenario` (or `plant` from `initial_state`, as for run), and its gap to the optimum of the same problem (Ipopt, multiple shooting; with actuator_limits "
      "bounded by their magnitudes, then unbounded). Returns an Optimality (report, runs, converged); with `out` "
      "also writes what the command writes there. progress(done, total) per task (flights, then Ipopt "
      "iterations); Ctrl-C raises KeyboardInterrupt.");
}

}  // namespace thetad::python
