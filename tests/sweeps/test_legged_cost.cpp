// The timed cost-and-accuracy point (sweeps/points/legged_cost.cpp): check() rejects bad keys
// naming them; on small cases (a hexapod and a 12-leg disk, a few random frames) each friction
// solver's error against the tight Coulomb reference shrinks as its knob tightens — the Coulomb
// solver's certificate target tol and the ε of eq. 3.14 — monotone within a factor, and the rows
// other than the timings are deterministic. No speed is asserted: of the timings only that they
// are positive and that their quartiles bracket their median.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "sweeps/engine/point_kind.hpp"
#include "sweeps/engine/spec.hpp"
#include "sweeps/points/families.hpp"

namespace slipwalk::sweeps {
namespace {

const PointKind& fn() {
  const PointKind* f = find_point_kind(points::all_kinds(), "legged_cost");
  if (f == nullptr) {
    throw std::runtime_error("no point kind legged_cost");
  }
  return *f;
}

std::vector<Point> points(const std::string& body) {
  return expand(
      parse_spec("study = \"t\"\nname = \"t\"\nkind = \"legged_cost\"\n" + body, "cost.toml"));
}

std::size_t col(const std::string& name) {
  const auto c = fn().column_names();
  const auto it = std::find(c.begin(), c.end(), name);
  if (it == c.end()) {
    throw std::runtime_error("no column " + name);
  }
  return static_cast<std::size_t>(it - c.begin());
}

double num(const Cells& r, const std::string& name) {
  const Cell& c = r[col(name)];
  if (const auto* d = std::get_if<double>(&c)) {
    return *d;
  }
  return static_cast<double>(std::get<long long>(c));
}

/// The single row of each point, checked first.
std::vector<Cells> run(const std::string& body) {
  std::vector<Cells> rows;
  for (const Point& p : points(body)) {
    fn().check(p);
    PointResult r = fn().run(p);
    EXPECT_FALSE(r.failed) << r.message;
    EXPECT_EQ(r.rows.size(), 1u);
    EXPECT_EQ(r.rows.at(0).size(), fn().columns.size());
    rows.push_back(r.rows.at(0));
  }
  return rows;
}

const std::vector<std::string> kRobots = {"robot = \"hexapod\"\n", "robot = \"disk\"\nN = 12\n"};

TEST(LeggedCost, RejectsBadKeysNamingThem) {
  const auto rejects = [](const std::string& body, const std::string& key) {
    const std::vector<Point> pts = points(body);
    ASSERT_EQ(pts.size(), 1u);
    try {
      fn().check(pts[0]);
      ADD_FAILURE() << "accepted: " << body;
    } catch (const core::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  };
  rejects("[params]\nmethod = \"coulomb\"\neps = 0.1\n", "eps");
  rejects("[params]\nmethod = \"epsilon\"\n", "eps");
  rejects("[params]\nmethod = \"epsilon\"\neps = 0.0\n", "eps");
  rejects("[params]\nmethod = \"viscous\"\ntol = 1e-9\n", "tol");
  rejects("[params]\nmethod = \"newton\"\n", "method");
  rejects("[params]\nrobot = \"hexapod\"\nN = 8\n", "N");
  rejects("[params]\nrobot = \"disk\"\n", "N");
  rejects("[params]\nrobot = \"disk\"\nN = 2\n", "N");
  rejects("[params]\nframes = 0\n", "frames");
  rejects("[params]\nlegs = 6\n", "legs");
  rejects("[params]\nrobot = \"disk\"\nN = 6\nsequence = \"trajectory\"\n", "sequence");
  rejects("[params]\nsequence = \"walk\"\n", "sequence");
  rejects("[params]\nsequence = \"trajectory\"\nspeed = 0.2\n", "speed");
  // The batched methods take independent frames only.
  rejects("[params]\nsequence = \"trajectory\"\nmethod = \"model_batch\"\n", "method");
  rejects("[params]\nsequence = \"trajectory\"\nmethod = \"support_batch\"\n", "method");
}

// The batched rows are the one-per-call rows' frames solved four per call: the same frames and
// contacts, the support's Newton steps per frame (the batch's start is the one-frame route's
// below 20 legs, so the same steps to within a refinement), and a time of their own.
TEST(LeggedCost, BatchedRowsSolveTheSameFramesFourPerCall) {
  for (const std::string& robot : kRobots) {
    const std::vector<Cells> rows =
        run("[params]\n" + robot + "frames = 13\nrepeats = 2\nseed = 3\n" +
            "[axes]\nmethod = [\"support\", \"support_batch\", \"model\", \"model_batch\"]\n");
    ASSERT_EQ(rows.size(), 4u);
    for (const Cells& r : rows) {
      EXPECT_EQ(num(r, "contacts_mean"), num(rows[0], "contacts_mean")) << robot;
      EXPECT_NEAR(num(r, "newton_steps_mean"), num(rows[0], "newton_steps_mean"), 0.2) << robot;
      EXPECT_EQ(num(r, "unconverged"), 0.0);
      EXPECT_GT(num(r, "time_ns"), 0.0);
      EXPECT_TRUE(std::isnan(num(r, "err_v_max")));  // no friction error for the stages
    }
    EXPECT_EQ(num(rows[1], "iterations_mean"), num(rows[0], "iterations_mean")) << robot;
  }
}

// Coulomb to a relative duality gap tol: the error against the 1e-14 reference falls as tol
// tightens. The gap bounds D(v) − D(v*), which grows at least quadratically away from a smooth
// minimum, so ‖Δv‖ ≲ √tol (and ~tol at a kink, a static foot); allow a factor 10 for the
// non-monotone steps of an active-set method (one more polish step can land anywhere below tol).
TEST(LeggedCost, CoulombErrorShrinksAsTolTightens) {
  for (const std::string& robot : kRobots) {
    const std::vector<Cells> rows =
        run("[params]\nmethod = \"coulomb\"\nframes = 6\nrepeats = 1\nseed = 3\n" + robot +
            "[axes]\ntol = { logspace = [1e-2, 1e-12], n = 6 }\n");
    ASSERT_EQ(rows.size(), 6u);
    double prev_v = INFINITY;
    double prev_F = INFINITY;
    for (const Cells& r : rows) {
      const double tol = num(r, "tol");
      const double ev = num(r, "err_v_max");
      const double eF = num(r, "err_F_max");
      SCOPED_TRACE(robot + " tol " + std::to_string(tol));
      EXPECT_EQ(num(r, "error_frames") + num(r, "nonunique") + num(r, "ref_unconverged"), 6.0);
      EXPECT_GE(num(r, "error_frames"), 4.0);
      EXPECT_EQ(num(r, "unconverged"), 0.0);
      EXPECT_LE(ev, 10.0 * prev_v + 1e-12);
      EXPECT_LE(eF, 10.0 * prev_F + 1e-12);
      EXPECT_LE(ev, 10.0 * std::sqrt(tol));
      prev_v = ev;
      prev_F = eF;
    }
    // The gap weighs a foot by its load, the force error does not (a lightly loaded foot's force
    // direction costs little dissipation): no rate for it, but it must vanish too.
    EXPECT_LT(num(rows.back(), "err_v_max"), 1e-5);
    EXPECT_LT(num(rows.back(), "err_F_max"), 1e-6);
  }
}

// The ε-family of eq. 3.14 tends to Coulomb friction as ε → 0 (and to viscous-Coulomb as
// ε → ∞): its error against the Coulomb reference falls with ε, monotone within a factor, from
// about the viscous-Coulomb error at ε = 10 m/s (≫ the feet's 0.1 m/s). Rate: the force
// magnitude s φ(s) = s (ε + s)/(ε + s²) is ≈ s²/ε for ε ≪ s ≪ √ε and reaches Coulomb's 1 only
// for s ≫ √ε, so a foot that Coulomb friction holds static slips at s ~ √ε: err_v ~ √ε / V.
TEST(LeggedCost, EpsilonErrorShrinksAsEpsilonFallsAndViscousIsTheLimit) {
  for (const std::string& robot : kRobots) {
    const std::string common = "frames = 6\nrepeats = 1\nseed = 3\n" + robot;
    const std::vector<Cells> viscous = run("[params]\nmethod = \"viscous\"\n" + common);
    const std::vector<Cells> rows = run("[params]\nmethod = \"epsilon\"\n" + common +
                                        "[axes]\neps = { logspace = [1e1, 1e-6], n = 8 }\n");
    ASSERT_EQ(rows.size(), 8u);
    const double visc = num(viscous[0], "err_v_median");
    SCOPED_TRACE(robot);
    EXPECT_GT(visc, 1e-3);  // the ansatz is a different law: not a vanishing error
    EXPECT_NEAR(num(rows.front(), "err_v_median"), visc, 0.1 * visc);
    double prev = INFINITY;
    for (const Cells& r : rows) {
      const double eps = num(r, "eps");
      const double e = num(r, "err_v_median");
      EXPECT_LE(e, 3.0 * prev) << "eps " << eps;
      if (eps <= 1e-3) {
        EXPECT_LE(e, 20.0 * std::sqrt(eps)) << "eps " << eps;  // V ≈ 0.1 m/s
      }
      EXPECT_EQ(num(r, "unconverged"), 0.0);
      prev = e;
    }
    // ε / 100 → the error falls ≥ 3× (√100 = 10× at the rate above), and ends far below viscous.
    EXPECT_LE(num(rows[7], "err_v_median"), 0.3 * num(rows[5], "err_v_median"));
    EXPECT_LT(num(rows.back(), "err_v_median"), 0.1 * visc);
  }
}

TEST(LeggedCost, RowsAreDeterministicApartFromTimings) {
  EXPECT_EQ(fn().timed, Timed::kYes);  // the runner runs its points one at a time
  const std::string body =
      "[params]\nrobot = \"disk\"\nN = 12\nframes = 5\nrepeats = 2\n"
      "[axes]\nmethod = [\"viscous\", \"support\", \"model\"]\n";
  const std::vector<Cells> a = run(body);
  const std::vector<Cells> b = run(body);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = 0; j < a[i].size(); ++j) {
      if (fn().columns[j].timing) {
        continue;  // the timings, and only they, vary
      }
      EXPECT_TRUE(a[i][j] == b[i][j] ||
                  (std::holds_alternative<double>(a[i][j]) &&
                   std::isnan(std::get<double>(a[i][j])) && std::isnan(std::get<double>(b[i][j]))))
          << fn().columns[j].name;
    }
    // The frames are the model's own: at least three feet down, some lifted.
    EXPECT_GE(num(a[i], "contacts_min"), 3.0);
    EXPECT_GT(num(a[i], "time_ns"), 0.0);
    EXPECT_LE(num(a[i], "time_ns_p25"), num(a[i], "time_ns"));
    EXPECT_LE(num(a[i], "time_ns"), num(a[i], "time_ns_p75"));
  }
  EXPECT_TRUE(std::isnan(num(a[1], "err_v_max")));  // support: no friction balance
}

// Along the walk (sequence = "trajectory") Coulomb warm-starts from the previous frame: its
// answers are the reference's within the certificate (as independent frames, ‖Δv‖ ≲ √tol), and
// the frames are the walk's own, 3–6 feet down.
TEST(LeggedCost, TrajectoryFramesAreSolvedInOrderWithinTheCertificate) {
  const std::vector<Cells> rows =
      run("[params]\nsequence = \"trajectory\"\nframes = 60\nrepeats = 1\nseed = 4\n"
          "[[block]]\nparams.method = \"coulomb\"\nparams.tol = 1e-9\n"
          "[[block]]\nparams.method = \"viscous\"\n");
  ASSERT_EQ(rows.size(), 2u);
  for (const Cells& r : rows) {
    EXPECT_EQ(std::get<std::string>(r[col("sequence")]), "trajectory");
    EXPECT_EQ(num(r, "unconverged"), 0.0);
    EXPECT_EQ(num(r, "ref_unconverged"), 0.0);
    EXPECT_GE(num(r, "contacts_min"), 3.0);
    EXPECT_GT(num(r, "contacts_max"), 3.0);  // the hand-overs between the tripods
  }
  EXPECT_GE(num(rows[0], "error_frames"), 50.0);
  EXPECT_LE(num(rows[0], "err_v_max"), 10.0 * std::sqrt(1e-9));
  EXPECT_GT(num(rows[1], "err_v_median"), 1e-3);  // viscous-Coulomb: another law
}

// Coulomb's and the ε-family's rows time the viscous-Coulomb balance in the same repeats: a ratio
// whose two times were taken together, within the range of the per-repeat times it is the median
// of (a ratio of medians and the median of ratios agree to within the spread of the repeats);
// the other rows have neither column.
TEST(LeggedCost, FrictionLawsAreTimedAlternatelyWithTheViscousBalance) {
  const std::vector<Cells> rows =
      run("[params]\nrobot = \"hexapod\"\nframes = 40\nrepeats = 5\nseed = 2\n"
          "[[block]]\nparams.method = \"coulomb\"\nparams.tol = 1e-9\n"
          "[[block]]\nparams.method = \"epsilon\"\nparams.eps = 1e-3\nparams.tol = 1e-9\n"
          "[[block]]\naxes.method = [\"viscous\", \"model\"]\n");
  ASSERT_EQ(rows.size(), 4u);
  for (std::size_t i = 0; i < 2; ++i) {
    const double ratio = num(rows[i], "ratio_viscous");
    const double viscous = num(rows[i], "viscous_time_ns");
    ASSERT_TRUE(std::isfinite(ratio) && std::isfinite(viscous)) << i;
    EXPECT_GT(viscous, 0.0);
    // Both solve far more per frame than the viscous ansatz's one 3 × 3 system.
    EXPECT_GT(ratio, 1.0) << i;
    const double low = num(rows[i], "time_ns_p25") / viscous;
    const double high = num(rows[i], "time_ns_p75") / viscous;
    EXPECT_GT(ratio, 0.5 * low) << i;
    EXPECT_LT(ratio, 2.0 * high) << i;
  }
  for (std::size_t i = 2; i < 4; ++i) {
    EXPECT_TRUE(std::isnan(num(rows[i], "ratio_viscous"))) << i;
    EXPECT_TRUE(std::isnan(num(rows[i], "viscous_time_ns"))) << i;
  }
}

}  // namespace
}  // namespace slipwalk::sweeps
