#pragma once
// What `slipwalk inchworm vss` prints for one steady-state solve: a JSON object (--json) or
// aligned `key value unit` lines. A solve that never produced a number shows none (JSON null,
// "n/a") rather than zeros; JSON has no NaN, so non-finite numbers are null too.
#include <nlohmann/json.hpp>
#include <string>

#include "inchworm/params.hpp"
#include "inchworm/vss.hpp"

namespace slipwalk::inchworm {

/// True when `result` holds no steady state at all: a closed form that failed, or a simulation
/// that failed before its first stroke.
[[nodiscard]] bool vss_has_no_numbers(Method method, const VssResult& result);

/// {"v_ss", "period", "c0", "regime", "method", "F", "mu", "mu_s", "model", "alpha" (null for the
/// instant model), "swap_stopped", "rtol", "est_error", "last_difference", "contraction",
/// "converged", "strokes", "steps", "rhs_evals", "wall_s", "message"}.
[[nodiscard]] nlohmann::json vss_to_json(const Params& params, Method method,
                                         const VssOptions& options, const VssResult& result);

/// The text form: one `%-12s value unit` line per quantity (alpha and swap_stopped only for the
/// dm model; est_error, strokes and converged only for simulations; message only on failure).
[[nodiscard]] std::string vss_to_text(const Params& params, Method method, const VssResult& result);

}  // namespace slipwalk::inchworm
