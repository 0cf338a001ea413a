#pragma once

// What the campaign tests share: a small campaign file, and comparing campaign databases run for
// run as the acceptance tests do (every input and every figure bit for bit, except the wall-clock
// columns).
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "campaigns/campaign_store.hpp"
#include "campaigns/run_record.hpp"

namespace thetad::testing {

// A campaign of short (0.2 s) scenario-I flights by the LQR and θ–D (label td) over `sweep` (a
// `sweep:` value, e.g. "{grid: {gust_scale: [0, 2]}}").
inline std::string small_campaign(const std::string& name, int draws, int base_seed, const std::string& sweep) {
  return "campaign: " + name + "\nscenarios: [scenario-1]\ncontrollers: [{controller: lqr}, {label: td, controller: theta-d}]\n" +
         "draws: {count: " + std::to_string(draws) + ", base_seed: " + std::to_string(base_seed) + "}\n" +
         "fixed: {duration_s: 0.2}\nsweep: " + sweep + "\n";
}

inline std::vector<RunRecord> stored_records(const std::filesystem::path& out) {
  return CampaignStore(store_file(out)).records();
}

inline void expect_same_runs(const std::vector<RunRecord>& expected, const std::vector<RunRecord>& actual) {
  ASSERT_EQ(expected.size(), actual.size());
  const auto& columns = metric_columns();
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const RunRecord &a = expected[i], &b = actual[i];
    SCOPED_TRACE("run " + std::to_string(a.index));
    EXPECT_EQ(a.index, b.index);
    EXPECT_EQ(a.cell, b.cell);
    EXPECT_EQ(a.draw, b.draw);
    EXPECT_EQ(a.scenario, b.scenario);
    EXPECT_EQ(a.label, b.label);
    EXPECT_EQ(a.controller, b.controller);
    EXPECT_EQ(a.seed, b.seed);
    EXPECT_EQ(a.factors, b.factors);
    EXPECT_EQ(a.status, b.status);
    EXPECT_EQ(a.reason, b.reason);
    EXPECT_EQ(a.end_time_s, b.end_time_s);
    EXPECT_EQ(a.controller_samples, b.controller_samples);
    ASSERT_EQ(a.metrics.size(), columns.size());
    ASSERT_EQ(b.metrics.size(), columns.size());
    for (std::size_t m = 0; m < columns.size(); ++m) {
      // NULL (NaN: a figure the run does not have) equals NULL.
      if (!columns[m].timing && !(std::isnan(a.metrics[m]) && std::isnan(b.metrics[m]))) {
        EXPECT_EQ(a.metrics[m], b.metrics[m]) << columns[m].name;
      }
    }
  }
}

}  // namespace thetad::testing
