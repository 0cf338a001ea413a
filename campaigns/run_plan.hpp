#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "campaigns/campaign.hpp"

namespace thetad {

// The seed of draw k: a function of the base seed and k only (SplitMix64 of both), so the same
// draw is the same realization in every cell, for every scenario and controller, whatever the
// number of workers, ranks or shards.
std::uint64_t draw_seed(std::uint64_t base_seed, std::int64_t draw);

// One run of a campaign, by its run index: index = ((cell * S + scenario) * D + draw) * C + controller
// (S scenarios, D draws, C controllers), so the controllers of one draw are neighbours.
struct PlannedRun {
  std::int64_t index = 0;
  int cell = 0;
  int scenario = 0;
  int draw = 0;
  int controller = 0;
  std::uint64_t seed = 0;
};

PlannedRun planned_run(const Campaign& campaign, std::int64_t index);

// Part k (1-based) of n of a campaign's runs: run indices i with i mod n == k - 1, so every part
// mixes cells and controllers (and costs about the same). `text` is "k/n".
struct Shard {
  int k = 1;
  int n = 1;

  bool holds(std::int64_t index) const { return index % n == k - 1; }
  std::string text() const { return std::to_string(k) + "/" + std::to_string(n); }
};
// "k/n" with 1 <= k <= n; thetad::Error otherwise.
Shard parse_shard(const std::string& text);

}  // namespace thetad
