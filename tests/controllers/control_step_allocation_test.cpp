// A control step of the built-in controllers allocates nothing (design.md; issue 16): 1000 steps
// on the states the simulator handed θ–D along scenario I, each controller by its registered name
// as `thetad run` builds it. Two counts, both must be exactly 0: calls of the global operator new
// (replaced in this executable only, below) and heap allocations of any kind (malloc, interposed by
// tests/heap_counter.hpp: Eigen allocates through malloc, not operator new).
#include <gtest/gtest.h>

#include <atomic>
#include <cctype>
#include <cstdlib>
#include <new>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <yaml-cpp/yaml.h>

#include "controllers/feedforward_controller.hpp"
#include "controllers/registry.hpp"
#include "controllers/sdre.hpp"
#include "core/sim/recording_law.hpp"
#include "tests/controllers/scenario_one_flight.hpp"
#include "tests/heap_counter.hpp"

namespace {
std::atomic<long> operator_new_calls{0};

void* counted_new(std::size_t size) {
  if (thetad::testing::heap_counting.load(std::memory_order_relaxed))
    operator_new_calls.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}

void* counted_new(std::size_t size, std::align_val_t alignment) {
  if (thetad::testing::heap_counting.load(std::memory_order_relaxed))
    operator_new_calls.fetch_add(1, std::memory_order_relaxed);
  const auto a = static_cast<std::size_t>(alignment);
  if (void* p = std::aligned_alloc(a, (size + a - 1) / a * a)) return p;
  throw std::bad_alloc();
}
}  // namespace

void* operator new(std::size_t size) { return counted_new(size); }
void* operator new[](std::size_t size) { return counted_new(size); }
void* operator new(std::size_t size, std::align_val_t a) { return counted_new(size, a); }
void* operator new[](std::size_t size, std::align_val_t a) { return counted_new(size, a); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

namespace thetad {
namespace {

constexpr int kSteps = 1000;

struct Counts {
  long operator_new = 0;
  long heap = 0;
};

// reset, one step outside the count (the SDRE's first sample is a cold solve in either mode), then
// kSteps counted steps on the recorded samples in order.
Counts count_steps(Controller& controller) {
  const auto& f = testing::scenario_one_flight();
  controller.reset(f.scenario.initial_state, 0.0);
  Eigen::VectorXd u(f.model.input_dim());
  controller.control(f.samples[0].t, f.samples[0].state, f.samples[0].reference, u);
  operator_new_calls = 0;
  Counts counts;
  counts.heap = testing::heap_allocations_during([&] {
    for (int k = 1; k <= kSteps; ++k) {
      const sim::ControlSample& s = f.samples[static_cast<std::size_t>(k) % f.samples.size()];
      controller.control(s.t, s.state, s.reference, u);
    }
  });
  counts.operator_new = operator_new_calls.load();
  EXPECT_TRUE(u.allFinite());
  return counts;
}

struct Case {
  std::string label;
  std::string name;
  std::string settings;
};

class ControlStepAllocations : public ::testing::TestWithParam<Case> {};

TEST_P(ControlStepAllocations, AreExactlyZeroOver1000Steps) {
  const auto [label, name, settings] = GetParam();
  ASSERT_GE(testing::scenario_one_flight().samples.size(), static_cast<std::size_t>(kSteps));
  // The counters count: building a vector allocates once, through operator new.
  operator_new_calls = 0;
  const long probe = testing::heap_allocations_during([] { std::vector<double> v(4); });
  if (probe < 0) GTEST_SKIP() << "malloc cannot be interposed in this build (AddressSanitizer)";
  ASSERT_EQ(probe, 1);
  ASSERT_EQ(operator_new_calls.load(), 1);

  const auto controller = testing::scenario_one_flight().make(name, YAML::Load(settings));
  const Counts counts = count_steps(*controller);
  EXPECT_EQ(counts.operator_new, 0) << label;
  EXPECT_EQ(counts.heap, 0) << label;
  // The warm SDRE's count is of its Newton–Kleinman steps only if none fell back to the cold solve,
  // and the cold SDRE's of the matrix sign path only if no solve failed: so it was on these states.
  const auto* wrapper = dynamic_cast<const FeedForwardController*>(controller.get());
  if (const auto* sdre = dynamic_cast<const SdreController*>(wrapper ? &wrapper->inner() : controller.get())) {
    EXPECT_EQ(sdre->fallback_count(), 0);
    EXPECT_EQ(sdre->failure_count(), 0);
  }
}

INSTANTIATE_TEST_SUITE_P(BuiltIn, ControlStepAllocations,
                         ::testing::Values(Case{"theta_d", "theta-d", "{}"}, Case{"sdre_warm", "sdre", "{mode: warm}"},
                                           Case{"sdre_cold", "sdre", "{mode: cold}"}, Case{"sdre_capped", "sdre", "{mode: capped}"},
                                           Case{"lqr", "lqr", "{}"},
                                           Case{"lqr_scheduled", "lqr-scheduled", "{}"},
                                           Case{"theta_d_velocity_trim", "theta-d", "{feedforward: velocity+trim}"},
                                           Case{"sdre_warm_velocity", "sdre", "{feedforward: velocity}"},
                                           Case{"lqr_velocity_trim", "lqr", "{feedforward: velocity+trim}"},
                                           Case{"lqr_scheduled_exact", "lqr-scheduled", "{velocity_source: exact}"},
                                           Case{"theta_d_certificates", "theta-d", "{certificates: on}"},
                                           Case{"sdre_warm_certificates", "sdre", "{certificates: on}"}),
                         [](const auto& info) { return info.param.label; });

// Every registered controller with its defaults, whatever the list above names: a new controller
// is held to the rule without an edit here (gtest evaluates this after the registrations ran).
std::vector<Case> registered() {
  std::vector<Case> cases;
  for (const std::string& name : ControllerRegistry::instance().names()) {
    std::string label = name;
    for (char& c : label) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    cases.push_back({label, name, "{}"});
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Registered, ControlStepAllocations, ::testing::ValuesIn(registered()),
                         [](const auto& info) { return info.param.label; });

}  // namespace
}  // namespace thetad
