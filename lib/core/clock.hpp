#pragma once
// The clocks every timing in the project reads: the library's solves (inchworm v_ss, scene runs)
// and the sweep engine's timed point kinds (sweeps/engine/timing.hpp) take time the same way.
#include <chrono>

namespace slipwalk::core {

/// The calling thread's CPU time, s: unlike wall time it does not count the time the thread waits
/// for a core, which on a shared machine is most of the noise.
[[nodiscard]] double thread_cpu_seconds();
/// CPU time of the whole process (all threads), s: the work parallel sections did.
[[nodiscard]] double process_cpu_seconds();
/// Wall seconds on the steady clock since `start`.
[[nodiscard]] double seconds_since(std::chrono::steady_clock::time_point start);

}  // namespace slipwalk::core
