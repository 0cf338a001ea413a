#pragma once

// Counts heap allocations, for the tests that check a hot path allocates nothing. Eigen and
// operator new both end in malloc, so malloc is interposed (heap_counter.cpp, which every test
// executable links; glibc's __libc_malloc does the work).

#include <atomic>

#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__)
#define THETAD_HEAP_COUNTER 1
#endif

namespace thetad::testing {

inline std::atomic<bool> heap_counting{false};
inline std::atomic<long> heap_allocations{0};

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
