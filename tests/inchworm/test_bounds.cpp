// Ranges up front and honest results: every parameter of the inchworm, at every magnitude a
// hostile input can take, is either refused (core::InputError naming its option and stating the
// range) or gives a solve that ends quickly with finite numbers or an honest failure — never a
// "converged" result with a non-finite value. And every run bound (strokes, steps, rows) holds
// for every method.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "inchworm/params.hpp"
#include "inchworm/trace.hpp"
#include "inchworm/vss.hpp"

namespace slipwalk::inchworm {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The hostile magnitudes, both signs, and a seeded spread of log-uniform ones in between.
std::vector<double> magnitudes() {
  std::vector<double> v = {1e-320, 1e-30, 1e-12, 0.0,          -1.0, 1e12, 1e30,
                           1e308,  kInf,  -kInf, std::nan(""), 1.0,  2.5};
  std::mt19937_64 rng(15);
  std::uniform_real_distribution<double> exponent(-320.0, 308.0);
  for (int i = 0; i < 24; ++i) {
    v.push_back((i % 2 == 0 ? 1.0 : -1.0) * std::pow(10.0, exponent(rng)));
  }
  return v;
}

struct Field {
  const char* option;
  double Params::*member;
  core::Range range;
};

const std::vector<Field>& fields() {
  static const std::vector<Field> f = {
      {"--m", &Params::m, ranges::kMass},           {"--M", &Params::M, ranges::kMass},
      {"--L-min", &Params::L_min, ranges::kLength}, {"--L-max", &Params::L_max, ranges::kLength},
      {"--g", &Params::g, ranges::kGravity},        {"--mu", &Params::mu, ranges::kFriction},
      {"--mu-s", &Params::mu_s, ranges::kFriction}, {"--force", &Params::F, ranges::kForce},
      {"--alpha", &Params::alpha, ranges::kAlpha}};
  return f;
}

/// A converged result is made of finite numbers.
void expect_honest(const VssResult& r, const std::string& what) {
  if (r.converged) {
    EXPECT_TRUE(std::isfinite(r.v_ss) && std::isfinite(r.period) && std::isfinite(r.c0) &&
                std::isfinite(r.est_error))
        << what;
    EXPECT_GT(r.period, 0.0) << what;
    EXPECT_FALSE(std::isinf(r.contraction)) << what;
  } else {
    EXPECT_FALSE(r.message.empty()) << what;
  }
}

TEST(InchwormBounds, EveryParameterAtEveryMagnitudeIsRefusedWithItsRangeOrSolvedHonestly) {
  const auto start = std::chrono::steady_clock::now();
  VssOptions quick;
  quick.max_strokes = 400;
  int refused = 0;
  int solved = 0;
  for (const SwapModel model : {SwapModel::kInstant, SwapModel::kMass}) {
    for (const Field& f : fields()) {
      for (const double value : magnitudes()) {
        Params p;
        p.model = model;
        p.*f.member = value;
        const std::string what = std::string(f.option) + " = " + std::to_string(value);
        try {
          validate(p);
        } catch (const core::InputError& e) {
          ++refused;
          const std::string message = e.what();
          if (e.where() == f.option && !f.range.contains(value)) {
            EXPECT_NE(message.find("must be in " + f.range.describe()), std::string::npos)
                << message;
          }
          continue;
        }
        // Accepted: inside its range (alpha is not read by the instant model; mu_s NaN means mu).
        EXPECT_TRUE(f.range.contains(value) ||
                    (f.member == &Params::alpha && model == SwapModel::kInstant) ||
                    (f.member == &Params::mu_s && std::isnan(value)))
            << what;
        for (const Method m : {Method::kExact, Method::kRootfind, Method::kAnalytic}) {
          expect_honest(solve_vss(p, m, quick), what);
          ++solved;
        }
      }
    }
  }
  EXPECT_GT(refused, 200);
  EXPECT_GT(solved, 50);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10.0);
}

/// Log-uniform in a range (both ends positive).
double draw(std::mt19937_64& rng, const core::Range& r) {
  const double lo = std::max(r.lo, 1e-300);
  std::uniform_real_distribution<double> u(std::log(lo), std::log(r.hi));
  return std::exp(u(rng));
}

TEST(InchwormBounds, ParametersDrawnAcrossTheirWholeRangesGiveFiniteResultsOrAnHonestFailure) {
  const auto start = std::chrono::steady_clock::now();
  std::mt19937_64 rng(1515);
  VssOptions quick;
  quick.max_strokes = 200;
  quick.rtol = 1e-3;  // fixed_rk4: a 1 ms step
  quick.max_steps = 20'000;
  int cases = 0;
  int converged = 0;
  while (cases < 300) {
    Params p;
    p.model = cases % 3 == 0 ? SwapModel::kMass : SwapModel::kInstant;
    p.m = draw(rng, ranges::kMass);
    p.M = p.m * (1.0 + draw(rng, core::closed(1e-12, 1e6)));
    p.L_min = draw(rng, ranges::kLength);
    p.L_max = p.L_min * (1.0 + draw(rng, core::closed(1e-12, 1e6)));
    p.g = draw(rng, ranges::kGravity);
    p.mu = draw(rng, ranges::kFriction);
    p.F = p.mu * p.m * p.g * (1.0 + draw(rng, core::closed(1e-12, 1e6)));
    p.alpha = draw(rng, ranges::kAlpha);
    try {
      validate(p);
    } catch (const core::InputError&) {
      continue;  // a draw past an upper bound (M, L_max or F beyond its range)
    }
    ++cases;
    for (const Method m : {Method::kExact, Method::kRootfind, Method::kAnalytic, Method::kCvode,
                           Method::kOdeint, Method::kGsl, Method::kFixedRk4}) {
      const VssResult r = solve_vss(p, m, quick);
      expect_honest(r, "case " + std::to_string(cases) + " " + method_name(m));
      converged += r.converged ? 1 : 0;
    }
  }
  EXPECT_GT(converged, 300);  // most of the box is solvable
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10.0);
}

TEST(InchwormBounds, EveryIntegratorHonoursTheStrokeBound) {
  for (const Method m :
       {Method::kAnalytic, Method::kCvode, Method::kOdeint, Method::kGsl, Method::kCvodeBdf,
        Method::kOdeintRkf78, Method::kGslRkf45, Method::kGslMsadams, Method::kFixedRk4}) {
    for (const SwapModel model : {SwapModel::kInstant, SwapModel::kMass}) {
      Params p;
      p.model = model;
      p.F = 73.575;
      p.mu = 0.05;  // slow convergence: 8 strokes are far from enough
      VssOptions opt;
      opt.rtol = 1e-4;  // fixed_rk4: a 1e-4 s step
      opt.max_strokes = 8;
      const VssResult r = solve_vss(p, m, opt);
      EXPECT_FALSE(r.converged) << method_name(m);
      EXPECT_EQ(r.strokes, 8) << method_name(m) << ": " << r.message;
    }
  }
}

TEST(InchwormBounds, EveryIntegratorStopsAtItsStepBudgetAndSaysSo) {
  for (const Method m :
       {Method::kAnalytic, Method::kCvode, Method::kOdeint, Method::kGsl, Method::kCvodeBdf,
        Method::kOdeintRkf78, Method::kGslRkf45, Method::kGslMsadams, Method::kFixedRk4}) {
    VssOptions opt;
    opt.rtol = 1e-4;
    opt.max_steps = 5;
    const VssResult r = solve_vss(Params{}, m, opt);
    EXPECT_FALSE(r.converged) << method_name(m);
    EXPECT_NE(r.message.find("step budget of 5 steps"), std::string::npos)
        << method_name(m) << ": " << r.message;
    EXPECT_LE(r.stats.steps, 6) << method_name(m);  // CVODE's own count may be one ahead
  }
}

TEST(InchwormBounds, AFixedStepTooSmallForTheBudgetIsRefusedUpFront) {
  VssOptions opt;
  opt.rtol = 1e-12;  // fixed_rk4: ~1.3e11 steps a stroke
  try {
    check_fixed_step_budget(Params{}, Method::kFixedRk4, opt, 8.0, "--rtol");
    ADD_FAILURE() << "not refused";
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.where(), "--rtol");
    EXPECT_NE(std::string(e.what()).find("step budget"), std::string::npos) << e.what();
  }
  // Other methods, and a step the budget pays for, pass.
  EXPECT_NO_THROW(check_fixed_step_budget(Params{}, Method::kCvode, opt, 8.0, "--rtol"));
  opt.rtol = 1e-4;
  EXPECT_NO_THROW(check_fixed_step_budget(Params{}, Method::kFixedRk4, opt, 8.0, "--rtol"));
}

std::size_t lines(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

TEST(InchwormBounds, EveryMethodTracesAtMostOneSampleRowPerDtAndWithinTheEstimate) {
  TraceOptions opt;
  opt.cycles = 2;
  opt.sample_dt = 1e-2;
  opt.rtol = 1e-5;  // fixed_rk4: a 1e-5 s step, 25,000 steps over the trace
  const TraceSize size = estimate_trace_size(Params{}, opt);
  for (const Method m :
       {Method::kAnalytic, Method::kCvode, Method::kOdeint, Method::kGsl, Method::kCvodeBdf,
        Method::kOdeintRkf78, Method::kGslRkf45, Method::kGslMsadams, Method::kFixedRk4}) {
    std::ostringstream out;
    write_trace(Params{}, m, opt, out);
    const std::size_t rows = lines(out.str()) - 1;
    EXPECT_GT(rows, 20U) << method_name(m);
    EXPECT_LE(static_cast<double>(rows), size.rows) << method_name(m);
  }
}

TEST(InchwormBounds, ATraceStopsAtItsRowBound) {
  TraceOptions opt;
  opt.max_rows = 10;
  for (const Method m : {Method::kAnalytic, Method::kCvode, Method::kFixedRk4}) {
    opt.rtol = m == Method::kFixedRk4 ? 1e-4 : 1e-10;
    std::ostringstream out;
    try {
      write_trace(Params{}, m, opt, out);
      ADD_FAILURE() << method_name(m) << ": no row bound";
    } catch (const core::ComputationError& e) {
      EXPECT_NE(std::string(e.what()).find("row bound of 10 rows"), std::string::npos) << e.what();
    }
    EXPECT_LE(lines(out.str()), 11U) << method_name(m);
  }
}

TEST(InchwormBounds, ATraceEstimatedPastItsRowBoundIsRefusedNamingDt) {
  TraceOptions opt;
  opt.cycles = 100;
  opt.sample_dt = 1e-7;  // 100 cycles of 0.25 s: 2.5e8 rows
  try {
    check_trace_size(Params{}, Method::kAnalytic, opt);
    ADD_FAILURE() << "not refused";
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.where(), "--dt");
    EXPECT_NE(std::string(e.what()).find("2.5e+08 rows"), std::string::npos) << e.what();
  }
  opt.sample_dt = 1e-3;
  EXPECT_NO_THROW(check_trace_size(Params{}, Method::kAnalytic, opt));
}

}  // namespace
}  // namespace slipwalk::inchworm
