#pragma once
// Counts heap allocations made through operator new, to check that per-step and per-frame paths
// allocate nothing. Replaces the global operator new/delete, so include it in exactly one
// translation unit of a test executable (each tests/**/test_*.cpp is its own executable).
#include <atomic>
#include <cstdlib>
#include <new>

namespace slipwalk::testing::detail {
inline std::atomic<long long> g_allocations{0};
}  // namespace slipwalk::testing::detail

void* operator new(std::size_t size) {
  slipwalk::testing::detail::g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) {
    return p;
  }
  throw std::bad_alloc();
}
// GCC 12 flags free() of what it takes for the built-in operator new once it inlines these.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#pragma GCC diagnostic pop

namespace slipwalk::testing {
/// Allocations through operator new since the program started.
inline long long allocation_count() {
  return detail::g_allocations.load(std::memory_order_relaxed);
}
}  // namespace slipwalk::testing
