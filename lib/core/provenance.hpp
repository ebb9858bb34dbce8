#pragma once
// Provenance sidecars: every result file data/<study>/<name>.csv gets <name>.json with the spec,
// the git commit, compiler and library versions, thread count and wall time (DESIGN.md: Data).
#include <nlohmann/json.hpp>

namespace slipwalk::core {

/// Build-time facts: version, git commit, compiler, Eigen/SUNDIALS/GSL/Boost versions; and the
/// machine it runs on (machine_description()), so that timings can be read against it.
nlohmann::json build_provenance();

/// The machine: {"cpu": model name from /proc/cpuinfo ("unknown" elsewhere), "logical_cores":
/// std::thread::hardware_concurrency(), "os": uname's system and release,
/// "load_average_1min": from /proc/loadavg when it exists}.
nlohmann::json machine_description();

}  // namespace slipwalk::core
