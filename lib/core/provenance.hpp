#pragma once
// Provenance sidecars: every result file data/<study>/<name>.csv gets <name>.json with the spec,
// the git commit, compiler and library versions, thread count and wall time (DESIGN.md: Data).
#include <nlohmann/json.hpp>

namespace slipwalk::core {

/// Build-time facts: version, git commit, compiler, Eigen/SUNDIALS/GSL/Boost versions.
nlohmann::json build_provenance();

}  // namespace slipwalk::core
