// Sweep specs: axis expansion, product order and ids, [[points]] and [[block]], the [quick] and
// [full] sizes, budget_stops, and bad specs rejected with file:line:col before anything runs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "sweeps/engine/runner.hpp"
#include "sweeps/engine/spec.hpp"
#include "sweeps/engine/study.hpp"
#include "sweeps/points/families.hpp"

namespace slipwalk::sweeps {
namespace {

const std::string kHead = R"(study = "test"
name = "t"
kind = "inchworm_vss"
)";

Spec parse(const std::string& body, bool quick = false) {
  return parse_spec(kHead + body, "spec.toml", quick);
}

/// The InputError's location ("" if none was thrown).
std::string where_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const core::InputError& e) {
    return e.where();
  }
  return "";
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const core::InputError& e) {
    return e.what();
  }
  return "";
}

double num(const Point& p, const char* key) { return p.find(key)->number(); }
std::string text(const Point& p, const char* key) { return p.find(key)->text(); }

TEST(Spec, LinspaceAndLogspaceEndpointsExact) {
  const auto lin = linspace(0.005, 1.0, 80);
  ASSERT_EQ(lin.size(), 80U);
  EXPECT_EQ(lin.front(), 0.005);
  EXPECT_EQ(lin.back(), 1.0);
  EXPECT_NEAR(lin[1] - lin[0], (1.0 - 0.005) / 79, 1e-16);
  const auto geo = logspace(1e-6, 1e-12, 7);
  ASSERT_EQ(geo.size(), 7U);
  EXPECT_EQ(geo.front(), 1e-6);
  EXPECT_EQ(geo.back(), 1e-12);
  for (int i = 0; i < 7; ++i) {
    EXPECT_NEAR(geo[i] / std::pow(10.0, -6 - i), 1.0, 1e-14);
  }
  EXPECT_EQ(linspace(2.0, 3.0, 1), std::vector<double>{2.0});
}

TEST(Spec, AxesFromTheFile) {
  const Spec s = parse(R"(
[axes]
mu = [1.0, 0.2]
F_frac = { linspace = [0.005, 1.0], n = 80 }
F_max = { logspace = [10.0, 1000.0], n = 3 }
method = ["exact", "analytic"]
)");
  const auto points = expand(s);
  ASSERT_EQ(points.size(), 2U * 80U * 3U * 2U);
  EXPECT_EQ(num(points.front(), "F_frac"), 0.005);
  EXPECT_EQ(num(points.back(), "F_frac"), 1.0);
  EXPECT_EQ(num(points.back(), "F_max"), 1000.0);
  EXPECT_NEAR(num(points[2], "F_max"), 100.0, 1e-12);
}

TEST(Spec, ProductOrderFollowsTheFileFirstAxisSlowest) {
  // "z" is written before "a": the written order counts, not the alphabetical one.
  const Spec s = parse(R"(
[params]
rtol = 1e-8
[axes]
z = [1, 2]
a = ["x", "y", "w"]
)");
  const auto points = expand(s);
  ASSERT_EQ(points.size(), 6U);
  const std::vector<std::pair<double, std::string>> expected = {{1, "x"}, {1, "y"}, {1, "w"},
                                                                {2, "x"}, {2, "y"}, {2, "w"}};
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_EQ(points[i].id, static_cast<long long>(i));
    EXPECT_EQ(num(points[i], "z"), expected[i].first);
    EXPECT_EQ(text(points[i], "a"), expected[i].second);
    EXPECT_EQ(num(points[i], "rtol"), 1e-8);
  }
  EXPECT_TRUE(points[0].find("z")->integer);
}

TEST(Spec, PointsTimesAxesAndParamsAsDefaults) {
  const Spec s = parse(R"(
[params]
mu = 0.5
rtol = 1e-9
[[points]]
F = 45.0
mu = 1.0
[[points]]
F = 73.575
[axes]
rtol = [1e-6, 1e-8]
)");
  const auto points = expand(s);
  ASSERT_EQ(points.size(), 4U);
  EXPECT_EQ(num(points[0], "F"), 45.0);
  EXPECT_EQ(num(points[0], "mu"), 1.0);     // the point overrides the param
  EXPECT_EQ(num(points[0], "rtol"), 1e-6);  // the axis overrides the param
  EXPECT_EQ(num(points[1], "rtol"), 1e-8);
  EXPECT_EQ(num(points[2], "F"), 73.575);
  EXPECT_EQ(num(points[2], "mu"), 0.5);  // the param where the point says nothing
  EXPECT_EQ(points[3].id, 3);
}

TEST(Spec, BlocksAreConcatenatedWithContinuingIds) {
  const Spec s = parse(R"(
[params]
F = 45.0
mu = 1.0
[[block]]
params = { method = "analytic" }
axes.rtol = [1e-6, 1e-8, 1e-10]
[[block]]
axes.method = ["exact", "rootfind"]
[[block.points]]
mu = 0.2
)");
  const auto points = expand(s);
  ASSERT_EQ(points.size(), 5U);
  EXPECT_EQ(text(points[0], "method"), "analytic");
  EXPECT_EQ(num(points[2], "rtol"), 1e-10);
  EXPECT_EQ(text(points[3], "method"), "exact");
  EXPECT_EQ(num(points[3], "mu"), 0.2);
  EXPECT_EQ(points[3].find("rtol"), nullptr);
  EXPECT_EQ(points[4].id, 4);
}

TEST(Spec, ParamsOnlyIsOnePoint) {
  const auto points = expand(parse("[params]\nF = 45.0\nmu = 1.0\n"));
  ASSERT_EQ(points.size(), 1U);
  EXPECT_EQ(points[0].id, 0);
}

TEST(Spec, QuickOverrides) {
  const std::string body = R"(
[params]
rtol = 1e-10
[axes]
mu = [1.0, 0.2]
F_frac = { linspace = [0.005, 1.0], n = 80 }
[quick]
axes.F_frac = { linspace = [0.05, 1.0], n = 5 }
params.rtol = 1e-6
)";
  const auto full = expand(parse(body, false));
  const auto quick = expand(parse(body, true));
  ASSERT_EQ(full.size(), 160U);
  ASSERT_EQ(quick.size(), 10U);
  EXPECT_EQ(num(quick[0], "F_frac"), 0.05);
  EXPECT_EQ(num(quick[4], "F_frac"), 1.0);
  EXPECT_EQ(num(quick[5], "mu"), 0.2);  // the axis keeps its place
  EXPECT_EQ(num(quick[0], "rtol"), 1e-6);
  EXPECT_EQ(num(full[0], "rtol"), 1e-10);
  EXPECT_TRUE(parse(body, true).quick());
}

TEST(Spec, FullOverridesAreTheLongVariantAndEachSizeRunsOnlyItsOwn) {
  const std::string body = R"(
[params]
rtol = 1e-10
repeats = 1
[axes]
mu = [1.0, 0.2]
F_frac = { linspace = [0.005, 1.0], n = 8 }
[quick]
axes.F_frac = [0.5]
[full]
axes.F_frac = { linspace = [0.005, 1.0], n = 80 }
params.repeats = 5
)";
  const std::string path = "spec.toml";
  const Spec def = parse_spec(kHead + body, path, Variant::kDefault);
  const Spec quick = parse_spec(kHead + body, path, Variant::kQuick);
  const Spec full = parse_spec(kHead + body, path, Variant::kFull);
  EXPECT_EQ(expand(def).size(), 16U);
  EXPECT_EQ(expand(quick).size(), 2U);
  ASSERT_EQ(expand(full).size(), 160U);
  EXPECT_EQ(num(expand(full)[0], "repeats"), 5.0);
  EXPECT_EQ(num(expand(def)[0], "repeats"), 1.0);
  EXPECT_EQ(num(expand(quick)[0], "repeats"), 1.0);  // [full] does not leak into --quick
  EXPECT_EQ(full.variant, Variant::kFull);
  EXPECT_FALSE(full.quick());
  EXPECT_TRUE(quick.quick());
  // The two sizes not run are kept for prepare() to check.
  ASSERT_EQ(full.others.size(), 2U);
  EXPECT_EQ(full.others[0].variant, Variant::kDefault);
  EXPECT_EQ(full.others[1].variant, Variant::kQuick);
  EXPECT_EQ(expand_other(full, full.others[0]).size(), 16U);
  EXPECT_STREQ(variant_name(Variant::kFull), "full");
  // Without a [full] section --full runs the default values.
  EXPECT_EQ(
      expand(parse_spec(kHead + "[axes]\nmu = [1.0, 0.2]\nF = [45.0]\n", path, Variant::kFull))
          .size(),
      2U);
}

TEST(Spec, ABadValueInAnySizeIsRefusedWhicheverSizeRuns) {
  // A value only [full] sets, out of range: refused by a default and a quick run too, and
  // the message says where it would have run.
  const std::string body = R"(
[params]
F = 45.0
mu = 1.0
[full]
params.rtol = 5.0
)";
  for (const Variant v : {Variant::kDefault, Variant::kQuick, Variant::kFull}) {
    const std::string msg =
        message_of([&] { (void)points::prepare(parse_spec(kHead + body, "spec.toml", v)); });
    EXPECT_NE(msg.find("spec.toml:9:"), std::string::npos) << variant_name(v) << ": " << msg;
    EXPECT_NE(msg.find("rtol"), std::string::npos) << msg;
    if (v != Variant::kFull) {
      EXPECT_NE(msg.find("under --full"), std::string::npos) << msg;
    }
  }
  EXPECT_NE(
      message_of([&] { (void)parse(std::string(body) + "nonesuch = 1\n"); }).find("full.nonesuch"),
      std::string::npos);
  EXPECT_EQ(where_of([&] {
              (void)parse("[params]\nF = 45.0\n[full]\naxes.mu = [1.0]\n");
            }).rfind("spec.toml:7:", 0),
            0U);
}

TEST(Spec, BudgetStopsAreFailuresUnlessTheSpecExpectsThem) {
  EXPECT_FALSE(parse("[params]\nF = 45.0\n").budget_stops_expected);
  EXPECT_TRUE(parse("budget_stops = \"expected\"\n[params]\nF = 45.0\n").budget_stops_expected);
  EXPECT_FALSE(parse("budget_stops = \"failures\"\n[params]\nF = 45.0\n").budget_stops_expected);
  EXPECT_EQ(where_of([&] {
              (void)parse("budget_stops = \"maybe\"\n[params]\nF = 45.0\n");
            }).rfind("spec.toml:4:", 0),
            0U);
}

TEST(Spec, QuickPointsReplaceThePoints) {
  const auto quick = expand(parse(R"(
[[points]]
F = 45.0
[[points]]
F = 50.0
[[points]]
F = 60.0
[quick]
points = [{ F = 45.0 }]
)",
                                  true));
  ASSERT_EQ(quick.size(), 1U);
}

TEST(Spec, MalformedTomlNamesFileLineColumn) {
  const std::string where = where_of([] {
    (void)parse_spec("study = \"a\"\nname = \"b\"\nkind = \"inchworm_vss\"\n[axes]\nmu = [1.0,\n",
                     "bad.toml");
  });
  EXPECT_EQ(where.rfind("bad.toml:", 0), 0U) << where;
  // line:col after the file name
  ASSERT_NE(where.find(':', 9), std::string::npos) << where;
  EXPECT_GE(std::stoi(where.substr(9)), 5) << where;
  EXPECT_EQ(where_of([] { (void)parse_spec("x = = 1\n", "bad.toml"); }), "bad.toml:1:5");
}

TEST(Spec, BadSpecsAreInputErrors) {
  // Unknown top-level key, with its position.
  EXPECT_EQ(where_of([] { (void)parse("\n\nbogus = 1\n"); }), "spec.toml:6:1");
  // Missing required keys.
  EXPECT_NE(
      message_of([] { (void)parse_spec("study = \"a\"\nname = \"b\"\n", "s.toml"); }).find("kind"),
      std::string::npos);
  // A study or name that is no plain file name.
  EXPECT_NE(where_of([] {
              (void)parse_spec("study = \"../x\"\nname = \"b\"\nkind = \"k\"\n", "s.toml");
            }),
            "");
  for (const char* body : {
           "[axes]\nmu = []\n",                                       // empty list
           "[axes]\nmu = [1.0, \"a\"]\n",                             // mixed
           "[axes]\nmu = { linspace = [0.1, 1.0], n = 0 }\n",         // n < 1
           "[axes]\nmu = { linspace = [0.1, 1.0], n = 2.5 }\n",       // n not an integer
           "[axes]\nmu = { linspace = [0.1], n = 3 }\n",              // one end
           "[axes]\nmu = { logspace = [-1.0, 1.0], n = 3 }\n",        // geometric through 0
           "[axes]\nmu = { linspace = [0.1, 1.0], n = 3, k = 1 }\n",  // unknown key
           "[axes]\nmu = 1.0\n",                                      // not a list
           "[axes]\nmu = [true]\n",                                   // not a number or string
           "[axes]\nmu = [nan]\n",                                    // not finite
           "[params]\nmu = [1.0]\n",                                  // a param is one value
           "[[points]]\nmu = 1.0\n[axes]\nmu = [1.0]\n",              // both point and axis
           "[quick]\naxes.nope = [1.0]\n",                            // quick names no axis
           "[axes]\nmu = [1.0]\n[quick]\nparams.mu = 1.0\n",          // quick param over an axis
           "[quick]\nbogus = 1\n",                                    // unknown quick key
           "[[block]]\nbogus = 1\n",                                  // unknown block key
           "[axes]\na = { linspace = [0, 1], n = 10000 }\nb = { linspace = [0, 1], n = 10000 }\n",
       }) {
    const std::string where = where_of([&] { (void)parse(body); });
    EXPECT_EQ(where.rfind("spec.toml", 0), 0U) << body << " -> '" << where << "'";
  }
}

TEST(Spec, UnknownKindAndUnknownKeyBeforeAnyPointRuns) {
  const std::string kind = where_of([] {
    (void)points::prepare(parse_spec("study = \"a\"\nname = \"b\"\nkind = \"nope\"\n", "s.toml"));
  });
  EXPECT_EQ(kind, "s.toml:3:8");
  const std::string message =
      message_of([] { (void)points::prepare(parse("[params]\nmu = 1.0\nForce = 45.0\n")); });
  EXPECT_NE(message.find("spec.toml:6:9"), std::string::npos) << message;
  EXPECT_NE(message.find("Force"), std::string::npos) << message;
}

TEST(Spec, ValueOutOfRangeAtOnePointIsReportedWithKeyAndPoint) {
  struct Case {
    std::string body, key, where;
  };
  for (const Case& c : std::vector<Case>{
           {"[params]\nF = 45.0\n[axes]\nmu = [1.0, 0.5, -0.2]\n", "mu", "spec.toml:7:17"},
           {"[params]\nmu = 1.0\n[axes]\nF_frac = [0.5, 1.5]\n", "F_frac", "spec.toml:7:16"},
           {"[params]\nmu = 1.0\n[axes]\nF = [45.0, 9.81]\n", "F", "spec.toml:7:12"},
           {"[params]\nmu = 1.0\nF = 45.0\nF_frac = 0.5\n", "", "spec.toml"},
           {"[params]\nmu = 1.0\nF = 45.0\nmethod = \"euler\"\n", "method", "spec.toml:7:10"},
           {"[params]\nmu = 1.0\nF = 45.0\nrtol = 0\n", "rtol", "spec.toml:7:8"},
           {"[params]\nmu = 1.0\nF = 45.0\nstop = \"never\"\n", "stop", "spec.toml:7:8"},
           {"[params]\nmu = 1.0\nF = 45.0\nmax_strokes = 10.5\n", "max_strokes", ""},
           {"[params]\nmu = 1.0\nF = 45.0\nmu_s = 0.5\n", "mu_s", "spec.toml:7:8"},
           {"[params]\nmu = \"one\"\nF = 45.0\n", "mu", "spec.toml:5:6"},
           {"[params]\nmu = 1.0\nF_frac = 0.5\nF_lo = \"nope\"\n", "F_lo", ""},
           {"[params]\nmu = 1.0\nF = 45.0\nF_lo = \"muMg\"\n", "F_lo", ""},
       }) {
    const std::string message = message_of([&] { (void)points::prepare(parse(c.body)); });
    EXPECT_EQ(message.rfind(c.where, 0), 0U) << c.body << " -> " << message;
    EXPECT_NE(message.find(c.key), std::string::npos) << c.body << " -> " << message;
    EXPECT_NE(message.find("point"), std::string::npos) << c.body << " -> " << message;
  }
}

TEST(Spec, ConvergenceKindNeedsCyclesAndTheExactBackend) {
  const std::string head = "study = \"a\"\nname = \"b\"\nkind = \"inchworm_convergence\"\n";
  EXPECT_NO_THROW(
      (void)points::prepare(parse_spec(head + "[params]\nF = 45.0\nmu = 1.0\ncycles = 10\n", "s")));
  EXPECT_NE(
      where_of([&] { (void)points::prepare(parse_spec(head + "[params]\nF = 45.0\n", "s")); }), "");
  EXPECT_NE(where_of([&] {
              (void)points::prepare(
                  parse_spec(head + "[params]\nF = 45.0\ncycles = 10\nmethod = \"cvode\"\n", "s"));
            }),
            "");
  EXPECT_NE(where_of([&] {
              (void)points::prepare(
                  parse_spec(head + "[params]\nF = 45.0\ncycles = 10\nrtol = 1e-6\n", "s"));
            }),
            "");
}

TEST(Spec, ForceRanges) {
  // F_frac over [F_lo, F_max]: from mu_s m g by default, from mu_s M g with F_lo = "muMg".
  const auto p = points::prepare(parse(R"(
[params]
method = "exact"
F_lo = "muMg"
F_lo_factor = 1.0001
[axes]
mu = [0.05, 1.0]
F_frac = [0.0, 1.0]
)"));
  ASSERT_EQ(p.points.size(), 4U);
  const PointResult first = p.kind->run(p.points[0]);
  const PointResult last = p.kind->run(p.points[3]);
  const auto cell = [](const PointResult& r, int i) { return std::get<double>(r.rows[0][i]); };
  EXPECT_NEAR(cell(first, 3), 1.0001 * 0.05 * 1.5 * 9.81, 1e-13);  // F
  EXPECT_NEAR(cell(first, 4), 1.0001, 1e-13);                      // f_tilde
  EXPECT_EQ(std::get<long long>(first.rows[0][13]), 2);            // regime II
  EXPECT_NEAR(cell(last, 3), 5 * 1.5 * 9.81, 1e-12);
  EXPECT_NEAR(cell(last, 4), 5.0, 1e-13);
}

/// The column of `name` in the inchworm_vss output.
std::size_t column(const PreparedSweep& p, const std::string& name) {
  const auto cols = p.kind->column_names();
  const auto it = std::find(cols.begin(), cols.end(), name);
  EXPECT_NE(it, cols.end()) << name;
  return static_cast<std::size_t>(it - cols.begin());
}

TEST(Spec, VssColumnsEndWithTheModel) {
  const auto p = points::prepare(parse("[params]\nF = 45.0\nmu = 1.0\n"));
  const auto cols = p.kind->column_names();
  ASSERT_GE(cols.size(), 33U);
  // appended after the chapter 2 columns, which keep their places
  EXPECT_EQ(cols[22], "message");
  EXPECT_EQ(cols[23], "model");
  EXPECT_EQ(cols[24], "alpha");
  EXPECT_EQ(cols[25], "swap_stopped");
  EXPECT_EQ(cols[0], "id");
  EXPECT_EQ(cols[13], "regime");
  // then the cost-of-accuracy columns
  EXPECT_EQ(cols[26], "cpu_s");
  EXPECT_EQ(cols[32], "event_times");
}

TEST(Spec, ModelAndAlpha) {
  const auto p = points::prepare(parse(R"(
[params]
mu = 1.0
method = "analytic"
[[points]]
F = 12.0
[[points]]
F = 12.0
model = "dm"
alpha = 1.0
[[points]]
F = 20.0
model = "dm"
alpha = 5.0
)"));
  ASSERT_EQ(p.points.size(), 3U);
  const std::size_t model = column(p, "model");
  const std::size_t alpha = column(p, "alpha");
  const std::size_t stopped = column(p, "swap_stopped");
  const std::size_t converged = column(p, "converged");
  const std::size_t regime = column(p, "regime");
  const PointResult instant = p.kind->run(p.points[0]);
  const PointResult slow = p.kind->run(p.points[1]);
  const PointResult fast = p.kind->run(p.points[2]);
  EXPECT_EQ(std::get<std::string>(instant.rows[0][model]), "instant");
  EXPECT_TRUE(std::isnan(std::get<double>(instant.rows[0][alpha])));
  EXPECT_EQ(std::get<long long>(instant.rows[0][stopped]), 0);
  // alpha F = 12 N <= mu g (2m + dm) = 24.5 N: the m-m body stops and sticks during the swap
  EXPECT_EQ(std::get<std::string>(slow.rows[0][model]), "dm");
  EXPECT_EQ(std::get<double>(slow.rows[0][alpha]), 1.0);
  EXPECT_EQ(std::get<long long>(slow.rows[0][converged]), 1);
  EXPECT_EQ(std::get<long long>(slow.rows[0][stopped]), 1);
  EXPECT_EQ(std::get<long long>(slow.rows[0][regime]), 1);
  // alpha F = 100 N: pushed out of the friction cone, never stuck; F > mu M g: regime II
  EXPECT_EQ(std::get<double>(fast.rows[0][alpha]), 5.0);
  EXPECT_EQ(std::get<long long>(fast.rows[0][converged]), 1);
  EXPECT_EQ(std::get<long long>(fast.rows[0][stopped]), 0);
  EXPECT_EQ(std::get<long long>(fast.rows[0][regime]), 2);
}

TEST(Spec, ModelAndAlphaRejected) {
  struct Case {
    std::string body, key, where;
  };
  for (const Case& c : std::vector<Case>{
           {"[params]\nF = 45.0\nmu = 1.0\nmodel = \"slow\"\n", "model", "spec.toml:7:9"},
           {"[params]\nF = 45.0\nmu = 1.0\nmodel = 1.0\n", "model", "spec.toml:7:9"},
           {"[params]\nF = 45.0\nmu = 1.0\nalpha = 5.0\n", "alpha", "spec.toml:7:9"},
           {"[params]\nF = 45.0\nmu = 1.0\nmodel = \"instant\"\nalpha = 5.0\n", "alpha",
            "spec.toml:8:9"},
           {"[params]\nF = 45.0\nmu = 1.0\nmodel = \"dm\"\n[axes]\nalpha = [1.0, 0.0]\n", "alpha",
            "spec.toml:9:15"},
           {"[params]\nF = 45.0\nmu = 1.0\nmodel = \"dm\"\nalpha = -2.0\n", "alpha",
            "spec.toml:8:9"},
           {"[params]\nF = 45.0\nmu = 1.0\nmodel = \"dm\"\nalpha = \"big\"\n", "alpha",
            "spec.toml:8:9"},
       }) {
    const std::string message = message_of([&] { (void)points::prepare(parse(c.body)); });
    EXPECT_EQ(message.rfind(c.where, 0), 0U) << c.body << " -> " << message;
    EXPECT_NE(message.find(c.key), std::string::npos) << c.body << " -> " << message;
    EXPECT_NE(message.find("point"), std::string::npos) << c.body << " -> " << message;
  }
  // the convergence kind is the instant model's only
  const std::string head = "study = \"a\"\nname = \"b\"\nkind = \"inchworm_convergence\"\n";
  EXPECT_NE(where_of([&] {
              (void)points::prepare(parse_spec(
                  head + "[params]\nF = 45.0\nmu = 1.0\ncycles = 10\nmodel = \"dm\"\n", "s"));
            }),
            "");
}

/// Every study spec in the repository loads and checks, full and quick.
TEST(Spec, StudySpecsLoad) {
  const std::filesystem::path dir = std::filesystem::path(SLIPWALK_SOURCE_DIR) / "studies";
  // Every sweep spec a study lists (a study folder may also hold scenes and robot files).
  int specs = 0;
  for (const auto& study_dir : find_studies(dir)) {
    for (const auto& spec : load_study(study_dir).sweeps) {
      ++specs;
      for (bool quick : {false, true}) {
        const PreparedSweep p = points::prepare(load_spec(spec, quick));
        EXPECT_GT(p.points.size(), 0U) << spec;
        if (quick) {
          EXPECT_LE(p.points.size(), 200U) << spec;
        }
      }
    }
  }
  EXPECT_GE(specs, 9);
  const auto count = [&](const char* name) {
    return point_count(load_spec(dir / "ch2_inchworm" / name));
  };
  // Blocks add up: regime I for each mu (25 F x 2 methods), then regime II (2 mu x 60 F x 2).
  EXPECT_EQ(count("fig2_3.toml"), 2U * 25U * 2U + 2U * 60U * 2U);
  EXPECT_EQ(count("scaling.toml"), 5U * 50U);
  EXPECT_EQ(count("regression.toml"), 20U * 40U);
  EXPECT_EQ(count("eq2_6_map.toml"), 40U * 60U);
  EXPECT_EQ(count("hard_cases.toml"), 8U * 6U);
  EXPECT_EQ(count("cost.toml"), 2U * 4U * 7U + 2U * 2U);
  EXPECT_EQ(count("convergence.toml"), 2U);
  // §2.5: per mu, regime I (12 F) and regime II (30 F) x alpha 1, 5, 10 x analytic, exact; the
  // instant swap by its closed form on the same forces; the regime maps 40 F x 40 alpha x 2.
  const auto dm = [&](const char* name, bool quick) {
    return point_count(load_spec(dir / "ch2_dm_swap" / name, quick));
  };
  EXPECT_EQ(dm("fig2_7.toml", false), 3U * (12U + 30U) * 3U * 2U + 3U * (12U + 30U));
  EXPECT_EQ(dm("fig2_7.toml", true), 3U * (3U + 3U) * 3U * 2U + 3U * (3U + 3U));
  EXPECT_EQ(dm("regime_map.toml", false), 3U * 40U * 40U * 2U);
  EXPECT_EQ(dm("regime_map.toml", true), 3U * 5U * 6U * 2U);
}

}  // namespace
}  // namespace slipwalk::sweeps
