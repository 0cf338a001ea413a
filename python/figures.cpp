// The plumbing under thetad.plot and thetad.campaign_report (thetad/figures.py, thetad/campaigns.py):
// the figures of a folder of runs (experiment/run_figures.hpp) and where the shipped scripts are.

#include <string>
#include <vector>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "experiment/python_script.hpp"
#include "experiment/run_figures.hpp"
#include "python/bindings.hpp"

namespace thetad::python {

namespace py = pybind11;

void bind_figures(py::module_& module) {
  module.def(
      "_draw_figures",
      [](const std::string& in, const std::string& out, const std::vector<std::string>& formats, int dpi,
         const std::string& baseline) {
        FigureOptions options;
        options.formats = formats;
        options.dpi = dpi;
        options.baseline = baseline;
        py::gil_scoped_release unlocked;
        return draw_run_figures(in, out, options);
      },
      py::arg("folder"), py::arg("out"), py::arg("formats"), py::arg("dpi"), py::arg("baseline"));
  module.def("_shipped_script", &shipped_script, py::arg("name"),
             "scripts/NAME of the installed thetad, or of the source tree of a build");
}

}  // namespace thetad::python
