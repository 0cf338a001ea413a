#include "campaigns/run_record.hpp"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace thetad {
namespace {

// An MPI rank sends its records to rank 0 as JSON, which has no NaN: a figure a run does not have
// (J_dev off the trims, timing off) travels as null and arrives as NaN, the others exactly.
TEST(RunRecord, FiguresARunDoesNotHaveTravelAsNullAndReturnAsNan) {
  RunRecord record;
  record.index = 7;
  record.seed = 18446744073709551615ULL;
  record.status = "completed";
  record.label = "td";
  record.controller = "theta-d";
  record.end_time_s = 1.5;
  record.controller_samples = 1500;
  record.factors = {{"course", 1.5707963267948966}};
  const double none = std::numeric_limits<double>::quiet_NaN();
  record.metrics = {0.1, 1.0 / 3.0, none, 2e-310, none};
  const nlohmann::json wire = nlohmann::json::parse(to_json(record).dump());
  EXPECT_TRUE(wire.at("metrics").at(2).is_null());
  const RunRecord received = record_from_json(wire);
  ASSERT_EQ(received.metrics.size(), record.metrics.size());
  EXPECT_EQ(received.metrics[0], 0.1);
  EXPECT_EQ(received.metrics[1], 1.0 / 3.0);
  EXPECT_TRUE(std::isnan(received.metrics[2]));
  EXPECT_EQ(received.metrics[3], 2e-310);
  EXPECT_TRUE(std::isnan(received.metrics[4]));
  EXPECT_EQ(received.seed, record.seed);
  EXPECT_EQ(received.factors, record.factors);
  // docs/glossary.md's names on the wire too.
  EXPECT_EQ(wire.at("label"), "td");
  EXPECT_EQ(wire.at("controller"), "theta-d");
  EXPECT_EQ(wire.at("end_time_s"), 1.5);
  EXPECT_EQ(wire.at("controller_samples"), 1500);
  EXPECT_EQ(received.label, record.label);
  EXPECT_EQ(received.controller, record.controller);
  EXPECT_EQ(received.end_time_s, record.end_time_s);
  EXPECT_EQ(received.controller_samples, record.controller_samples);
}

}  // namespace
}  // namespace thetad
