
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "core/csv.hpp"
#include "core/error.hpp"
#include "events/exact_backend.hpp"
#include "inchworm/closed_form.hpp"
#include "inchworm/instant_swap.hpp"
#include "inchworm/params.hpp"
#include "inchworm/simulate.hpp"
#include "inchworm/vss.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/point_reader.hpp"
#include "sweeps/engine/timing.hpp"
#include "sweeps/points/families.hpp"

namespace slipwalk::sweeps::points {

namespace {

using core::InputError;
using inchworm::Method;
using inchworm::Params;

// --- the inchworm's inputs ----------------------------------------------------------------------

const std::vector<std::string_view> kParamKeys = {"m", "M", "L_min", "L_max", "g", "mu", "mu_s"};
const std::vector<std::string_view> kForceKeys = {"F",    "F_frac",      "f_tilde",
                                                  "F_lo", "F_lo_factor", "F_max"};

std::vector<std::string_view> keys(std::initializer_list<std::vector<std::string_view>> groups) {
  std::vector<std::string_view> out;
  for (const auto& g : groups) {
    out.insert(out.end(), g.begin(), g.end());
  }
  return out;
}

struct InchwormInputs {
  Params p;
  Method method = Method::kExact;
  inchworm::VssOptions opt;
  double F_lo = 0.0;   ///< N, the bottom of the F_frac range
  double F_max = 0.0;  ///< N, the top of the F_frac range
  std::string_view force_key;
};

/// The F_frac range [F_lo, F_max] of a point (defaults where the keys are absent).
void force_range(const Reader& r, InchwormInputs& in) {
  const Params& p = in.p;
  double base = p.static_mu() * p.m * p.g;
  if (const Value* lo = r.point().find("F_lo")) {
    if (lo->is_number()) {
      base = lo->number();
    } else if (lo->text() == "muMg") {
      base = p.static_mu() * p.M * p.g;
    } else if (lo->text() != "mumg") {
      r.fail("F_lo", "expected \"mumg\" (mu_s m g), \"muMg\" (mu_s M g) or a force in N, got " +
                         lo->repr());
    }
  }
  const double factor = r.number("F_lo_factor", 1.0);
  if (!(factor > 0.0)) {
    r.fail("F_lo_factor", "must be positive, got " + core::format_double(factor));
  }
  in.F_lo = base * factor;
  in.F_max = r.number("F_max", 5.0 * p.M * p.g);
}

/// inchworm::validate(p), its errors named by the spec's keys instead of command-line options
/// (--force maps to whichever force key the point used: F, F_frac or f_tilde).
void validate_at_keys(const Reader& r, const Params& p, std::string_view force_key) {
  try {
    inchworm::validate(p);
  } catch (const InputError& e) {
    const std::string_view mapped = inchworm::param_key_of_option(e.where());
    std::string_view key = mapped.empty() || mapped == "F" ? force_key : mapped;
    // A ratio constraint broken by the other value of its pair names the one the spec gives,
    // which has a place in the file (M > m with only m given names m).
    static constexpr std::pair<std::string_view, std::string_view> kPartner[] = {
        {"M", "m"}, {"m", "M"}, {"L_max", "L_min"}, {"L_min", "L_max"}, {"mu_s", "mu"}};
    for (const auto& [a, b] : kPartner) {
      if (key == a && !r.has(a) && r.has(b)) {
        key = b;
        break;
      }
    }
    const std::string what = e.what();
    r.fail(key, what.substr(std::min(what.size(), e.where().size() + 2)));
  }
}

/// The model's parameters of a point, each in its own range (inchworm::ranges, the command
/// line's table) at its own place; the ratio constraints are checked once the force is known.
void read_params(const Reader& r, Params& p) {
  namespace ranges = inchworm::ranges;
  p.m = r.number("m", p.m, ranges::kMass);
  p.M = r.number("M", p.M, ranges::kMass);
  p.L_min = r.number("L_min", p.L_min, ranges::kLength);
  p.L_max = r.number("L_max", p.L_max, ranges::kLength);
  p.g = r.number("g", p.g, ranges::kGravity);
  p.mu = r.number("mu", p.mu, ranges::kFriction);
  if (r.has("mu_s")) {  // absent: NaN, meaning mu_s = mu
    p.mu_s = r.number("mu_s", p.mu_s, ranges::kFriction);
  }
}

/// The ratio constraints (M > m, L_max > L_min, mu_s >= mu): validate() with the largest
/// admissible force checks everything but the force, naming `force_key` for nothing else.
void validate_but_force(const Reader& r, const Params& p, std::string_view force_key) {
  Params largest_force = p;
  largest_force.F = inchworm::ranges::kForce.hi;
  validate_at_keys(r, largest_force, force_key);
}

void read_solver(const Reader& r, InchwormInputs& in, bool solver_keys);

/// Params, the force and the method of an inchworm point; throws InputError naming the key.
InchwormInputs read_inchworm(const Reader& r, bool solver_keys, const Params& base = {}) {
  InchwormInputs in;
  in.p = base;
  Params& p = in.p;
  // The parameters first: the force range below is computed from them.
  read_params(r, p);

  int given = 0;
  for (auto key : {"F", "F_frac", "f_tilde"}) {
    if (r.has(key)) {
      ++given;
      in.force_key = key;
    }
  }
  if (given != 1) {
    r.fail(given == 0 ? "F" : in.force_key,
           "give the force as exactly one of F (N), F_frac or f_tilde");
  }
  for (auto key : {"F_lo", "F_lo_factor", "F_max"}) {
    if (r.has(key) && in.force_key != "F_frac") {
      r.fail(key, "only used with F_frac");
    }
  }
  // The ratio constraints before the force range is built from them.
  validate_but_force(r, p, in.force_key);
  force_range(r, in);
  if (in.force_key == "F") {
    p.F = *r.number("F");
  } else if (in.force_key == "f_tilde") {
    const double f = *r.number("f_tilde");
    if (!(f > 0.0)) {
      r.fail("f_tilde", "must be positive, got " + core::format_double(f));
    }
    p.F = f * p.mu * p.M * p.g;
  } else {
    const double frac = *r.number("F_frac");
    if (!(frac >= 0.0 && frac <= 1.0)) {
      r.fail("F_frac", "must be in [0, 1], got " + core::format_double(frac));
    }
    if (!(in.F_max > in.F_lo)) {
      // Name a key the spec gives (it has a place): the range's own, else what F_lo is made of.
      std::string_view key = "F_lo";
      for (auto k : {"F_max", "F_lo", "F_lo_factor", "mu_s", "mu", "m", "M", "g"}) {
        if (r.has(k)) {
          key = k;
          break;
        }
      }
      r.fail(key, "F_max = " + core::format_double(in.F_max) +
                      " N must exceed F_lo = " + core::format_double(in.F_lo) + " N");
    }
    p.F = in.F_lo + frac * (in.F_max - in.F_lo);
  }
  validate_at_keys(r, p, in.force_key);
  read_solver(r, in, solver_keys);
  return in;
}

/// The method of a point and, with `solver_keys`, its solver's settings (rtol, stop, estimator,
/// budgets, event location, fixed step).
void read_solver(const Reader& r, InchwormInputs& in, bool solver_keys) {
  if (const auto name = r.text("method")) {
    const auto m = inchworm::parse_method(*name);
    if (!m) {
      r.fail("method", "unknown method '" + *name + "'; expected " + inchworm::method_names());
    }
    in.method = *m;
  }
  if (!solver_keys) {
    return;
  }
  in.opt.rtol = r.number("rtol", in.opt.rtol);
  if (!inchworm::ranges::kRtol.contains(in.opt.rtol)) {
    r.fail("rtol", "must be in " + inchworm::ranges::kRtol.describe() + ", got " +
                       core::format_double(in.opt.rtol));
  }
  if (const auto stop = r.text("stop")) {
    if (*stop == "estimate") {
      in.opt.stop = inchworm::StopRule::kEstimatedError;
    } else if (*stop == "difference") {
      in.opt.stop = inchworm::StopRule::kConsecutiveDifference;
    } else {
      r.fail("stop", "expected \"estimate\" or \"difference\", got '" + *stop + "'");
    }
  }
  if (const auto estimator = r.text("estimator")) {
    if (*estimator == "cycle") {
      in.opt.estimator = inchworm::Estimator::kCycleAverage;
    } else if (*estimator == "running") {
      in.opt.estimator = inchworm::Estimator::kRunningMean;
    } else {
      r.fail("estimator", "expected \"cycle\" or \"running\", got '" + *estimator + "'");
    }
  }
  in.opt.max_strokes = r.integer("max_strokes", in.opt.max_strokes, 8, 1'000'000'000LL);
  if (const auto target = r.number("target")) {
    if (!(*target > 0.0 && *target < 1.0)) {
      r.fail("target", "must be in (0, 1), got " + core::format_double(*target));
    }
    in.opt.target = *target;
  }
  if (const auto event_tol = r.number("event_tol")) {
    if (!(*event_tol >= 0.0 && *event_tol < 1.0)) {
      r.fail("event_tol",
             "must be in [0, 1) s (0: automatic), got " + core::format_double(*event_tol));
    }
    in.opt.event_tol = *event_tol;
  }
  if (const auto h = r.number("h")) {
    if (in.method != Method::kFixedRk4) {
      r.fail("h", "only used with method = \"fixed_rk4\" (the fixed step in s)");
    }
    if (!inchworm::ranges::kFixedStep.contains(*h)) {
      r.fail("h", "the fixed step must be in " + inchworm::ranges::kFixedStep.describe() +
                      ", got " + core::format_double(*h));
    }
    in.opt.step = *h;
  }
  in.opt.max_steps = r.integer("max_steps", 0, 0, 1'000'000'000'000LL);
  if (const auto times = r.text("event_times")) {
    if (*times == "exact") {
      if (!inchworm::is_simulation(in.method)) {
        r.fail("event_times", "only used with a simulation method");
      }
      in.opt.exact_event_times = true;
    } else if (*times != "located") {
      r.fail("event_times",
             "expected \"located\" (the method's own) or \"exact\" (the exact "
             "event times: integration error only), got '" +
                 *times + "'");
    }
  }
}

double f_tilde_of(const Params& p) { return p.F / (p.mu * p.M * p.g); }

/// The spec's names of a solve's stopping rule and estimator (read by read_solver).
const char* stop_name(const inchworm::VssOptions& opt) {
  return opt.stop == inchworm::StopRule::kEstimatedError ? "estimate" : "difference";
}
const char* estimator_name(const inchworm::VssOptions& opt) {
  return opt.estimator == inchworm::Estimator::kCycleAverage ? "cycle" : "running";
}
double f_frac_of(const InchwormInputs& in) {
  return in.F_max > in.F_lo ? (in.p.F - in.F_lo) / (in.F_max - in.F_lo) : std::nan("");
}

// --- inchworm_vss -------------------------------------------------------------------------------

const std::vector<std::string_view> kVssKeys =
    keys({kParamKeys,
          kForceKeys,
          {"model", "alpha", "method", "rtol", "stop", "estimator", "max_strokes", "repeats",
           "target", "event_tol", "h", "max_steps", "event_times"}});

/// The swap model of a point (`model`: "instant" | "dm") and the dm model's `alpha`, set
/// before the other parameters are validated.
void read_model(const Reader& r, Params& p) {
  if (const auto model = r.text("model")) {
    if (*model == "instant") {
      p.model = inchworm::SwapModel::kInstant;
    } else if (*model == "dm") {
      p.model = inchworm::SwapModel::kMass;
    } else {
      r.fail("model", "expected \"instant\" or \"dm\", got '" + *model + "'");
    }
  }
  if (const auto alpha = r.number("alpha")) {
    if (p.model != inchworm::SwapModel::kMass) {
      r.fail("alpha", "only used with model = \"dm\" (the instant swap has no swap force)");
    }
    if (!(*alpha > 0.0)) {
      r.fail("alpha", "the swap force factor must be positive, got " + core::format_double(*alpha));
    }
    p.alpha = *alpha;
  }
}

struct VssInputs {
  InchwormInputs in;
  long long repeats = 1;  ///< solves; wall_s is their median
};

VssInputs read_vss(const Point& point) {
  const Reader r(point, "inchworm_vss", kVssKeys);
  Params base;
  read_model(r, base);
  VssInputs v{read_inchworm(r, true, base), 1};
  v.repeats = r.integer("repeats", 1, 1, 1000);
  return v;
}

/// One row per point: the solve's result, its cost and the inputs that shaped it.
struct VssRow {
  long long id = 0;
  double mu = 0.0;
  double mu_s = 0.0;
  double F = 0.0;
  double f_tilde = 0.0;
  double F_frac = 0.0;
  std::string method;
  double rtol = 0.0;
  std::string stop;
  std::string estimator;
  double v_ss = 0.0;
  double period = 0.0;
  double c0 = 0.0;
  long long regime = 0;
  double est_error = 0.0;
  double last_difference = 0.0;
  double contraction = 0.0;
  long long strokes = 0;
  bool converged = false;
  long long steps = 0;
  long long rhs_evals = 0;
  double wall_s = 0.0;
  std::string message;
  std::string model;
  double alpha = 0.0;
  bool swap_stopped = false;
  double cpu_s = 0.0;
  long long guard_evals = 0;
  long long events = 0;
  double target = 0.0;
  double event_tol = 0.0;
  double h = 0.0;
  std::string event_times;
  std::string status;  ///< "converged", "step budget", "stroke budget" or "failed"

  static std::vector<Column<VssRow>> columns() {
    return {value("id", &VssRow::id),
            value("mu", &VssRow::mu),
            value("mu_s", &VssRow::mu_s),
            value("F", &VssRow::F, "N"),
            value("f_tilde", &VssRow::f_tilde),
            value("F_frac", &VssRow::F_frac),
            value("method", &VssRow::method),
            value("rtol", &VssRow::rtol),
            value("stop", &VssRow::stop),
            value("estimator", &VssRow::estimator),
            value("v_ss", &VssRow::v_ss, "m/s"),
            value("period", &VssRow::period, "s"),
            value("c0", &VssRow::c0, "m/s"),
            value("regime", &VssRow::regime),
            value("est_error", &VssRow::est_error),
            value("last_difference", &VssRow::last_difference, "m/s"),
            value("contraction", &VssRow::contraction),
            value("strokes", &VssRow::strokes),
            value("converged", &VssRow::converged),
            value("steps", &VssRow::steps),
            value("rhs_evals", &VssRow::rhs_evals),
            timing("wall_s", &VssRow::wall_s, "s"),
            value("message", &VssRow::message),
            value("model", &VssRow::model),
            value("alpha", &VssRow::alpha),
            value("swap_stopped", &VssRow::swap_stopped),
            timing("cpu_s", &VssRow::cpu_s, "s"),
            value("guard_evals", &VssRow::guard_evals),
            value("events", &VssRow::events),
            value("target", &VssRow::target),
            value("event_tol", &VssRow::event_tol, "s"),
            value("h", &VssRow::h, "s"),
            value("event_times", &VssRow::event_times),
            value("status", &VssRow::status)};
  }
};

/// A row's status: "converged", the budget that stopped a solve ("step budget": `max_steps`,
/// "stroke budget": `max_strokes`) or "failed". Whether a budget stop is a failure is the spec's
/// to say (`budget_stops`, sweeps/README.md).
std::string vss_status(const inchworm::VssResult& s) {
  if (s.converged) {
    return "converged";
  }
  switch (s.budget) {
    case inchworm::Budget::kSteps:
      return "step budget";
    case inchworm::Budget::kStrokes:
      return "stroke budget";
    case inchworm::Budget::kNone:
      break;
  }
  return "failed";
}

Rows<VssRow> run_vss(const Point& point) {
  const auto [in, repeats] = read_vss(point);
  inchworm::VssResult s;
  std::vector<double> times;
  std::vector<double> cpu_times;
  for (long long k = 0; k < repeats; ++k) {
    s = inchworm::solve_vss(in.p, in.method, in.opt);
    times.push_back(s.wall_s);
    cpu_times.push_back(s.cpu_s);
    if (!s.converged) {
      break;  // a failed solve is not timed again
    }
  }
  s.wall_s = median(times);
  s.cpu_s = median(cpu_times);
  // A solve that never produced a number reports NaN rather than zeros.
  const bool nothing = !s.converged && inchworm::is_simulation(in.method) && s.strokes == 0;
  const bool closed_form_failed = !s.converged && !inchworm::is_simulation(in.method);
  const double nan = std::nan("");
  const auto shown = [&](double v) { return nothing || closed_form_failed ? nan : v; };
  const inchworm::Regime regime =
      nothing || closed_form_failed ? inchworm::regime_of(in.p) : s.regime;
  VssRow row;
  row.id = point.id;
  row.mu = in.p.mu;
  row.mu_s = in.p.static_mu();
  row.F = in.p.F;
  row.f_tilde = f_tilde_of(in.p);
  row.F_frac = f_frac_of(in);
  row.method = inchworm::method_name(in.method);
  row.rtol = in.opt.rtol;
  row.stop = stop_name(in.opt);
  row.estimator = estimator_name(in.opt);
  row.v_ss = shown(s.v_ss);
  row.period = shown(s.period);
  row.c0 = shown(s.c0);
  row.regime = static_cast<long long>(regime);
  row.est_error = shown(s.est_error);
  row.last_difference = shown(s.last_difference);
  row.contraction = shown(s.contraction);
  row.strokes = s.strokes;
  row.converged = s.converged;
  row.steps = s.stats.steps;
  row.rhs_evals = s.stats.rhs_evals;
  row.wall_s = s.wall_s;
  row.message = s.message;
  row.model = in.p.model == inchworm::SwapModel::kMass ? "dm" : "instant";
  row.alpha = in.p.model == inchworm::SwapModel::kMass ? in.p.alpha : nan;
  row.swap_stopped = s.swap_stopped;
  row.cpu_s = s.cpu_s;
  row.guard_evals = s.stats.guard_evals;
  row.events = s.stats.segments;
  row.target = inchworm::is_simulation(in.method)
                   ? (in.opt.target > 0.0 ? in.opt.target : in.opt.rtol)
                   : nan;
  row.event_tol = in.opt.event_tol;
  row.h = in.method == Method::kFixedRk4 ? inchworm::backend_options(in.opt).step : nan;
  row.event_times = in.opt.exact_event_times ? "exact" : "located";
  row.status = vss_status(s);
  Rows<VssRow> out;
  out.failed = !s.converged && s.budget == inchworm::Budget::kNone;
  out.at_budget = !s.converged && s.budget != inchworm::Budget::kNone;
  out.rows.push_back(std::move(row));
  if (!s.converged) {
    out.message = s.message;
  }
  return out;
}

// --- inchworm_convergence -----------------------------------------------------------------------

const std::vector<std::string_view> kConvergenceKeys =
    keys({kParamKeys, kForceKeys, {"method", "cycles"}});

struct ConvergenceInputs {
  InchwormInputs in;
  long long cycles = 0;
};

ConvergenceInputs read_convergence(const Point& point) {
  const Reader r(point, "inchworm_convergence", kConvergenceKeys);
  ConvergenceInputs c;
  c.in = read_inchworm(r, false);
  if (r.has("method") && c.in.method != Method::kAnalytic) {
    r.fail("method",
           "inchworm_convergence integrates with the exact event-driven backend; "
           "only \"analytic\" is supported");
  }
  c.in.method = Method::kAnalytic;
  if (!r.has("cycles")) {
    r.fail("cycles", "required (the number of cycles to simulate)");
  }
  c.cycles = r.integer("cycles", 0, 1, 10'000'000);
  return c;
}

/// One row per simulated cycle.
struct ConvergenceRow {
  long long id = 0;
  double mu = 0.0;
  double F = 0.0;
  std::string method;
  long long cycle = 0;
  double cycle_average = 0.0;
  double running_mean = 0.0;
  double exact = 0.0;
  double err_cycle = 0.0;
  double err_running = 0.0;

  static std::vector<Column<ConvergenceRow>> columns() {
    using R = ConvergenceRow;
    return {value("id", &R::id),
            value("mu", &R::mu),
            value("F", &R::F, "N"),
            value("method", &R::method),
            value("cycle", &R::cycle),
            value("cycle_average", &R::cycle_average, "m/s"),
            value("running_mean", &R::running_mean, "m/s"),
            value("exact", &R::exact, "m/s"),
            value("err_cycle", &R::err_cycle),
            value("err_running", &R::err_running)};
  }
};

// Simulates `cycles` cycles from rest with the exact backend and no stopping rule, stroke by
// stroke as inchworm::steady_state_by_simulation does (same arithmetic, so its cycle averages
// and running mean are the ones the simulation's estimators see). The running mean is the total
// CoM displacement over the total time since rest, i.e. the cycle averages weighted by the
// cycle durations. Errors are relative to the closed form: |V − v_ss| / v_ss.
Rows<ConvergenceRow> run_convergence(const Point& point) {
  const ConvergenceInputs c = read_convergence(point);
  const Params& p = c.in.p;
  Rows<ConvergenceRow> out;
  try {
    const double exact = inchworm::steady_state_closed_form(p).v_ss;
    const inchworm::InstantSwapSystem sys(p);
    auto x = sys.rest_state();
    auto mode = sys.mode_of(x, 1);
    events::ExactBackend backend;
    double total_displacement = 0.0;
    double total_time = 0.0;
    for (long long cycle = 1; cycle <= c.cycles; ++cycle) {
      const auto a = inchworm::simulate_half_cycle(sys, backend, mode, x);
      const auto b = inchworm::simulate_half_cycle(sys, backend, mode, x);
      const double average = (a.displacement + b.displacement) / (a.duration + b.duration);
      total_displacement += a.displacement + b.displacement;
      total_time += a.duration + b.duration;
      const double running = total_displacement / total_time;
      out.rows.push_back({point.id, p.mu, p.F, "analytic", cycle, average, running, exact,
                          std::abs(average - exact) / exact, std::abs(running - exact) / exact});
    }
  } catch (const std::exception& e) {
    out.failed = true;
    out.message = e.what();
  }
  return out;
}

// --- inchworm_force_grid ------------------------------------------------------------------------

// One point is one μ and one solver on a force grid the same for every μ, in newtons: the
// forces k F_step (k = 1, 2, ...) up to F_end, keeping those above μ_s m g, where the inchworm
// moves. A thesis that sampled forces on such a grid for each μ (rather than from μMg, as our
// regression study does) is what studies/ch2_inchworm/forensics.toml searches for.
const std::vector<std::string_view> kForceGridKeys =
    keys({kParamKeys,
          {"F_step", "F_end", "method", "rtol", "stop", "estimator", "max_strokes", "target",
           "event_tol", "h", "max_steps"}});

/// Forces a point may hold: a grid finer than this is a typo, not a study.
constexpr long long kMaxGridForces = 100'000;

struct ForceGridInputs {
  InchwormInputs in;
  double F_step = 0.0;  ///< N
  double F_end = 0.0;   ///< N
  long long k_first = 1;
  long long k_last = 0;
};

ForceGridInputs read_force_grid(const Point& point) {
  const Reader r(point, "inchworm_force_grid", kForceGridKeys);
  ForceGridInputs g;
  Params& p = g.in.p;
  read_params(r, p);
  validate_but_force(r, p, "F_step");
  for (auto key : {"F_step", "F_end"}) {
    if (!r.has(key)) {
      r.fail(key, "required (the grid's spacing and its largest force, N)");
    }
  }
  g.F_step = *r.number("F_step");
  g.F_end = *r.number("F_end");
  if (!(g.F_step > 0.0)) {
    r.fail("F_step", "must be positive, got " + core::format_double(g.F_step));
  }
  if (!inchworm::ranges::kForce.contains(g.F_end)) {
    r.fail("F_end", "must be in " + inchworm::ranges::kForce.describe() + ", got " +
                        core::format_double(g.F_end));
  }
  // The first multiple of the step above μ_s m g, where m starts to move (eq. 2.7).
  const double moves = p.static_mu() * p.m * p.g;
  g.k_first = static_cast<long long>(std::floor(moves / g.F_step)) + 1;
  g.k_last = static_cast<long long>(std::floor(g.F_end / g.F_step * (1.0 + 1e-12)));
  if (g.k_last < g.k_first) {
    r.fail("F_end", "F_end = " + core::format_double(g.F_end) +
                        " N leaves no force of the grid above mu_s m g = " +
                        core::format_double(moves) + " N");
  }
  if (g.k_last - g.k_first + 1 > kMaxGridForces) {
    r.fail("F_step", "the grid holds " + std::to_string(g.k_last - g.k_first + 1) +
                         " forces, more than " + std::to_string(kMaxGridForces));
  }
  p.F = static_cast<double>(g.k_first) * g.F_step;
  validate_at_keys(r, p, "F_step");
  read_solver(r, g.in, true);
  return g;
}

/// One row per force of the grid.
struct ForceGridRow {
  long long id = 0;
  double mu = 0.0;
  double F = 0.0;
  double f_tilde = 0.0;
  std::string method;
  std::string stop;
  std::string estimator;
  double rtol = 0.0;
  double g = 0.0;
  double m = 0.0;
  double M = 0.0;
  double L_min = 0.0;
  double L_max = 0.0;
  double v_ss = 0.0;
  long long regime = 0;
  long long strokes = 0;
  std::string status;

  static std::vector<Column<ForceGridRow>> columns() {
    using R = ForceGridRow;
    return {value("id", &R::id),
            value("mu", &R::mu),
            value("F", &R::F, "N"),
            value("f_tilde", &R::f_tilde),
            value("method", &R::method),
            value("stop", &R::stop),
            value("estimator", &R::estimator),
            value("rtol", &R::rtol),
            value("g", &R::g, "m/s^2"),
            value("m", &R::m, "kg"),
            value("M", &R::M, "kg"),
            value("L_min", &R::L_min, "m"),
            value("L_max", &R::L_max, "m"),
            value("v_ss", &R::v_ss, "m/s"),
            value("regime", &R::regime),
            value("strokes", &R::strokes),
            value("status", &R::status)};
  }
};

Rows<ForceGridRow> run_force_grid(const Point& point) {
  const ForceGridInputs g = read_force_grid(point);
  Params p = g.in.p;
  Rows<ForceGridRow> out;
  out.rows.reserve(static_cast<std::size_t>(g.k_last - g.k_first + 1));
  for (long long k = g.k_first; k <= g.k_last; ++k) {
    p.F = static_cast<double>(k) * g.F_step;
    const inchworm::VssResult s = inchworm::solve_vss(p, g.in.method, g.in.opt);
    ForceGridRow row;
    row.id = point.id;
    row.mu = p.mu;
    row.F = p.F;
    row.f_tilde = f_tilde_of(p);
    row.method = inchworm::method_name(g.in.method);
    row.stop = stop_name(g.in.opt);
    row.estimator = estimator_name(g.in.opt);
    row.rtol = g.in.opt.rtol;
    row.g = p.g;
    row.m = p.m;
    row.M = p.M;
    row.L_min = p.L_min;
    row.L_max = p.L_max;
    row.v_ss = s.converged ? s.v_ss : std::nan("");
    row.regime = static_cast<long long>(s.converged ? s.regime : inchworm::regime_of(p));
    row.strokes = s.strokes;
    row.status = vss_status(s);
    out.rows.push_back(std::move(row));
    if (!s.converged && out.message.empty()) {
      out.failed = out.failed || s.budget == inchworm::Budget::kNone;
      out.at_budget = s.budget != inchworm::Budget::kNone;
      out.message = "F = " + core::format_double(p.F) + " N: " + s.message;
    }
  }
  return out;
}

}  // namespace

std::vector<PointKind> inchworm_kinds() {
  return {make_point_kind<VssRow>(
              "inchworm_vss",
              "steady-state CoM speed of the inchworm (instant swap or moving dm) by any method "
              "(one row per point)",
              Timed::kNo, [](const Point& p) { (void)read_vss(p); }, run_vss),
          make_point_kind<ConvergenceRow>(
              "inchworm_convergence",
              "cycle averages and running mean from rest against the closed form (one row per "
              "cycle)",
              Timed::kNo, [](const Point& p) { (void)read_convergence(p); }, run_convergence),
          make_point_kind<ForceGridRow>(
              "inchworm_force_grid",
              "v_ss on a force grid in newtons shared by every mu (k F_step up to F_end, above "
              "mu_s m g; one row per force)",
              Timed::kNo, [](const Point& p) { (void)read_force_grid(p); }, run_force_grid)};
}

}  // namespace slipwalk::sweeps::points
