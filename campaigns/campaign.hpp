#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "campaigns/factors.hpp"
#include "experiment/controller_spec.hpp"

namespace thetad {

// A campaign file read and checked (docs/campaigns.md): scenarios x controllers x sweep cells x
// draws. Draw k uses the seed draw_seed(base_seed, k) in every cell, for every scenario and every
// controller, so controllers are compared on the same realizations (paired).
struct Campaign {
  std::string name;
  std::filesystem::path file;
  std::string text;    // the file's bytes, stored with the results
  std::string sha256;  // of `text`: the campaign's identity (resume and merge compare it)
  std::vector<std::string> scenarios;         // as written: files (relative to the campaign file) or shipped names
  std::vector<ControllerSpec> controllers;
  int draws = 0;
  std::uint64_t base_seed = 1;
  bool summary_only = true;                   // campaigns fly summary-only unless asked otherwise
  std::vector<std::string> swept;             // the sweep axes, in file order
  std::vector<FactorValues> cells;            // every cell: the fixed factors, then the swept ones

  std::int64_t run_count() const {
    return static_cast<std::int64_t>(cells.size() * scenarios.size() * controllers.size()) * draws;
  }
};

// Reads and checks a campaign file: unknown keys, bad values, unknown factors or controllers,
// repeated labels and unreadable scenarios are thetad::Error naming the file, line and field,
// before anything flies.
Campaign load_campaign(const std::filesystem::path& file);
// The same from `text` (as if read from `file`).
Campaign parse_campaign(const std::string& text, const std::filesystem::path& file);

}  // namespace thetad
