// The multi-legged model's point kinds (sweeps/points/legged_laws.cpp and legged_frames.cpp):
// check() rejects bad keys and values naming the spec key; run() gives the known answers on tiny
// cases (§3.1.2: Coulomb = −median, viscous-Coulomb = −mean; §3.6.2: the single-foot force errors
// in closed form).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "cli/command.hpp"
#include "contact/frame_json.hpp"
#include "contact/spring_support.hpp"
#include "core/error.hpp"
#include "support/point_rows.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/spec.hpp"
#include "sweeps/points/families.hpp"

namespace slipwalk::sweeps {
namespace {

using testing::ScratchDir;
using testing::write_text;

/// The points of a spec text (kind and body given); `path` names the spec file.
std::vector<Point> points(const std::string& kind, const std::string& body,
                          const std::string& path = "legged.toml") {
  const std::string text = "study = \"t\"\nname = \"t\"\nkind = \"" + kind + "\"\n" + body;
  return expand(parse_spec(text, path));
}

const PointKind& fn(const std::string& name) { return test_support::point_kind(name); }

/// Checks then runs every point; the rows of all points.
std::vector<Cells> run_all(const std::string& kind, const std::vector<Point>& pts) {
  std::vector<Cells> rows;
  for (const Point& p : pts) {
    fn(kind).check(p);
    PointResult r = fn(kind).run(p);
    EXPECT_FALSE(r.failed) << r.message;
    for (auto& row : r.rows) {
      EXPECT_EQ(row.size(), fn(kind).columns.size());
      rows.push_back(std::move(row));
    }
  }
  return rows;
}

std::size_t col(const std::string& kind, const std::string& name) {
  return test_support::column(fn(kind), name);
}

double num(const Cells& row, std::size_t i) {
  if (const auto* d = std::get_if<double>(&row[i])) {
    return *d;
  }
  return static_cast<double>(std::get<long long>(row[i]));
}
std::string str(const Cells& row, std::size_t i) { return std::get<std::string>(row[i]); }

/// check() throws an InputError whose message names `key` and a file:line:col or the file.
void expect_rejected(const std::string& kind, const std::string& body, const std::string& key,
                     const std::string& path = "legged.toml") {
  const auto pts = points(kind, body, path);
  ASSERT_FALSE(pts.empty());
  bool thrown = false;
  for (const Point& p : pts) {
    try {
      fn(kind).check(p);
    } catch (const core::InputError& e) {
      thrown = true;
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
      EXPECT_NE(e.where().find(path), std::string::npos) << e.where();
    }
  }
  EXPECT_TRUE(thrown) << body;
}

// --- legged_1d --------------------------------------------------------------------------------

TEST(Legged1d, OddNCoulombIsMinusTheMedianViscousMinusTheMean) {
  const auto rows = run_all("legged_1d", points("legged_1d", "[params]\nspeeds = \"5, 0, 1\"\n"));
  ASSERT_EQ(rows.size(), 1u);
  const auto& r = rows[0];
  EXPECT_NEAR(num(r, col("legged_1d", "v_coulomb")), -1.0, 1e-9);
  EXPECT_NEAR(num(r, col("legged_1d", "v_viscous")), -2.0, 1e-12);
  EXPECT_DOUBLE_EQ(num(r, col("legged_1d", "neg_median")), -1.0);
  EXPECT_DOUBLE_EQ(num(r, col("legged_1d", "neg_mean")), -2.0);
  EXPECT_EQ(num(r, col("legged_1d", "in_interval")), 1.0);
  EXPECT_EQ(num(r, col("legged_1d", "unique")), 1.0);
  EXPECT_EQ(num(r, col("legged_1d", "static_feet")), 1.0);  // the median foot sticks
  EXPECT_NEAR(num(r, col("legged_1d", "vy_coulomb")), 0.0, 1e-9);
  EXPECT_NEAR(num(r, col("legged_1d", "w_coulomb")), 0.0, 1e-9);
  EXPECT_NEAR(num(r, col("legged_1d", "w_viscous")), 0.0, 1e-12);
  EXPECT_EQ(str(r, col("legged_1d", "distribution")), "given");
}

TEST(Legged1d, EvenNCoulombIsAnIntervalBetweenTheMiddleSpeeds) {
  const auto rows =
      run_all("legged_1d", points("legged_1d", "[params]\nspeeds = \"0, 1, 3, 5\"\nN = 4\n"));
  ASSERT_EQ(rows.size(), 1u);
  const auto& r = rows[0];
  EXPECT_DOUBLE_EQ(num(r, col("legged_1d", "interval_lo")), -3.0);
  EXPECT_DOUBLE_EQ(num(r, col("legged_1d", "interval_hi")), -1.0);
  EXPECT_EQ(num(r, col("legged_1d", "in_interval")), 1.0);
  const double v = num(r, col("legged_1d", "v_coulomb"));
  EXPECT_GE(v, -3.0 - 1e-9);
  EXPECT_LE(v, -1.0 + 1e-9);
  EXPECT_EQ(num(r, col("legged_1d", "unique")), 0.0);  // a continuum of balances
  EXPECT_NEAR(num(r, col("legged_1d", "v_viscous")), -2.25, 1e-12);
}

TEST(Legged1d, RandomTrialsAreDeterministicAndMatchMedianAndMean) {
  const std::string body =
      "[params]\nseed = 7\ntrials = 20\n[axes]\nN = [3, 4, 9]\n"
      "distribution = [\"uniform\", \"normal\", \"exponential\"]\n";
  const auto a = run_all("legged_1d", points("legged_1d", body));
  const auto b = run_all("legged_1d", points("legged_1d", body));
  ASSERT_EQ(a.size(), 3u * 3u * 20u);
  EXPECT_EQ(a, b);
  for (const Cells& r : a) {
    const double scale = std::max(1.0, num(r, col("legged_1d", "speed_range")));
    EXPECT_EQ(num(r, col("legged_1d", "in_interval")), 1.0);
    EXPECT_NEAR(num(r, col("legged_1d", "v_viscous")), num(r, col("legged_1d", "neg_mean")),
                1e-12 * scale);
    if (static_cast<long long>(num(r, col("legged_1d", "N"))) % 2 == 1) {
      EXPECT_NEAR(num(r, col("legged_1d", "v_coulomb")), num(r, col("legged_1d", "neg_median")),
                  1e-7 * scale);
    }
    EXPECT_NEAR(num(r, col("legged_1d", "w_coulomb")), 0.0, 1e-7 * scale);
    EXPECT_NEAR(num(r, col("legged_1d", "vy_viscous")), 0.0, 1e-12 * scale);
  }
  // Different seeds give different speeds.
  const auto c = run_all("legged_1d", points("legged_1d",
                                             "[params]\nseed = 8\ntrials = 20\n"
                                             "[axes]\nN = [3, 4, 9]\n"
                                             "distribution = [\"uniform\", "
                                             "\"normal\", \"exponential\"]\n"));
  EXPECT_NE(a, c);
}

TEST(Legged1d, CheckRejectsBadKeysAndValues) {
  expect_rejected("legged_1d", "[params]\nN = 3\nmass = 2\n", "unknown key 'mass'");
  expect_rejected("legged_1d", "[params]\nseed = 1\n", "N");
  expect_rejected("legged_1d", "[params]\nN = 0\n", "N");
  expect_rejected("legged_1d", "[params]\nN = 2.5\n", "N");
  expect_rejected("legged_1d", "[params]\nN = 3\ndistribution = \"cauchy\"\n", "distribution");
  expect_rejected("legged_1d", "[params]\nN = 3\nscale = -1\n", "scale");
  expect_rejected("legged_1d", "[params]\nN = 3\ntrials = 0\n", "trials");
  expect_rejected("legged_1d", "[params]\nspeeds = \"1, x\"\n", "speeds");
  expect_rejected("legged_1d", "[params]\nspeeds = \"\"\n", "speeds");
  expect_rejected("legged_1d", "[params]\nspeeds = \"1, 2\"\nseed = 3\n", "seed");
  expect_rejected("legged_1d", "[params]\nspeeds = \"1, 2\"\nN = 3\n", "N");
  expect_rejected("legged_1d", "[params]\nN = \"three\"\n", "N");
}

// --- legged_eps_error ---------------------------------------------------------------------------

/// The row of a grid at δv/|v| = (x, y).
const Cells& at(const std::vector<Cells>& rows, double x, double y) {
  const std::size_t cx = col("legged_eps_error", "dvx");
  const std::size_t cy = col("legged_eps_error", "dvy");
  for (const Cells& r : rows) {
    if (std::abs(num(r, cx) - x) < 1e-12 && std::abs(num(r, cy) - y) < 1e-12) {
      return r;
    }
  }
  throw std::runtime_error("no grid point");
}

TEST(LeggedEpsError, ClosedFormsOfTheSingleFootErrors) {
  const std::string kind = "legged_eps_error";
  const std::size_t e = col(kind, "rel_error");
  // Viscous: F = −u/|v| is parallel to F_C = −u/|u|: the error is ||u|/|v| − 1|.
  const auto visc = run_all(kind, points(kind,
                                         "[params]\nmodel = \"viscous\"\nn = 5\n"
                                         "range = 0.2\nspeed = 2.0\n"));
  ASSERT_EQ(visc.size(), 25u);
  EXPECT_NEAR(num(at(visc, 0.2, 0.0), e), 0.2, 1e-12);
  EXPECT_NEAR(num(at(visc, -0.2, 0.0), e), 0.2, 1e-12);
  EXPECT_NEAR(num(at(visc, 0.0, 0.2), e), std::hypot(1.0, 0.2) - 1.0, 1e-12);
  EXPECT_NEAR(num(at(visc, 0.0, 0.0), e), 0.0, 1e-15);
  // Tangent: second order; along x exact, across x |(1, δ) − (1, δ)/√(1+δ²)|.
  const auto tan = run_all(kind, points(kind,
                                        "[params]\nmodel = \"tangent\"\nn = 5\n"
                                        "range = 0.2\n"));
  EXPECT_NEAR(num(at(tan, 0.2, 0.0), e), 0.0, 1e-15);
  EXPECT_NEAR(num(at(tan, 0.0, 0.2), e), std::hypot(1.0, 0.2) - 1.0, 1e-12);
  // ε-family: ε → ∞ is the viscous ansatz, ε → 0 Coulomb.
  const auto big = run_all(kind, points(kind,
                                        "[params]\nmodel = \"epsilon\"\nepsilon = 1e9\n"
                                        "n = 5\nrange = 0.2\n"));
  EXPECT_NEAR(num(at(big, 0.2, 0.0), e), 0.2, 1e-8);
  const auto small = run_all(kind, points(kind,
                                          "[params]\nmodel = \"epsilon\"\nepsilon = 1e-9\n"
                                          "n = 5\nrange = 0.2\n"));
  EXPECT_NEAR(num(at(small, 0.2, 0.0), e), 0.0, 1e-8);
  // Polar: n radii × angles rows, the largest radius = range.
  const auto polar = run_all(kind, points(kind,
                                          "[params]\nshape = \"polar\"\nn = 3\n"
                                          "angles = 8\nrange = 0.1\n"));
  ASSERT_EQ(polar.size(), 24u);
  EXPECT_NEAR(num(polar.back(), col(kind, "dv_rel")), 0.1, 1e-15);
}

TEST(LeggedEpsError, CheckRejectsBadKeysAndValues) {
  const std::string kind = "legged_eps_error";
  expect_rejected(kind, "[params]\nmodel = \"epsilon\"\n", "epsilon");
  expect_rejected(kind, "[params]\nmodel = \"viscous\"\nepsilon = 1\n", "epsilon");
  expect_rejected(kind, "[params]\nmodel = \"quadratic\"\n", "model");
  expect_rejected(kind, "[params]\nrange = 1.5\n", "range");
  expect_rejected(kind, "[params]\nspeed = 0\n", "speed");
  expect_rejected(kind, "[params]\nangles = 12\n", "angles");
  expect_rejected(kind, "[params]\nshape = \"square\"\n", "shape");
  expect_rejected(kind, "[params]\nn = 1\n", "n");
  expect_rejected(kind, "[params]\nfoo = 1\n", "unknown key 'foo'");
}

// --- legged_force_map ---------------------------------------------------------------------------

// A square robot whose four feet all slide backwards at 1 m/s: both laws balance at v = (1, 0),
// ω = 0, and the feet's rest velocities all sit at that one point.
const std::string kSquare = R"({
  "q": [[0.5, 0.5, -0.1], [0.5, -0.5, -0.1], [-0.5, 0.5, -0.1], [-0.5, -0.5, -0.1]],
  "qdot": [[-1, 0, 0], [-1, 0, 0], [-1, 0, 0], [-1, 0, 0]],
  "K": [10, 10, 10, 10]
})";

TEST(LeggedForceMap, BalancesGridAndRestVelocities) {
  const ScratchDir dir;
  write_text(dir / "square.json", kSquare);
  const std::string kind = "legged_force_map";
  const auto rows =
      run_all(kind, points(kind,
                           "[params]\nrobot = \"square.json\"\nn = 5\neps_n = 3\n"
                           "vx_min = 0.0\nvx_max = 2.0\nvy_min = -1.0\nvy_max = 1.0\n",
                           (dir / "spec.toml").string()));
  int feet = 0, balances = 0, grid = 0;
  for (const Cells& r : rows) {
    const std::string row = str(r, col(kind, "row"));
    if (row == "foot") {
      ++feet;
      EXPECT_DOUBLE_EQ(num(r, col(kind, "vx")), 1.0);
      EXPECT_NEAR(num(r, col(kind, "Fz")), 0.25, 1e-12);
    } else if (row == "balance") {
      ++balances;
      EXPECT_NEAR(num(r, col(kind, "vx")), 1.0, 1e-9);
      EXPECT_NEAR(num(r, col(kind, "vy")), 0.0, 1e-9);
      EXPECT_NEAR(num(r, col(kind, "omega")), 0.0, 1e-9);
      EXPECT_EQ(num(r, col(kind, "converged")), 1.0);
    } else if (row == "grid") {
      ++grid;
      const double vx = num(r, col(kind, "vx"));
      const double vy = num(r, col(kind, "vy"));
      const double expected = str(r, col(kind, "law")) == "viscous"
                                  ? std::hypot(vx - 1.0, vy)  // Σ μ F_z |u| with Σ F_z = 1
                                  : (vx == 1.0 && vy == 0.0 ? 0.0 : 1.0);
      EXPECT_NEAR(num(r, col(kind, "F_norm")), expected, 1e-12) << vx << " " << vy;
    }
  }
  EXPECT_EQ(feet, 4);
  EXPECT_EQ(balances, 2 + 3);
  EXPECT_EQ(grid, 2 * 5 * 5);
}

TEST(LeggedForceMap, CheckRejectsBadKeysAndFiles) {
  const ScratchDir dir;
  write_text(dir / "square.json", kSquare);
  write_text(dir / "bad.json", R"({"q": [[0, 0, -1]], "qdot": [[0, 0, 0]], "K": [-1]})");
  const std::string spec = (dir / "spec.toml").string();
  const std::string kind = "legged_force_map";
  expect_rejected(kind, "[params]\nn = 5\n", "robot", spec);
  expect_rejected(kind, "[params]\nrobot = \"missing.json\"\n", "robot", spec);
  expect_rejected(kind, "[params]\nrobot = \"bad.json\"\n", "K[0]", spec);
  // The robot file goes through the one JSON reader: nesting and duplicate keys are refused.
  write_text(dir / "deep.json", std::string(70000, '[') + std::string(70000, ']'));
  expect_rejected(kind, "[params]\nrobot = \"deep.json\"\n", "deep.json:1:65: JSON nested", spec);
  write_text(dir / "dup.json", R"({"q": [[0, 0, -1]], "qdot": [[0, 0, 0]], "qdot": []})");
  expect_rejected(kind, "[params]\nrobot = \"dup.json\"\n", "dup.json:1:42: duplicate key", spec);
  expect_rejected(kind, "[params]\nrobot = \"square.json\"\nvx_min = 1\n", "vx_max", spec);
  expect_rejected(kind, "[params]\nrobot = \"square.json\"\nvx_min = 1\nvx_max = 0\n", "vx_max",
                  spec);
  expect_rejected(kind, "[params]\nrobot = \"square.json\"\nn = 1\n", "n", spec);
  expect_rejected(kind, "[params]\nrobot = \"square.json\"\ncolor = 1\n", "unknown key", spec);
}

// --- legged_support_path ------------------------------------------------------------------------

TEST(LeggedSupportPath, PathEndsAtTheLibraryBalanceWithConsistentContactSets) {
  const ScratchDir dir;
  // Four legs of different lengths on an irregular quadrilateral (studies/ch3_legged's Fig. 3.4
  // robot): the search starts on one foot, tilts (eqs. 3.11, 3.12) and ends on three.
  const std::string robot = R"({
    "q": [[0.45, 0.25, -0.113], [0.35, -0.3, -0.097], [-0.4, 0.3, -0.238], [-0.45, -0.22, -0.084]],
    "qdot": [[0, 0, 0], [0, 0, 0], [0, 0, 0], [0, 0, 0]],
    "K": [10, 10, 10, 10]
  })";
  write_text(dir / "r.json", robot);
  const std::string kind = "legged_support_path";
  const auto rows =
      run_all(kind, points(kind, "[params]\nrobot = \"r.json\"\n", (dir / "spec.toml").string()));
  contact::FrameInput in = contact::parse_frame_json(robot, "r.json");
  contact::spring_support(in.robot, in.frame);

  int steps = 0;
  const Cells* last_step = nullptr;
  const Cells* result = nullptr;
  for (const Cells& r : rows) {
    const std::string row = str(r, col(kind, "row"));
    if (row == "step") {
      ++steps;
      const std::string mask = str(r, col(kind, "mask"));
      ASSERT_EQ(mask.size(), 4u);
      EXPECT_EQ(std::count(mask.begin(), mask.end(), 'C'), num(r, col(kind, "contacts")));
      EXPECT_EQ(std::count(mask.begin(), mask.end(), '-'), 4 - num(r, col(kind, "contacts")));
      last_step = &r;
    } else if (row == "result") {
      result = &r;
    } else {
      EXPECT_EQ(row, "foot");
    }
  }
  ASSERT_NE(last_step, nullptr);
  ASSERT_NE(result, nullptr);
  EXPECT_EQ(steps, 4);  // the start, two contact changes, the balance
  EXPECT_EQ(str(*result, col(kind, "status")), "balanced");
  EXPECT_DOUBLE_EQ(num(*result, col(kind, "alpha")), in.frame.alpha);
  EXPECT_DOUBLE_EQ(num(*result, col(kind, "beta")), in.frame.beta);
  EXPECT_DOUBLE_EQ(num(*result, col(kind, "z")), in.frame.z);
  // The path ends at the balance, which is also the balance of its own contact set.
  EXPECT_NEAR(num(*last_step, col(kind, "z")), in.frame.z, 1e-12);
  EXPECT_NEAR(num(*last_step, col(kind, "target_z")), in.frame.z, 1e-9);
  EXPECT_NEAR(num(*last_step, col(kind, "target_alpha")), in.frame.alpha, 1e-9);
  EXPECT_NEAR(num(*last_step, col(kind, "target_beta")), in.frame.beta, 1e-9);
  EXPECT_EQ(str(*last_step, col(kind, "mask")), str(*result, col(kind, "mask")));
}

TEST(LeggedSupportPath, CheckRejectsBadKeys) {
  const ScratchDir dir;
  write_text(dir / "r.json", kSquare);
  const std::string spec = (dir / "spec.toml").string();
  expect_rejected("legged_support_path", "[params]\nrobot = \"r.json\"\nn = 3\n", "unknown key",
                  spec);
  expect_rejected("legged_support_path", "[params]\nrobot = 3\n", "robot", spec);
  expect_rejected("legged_support_path", "[params]\n", "robot", spec);
}

}  // namespace
}  // namespace slipwalk::sweeps
