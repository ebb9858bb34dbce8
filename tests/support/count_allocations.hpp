#pragma once
// Counts heap allocations made through operator new, to check that per-step and per-frame paths
// allocate nothing. The replaced operator new/delete are in count_allocations.cpp, linked into
// every test executable (tests/CMakeLists.txt), so any test file may include this header.

namespace slipwalk::testing {
/// Allocations through operator new since the program started.
long long allocation_count();
}  // namespace slipwalk::testing
