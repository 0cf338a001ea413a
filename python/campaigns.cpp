// thetad.campaign_run: a campaign file flown from Python (campaigns/campaign_runner.hpp) into
// OUT/campaign.sqlite, the GIL released while the workers fly. The report and the database's
// tables as pandas DataFrames are pure Python (thetad/campaigns.py).

#include <optional>
#include <string>

#include <pybind11/stl.h>

#include "campaigns/campaign.hpp"
#include "campaigns/campaign_runner.hpp"
#include "campaigns/campaign_store.hpp"
#include "experiment/scenario_files.hpp"
#include "python/bindings.hpp"
#include "python/task_observer.hpp"

namespace thetad::python {

void bind_campaigns(py::module_& module) {
  module.def(
      "campaign_run",
      [](const std::string& file, const std::string& out, int jobs, bool resume, bool timing,
         std::optional<int> keep_logs, py::object progress) {
        const Campaign campaign = load_campaign(find_campaign(file));
        CampaignOptions options;
        options.out = out;
        options.jobs = jobs;
        options.resume = resume;
        options.timing = timing;
        options.keep_logs = keep_logs;
        options.progress = Progress::Mode::quiet;
        TaskObserver observer(std::move(progress));
        options.observer = observer.tasks();
        CampaignOutcome outcome;
        {
          py::gil_scoped_release unlocked;
          outcome = run_campaign(campaign, options);
        }
        py::dict result;
        result["campaign"] = campaign.name;
        result["database"] = store_file(out).string();
        result["runs"] = outcome.runs;
        result["flown"] = outcome.flown;
        result["not_completed"] = outcome.not_completed;
        return result;
      },
      py::arg("file"), py::kw_only(), py::arg("out"), py::arg("jobs") = 0, py::arg("resume") = false,
      py::arg("timing") = true, py::arg("keep_logs") = py::none(), py::arg("progress") = py::none(),
      "`thetad campaign run`: flies the campaign `file` (a file or a shipped campaign's name) into "
      "out/campaign.sqlite with `jobs` worker threads (0: every core); resume continues a database, skipping "
      "the runs it holds. Returns {campaign, database, runs, flown, not_completed} (not_completed: the runs flown "
      "that diverged or failed). progress(runs done, runs). Ctrl-C raises KeyboardInterrupt within a second: the "
      "runs stored stay (resume=True continues), the flights under way are abandoned.");
}

}  // namespace thetad::python
