// `slipwalk inchworm vss|trace`: results against the closed form, and every bad input rejected
// with exit code 2, a message naming the option and no output file.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/command.hpp"
#include "core/range.hpp"
#include "inchworm/closed_form.hpp"
#include "inchworm/params.hpp"

namespace slipwalk::testing {
namespace {

double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

std::vector<std::string> concat(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

TEST(CliInchworm, VssJsonMatchesClosedForm) {
  struct Case {
    std::string force, mu, mu_s;
  };
  for (const Case& c : std::vector<Case>{{"45", "1", ""},
                                         {"12", "1", ""},
                                         {"73.575", "0.05", ""},
                                         {"3.5", "0.2", ""},
                                         {"20", "1", "1.3"}}) {
    std::vector<std::string> args = {"inchworm", "vss", "--force", c.force, "--mu", c.mu, "--json"};
    inchworm::Params p;
    p.F = std::stod(c.force);
    p.mu = std::stod(c.mu);
    if (!c.mu_s.empty()) {
      args.insert(args.end(), {"--mu-s", c.mu_s});
      p.mu_s = std::stod(c.mu_s);
    }
    const CommandResult r = run_slipwalk(args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err, "");
    const auto j = nlohmann::json::parse(r.out);
    const inchworm::SteadyState s = inchworm::steady_state_closed_form(p);
    EXPECT_LE(rel(j.at("v_ss").get<double>(), s.v_ss), 1e-15) << c.force << " " << c.mu;
    EXPECT_LE(rel(j.at("period").get<double>(), s.period), 1e-15);
    EXPECT_LE(rel(j.at("c0").get<double>(), s.c0), 1e-15);
    EXPECT_EQ(j.at("regime"), inchworm::regime_name(s.regime));
    EXPECT_EQ(j.at("method"), "exact");
    EXPECT_EQ(j.at("converged"), true);
    for (const char* key : {"est_error", "strokes", "contraction", "wall_s"}) {
      EXPECT_TRUE(j.contains(key)) << key;
    }
  }
}

TEST(CliInchworm, VssRegimes) {
  const auto one = nlohmann::json::parse(
      run_slipwalk({"inchworm", "vss", "--force", "12", "--mu", "1", "--json"}).out);
  const auto two = nlohmann::json::parse(
      run_slipwalk({"inchworm", "vss", "--force", "45", "--mu", "1", "--json"}).out);
  EXPECT_EQ(one.at("regime"), "I");
  EXPECT_EQ(two.at("regime"), "II");
}

TEST(CliInchworm, VssAnalyticIntegratorConverges) {
  const CommandResult r = run_slipwalk(
      {"inchworm", "vss", "--force", "45", "--mu", "1", "--method", "analytic", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  inchworm::Params p;
  p.F = 45;
  p.mu = 1;
  EXPECT_EQ(j.at("method"), "analytic");
  EXPECT_EQ(j.at("converged"), true);
  EXPECT_GT(j.at("strokes").get<long long>(), 0);
  EXPECT_LE(j.at("est_error").get<double>(), 1e-10);
  EXPECT_LE(rel(j.at("v_ss").get<double>(), inchworm::steady_state_closed_form(p).v_ss), 1e-9);
}

TEST(CliInchworm, VssHumanReadable) {
  const CommandResult r = run_slipwalk({"inchworm", "vss", "--force", "45", "--mu", "1"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* key : {"v_ss", "period", "c0", "regime", "method"}) {
    EXPECT_NE(r.out.find(key), std::string::npos) << key;
  }
  const CommandResult a =
      run_slipwalk({"inchworm", "vss", "--force", "45", "--mu", "1", "--method", "analytic"});
  EXPECT_NE(a.out.find("est_error"), std::string::npos);
  EXPECT_NE(a.out.find("converged"), std::string::npos);
}

TEST(CliInchworm, VssNotConvergedPrintsResultAndExits1) {
  const CommandResult r = run_slipwalk({"inchworm", "vss", "--force", "73.575", "--mu", "0.05",
                                        "--method", "analytic", "--max-strokes", "8", "--json"});
  EXPECT_EQ(r.exit_code, 1);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("converged"), false);
  EXPECT_EQ(j.at("strokes"), 8);
  EXPECT_NE(r.err.find("slipwalk: error: "), std::string::npos);
  EXPECT_NE(r.err.find("no convergence"), std::string::npos);
}

TEST(CliInchworm, VssJsonNamesTheModel) {
  const CommandResult r = run_slipwalk({"inchworm", "vss", "--force", "45", "--mu", "1", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("model"), "instant");
  EXPECT_TRUE(j.at("alpha").is_null());  // the instant model has no swap force
  EXPECT_EQ(j.at("swap_stopped"), false);
  // --model instant is the default, spelled out
  const CommandResult same = run_slipwalk(
      {"inchworm", "vss", "--force", "45", "--mu", "1", "--model", "instant", "--json"});
  ASSERT_EQ(same.exit_code, 0) << same.err;
  EXPECT_EQ(nlohmann::json::parse(same.out).at("v_ss"), j.at("v_ss"));
}

// The dm model of §2.5 at the conditions of Fig. 2.6 (mu = 1): with alpha = 1 the m-m body
// stops and sticks during the swap (alpha F <= mu g (2m + dm) = 24.525 N at F = 12 and 20 N);
// with alpha = 5 it is pushed out of its friction cone and never sticks.
TEST(CliInchworm, VssDmModel) {
  struct Case {
    std::string force, alpha;
    bool stopped;
    std::string regime;
  };
  for (const Case& c : std::vector<Case>{{"12", "1", true, "I"},
                                         {"20", "1", true, "II"},
                                         {"12", "5", false, "I"},
                                         {"20", "5", false, "II"}}) {
    const CommandResult r =
        run_slipwalk({"inchworm", "vss", "--force", c.force, "--mu", "1", "--model", "dm",
                      "--alpha", c.alpha, "--method", "analytic", "--json"});
    ASSERT_EQ(r.exit_code, 0) << c.force << " " << c.alpha << "\n" << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j.at("model"), "dm");
    EXPECT_EQ(j.at("alpha").get<double>(), std::stod(c.alpha));
    EXPECT_EQ(j.at("swap_stopped"), c.stopped) << c.force << " " << c.alpha;
    EXPECT_EQ(j.at("regime"), c.regime) << c.force << " " << c.alpha;
    EXPECT_EQ(j.at("converged"), true);
    EXPECT_GT(j.at("v_ss").get<double>(), 0.0);
  }
  // alpha defaults to 1
  const CommandResult d = run_slipwalk({"inchworm", "vss", "--force", "12", "--mu", "1", "--model",
                                        "dm", "--method", "analytic", "--json"});
  ASSERT_EQ(d.exit_code, 0) << d.err;
  EXPECT_EQ(nlohmann::json::parse(d.out).at("alpha").get<double>(), 1.0);
  // the moving load is slower than the instant swap at the same force
  const auto dm = nlohmann::json::parse(d.out);
  const auto instant = nlohmann::json::parse(
      run_slipwalk({"inchworm", "vss", "--force", "12", "--mu", "1", "--json"}).out);
  EXPECT_NE(dm.at("v_ss").get<double>(), instant.at("v_ss").get<double>());
}

TEST(CliInchworm, VssDmHumanReadable) {
  const CommandResult r = run_slipwalk({"inchworm", "vss", "--force", "12", "--mu", "1", "--model",
                                        "dm", "--alpha", "1", "--method", "analytic"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* key : {"model", "alpha", "swap_stopped"}) {
    EXPECT_NE(r.out.find(key), std::string::npos) << key;
  }
  EXPECT_NE(r.out.find("dm"), std::string::npos);
}

struct BadInput {
  std::vector<std::string> args;  ///< after `inchworm vss|trace`
  std::string option;             ///< must appear in the message
  std::string text = "";          ///< and this too, if not empty
};

const std::vector<std::string> kModel = {"--force", "45", "--mu", "1"};

std::vector<BadInput> bad_model_inputs() {
  return {
      {{"--force", "9.81", "--mu", "1"}, "--force"},  // F = mu m g: m never slides
      {{"--force", "5", "--mu", "1"}, "--force"},
      {{"--force", "-5", "--mu", "1"}, "--force"},
      {{"--force", "45", "--mu", "0"}, "--mu"},
      {{"--force", "45", "--mu", "-0.5"}, "--mu"},
      {{"--force", "45", "--mu", "abc"}, "--mu", "abc"},
      {{"--force", "nan", "--mu", "1"}, "--force", "nan"},
      {{"--force", "inf", "--mu", "1"}, "--force", "inf"},
      {{"--force", "", "--mu", "1"}, "--force"},
      {{"--force", "1.0x", "--mu", "1"}, "--force", "1.0x"},
      {{"--force", "1e999", "--mu", "1"}, "--force"},
      {{"--mu", "1"}, "--force"},  // missing
      {{"--force", "45"}, "--mu"},
      {concat(kModel, {"--mu-s", "0.5"}), "--mu-s"},  // static below dynamic
      {concat(kModel, {"--M", "0.5"}), "--M"},
      {concat(kModel, {"--m", "0"}), "--m"},
      {concat(kModel, {"--L-max", "0.01"}), "--L-max"},
      {concat(kModel, {"--g", "-9.81"}), "--g"},
      {concat(kModel, {"--method", "euler"}), "--method", "euler"},
      {concat(kModel, {"--rtol", "0"}), "--rtol"},
      {concat(kModel, {"--rtol", "1"}), "--rtol"},
      {concat(kModel, {"--rtol", "x"}), "--rtol"},
      // the swap model and its force factor
      {concat(kModel, {"--model", "slow"}), "--model", "slow"},
      {concat(kModel, {"--alpha", "5"}), "--alpha"},  // alpha with the instant model
      {concat(kModel, {"--model", "instant", "--alpha", "5"}), "--alpha"},
      {concat(kModel, {"--model", "dm", "--alpha", "0"}), "--alpha"},
      {concat(kModel, {"--model", "dm", "--alpha", "-1"}), "--alpha"},
      {concat(kModel, {"--model", "dm", "--alpha", "abc"}), "--alpha", "abc"},
      {concat(kModel, {"--model", "dm", "--alpha", "nan"}), "--alpha", "nan"},
      {concat(kModel, {"--model", "dm", "--alpha", "inf"}), "--alpha", "inf"},
      {concat(kModel, {"--model", "dm", "--alpha", ""}), "--alpha"},
      {{"--force", "5", "--mu", "1", "--model", "dm", "--alpha", "2"}, "--force"},
  };
}

void expect_rejected(const CommandResult& r, const BadInput& bad) {
  std::string args;
  for (const auto& a : bad.args) {
    args += " [" + a + "]";
  }
  EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
  EXPECT_EQ(r.err.rfind("slipwalk: error: ", 0), 0U) << args << "\n" << r.err;
  EXPECT_NE(r.err.find(bad.option), std::string::npos) << args << "\n" << r.err;
  if (!bad.text.empty()) {
    EXPECT_NE(r.err.find(bad.text), std::string::npos) << args << "\n" << r.err;
  }
}

TEST(CliInchworm, VssRejectsBadInput) {
  std::vector<BadInput> cases = bad_model_inputs();
  cases.push_back({concat(kModel, {"--stop", "never"}), "--stop"});
  cases.push_back({concat(kModel, {"--estimator", "median"}), "--estimator"});
  cases.push_back({concat(kModel, {"--max-strokes", "2.5"}), "--max-strokes"});
  for (const BadInput& bad : cases) {
    const CommandResult r = run_slipwalk(concat({"inchworm", "vss"}, bad.args));
    expect_rejected(r, bad);
    EXPECT_EQ(r.out, "");
  }
}

TEST(CliInchworm, TraceWritesCsv) {
  const ScratchDir dir;
  const auto out = dir / "trace.csv";
  const CommandResult r = run_slipwalk({"inchworm", "trace", "--force", "45", "--mu", "1",
                                        "--cycles", "2", "--dt", "0.01", "--out", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string text = read_text(out);
  EXPECT_EQ(text.rfind("t,x,y,z,com,xdot,ydot,zdot,comdot,phase,slide_x,slide_y,side,event\n", 0),
            0U);
  EXPECT_NE(text.find("collision_after"), std::string::npos);
  EXPECT_EQ(files_under(dir.path()), std::vector<std::string>{"trace.csv"});  // no temp files

  const CommandResult s = run_slipwalk({"inchworm", "trace", "--force", "45", "--mu", "1",
                                        "--cycles", "2", "--dt", "0.01", "--out", "-"});
  ASSERT_EQ(s.exit_code, 0) << s.err;
  EXPECT_EQ(s.out, text);
}

TEST(CliInchworm, TraceDmModel) {
  const CommandResult r =
      run_slipwalk({"inchworm", "trace", "--force", "12", "--mu", "1", "--model", "dm", "--alpha",
                    "5", "--cycles", "2", "--dt", "0.01", "--out", "-"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("t,x,y,z,com,", 0), 0U);
  EXPECT_NE(r.out.find("arrival_after"), std::string::npos);  // Delta m moved across
  const CommandResult instant = run_slipwalk({"inchworm", "trace", "--force", "12", "--mu", "1",
                                              "--cycles", "2", "--dt", "0.01", "--out", "-"});
  ASSERT_EQ(instant.exit_code, 0) << instant.err;
  EXPECT_EQ(instant.out.find("arrival_after"), std::string::npos);
}

TEST(CliInchworm, TraceRejectsBadInputAndWritesNothing) {
  const ScratchDir dir;
  const auto out = (dir / "trace.csv").string();
  std::vector<BadInput> cases = bad_model_inputs();
  cases.push_back({concat(kModel, {"--cycles", "0"}), "--cycles"});
  cases.push_back({concat(kModel, {"--cycles", "10001"}), "--cycles"});
  cases.push_back({concat(kModel, {"--cycles", "two"}), "--cycles", "two"});
  cases.push_back({concat(kModel, {"--cycles", "1.5"}), "--cycles"});
  cases.push_back({concat(kModel, {"--dt", "0"}), "--dt"});
  cases.push_back({concat(kModel, {"--dt", "-1e-3"}), "--dt"});
  cases.push_back({concat(kModel, {"--dt", "nan"}), "--dt"});
  for (const BadInput& bad : cases) {
    const CommandResult r =
        run_slipwalk(concat(concat({"inchworm", "trace"}, bad.args), {"--out", out}));
    expect_rejected(r, bad);
    EXPECT_FALSE(std::filesystem::exists(out));
    EXPECT_TRUE(files_under(dir.path()).empty());
  }
  // No --out at all.
  expect_rejected(run_slipwalk(concat({"inchworm", "trace"}, kModel)), {{}, "--out"});
  // An --out that cannot be written: under a file, or a folder.
  for (const std::string& bad_out : {std::string("/dev/null/trace.csv"), dir.path().string()}) {
    const CommandResult r =
        run_slipwalk(concat(concat({"inchworm", "trace"}, kModel), {"--out", bad_out}));
    expect_rejected(r, {{"--out", bad_out}, "--out"});
  }
  const auto nested = dir / "file_not_folder";
  write_text(nested, "x");
  const CommandResult r = run_slipwalk(
      concat(concat({"inchworm", "trace"}, kModel), {"--out", (nested / "t.csv").string()}));
  expect_rejected(r, {{}, "--out"});
  EXPECT_EQ(files_under(dir.path()), std::vector<std::string>{"file_not_folder"});
}

TEST(CliInchworm, UsageErrorsExit2) {
  EXPECT_EQ(run_slipwalk({}).exit_code, 2);
  EXPECT_EQ(run_slipwalk({"inchworm"}).exit_code, 2);
  EXPECT_EQ(run_slipwalk({"inchworm", "vss", "--force", "45", "--mu", "1", "--bogus"}).exit_code,
            2);
  EXPECT_EQ(run_slipwalk({"inchworm", "vss", "--help"}).exit_code, 0);
}

}  // namespace
/// The hostile magnitudes of a numeric option, as a user types them.
const std::vector<std::string> kMagnitudes = {"1e-320", "1e-30", "1e-12", "0",   "-1",
                                              "1e12",   "1e30",  "1e308", "inf", "nan"};

/// The range of each numeric option (inchworm::ranges, the table validate() reads).
core::Range range_of(const std::string& option) {
  namespace r = inchworm::ranges;
  const std::vector<std::pair<std::string, core::Range>> table = {{"--m", r::kMass},
                                                                  {"--M", r::kMass},
                                                                  {"--L-min", r::kLength},
                                                                  {"--L-max", r::kLength},
                                                                  {"--g", r::kGravity},
                                                                  {"--mu", r::kFriction},
                                                                  {"--mu-s", r::kFriction},
                                                                  {"--force", r::kForce},
                                                                  {"--alpha", r::kAlpha},
                                                                  {"--rtol", r::kRtol},
                                                                  {"--dt", r::kSampleDt},
                                                                  {"--cycles", r::kCycles},
                                                                  {"--max-strokes", r::kMaxStrokes},
                                                                  {"--max-rows", r::kMaxRows}};
  for (const auto& [name, range] : table) {
    if (name == option) {
      return range;
    }
  }
  return r::kMaxSteps;
}

/// What any command line of `inchworm vss|trace` may end with: exit 0, exit 2 naming the option
/// (a value out of its range: the option itself, and its range when the value is a number), or
/// exit 1 with a message; nothing else.
void expect_bounded_outcome(const CommandResult& r, const std::string& option,
                            const std::string& value, const std::string& what) {
  ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 1 || r.exit_code == 2) << what << "\n" << r.err;
  if (r.exit_code != 0) {
    EXPECT_EQ(r.err.rfind("slipwalk: error: ", 0), 0U) << what << "\n" << r.err;
  }
  const double v = std::strtod(value.c_str(), nullptr);
  const core::Range range = range_of(option);
  if (!range.contains(v)) {
    EXPECT_EQ(r.exit_code, 2) << what << "\n" << r.err;
    EXPECT_NE(r.err.find(option + ": "), std::string::npos) << what << "\n" << r.err;
    // Integer options refuse "1e12" as not an integer; a plain integer gets the range.
    const bool integer = option == "--cycles" || option.starts_with("--max");
    const bool plain = value.find_first_not_of("-0123456789") == std::string::npos;
    if (std::isfinite(v) && (!integer || plain)) {
      EXPECT_NE(r.err.find("must be in " + range.describe()), std::string::npos) << what << "\n"
                                                                                 << r.err;
    }
  }
}

TEST(CliInchworm, EveryNumericOptionAtEveryMagnitudeEndsQuicklyAndHonestly) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<std::string> methods = {"exact",     "rootfind",    "analytic",  "cvode",
                                            "odeint",    "gsl",         "cvode_bdf", "odeint_rkf78",
                                            "gsl_rkf45", "gsl_msadams", "fixed_rk4"};
  const std::vector<std::string> options = {"--force", "--mu",    "--mu-s",        "--m",
                                            "--M",     "--L-min", "--L-max",       "--g",
                                            "--alpha", "--rtol",  "--max-strokes", "--max-steps"};
  std::size_t k = 0;
  for (const std::string& option : options) {
    for (const std::string& value : kMagnitudes) {
      const std::string& method = methods[k++ % methods.size()];  // every method, in turn
      std::vector<std::string> args = {"inchworm", "vss", "--force",  "45",   "--mu",  "1",
                                       "--model",  "dm",  "--method", method, "--json"};
      if (option != "--rtol" && method == "fixed_rk4") {
        args.insert(args.end(), {"--rtol", "1e-3"});  // a 1 ms step
      }
      if (option != "--max-strokes") {
        args.insert(args.end(), {"--max-strokes", "2000"});
      }
      if (option == "--force" || option == "--mu") {
        args.erase(args.begin() + (option == "--force" ? 2 : 4),
                   args.begin() + (option == "--force" ? 4 : 6));
      }
      args.insert(args.end(), {option, value});
      std::string what = option;
      what.append(" ").append(value).append(" --method ").append(method);
      const CommandResult r = run_slipwalk(args);
      expect_bounded_outcome(r, option, value, what);
      if (r.exit_code == 2) {
        continue;
      }
      // A printed result: never converged with a non-finite number (JSON null).
      const auto j = nlohmann::json::parse(r.out);
      if (j.at("converged").get<bool>()) {
        EXPECT_EQ(r.exit_code, 0) << what;
        for (const char* key : {"v_ss", "period", "c0", "est_error"}) {
          EXPECT_TRUE(j.at(key).is_number()) << what << " " << key << "\n" << r.out;
        }
      } else {
        EXPECT_EQ(r.exit_code, 1) << what;
      }
    }
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10.0);
}

TEST(CliInchworm, EveryTraceOptionAtEveryMagnitudeEndsQuicklyAndLeavesAFileOnlyOnSuccess) {
  const auto start = std::chrono::steady_clock::now();
  const ScratchDir dir;
  const auto out = (dir / "trace.csv").string();
  const std::vector<std::string> methods = {"analytic", "cvode", "odeint", "gsl", "fixed_rk4"};
  std::size_t k = 0;
  for (const std::string option :
       {"--force", "--m", "--L-max", "--dt", "--cycles", "--rtol", "--max-rows", "--max-steps"}) {
    for (const std::string& value : kMagnitudes) {
      const std::string& method = methods[k++ % methods.size()];
      std::vector<std::string> args = {"inchworm", "trace", "--mu", "1", "--method", method};
      for (const auto& [name, base] : {std::pair<std::string, std::string>{"--force", "45"},
                                       {"--cycles", "1"},
                                       {"--dt", "0.01"}}) {
        if (name != option) {
          args.insert(args.end(), {name, base});
        }
      }
      if (std::string(option) != "--rtol" && method == "fixed_rk4") {
        args.insert(args.end(), {"--rtol", "1e-4"});
      }
      args.insert(args.end(), {option, value, "--out", out});
      std::string what = option;
      what.append(" ").append(value).append(" --method ").append(method);
      const CommandResult r = run_slipwalk(args);
      expect_bounded_outcome(r, option, value, what);
      if (r.exit_code == 0) {
        const std::string text = read_text(out);
        EXPECT_EQ(text.find("nan"), std::string::npos) << what;
        EXPECT_EQ(text.find("inf"), std::string::npos) << what;
        EXPECT_EQ(files_under(dir.path()), std::vector<std::string>{"trace.csv"}) << what;
        std::filesystem::remove(out);
      } else {
        EXPECT_TRUE(files_under(dir.path()).empty()) << what;  // no file, no temporary
      }
    }
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10.0);
}

TEST(CliInchworm, ARangeRefusalStatesTheRangeAndTheBoundsSayHowToRaiseThem) {
  const CommandResult m =
      run_slipwalk(concat({"inchworm", "vss"}, concat(kModel, {"--m", "1e-320"})));
  EXPECT_EQ(m.exit_code, 2);
  EXPECT_NE(m.err.find("--m: must be in [1e-06, 1000000] kg"), std::string::npos) << m.err;
  const CommandResult rk4 = run_slipwalk(
      concat({"inchworm", "vss"},
             concat(kModel, {"--method", "fixed_rk4", "--rtol", "1e-14", "--max-strokes", "8"})));
  EXPECT_EQ(rk4.exit_code, 2);
  EXPECT_NE(rk4.err.find("--rtol"), std::string::npos) << rk4.err;
  EXPECT_NE(rk4.err.find("--max-steps"), std::string::npos) << rk4.err;
  const CommandResult strokes = run_slipwalk(
      concat({"inchworm", "vss"}, {"--force", "73.575", "--mu", "0.05", "--method", "fixed_rk4",
                                   "--rtol", "1e-4", "--max-strokes", "8"}));
  EXPECT_EQ(strokes.exit_code, 1);
  EXPECT_NE(strokes.err.find("no convergence within 8 strokes (raise --max-strokes)"),
            std::string::npos)
      << strokes.err;
  const CommandResult rows = run_slipwalk(concat(
      {"inchworm", "trace"}, concat(kModel, {"--dt", "1e-7", "--cycles", "100", "--out", "-"})));
  EXPECT_EQ(rows.exit_code, 2);
  EXPECT_EQ(rows.out, "");
  EXPECT_NE(rows.err.find("--dt"), std::string::npos) << rows.err;
  EXPECT_NE(rows.err.find("--max-rows"), std::string::npos) << rows.err;
}

}  // namespace slipwalk::testing
