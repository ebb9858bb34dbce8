#pragma once
// Point functions: what a sweep computes at one point. A spec's `kind` names one of them.
//
// Each has fixed output columns (the first is always `id`), a check that validates a point's
// inputs (throws core::InputError naming the spec file:line:col and the key; the runner checks
// every point before it runs any, so a bad spec writes nothing) and a run that returns the
// point's rows. A run never throws for numerical trouble: the rows say what happened and
// `failed` marks the point, which is counted in the sidecar and does not stop the sweep.
#include <functional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "sweeps/spec.hpp"

namespace slipwalk::sweeps {

using Cell = std::variant<double, long long, std::string>;
using Row = std::vector<Cell>;

struct PointResult {
  std::vector<Row> rows;
  bool failed = false;
  std::string message;  ///< why it failed (empty otherwise)
};

struct PointFunction {
  std::string name;
  std::string summary;
  std::vector<std::string> columns;
  std::function<void(const Point&)> check;       ///< throws core::InputError
  std::function<PointResult(const Point&)> run;  ///< for a checked point
};

/// The multi-legged model's point functions (sweeps/legged_points.cpp), merged into the registry.
[[nodiscard]] std::vector<PointFunction> legged_point_functions();
/// The timed cost-and-accuracy point of the multi-legged model (sweeps/legged_cost_points.cpp).
[[nodiscard]] PointFunction legged_cost_point_function();
/// The speed comparisons of §3.5.3, Fig. 3.13: MuJoCo peer and parallel steps (peer_points.cpp).
[[nodiscard]] std::vector<PointFunction> peer_point_functions();
/// The sim-to-sim accuracy comparison of §3.5.4, Fig. 3.14: BigANT in MuJoCo
/// (peer_bigant_points.cpp).
[[nodiscard]] PointFunction peer_bigant_point_function();

/// The per-effect cost of composed scenes (issue 8; sweeps/scene_cost_points.cpp).
[[nodiscard]] PointFunction scene_cost_point_function();
/// BigANT up a slope: progress per cycle and the stall slope (§5.2.1; sweeps/slope_points.cpp).
[[nodiscard]] std::vector<PointFunction> slope_point_functions();

/// nullptr if no point function has this name.
[[nodiscard]] const PointFunction* find_point_function(std::string_view name);
/// "inchworm_vss|inchworm_convergence", for messages.
[[nodiscard]] std::string point_function_names();

}  // namespace slipwalk::sweeps
