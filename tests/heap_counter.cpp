#include "tests/heap_counter.hpp"

#include <cstddef>

#ifdef THETAD_HEAP_COUNTER
extern "C" void* __libc_malloc(std::size_t size);
extern "C" void* malloc(std::size_t size) noexcept {
  if (thetad::testing::heap_counting.load(std::memory_order_relaxed)) {
    thetad::testing::heap_allocations.fetch_add(1, std::memory_order_relaxed);
  }
  return __libc_malloc(size);
}
#endif
