// What `thetad bench` records of the host and how it decides its verdict: a loaded host is named,
// a quiet one is not, and the verdict needs a margin, not one lucky maximum.
#include "experiment/host_conditions.hpp"

#include <atomic>
#include <chrono>
#include <thread>

#include <pthread.h>
#include <sched.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "experiment/step_timing.hpp"

namespace thetad {
namespace {

using ::testing::HasSubstr;

HostSnapshot snapshot(double load, std::vector<HostSnapshot::Cpu> cpus, double wait_ns, double wall_ns) {
  return {std::move(cpus), load, wait_ns, wall_ns};
}

TEST(HostConditions, AQuietHostHasNoWarning) {
  const HostSnapshot before = snapshot(0.1, {{0, 0, 0}, {0, 0, 0}}, 0, 0);
  const HostSnapshot after = snapshot(0.2, {{100, 100, 0}, {3, 100, 0}}, 1e5, 1e9);
  const HostConditions c = host_conditions(before, after, 0);
  EXPECT_FALSE(c.loaded()) << c.warnings.front();
  EXPECT_DOUBLE_EQ(c.other_cores_busy, 0.03);
  EXPECT_DOUBLE_EQ(c.own_wait, 1e-4);
}

TEST(HostConditions, EachSignOfLoadIsNamed) {
  const HostSnapshot before = snapshot(1.5, {{0, 0, 0}, {0, 0, 0}}, 0, 0);
  const HostSnapshot after = snapshot(1.6, {{100, 100, 10}, {90, 100, 0}}, 5e7, 1e9);
  const HostConditions c = host_conditions(before, after, 0);
  ASSERT_EQ(c.warnings.size(), 3u);
  EXPECT_THAT(c.warnings[0], HasSubstr("another core was 90.0 % busy"));
  EXPECT_THAT(c.warnings[1], HasSubstr("waited for its core 5.0 %"));
  EXPECT_THAT(c.warnings[2], HasSubstr("hypervisor took 5.0 %"));
  EXPECT_DOUBLE_EQ(c.load_before, 1.5);
}

// The real counters: a thread spinning on the other core shows as that core's load.
TEST(HostConditions, AHogOnTheOtherCoreIsSeen) {
  if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "one core";
  std::atomic<bool> stop{false};
  std::thread hog([&] {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(0, &set);
    pthread_setaffinity_np(pthread_self(), sizeof set, &set);
    while (!stop.load(std::memory_order_relaxed)) {
    }
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  const HostSnapshot before = host_snapshot();
  std::this_thread::sleep_for(std::chrono::milliseconds(400));
  const HostSnapshot after = host_snapshot();
  stop = true;
  hog.join();
  const HostConditions c = host_conditions(before, after, 1);
  EXPECT_GT(c.other_cores_busy, 0.9);
  EXPECT_TRUE(c.loaded());
  EXPECT_FALSE(c.cpu_model.empty());
}

TEST(RealTimeVerdict, NeedsAMarginAndToleratesAnIsolatedOverrun) {
  const double budget = 1000.0;
  EXPECT_EQ(real_time_verdict(20.0, 0.0, budget), RealTimeVerdict::capable);
  // One preempted call in two thousand does not decide it; one in a hundred does.
  EXPECT_EQ(real_time_verdict(20.0, 0.0005, budget), RealTimeVerdict::capable);
  EXPECT_EQ(real_time_verdict(20.0, 0.01, budget), RealTimeVerdict::marginal);
  // Near the period: neither verdict, whichever side of it a run lands.
  EXPECT_EQ(real_time_verdict(600.0, 0.0, budget), RealTimeVerdict::marginal);
  EXPECT_EQ(real_time_verdict(999.0, 0.009, budget), RealTimeVerdict::marginal);
  EXPECT_EQ(real_time_verdict(1001.0, 0.011, budget), RealTimeVerdict::not_capable);
  EXPECT_STREQ(verdict_name(RealTimeVerdict::not_capable), "not capable");
}

}  // namespace
}  // namespace thetad
