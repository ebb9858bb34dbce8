// The replaced global operator new/delete behind count_allocations.hpp: one definition per
// program, so this file is its own object, linked into each test executable.
#include "support/count_allocations.hpp"

#include <atomic>
#include <cstdlib>
#include <new>

namespace {
std::atomic<long long> g_allocations{0};
}  // namespace

// Under the sanitizers the allocator stays theirs (they check new/delete pairs); the tests that
// count skip there (SLIPWALK_SANITIZED).
#ifndef SLIPWALK_SANITIZED
void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
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
#endif

namespace slipwalk::testing {
long long allocation_count() { return g_allocations.load(std::memory_order_relaxed); }
}  // namespace slipwalk::testing
