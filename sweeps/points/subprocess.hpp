#pragma once
// Starting the `slipwalk` binary (or mpirun with it) as a child process, for the point kinds that
// measure or test the tool as a whole: the scaling benchmark (scale_out.cpp) and the hostile-input
// campaign (hostile_inputs_*.cpp).
#include <sys/types.h>

#include <filesystem>
#include <string>
#include <vector>

namespace slipwalk::sweeps::points {

/// The path of the running executable (/proc/self/exe): the `slipwalk` binary when the point runs
/// inside it.
[[nodiscard]] std::filesystem::path self_executable();

/// self_executable() when it is the `slipwalk` binary; throws std::logic_error otherwise (a point
/// kind that runs the binary as a child, run inside another program such as a test).
[[nodiscard]] std::filesystem::path slipwalk_binary();

/// Starts `argv` (argv[0]: the program's path) in a process group of its own, stdin from
/// /dev/null, stdout and stderr to the given files. Throws std::runtime_error when it cannot.
[[nodiscard]] pid_t start_child(const std::vector<std::string>& argv,
                                const std::filesystem::path& out, const std::filesystem::path& err);

/// Waits for a child of start_child() at most `limit_s` seconds, then kills its process group.
/// Returns its exit code, 128 + the signal that ended it, or -1 when it ran past the limit.
[[nodiscard]] int wait_child(pid_t pid, double limit_s);

}  // namespace slipwalk::sweeps::points
