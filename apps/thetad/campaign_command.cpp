#include "apps/thetad/campaign_command.hpp"

#include <algorithm>
#include <cstdio>
#include <thread>

#include "experiment/python_script.hpp"
#include "campaigns/campaign.hpp"
#include "campaigns/campaign_merge.hpp"
#include "campaigns/campaign_runner.hpp"
#include "campaigns/campaign_store.hpp"
#include "campaigns/cost_estimate.hpp"
#include "core/error.hpp"
#include "experiment/progress.hpp"
#include "experiment/scenario_files.hpp"

namespace thetad::app {

namespace fs = std::filesystem;

CLI::App* add_campaign_command(CLI::App& app, CampaignArguments& a) {
  auto* campaign = app.add_subcommand("campaign", "Fly, merge and report campaigns: many draws and sweep cells per controller");
  campaign->require_subcommand(1);

  a.run = campaign->add_subcommand("run", "Fly a campaign file into DIR/campaign.sqlite (threads, or ranks under mpirun)");
  a.run->add_option("file", a.file,
                    "The campaign file (docs/campaigns.md), or the name of a shipped one (scenario-1-paired, fair/legs)")
      ->required();
  a.run->add_option("--out", a.out, "Output directory (holds campaign.sqlite)");
  a.run->add_option("--jobs", a.jobs, "Worker threads (default: every core; one per rank under mpirun)")
      ->check(CLI::Range(1, 4096));
  a.run->add_flag("--resume", a.resume, "Continue the database in --out, skipping the runs it holds");
  a.run->add_option("--shard", a.shard, "Fly part k of N (k/N) into its own database; `campaign merge` joins them")
      ->capture_default_str();
  a.run->add_flag("--no-timing", a.no_timing, "No wall-clock figures: identical databases for identical campaigns");
  a.run->add_option("--keep-logs", a.keep_logs,
                    "Keep the full logs (CSV and JSON) of the first K draws of every cell and of every run that did "
                    "not complete, in DIR/logs/RUN_INDEX/")
      ->check(CLI::Range(0, 1000000))
      ->type_name("K");
  a.run->add_flag("--dry-run", a.dry_run, "Check the file, print the run count and a cost estimate from a short pilot");
  a.run->add_option("--pilot", a.pilot_seconds, "Simulated seconds each controller flies in the --dry-run pilot")
      ->check(CLI::Range(0.01, 3600.0))
      ->capture_default_str();
  a.run->add_flag("--quiet", a.quiet, "No progress lines");

  a.merge = campaign->add_subcommand("merge", "Join the shard databases of one campaign");
  a.merge->add_option("shards", a.shards, "The shard output directories")->required();
  a.merge->add_option("--out", a.merge_out, "Output directory for the merged campaign.sqlite")->required();

  a.report = campaign->add_subcommand("report", "Statistics, tables and figures of a campaign database");
  a.report->add_option("dir", a.report_in, "A campaign output directory")->required();
  a.report->add_option("--out", a.report_out, "Where report.md, report.json and the figures go (default DIR/report)");
  a.report->add_option("--seed", a.bootstrap_seed, "Seed of the bootstrap resampling")->capture_default_str();
  a.report->add_option("--resamples", a.resamples, "Bootstrap resamples")->check(CLI::Range(100, 1000000))->capture_default_str();
  return campaign;
}

namespace {

int dry_run(const Campaign& campaign, const CampaignArguments& a) {
  std::printf("%s: %zu scenario(s) x %zu controller(s) x %zu cell(s) x %d draws = %lld runs\n", campaign.name.c_str(),
              campaign.scenarios.size(), campaign.controllers.size(), campaign.cells.size(), campaign.draws,
              static_cast<long long>(campaign.run_count()));
  const CostEstimate estimate = estimate_cost(campaign, a.pilot_seconds);
  for (const auto& pilot : estimate.pilots)
    std::printf("  pilot %-20s %.4f s wall per simulated s\n", pilot.label.c_str(), pilot.wall_per_simulated_second);
  const int workers = a.jobs > 0 ? a.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::printf("estimated cost: %.2f core-hours, %s on %d worker(s) (an upper bound: runs that do not complete end early)\n",
              estimate.core_seconds / 3600.0, format_duration(estimate.wall_seconds(workers)).c_str(), workers);
  return 0;
}

int run(const CampaignArguments& a) {
  const Campaign campaign = load_campaign(find_campaign(a.file.string()));
  CampaignOptions options;
  options.shard = parse_shard(a.shard);
  if (a.dry_run) return dry_run(campaign, a);
  if (a.out.empty()) throw Error("campaign run: --out DIR is required (unless --dry-run)");
  options.out = a.out;
  options.jobs = a.jobs;
  options.resume = a.resume;
  options.timing = !a.no_timing;
  options.keep_logs = a.keep_logs;
  options.progress = Progress::mode_for_stderr(a.quiet);
  const CampaignOutcome outcome = run_campaign(campaign, options);
  if (outcome.writer) {
    std::printf("%s: %lld runs in shard %s, %lld flown now (%lld not completed); %s\n", campaign.name.c_str(),
                static_cast<long long>(outcome.runs), options.shard.text().c_str(),
                static_cast<long long>(outcome.flown), static_cast<long long>(outcome.not_completed),
                store_file(a.out).c_str());
  }
  return 0;
}

int report(const CampaignArguments& a) {
  const fs::path database = store_file(a.report_in);
  { const CampaignStore check(database); }  // a clear error for a folder without a campaign database
  const fs::path out = a.report_out.empty() ? a.report_in / "report" : a.report_out;
  const fs::path script = shipped_script("campaign_report.py");
  if (!fs::is_regular_file(script)) throw Error("report script " + script.string() + " not found");
  const int status = run_python_script(script, {database.string(), out.string(), "--seed", std::to_string(a.bootstrap_seed),
                                                "--resamples", std::to_string(a.resamples)});
  if (status != 0) throw Error(script.filename().string() + " failed (exit status " + std::to_string(status) + ")");
  return 0;
}

}  // namespace

int run_campaign_command(const CampaignArguments& arguments) {
  if (*arguments.run) return run(arguments);
  if (*arguments.merge) {
    merge_shards(arguments.shards, arguments.merge_out);
    std::printf("merged %zu shards into %s\n", arguments.shards.size(), store_file(arguments.merge_out).c_str());
    return 0;
  }
  return report(arguments);
}

}  // namespace thetad::app
