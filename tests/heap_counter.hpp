#pragma once

// Counts heap allocations, for the tests that check a hot path allocates nothing. Eigen and
// operator new both end in malloc, so malloc is interposed (glibc's __libc_malloc does the work).
// It defines malloc: include it from exactly one source file of a test executable.

#include <atomic>
#include <cstddef>

namespace thetad::testing {
inline std::atomic<bool> heap_counting{false};
inline std::atomic<long> heap_allocations{0};
}  // namespace thetad::testing

#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__)
#define THETAD_HEAP_COUNTER 1
extern "C" void* __libc_malloc(std::size_t size);
extern "C" void* malloc(std::size_t size) noexcept {
  if (thetad::testing::heap_counting.load(std::memory_order_relaxed)) {
    thetad::testing::heap_allocations.fetch_add(1, std::memory_order_relaxed);
  }
  return __libc_malloc(size);
}
#endif

namespace thetad::testing {

// The number of heap allocations `action` makes; -1 where they cannot be counted (AddressSanitizer
// owns malloc, or not glibc).
template <class Action>
long heap_allocations_during(Action&& action) {
#ifdef THETAD_HEAP_COUNTER
  heap_allocations = 0;
  heap_counting = true;
  action();
  heap_counting = false;
  return heap_allocations.load();
#else
  action();
  return -1;
#endif
}

}  // namespace thetad::testing
