#include "campaigns/run_plan.hpp"

#include <charconv>

#include "core/error.hpp"
#include "core/sim/seed.hpp"

namespace thetad {

std::uint64_t draw_seed(std::uint64_t base_seed, std::int64_t draw) {
  return sim::splitmix64(sim::splitmix64(base_seed) ^ static_cast<std::uint64_t>(draw));
}

PlannedRun planned_run(const Campaign& campaign, std::int64_t index) {
  if (index < 0 || index >= campaign.run_count())
    throw Error("run index " + std::to_string(index) + " outside the campaign's " +
                std::to_string(campaign.run_count()) + " runs");
  const auto controllers = static_cast<std::int64_t>(campaign.controllers.size());
  const auto scenarios = static_cast<std::int64_t>(campaign.scenarios.size());
  PlannedRun run;
  run.index = index;
  run.controller = static_cast<int>(index % controllers);
  index /= controllers;
  run.draw = static_cast<int>(index % campaign.draws);
  index /= campaign.draws;
  run.scenario = static_cast<int>(index % scenarios);
  run.cell = static_cast<int>(index / scenarios);
  run.seed = draw_seed(campaign.base_seed, run.draw);
  return run;
}

Shard parse_shard(const std::string& text) {
  Shard shard;
  const auto slash = text.find('/');
  const auto number = [&](std::size_t begin, std::size_t end, int& value) {
    const auto [last, error] = std::from_chars(text.data() + begin, text.data() + end, value);
    return error == std::errc() && last == text.data() + end && begin < end;
  };
  if (slash == std::string::npos || !number(0, slash, shard.k) || !number(slash + 1, text.size(), shard.n) ||
      shard.n < 1 || shard.k < 1 || shard.k > shard.n)
    throw Error("--shard " + text + ": expected k/N with 1 <= k <= N (e.g. 3/8)");
  return shard;
}

}  // namespace thetad
