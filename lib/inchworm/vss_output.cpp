#include "inchworm/vss_output.hpp"

#include <cmath>

#include "core/csv.hpp"

namespace slipwalk::inchworm {

namespace {

const char* model_name(const Params& p) { return p.model == SwapModel::kMass ? "dm" : "instant"; }

/// The keys that carry the solve's result (null when there is none).
bool is_result_key(const std::string& key) {
  return key == "v_ss" || key == "period" || key == "c0" || key == "contraction" ||
         key == "est_error" || key == "last_difference" || key == "regime" || key == "swap_stopped";
}

}  // namespace

bool vss_has_no_numbers(Method method, const VssResult& result) {
  return !result.converged && (!is_simulation(method) || result.strokes == 0);
}

nlohmann::json vss_to_json(const Params& p, Method method, const VssOptions& options,
                           const VssResult& r) {
  const bool nothing = vss_has_no_numbers(method, r);
  nlohmann::json out = {
      {"v_ss", r.v_ss},
      {"period", r.period},
      {"c0", r.c0},
      {"regime", regime_name(r.regime)},
      {"method", method_name(method)},
      {"F", p.F},
      {"mu", p.mu},
      {"mu_s", p.static_mu()},
      {"model", model_name(p)},
      {"alpha", p.model == SwapModel::kMass ? nlohmann::json(p.alpha) : nlohmann::json(nullptr)},
      {"swap_stopped", r.swap_stopped},
      {"rtol", options.rtol},
      {"est_error", r.est_error},
      {"last_difference", r.last_difference},
      {"contraction", r.contraction},
      {"converged", r.converged},
      {"strokes", r.strokes},
      {"steps", r.stats.steps},
      {"rhs_evals", r.stats.rhs_evals},
      {"wall_s", r.wall_s},
      {"message", r.message},
  };
  for (auto& [key, value] : out.items()) {
    if ((nothing && is_result_key(key)) ||
        (value.is_number_float() && !std::isfinite(value.get<double>()))) {
      value = nullptr;
    }
  }
  return out;
}

std::string vss_to_text(const Params& p, Method method, const VssResult& r) {
  const bool nothing = vss_has_no_numbers(method, r);
  const bool dm = p.model == SwapModel::kMass;
  std::string text;
  const auto line = [&](const std::string& key, const std::string& value, const char* unit = "") {
    text.append(key);
    text.append(key.size() < 12 ? 12 - key.size() : 0, ' ');  // printf's %-12s
    text.append(" ").append(value).append(unit).append("\n");
  };
  const auto num = [&](double v) { return nothing ? std::string("n/a") : core::format_double(v); };
  line("method", method_name(method));
  line("model", model_name(p));
  if (dm) {
    line("alpha", core::format_double(p.alpha));
  }
  line("v_ss", num(r.v_ss), " m/s");
  line("period", num(r.period), " s");
  line("c0", num(r.c0), " m/s");
  line("regime", nothing ? "n/a" : regime_name(r.regime));
  if (dm) {
    line("swap_stopped", nothing ? "n/a" : (r.swap_stopped ? "yes" : "no"));
  }
  line("contraction", num(r.contraction), " per cycle");
  if (is_simulation(method)) {
    line("est_error", num(r.est_error), " (relative)");
    line("strokes", std::to_string(r.strokes));
    line("converged", r.converged ? "yes" : "no");
  }
  line("wall_s", core::format_double(r.wall_s), " s");
  if (!r.converged) {
    line("message", r.message);
  }
  return text;
}

}  // namespace slipwalk::inchworm
