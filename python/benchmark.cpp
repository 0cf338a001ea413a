// thetad.bench: `thetad bench` from Python (experiment/step_timing.hpp), the GIL released while
// the recording flies and the steps are timed.

#include <string>
#include <vector>

#include <pybind11/stl.h>

#include "experiment/step_timing.hpp"
#include "python/bindings.hpp"
#include "python/entries.hpp"
#include "python/task_observer.hpp"
#include "python/values.hpp"

namespace thetad::python {

void bind_bench(py::module_& module) {
  module.def(
      "bench",
      [](const py::sequence& controllers, const std::string& scenario, int samples, int segments, int repetitions,
         int warmup, int cpu, py::object progress, const py::kwargs& controls) {
        RunControls parsed = run_controls(controls);
        parsed.summary_only = true;
        StepTimingOptions options;
        options.samples = samples;
        options.segments = segments;
        options.repetitions = repetitions;
        options.warmup_passes = warmup;
        options.cpu = cpu;
        std::vector<Entry> entries = entries_of(controllers);
        if (entries.empty()) throw py::value_error("bench: no controllers");
        TaskObserver observer(std::move(progress));
        nlohmann::ordered_json report;
        {
          py::gil_scoped_release unlocked;
          const Flight flight(scenario, parsed);
          std::vector<PreparedController> prepared;
          for (Entry& entry : entries) prepared.push_back(prepare(flight, entry));
          Progress watched(Progress::Mode::quiet, observer.tasks());
          const RecordedSamples recorded = record_samples(flight, prepared.front(), &watched);
          const StepTimingReport timing =
              time_steps(prepared, recorded, flight.scenario().initial_state, flight.plant().input_dim(), options);
          report = bench_json(flight, recorded, timing);
          report["table"] = step_timing_table(timing);
        }
        return to_python(report);
      },
      py::arg("controllers"), py::kw_only(), py::arg("scenario") = "scenario-1", py::arg("samples") = 1000,
      py::arg("segments") = 10, py::arg("repetitions") = 5, py::arg("warmup") = 1, py::arg("cpu") = -1,
      py::arg("progress") = py::none(),
      "`thetad bench`: the per-step cost of each controller on the states the first one flies through "
      "`scenario`, outside the simulation loop, pinned to one core (cpu: -1 the last this process may use, -2 "
      "none). Returns bench.json's content as a dict (its 'controllers' make a pandas.DataFrame; 'table' is the "
      "printed table). Run controls as keywords (duration_s, seed, ...). progress and Ctrl-C as for run (the "
      "recording flight; the timing itself is not interruptible).");
}

}  // namespace thetad::python
