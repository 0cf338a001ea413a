#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace thetad::app {

struct CampaignArguments {
  // campaign run
  std::filesystem::path file;
  std::filesystem::path out;
  int jobs = 0;
  bool resume = false;
  std::string shard = "1/1";
  bool no_timing = false;
  std::optional<int> keep_logs;
  bool dry_run = false;
  double pilot_seconds = 1.0;
  bool quiet = false;
  // campaign merge
  std::vector<std::filesystem::path> shards;
  std::filesystem::path merge_out;
  // campaign report
  std::filesystem::path report_in;
  std::filesystem::path report_out;  // default: <in>/report
  std::uint64_t bootstrap_seed = 1;
  int resamples = 2000;

  CLI::App* run = nullptr;
  CLI::App* merge = nullptr;
  CLI::App* report = nullptr;
};
CLI::App* add_campaign_command(CLI::App& app, CampaignArguments& arguments);

// thetad campaign run|merge|report (docs/campaigns.md).
int run_campaign_command(const CampaignArguments& arguments);

}  // namespace thetad::app
