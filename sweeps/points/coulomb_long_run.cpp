// coulomb_long_run: the long run of the Coulomb solver (friction::solve_coulomb, thesis §3.4) on
// random stress frames (coulomb_stress.hpp). One point is one chunk of `frames` frames, indices
// chunk·frames … chunk·frames + frames − 1 of stream `seed`, so a long run shows progress point by
// point and resumes; any frame is replayed alone as chunk = index, frames = 1.
//
// Per frame: the generated robot must pass contact::validate (a rejection is a generator bug,
// counted in invalid_robots), the solver runs with the default options at the point's `tol`,
// and its answer is checked by the oracle of coulomb_stress.hpp, which shares no code with the
// solver: the reported forces must be balanced, inside their friction ellipses, and prove the
// reported velocity optimal to the tolerance (weak duality). Counted:
//   certified       friction.converged (the solver's relative duality gap ≤ tol)
//   not_converged   the others: the solver's own flag that it could not certify
//   non_unique      friction.unique = false (a continuum of body velocities balances)
//   non_finite      any of v_body, Fxy, certificate, residual not finite
//   oracle_fail     certified by the solver but not by the oracle (gap above tol + 1e-12 + the
//                   oracle's own rounding, imbalance or ellipse excess above 1e-9, a force on a
//                   foot without friction)
//   wide_weights    frames whose weights c_k = μ_k F_z,k span more than 6 decades (and
//                   not_converged_wide: those of them not certified)
//   route_*         which of the solver's routes gave the answer (FrictionSummary::Route):
//                   direct (no Newton step), fast (the fast path), path (the smoothing path, the
//                   fast path not tried: a foot exactly at rest at the viscous start) and
//                   fallback (the smoothing path after the fast path stalled, a restart)
// A point is marked failed when any frame is not certified, not finite, rejected by the oracle
// or by validate; its message names the first such frames by index.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "contact/robot.hpp"
#include "contact/spring_support.hpp"
#include "core/csv.hpp"
#include "core/error.hpp"
#include "friction/solvers.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/point_reader.hpp"
#include "sweeps/engine/timing.hpp"
#include "sweeps/points/coulomb_stress.hpp"
#include "sweeps/points/families.hpp"

namespace slipwalk::sweeps::points {

namespace {

const std::vector<std::string_view> kKeys = {"seed", "chunk", "frames", "tol"};
constexpr double kOracleSlack = 1e-12;  // rounding of the oracle's own sums, relative to D
constexpr double kOracleBalance = 1e-9;
constexpr int kNamedFrames = 5;
// Friction weights c_k = μ_k F_z,k spanning more than this many decades make the solver's dual
// metric Σ B_kᵀB_k (∝ c_k²) singular to rounding along what only the lightest feet feel; the
// frames are counted apart.
constexpr double kWideDecades = 6.0;  // frames named in a failed point's message

struct Inputs {
  long long seed = 1;
  long long chunk = 0;
  long long frames = 10000;
  double tol = friction::CoulombOptions{}.tol;
};

Inputs read_inputs(const Point& point) {
  const Reader r(point, "coulomb_long_run", kKeys);
  Inputs in;
  in.seed = r.integer("seed", 1, 0, 1LL << 53);
  in.frames = r.integer("frames", 10000, 1, 1'000'000);
  // chunk · frames + frames must stay an exact integer in a double (the index column).
  in.chunk = r.integer("chunk", 0, 0, (1LL << 52) / in.frames - 1);
  in.tol = r.number("tol", friction::CoulombOptions{}.tol, 0.0, 1.0);
  return in;
}

struct LongRunRow {
  long long id = 0;
  long long seed = 0;
  long long chunk = 0;
  long long first_frame = 0;
  long long frames = 0;
  double tol = 0.0;
  double legs_mean = 0.0;
  long long certified = 0;
  long long not_converged = 0;
  long long non_unique = 0;
  long long non_finite = 0;
  long long oracle_fail = 0;
  long long invalid_robots = 0;
  long long wide_weights = 0;        ///< frames whose c_k span more than kWideDecades decades
  long long not_converged_wide = 0;  ///< of the not converged, those frames
  long long route_direct = 0;
  long long route_fast = 0;
  long long route_path = 0;
  long long route_fallback = 0;
  std::array<long long, stress::kLayouts> layout{};     ///< frames per layout
  std::array<long long, stress::kLayouts> smoothing{};  ///< path or fallback, per layout
  long long support_unbalanced = 0;  ///< spring-support frames whose status is not balanced
  long long iterations_max = 0;
  double max_certificate = 0.0;
  long long worst_frame = -1;  ///< the frame with the largest oracle gap
  double max_oracle_gap = 0.0;
  double max_oracle_imbalance = 0.0;
  double max_residual = 0.0;  ///< the solver's own friction.residual
  std::string failed_frames;
  double cpu_s = 0.0;
  double solve_ns_mean = 0.0;

  static std::vector<Column<LongRunRow>> columns() {
    using R = LongRunRow;
    std::vector<Column<R>> c = {value("id", &R::id),
                                value("seed", &R::seed),
                                value("chunk", &R::chunk),
                                value("first_frame", &R::first_frame),
                                value("frames", &R::frames),
                                value("tol", &R::tol),
                                value("legs_mean", &R::legs_mean),
                                value("certified", &R::certified),
                                value("not_converged", &R::not_converged),
                                value("non_unique", &R::non_unique),
                                value("non_finite", &R::non_finite),
                                value("oracle_fail", &R::oracle_fail),
                                value("invalid_robots", &R::invalid_robots),
                                value("wide_weights", &R::wide_weights),
                                value("not_converged_wide", &R::not_converged_wide),
                                value("route_direct", &R::route_direct),
                                value("route_fast", &R::route_fast),
                                value("route_path", &R::route_path),
                                value("route_fallback", &R::route_fallback)};
    for (int i = 0; i < stress::kLayouts; ++i) {
      const std::string name(stress::layout_name(static_cast<stress::Layout>(i)));
      c.push_back(value_at("frames_" + name, &R::layout, static_cast<std::size_t>(i)));
    }
    for (int i = 0; i < stress::kLayouts; ++i) {
      const std::string name(stress::layout_name(static_cast<stress::Layout>(i)));
      c.push_back(value_at("smoothing_" + name, &R::smoothing, static_cast<std::size_t>(i)));
    }
    for (Column<R>& col : std::vector<Column<R>>{
             value("support_unbalanced", &R::support_unbalanced),
             value("iterations_max", &R::iterations_max),
             value("max_certificate", &R::max_certificate), value("worst_frame", &R::worst_frame),
             value("max_oracle_gap", &R::max_oracle_gap),
             value("max_oracle_imbalance", &R::max_oracle_imbalance),
             value("max_residual", &R::max_residual), value("failed_frames", &R::failed_frames),
             timing("cpu_s", &R::cpu_s, "s"), timing("solve_ns_mean", &R::solve_ns_mean, "ns")}) {
      c.push_back(std::move(col));
    }
    return c;
  }
};

void name_frame(LongRunRow& row, long long& named, long long index, const char* what) {
  if (named++ < kNamedFrames) {
    row.failed_frames += row.failed_frames.empty() ? "" : " ";
    row.failed_frames += std::to_string(index) + ":" + what;
  }
}

Rows<LongRunRow> run_long(const Point& point) {
  const Inputs in = read_inputs(point);
  using Route = contact::FrictionSummary::Route;
  LongRunRow row;
  row.id = point.id;
  row.seed = in.seed;
  row.chunk = in.chunk;
  row.first_frame = in.chunk * in.frames;
  row.frames = in.frames;
  row.tol = in.tol;
  const friction::CoulombOptions options{in.tol};
  const double cpu0 = thread_cpu_seconds();
  double solve_s = 0.0;
  long long legs = 0;
  long long named = 0;
  for (long long j = 0; j < in.frames; ++j) {
    const long long index = row.first_frame + j;
    std::optional<stress::StressFrame> sf;
    try {
      sf.emplace(stress::make_stress_frame(static_cast<std::uint64_t>(in.seed),
                                           static_cast<std::uint64_t>(index)));
    } catch (const core::InputError&) {
      ++row.invalid_robots;
      name_frame(row, named, index, "invalid");
      continue;
    }
    contact::Frame& f = sf->frame;
    legs += f.legs();
    ++row.layout[static_cast<std::size_t>(sf->layout)];
    if (sf->loads == stress::Loads::kSupport &&
        f.support.status != contact::SupportSummary::Status::kBalanced) {
      ++row.support_unbalanced;
    }
    const double t0 = thread_cpu_seconds();
    friction::solve_coulomb(sf->robot, f, options);
    solve_s += thread_cpu_seconds() - t0;

    const auto& s = f.friction;
    const stress::OracleCheck o = stress::check_coulomb(sf->robot, f);
    switch (s.route) {
      case Route::kDirect:
        ++row.route_direct;
        break;
      case Route::kFastPath:
        ++row.route_fast;
        break;
      case Route::kPath:
        ++row.route_path;
        break;
      case Route::kFallback:
        ++row.route_fallback;
        break;
    }
    if (s.route == Route::kPath || s.route == Route::kFallback) {
      ++row.smoothing[static_cast<std::size_t>(sf->layout)];
    }
    row.iterations_max = std::max<long long>(row.iterations_max, s.iterations);
    row.non_unique += s.unique ? 0 : 1;
    if (!o.finite) {
      ++row.non_finite;
      name_frame(row, named, index, "non-finite");
      continue;
    }
    const bool wide = o.weight_decades > kWideDecades;
    row.wide_weights += wide ? 1 : 0;
    if (s.converged) {
      ++row.certified;
    } else {
      ++row.not_converged;
      row.not_converged_wide += wide ? 1 : 0;
      name_frame(row, named, index, "not-converged");
    }
    row.max_certificate = std::max(row.max_certificate, s.certificate);
    row.max_residual = std::max(row.max_residual, s.residual);
    row.max_oracle_imbalance = std::max(row.max_oracle_imbalance, o.imbalance);
    if (row.worst_frame < 0 || o.gap > row.max_oracle_gap) {
      row.max_oracle_gap = o.gap;
      row.worst_frame = index;
    }
    const bool oracle_ok = o.gap <= in.tol + kOracleSlack + o.rounding &&
                           o.imbalance <= kOracleBalance && o.outside <= kOracleBalance &&
                           o.idle_force == 0.0;
    if (s.converged && !oracle_ok) {
      ++row.oracle_fail;
      name_frame(row, named, index, "oracle");
    }
  }
  row.legs_mean = static_cast<double>(legs) / static_cast<double>(in.frames);
  row.cpu_s = thread_cpu_seconds() - cpu0;
  row.solve_ns_mean = 1e9 * solve_s / static_cast<double>(in.frames);
  Rows<LongRunRow> out;
  if (named > 0) {
    out.failed = true;
    out.message = std::to_string(named) + " of " + std::to_string(in.frames) +
                  " frames not certified, not finite, rejected by the oracle or invalid (seed " +
                  std::to_string(in.seed) + "; first: " + row.failed_frames + ")";
  }
  out.rows.push_back(std::move(row));
  return out;
}

}  // namespace

std::vector<PointKind> coulomb_long_run_kinds() {
  return {make_point_kind<LongRunRow>(
      "coulomb_long_run",
      "§3.4: the Coulomb solver on a chunk of random stress frames (3–50 legs, degenerate "
      "layouts, zero slip, extreme μ and K), each checked by an independent duality oracle: "
      "certified, non-unique, non-finite and route counts (one row per chunk)",
      Timed::kNo, [](const Point& p) { (void)read_inputs(p); }, run_long)};
}

}  // namespace slipwalk::sweeps::points
