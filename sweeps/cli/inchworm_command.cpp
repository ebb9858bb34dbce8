// slipwalk inchworm vss | trace (DESIGN.md: Command line): the options parsed and checked here,
// the solve and its output in inchworm/vss.hpp and vss_output.hpp, the trace in trace_file.hpp.
#include <gsl/gsl_errno.h>

#include <charconv>
#include <cmath>
#include <iostream>
#include <memory>
#include <string>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/range.hpp"
#include "inchworm/params.hpp"
#include "inchworm/trace.hpp"
#include "inchworm/trace_file.hpp"
#include "inchworm/vss.hpp"
#include "inchworm/vss_output.hpp"
#include "sweeps/cli/commands.hpp"

namespace slipwalk::cli {

namespace {

using core::InputError;

/// A finite number, the whole text: rejects "", "1.0x", "nan", "inf", "abc" naming the option.
double parse_number(const std::string& option, const std::string& text) {
  std::string_view s = text;
  if (s.size() > 1 && s.front() == '+' && s[1] != '-' && s[1] != '+') {
    s.remove_prefix(1);
  }
  double value = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (s.empty() || ec == std::errc::invalid_argument || end != s.data() + s.size()) {
    throw InputError(option, "expected a number, got '" + text + "'");
  }
  if (ec == std::errc::result_out_of_range) {
    throw InputError(option, "'" + text + "' is out of the range of a double");
  }
  if (!std::isfinite(value)) {
    throw InputError(option, "expected a finite number, got '" + text + "'");
  }
  return value;
}

long long parse_integer(const std::string& option, const std::string& text) {
  long long value = 0;
  const char* first = text.data() + (text.size() > 1 && text.front() == '+' ? 1 : 0);
  const auto [end, ec] = std::from_chars(first, text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size()) {
    throw InputError(option, "expected an integer, got '" + text + "'");
  }
  return value;
}

/// The model's options, shared by vss and trace; kept as text and parsed by hand.
struct ParamOptions {
  std::string force, mu, mu_s, m, M, L_min, L_max, g;
  std::string model = "instant";
  std::string alpha;

  void add(CLI::App& app) {
    app.add_option("--force", force, "actuator force F in N (> mu_s m g)")
        ->type_name("NUMBER")
        ->required();
    app.add_option("--mu", mu, "dynamic friction coefficient (> 0)")
        ->type_name("NUMBER")
        ->required();
    app.add_option("--mu-s", mu_s, "static friction coefficient (>= mu; default mu)")
        ->type_name("NUMBER");
    app.add_option("--m", m, "small mass in kg (default 1)")->type_name("NUMBER");
    app.add_option("--M", M, "large mass in kg (> m; default 1.5)")->type_name("NUMBER");
    app.add_option("--L-min", L_min, "shortest actuator length in m (default 0.02)")
        ->type_name("NUMBER");
    app.add_option("--L-max", L_max, "longest actuator length in m (default 0.5)")
        ->type_name("NUMBER");
    app.add_option("--g", g, "gravitational acceleration in m/s^2 (default 9.81)")
        ->type_name("NUMBER");
    app.add_option("--model", model,
                   "instant (instantaneous swap, thesis 2.2; default) | dm (the load dm = M - m "
                   "pushed across by alpha F, thesis 2.5)")
        ->type_name("NAME");
    app.add_option("--alpha", alpha,
                   "dm model: the swap force F_dm = alpha F, alpha > 0 (default 1)")
        ->type_name("NUMBER");
  }

  [[nodiscard]] inchworm::Params params(const CLI::App& app) const {
    inchworm::Params p;
    p.F = parse_number("--force", force);
    p.mu = parse_number("--mu", mu);
    const auto given = [&](const char* name) { return app.count(name) > 0; };
    if (given("--mu-s")) {
      p.mu_s = parse_number("--mu-s", mu_s);
    }
    if (given("--m")) {
      p.m = parse_number("--m", m);
    }
    if (given("--M")) {
      p.M = parse_number("--M", M);
    }
    if (given("--L-min")) {
      p.L_min = parse_number("--L-min", L_min);
    }
    if (given("--L-max")) {
      p.L_max = parse_number("--L-max", L_max);
    }
    if (given("--g")) {
      p.g = parse_number("--g", g);
    }
    if (model == "instant") {
      p.model = inchworm::SwapModel::kInstant;
      if (given("--alpha")) {
        throw InputError("--alpha",
                         "only used with --model dm (the instant swap has no swap force)");
      }
    } else if (model == "dm") {
      p.model = inchworm::SwapModel::kMass;
      if (given("--alpha")) {
        p.alpha = parse_number("--alpha", alpha);
      }
    } else {
      throw InputError("--model", "unknown model '" + model + "'; expected instant|dm");
    }
    inchworm::validate(p);
    return p;
  }
};

inchworm::Method parse_method(const std::string& name) {
  const auto m = inchworm::parse_method(name);
  if (!m) {
    throw InputError("--method",
                     "unknown method '" + name + "'; expected " + inchworm::method_names());
  }
  return *m;
}

double parse_rtol(const std::string& text) {
  const double rtol = parse_number("--rtol", text);
  core::require_in("--rtol", rtol, inchworm::ranges::kRtol);
  return rtol;
}

/// An integer option within `range` (inchworm::ranges), the message stating it.
long long parse_count(const std::string& option, const std::string& text,
                      const core::Range& range) {
  const long long n = parse_integer(option, text);
  core::require_in(option, static_cast<double>(n), range);
  return n;
}

/// The library's message of a run that hit a bound, with the option that raises it.
std::string with_hint(const std::string& message) {
  if (message.find("step budget") != std::string::npos) {
    return message + " (raise --max-steps)";
  }
  if (message.find("no convergence within") != std::string::npos) {
    return message + " (raise --max-strokes)";
  }
  return message;
}

struct VssCommand {
  ParamOptions params;
  std::string method = "exact";
  std::string rtol = "1e-10";
  std::string stop = "estimate";
  std::string estimator = "cycle";
  std::string max_strokes = "4000000";
  std::string max_steps = std::to_string(inchworm::kDefaultMaxSteps);
  bool json = false;

  void run(const CLI::App& app) const {
    // Every input is checked before anything is computed.
    const inchworm::Params p = params.params(app);
    const inchworm::Method m = parse_method(method);
    inchworm::VssOptions opt;
    opt.rtol = parse_rtol(rtol);
    if (stop == "estimate") {
      opt.stop = inchworm::StopRule::kEstimatedError;
    } else if (stop == "difference") {
      opt.stop = inchworm::StopRule::kConsecutiveDifference;
    } else {
      throw InputError("--stop", "unknown rule '" + stop + "'; expected estimate|difference");
    }
    if (estimator == "cycle") {
      opt.estimator = inchworm::Estimator::kCycleAverage;
    } else if (estimator == "running") {
      opt.estimator = inchworm::Estimator::kRunningMean;
    } else {
      throw InputError("--estimator",
                       "unknown estimator '" + estimator + "'; expected cycle|running");
    }
    opt.max_strokes = parse_count("--max-strokes", max_strokes, inchworm::ranges::kMaxStrokes);
    opt.max_steps = parse_count("--max-steps", max_steps, inchworm::ranges::kMaxSteps);
    // fixed_rk4 (step h = rtol s): the 8 strokes a solve takes at least must fit the budget.
    inchworm::check_fixed_step_budget(p, m, opt, 8.0, "--rtol");

    gsl_set_error_handler_off();
    const inchworm::VssResult r = inchworm::solve_vss(p, m, opt);
    if (json) {
      std::cout << inchworm::vss_to_json(p, m, opt, r).dump(2) << "\n";
    } else {
      std::cout << inchworm::vss_to_text(p, m, r) << std::flush;
    }
    if (!r.converged) {
      throw core::ComputationError(std::string("inchworm vss --method ") +
                                   inchworm::method_name(m) + ": " + with_hint(r.message));
    }
  }
};

struct TraceCommand {
  ParamOptions params;
  std::string method = "analytic";
  std::string cycles = "6";
  std::string dt = "1e-3";
  std::string rtol = "1e-10";
  std::string max_rows = std::to_string(inchworm::kDefaultMaxRows);
  std::string max_steps = std::to_string(inchworm::kDefaultMaxSteps);
  std::string out;

  void run(const CLI::App& app) const {
    const inchworm::Params p = params.params(app);
    const inchworm::Method m = parse_method(method);
    inchworm::TraceOptions opt;
    opt.cycles = static_cast<int>(parse_count("--cycles", cycles, inchworm::ranges::kCycles));
    opt.sample_dt = parse_number("--dt", dt);
    core::require_in("--dt", opt.sample_dt, inchworm::ranges::kSampleDt);
    opt.rtol = parse_rtol(rtol);
    opt.max_rows = parse_count("--max-rows", max_rows, inchworm::ranges::kMaxRows);
    opt.max_steps = parse_count("--max-steps", max_steps, inchworm::ranges::kMaxSteps);
    // Refused before a byte is written: more rows than --max-rows, or more fixed steps than
    // --max-steps, by the closed-form estimate.
    inchworm::check_trace_size(p, m, opt);
    if (out != "-") {
      core::check_output_path(out, "--out");
    }
    gsl_set_error_handler_off();
    if (out == "-") {
      inchworm::write_trace(p, m, opt, std::cout);
      std::cout.flush();
      return;
    }
    try {
      inchworm::write_trace_file(p, m, opt, out);
    } catch (const InputError&) {  // write_trace throws no InputError: the file could not open
      throw InputError("--out", "cannot write '" + out + "'");
    }
  }
};

}  // namespace

void add_inchworm_command(CLI::App& app) {
  auto* inchworm = app.add_subcommand("inchworm", "the inchworm of thesis chapter 2");
  inchworm->require_subcommand(1);

  auto vss = std::make_shared<VssCommand>();
  auto* v = inchworm->add_subcommand("vss", "steady-state CoM speed and stroke period");
  vss->params.add(*v);
  v->add_option("--method", vss->method,
                std::string("exact (closed form, default), rootfind, or an integrator: ") +
                    inchworm::method_names())
      ->type_name("NAME");
  v->add_option("--rtol", vss->rtol,
                "integrators: step tolerance and convergence target, in [1e-15, 1) (default "
                "1e-10; fixed_rk4: its step in s)")
      ->type_name("NUMBER");
  v->add_option("--stop", vss->stop,
                "integrators: estimate (remaining-error estimate, default) | difference "
                "(consecutive cycles, the thesis' rule)")
      ->type_name("RULE");
  v->add_option("--estimator", vss->estimator,
                "integrators: cycle (last cycle average, default) | running (mean from rest)")
      ->type_name("NAME");
  v->add_option("--max-strokes", vss->max_strokes,
                "integrators: give up (exit 1) after this many strokes (default 4000000)")
      ->type_name("INT");
  v->add_option("--max-steps", vss->max_steps,
                "integrators: give up (exit 1) after this many steps, 1 to 1e15 (default " +
                    std::to_string(inchworm::kDefaultMaxSteps) + ")")
      ->type_name("INT");
  v->add_flag("--json", vss->json, "print one JSON object");
  v->callback([vss, v] { vss->run(*v); });

  auto trace = std::make_shared<TraceCommand>();
  auto* t = inchworm->add_subcommand("trace", "time series of the masses and the CoM from rest");
  trace->params.add(*t);
  t->add_option(
       "--method", trace->method,
       std::string("analytic (default), cvode, odeint or gsl; of ") + inchworm::method_names())
      ->type_name("NAME");
  t->add_option("--cycles", trace->cycles, "cycles (two strokes each), 1 to 10000 (default 6)")
      ->type_name("INT");
  t->add_option("--dt", trace->dt,
                "sampling interval in s, 1e-9 to 1000 (default 1e-3): the exact method samples "
                "on this grid, integrators write their first step at or after each grid time")
      ->type_name("NUMBER");
  t->add_option("--rtol", trace->rtol,
                "integrators' tolerance, in [1e-15, 1) (default 1e-10; fixed_rk4: its step in s)")
      ->type_name("NUMBER");
  t->add_option("--max-rows", trace->max_rows,
                "refuse (exit 2, by an estimate) or stop (exit 1) past this many rows, 1 to 1e9 "
                "(default " +
                    std::to_string(inchworm::kDefaultMaxRows) + ", ~1.7 GB)")
      ->type_name("INT");
  t->add_option("--max-steps", trace->max_steps,
                "integrators: give up (exit 1) after this many steps, 1 to 1e15 (default " +
                    std::to_string(inchworm::kDefaultMaxSteps) + ")")
      ->type_name("INT");
  t->add_option("--out", trace->out, "CSV file to write, - for stdout")
      ->type_name("FILE")
      ->required();
  t->callback([trace, t] { trace->run(*t); });
}

}  // namespace slipwalk::cli
