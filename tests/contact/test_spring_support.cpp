// The spring-support search (thesis §3.3, Alg. 1) against its oracles: the direct minimizer of
// the convex potential U (tests/support/spring_support_oracle.hpp), closed forms of hand cases,
// the balance residuals, invariances of the model, and the sign of the tilt steps (U decreases
// along the recorded path). A fuzz-style test checks that every call returns with a status.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "contact/robot.hpp"
#include "contact/spring_support.hpp"
#include "support/spring_support_oracle.hpp"
#include "support/support_scenes.hpp"

namespace {

using namespace slipwalk::testing::support_scenes;  // NOLINT(google-build-using-namespace)

using slipwalk::contact::foot_height;
using slipwalk::contact::Frame;
using slipwalk::contact::Robot;
using slipwalk::contact::spring_support;
using slipwalk::contact::SupportOptions;
using slipwalk::contact::SupportStep;
using Status = slipwalk::contact::SupportSummary::Status;
using slipwalk::testing::minimize_support_potential;
using slipwalk::testing::support_potential;
using slipwalk::testing::SupportProblem;

// ---- the oracle: random robots ------------------------------------------------------------------

TEST(SpringSupport, RandomRobotsMatchTheConvexMinimizer) {
  std::mt19937_64 rng(20240611);
  int changes = 0;
  int most = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const int n = 3 + static_cast<int>(rng() % 58);  // 3 ... 60 legs
    const Scene s = random_supported(rng, n);
    const auto r = solve(s);
    const Frame& f = r.frame;
    SCOPED_TRACE("trial " + std::to_string(trial) + ", " + std::to_string(n) + " legs");
    ASSERT_EQ(f.support.status, Status::kBalanced) << f.support.message;
    expect_matches_oracle(s, f, "random robot");
    // Balance residuals of the outputs.
    const Balance b = balance(s, f);
    EXPECT_LE(b.force, 1e-10);
    EXPECT_LE(b.moment, 1e-10);
    EXPECT_LE(f.support.residual, 1e-10);
    changes += f.support.iterations;
    most = std::max(most, f.support.iterations);
  }
  std::printf("contact changes: %.2f per robot on average, at most %d\n", changes / 400.0, most);
}

TEST(SpringSupport, StiffnessesOverSixDecadesMatchTheConvexMinimizer) {
  std::mt19937_64 rng(77);
  for (int trial = 0; trial < 100; ++trial) {
    const int n = 3 + static_cast<int>(rng() % 20);
    const Scene s = random_supported(rng, n, 6.0);
    const auto r = solve(s);
    SCOPED_TRACE("trial " + std::to_string(trial));
    ASSERT_EQ(r.frame.support.status, Status::kBalanced);
    expect_matches_oracle(s, r.frame, "K over six decades");
    // Stiff legs with compressions ~1e-6 of the leg heights: the loads are only known to
    // rounding of the heights, which can exceed 1e-10 Mg here.
    EXPECT_LE(r.frame.support.residual, 1e-10 + 100.0 * rounding_floor(s, r.frame));
  }
}

TEST(SpringSupport, ManyLegsMatchTheConvexMinimizer) {
  std::mt19937_64 rng(5);
  for (const int n : {50, 60, 120, 200}) {
    const Scene s = random_supported(rng, n);
    const auto r = solve(s);
    ASSERT_EQ(r.frame.support.status, Status::kBalanced);
    expect_matches_oracle(s, r.frame, "many legs");
    EXPECT_LE(r.frame.support.residual, 1e-10);
  }
}

// ---- closed forms -------------------------------------------------------------------------------

TEST(SpringSupport, SymmetricHexapodOnFlatFeetCarriesMgOverSixEach) {
  const double K = 2000.0;
  const double Mg = 30.0;
  const double qz = -0.12;
  const Scene s = from_feet({{0.25, 0.15, qz},
                             {0.0, 0.2, qz},
                             {-0.25, 0.15, qz},
                             {0.25, -0.15, qz},
                             {0.0, -0.2, qz},
                             {-0.25, -0.15, qz}},
                            {K}, Mg);
  const auto r = solve(s);
  const Frame& f = r.frame;
  EXPECT_EQ(f.support.status, Status::kBalanced);
  EXPECT_EQ(f.support.iterations, 0);
  EXPECT_NEAR(f.alpha, 0.0, 1e-15);
  EXPECT_NEAR(f.beta, 0.0, 1e-15);
  EXPECT_NEAR(f.z, -qz - Mg / (6.0 * K), 1e-15);
  for (int j = 0; j < 6; ++j) {
    EXPECT_EQ(f.contact[j], 1);
    EXPECT_NEAR(f.Fz(j), Mg / 6.0, 1e-12 * Mg);
  }
}

// With exactly three contacts not on a line the loads are statically determined: Mg times the
// barycentric coordinates of the CoM in their triangle, whatever the stiffnesses and heights.
TEST(SpringSupport, ThreeContactsCarryTheBarycentricShares) {
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 200; ++trial) {
    Scene s;
    s.Mg = uniform(rng, 1.0, 100.0);
    s.q.resize(3, 6);
    s.K.resize(6);
    Eigen::Vector3d w;
    do {  // a triangle containing the CoM
      for (int j = 0; j < 3; ++j) {
        s.q(0, j) = uniform(rng, -0.5, 0.5);
        s.q(1, j) = uniform(rng, -0.5, 0.5);
      }
      Eigen::Matrix3d A;
      A << s.q(0, 0), s.q(0, 1), s.q(0, 2), s.q(1, 0), s.q(1, 1), s.q(1, 2), 1.0, 1.0, 1.0;
      w = A.colPivHouseholderQr().solve(Eigen::Vector3d(0.0, 0.0, 1.0));
    } while (w.minCoeff() < 0.05);
    for (int j = 0; j < 6; ++j) {
      s.K(j) = 1000.0 * std::pow(10.0, uniform(rng, 0.0, 2.0));
      s.q(2, j) = -0.1 + uniform(rng, 0.0, 0.01);
    }
    for (int j = 3; j < 6; ++j) {  // three more feet, far up: never touching
      s.q(0, j) = uniform(rng, -0.5, 0.5);
      s.q(1, j) = uniform(rng, -0.5, 0.5);
      s.q(2, j) = 10.0;
    }
    const auto r = solve(s);
    const Frame& f = r.frame;
    ASSERT_EQ(f.support.status, Status::kBalanced);
    for (int j = 0; j < 3; ++j) {
      EXPECT_NEAR(f.Fz(j), s.Mg * w(j), 1e-10 * s.Mg);
      // The compression that carries it (eq. 3.7).
      EXPECT_NEAR(foot_height(f, j, f.alpha, f.beta, f.z), -s.Mg * w(j) / s.K(j),
                  1e-10 * s.Mg / s.K(j));
    }
    for (int j = 3; j < 6; ++j) {
      EXPECT_EQ(f.contact[j], 0);
      EXPECT_EQ(f.Fz(j), 0.0);
    }
  }
}

// A square quadruped (feet at (±1, ±1), K = 1, Mg = 4) with foot 0 raised by Δ: for Δ < Mg/K
// all four feet carry, (Mg − KΔ)/4 on the diagonal of the raised foot and (Mg + KΔ)/4 on the
// other; for Δ ≥ Mg/K it rests on the other diagonal, Mg/2 on each of feet 1 and 3.
TEST(SpringSupport, QuadrupedWithOneFootRaised) {
  const double Mg = 4.0;
  const double K = 1.0;
  for (const double delta : {0.0, 0.5, 1.5, 3.999, 4.0, 4.001, 5.0, 5.5, 8.0, 100.0}) {
    const Scene s = from_feet(
        {{1.0, 1.0, -10.0 + delta}, {-1.0, 1.0, -10.0}, {-1.0, -1.0, -10.0}, {1.0, -1.0, -10.0}},
        {K}, Mg);
    const auto r = solve(s);
    const Frame& f = r.frame;
    SCOPED_TRACE("delta " + std::to_string(delta));
    EXPECT_LE(f.support.residual, 1e-12);
    if (delta < Mg / K) {
      ASSERT_EQ(f.support.status, Status::kBalanced);
      EXPECT_NEAR(f.Fz(0), (Mg - K * delta) / 4.0, 1e-12);
      EXPECT_NEAR(f.Fz(2), (Mg - K * delta) / 4.0, 1e-12);
      EXPECT_NEAR(f.Fz(1), (Mg + K * delta) / 4.0, 1e-12);
      EXPECT_NEAR(f.Fz(3), (Mg + K * delta) / 4.0, 1e-12);
      expect_matches_oracle(s, f, "four feet");
    } else {
      // Resting on the diagonal 1-3: the tilt about it is free between the two other feet.
      EXPECT_TRUE(f.support.status == Status::kBalanced || f.support.status == Status::kLine)
          << slipwalk::contact::status_name(f.support.status);
      EXPECT_NEAR(f.Fz(0), 0.0, 1e-12);
      EXPECT_NEAR(f.Fz(2), 0.0, 1e-12);
      EXPECT_NEAR(f.Fz(1), Mg / 2.0, 1e-12);
      EXPECT_NEAR(f.Fz(3), Mg / 2.0, 1e-12);
      EXPECT_NEAR(f.z, 10.0 - Mg / (2.0 * K), 1e-12);
      EXPECT_GE(foot_height(f, 0, f.alpha, f.beta, f.z), -1e-12);
      EXPECT_GE(foot_height(f, 2, f.alpha, f.beta, f.z), -1e-12);
      expect_matches_oracle_loads(s, f, "diagonal");
    }
  }
}

// ---- degenerate supports ------------------------------------------------------------------------

TEST(SpringSupport, OneFootUnderTheCoMIsAPoint) {
  const Scene s = from_feet({{0.0, 0.0, -0.2}}, {500.0}, 10.0);
  const auto r = solve(s);
  EXPECT_EQ(r.frame.support.status, Status::kPoint);
  EXPECT_NEAR(r.frame.alpha, 0.0, 1e-15);
  EXPECT_NEAR(r.frame.beta, 0.0, 1e-15);
  EXPECT_NEAR(r.frame.z, 0.2 - 10.0 / 500.0, 1e-15);
  EXPECT_NEAR(r.frame.Fz(0), 10.0, 1e-12);
  // With other feet high enough to stay off the ground.
  const Scene t = from_feet({{0.3, 0.1, -0.1}, {0.0, 0.0, -0.2}, {-0.2, 0.2, -0.1}}, {500.0}, 10.0);
  const auto u = solve(t);
  EXPECT_EQ(u.frame.support.status, Status::kPoint);
  EXPECT_NEAR(u.frame.alpha, 0.0, 1e-15);
  EXPECT_NEAR(u.frame.beta, 0.0, 1e-15);
  EXPECT_NEAR(u.frame.Fz(1), 10.0, 1e-12);
  EXPECT_EQ(u.frame.contact[0], 0);
  EXPECT_EQ(u.frame.contact[2], 0);
}

TEST(SpringSupport, OneOrTwoFeetBesideTheCoMTipOver) {
  for (const Scene& s : {from_feet({{0.1, 0.05, -0.2}}, {500.0}, 10.0),
                         from_feet({{0.1, 0.05, -0.2}, {0.1, -0.05, -0.21}}, {500.0, 90.0}, 10.0),
                         from_feet({{0.1, 0.0, -0.2}, {0.3, 0.0, -0.2}}, {500.0}, 10.0)}) {
    const auto r = solve(s);
    EXPECT_EQ(r.frame.support.status, Status::kUnsupported);
    EXPECT_FALSE(r.frame.support.message.empty());
    EXPECT_TRUE(std::isfinite(r.frame.alpha) && std::isfinite(r.frame.beta) &&
                std::isfinite(r.frame.z));
    // Vertical balance still holds where the tipping starts.
    EXPECT_NEAR(r.frame.Fz.sum(), 10.0, 1e-10);
  }
}

TEST(SpringSupport, TwoFeetAroundTheCoMBalanceByTheLeverRule) {
  // CoM between the feet on their line: F_1 = Mg·|q_2|/(|q_1| + |q_2|) whatever the stiffnesses.
  const double Mg = 12.0;
  const Scene s = from_feet({{-0.2, 0.1, -0.1}, {0.4, -0.2, -0.13}}, {300.0, 4000.0}, Mg);
  const auto r = solve(s);
  const Frame& f = r.frame;
  EXPECT_EQ(f.support.status, Status::kLine);
  EXPECT_NEAR(f.Fz(0), Mg * 2.0 / 3.0, 1e-12 * Mg);
  EXPECT_NEAR(f.Fz(1), Mg / 3.0, 1e-12 * Mg);
  EXPECT_LE(f.support.residual, 1e-12);
  // The free tilt about the line is set to the least: (α, β) normal to the line's direction.
  EXPECT_NEAR(f.alpha * 0.6 + f.beta * -0.3, 0.0, 1e-12 * (std::abs(f.alpha) + std::abs(f.beta)));
  expect_matches_oracle_loads(s, f, "two feet");
}

TEST(SpringSupport, CollinearContactsWithTheCoMOnTheirLine) {
  // Three feet on the x axis carry; two side feet are high enough to stay off at zero roll.
  const double Mg = 10.0;
  const double K = 1000.0;
  const Scene s = from_feet({{-0.3, 0.0, -0.1},
                             {0.1, 0.0, -0.1},
                             {0.4, 0.0, -0.102},
                             {0.0, 0.3, -0.05},
                             {0.05, -0.3, -0.05}},
                            {K}, Mg);
  const auto r = solve(s);
  const Frame& f = r.frame;
  EXPECT_EQ(f.support.status, Status::kLine);
  EXPECT_NEAR(f.alpha, 0.0, 1e-15);
  EXPECT_LE(f.support.residual, 1e-12);
  // Closed form on the line: F_k = K (c + β x_k + d_k) with ΣF = Mg, Σ x F = 0, d_k = −q_z,k −
  // offset; solve the 2x2 system for (c, β) with c = −z.
  Eigen::Matrix2d A = Eigen::Matrix2d::Zero();
  Eigen::Vector2d b(Mg, 0.0);
  for (int j = 0; j < 3; ++j) {
    const double x = s.q(0, j);
    A(0, 0) += K;
    A(0, 1) += K * x;
    A(1, 0) += K * x;
    A(1, 1) += K * x * x;
    b(0) += K * s.q(2, j);
    b(1) += K * x * s.q(2, j);
  }
  const Eigen::Vector2d cb = A.inverse() * b;  // (−z, β)
  EXPECT_NEAR(f.z, -cb(0), 1e-14);
  EXPECT_NEAR(f.beta, cb(1), 1e-12);
  expect_matches_oracle_loads(s, f, "collinear, CoM on the line");
}

TEST(SpringSupport, CollinearContactsWithTheCoMOffTheirLineTilt) {
  // Three low feet in a row beside the CoM cannot balance: the body rolls about the row until
  // one of the higher feet on the CoM's side touches down.
  const double Mg = 10.0;
  const Scene caught = from_feet({{-0.3, -0.1, -0.12},
                                  {0.0, -0.1, -0.12},
                                  {0.3, -0.1, -0.12},
                                  {0.2, 0.3, -0.1},
                                  {-0.25, 0.25, -0.1}},
                                 {800.0, 1200.0, 900.0, 1000.0, 700.0}, Mg);
  const auto r = solve(caught, true);
  EXPECT_EQ(r.frame.support.status, Status::kBalanced);
  EXPECT_EQ(r.path.front().contacts, 3);
  EXPECT_LE(r.frame.support.residual, 1e-10);
  expect_matches_oracle(caught, r.frame, "collinear row, caught");
  // Without the catching feet the robot tips.
  Scene alone = caught;
  alone.q.row(2).tail(2).setConstant(5.0);
  alone.q(1, 3) = -0.3;
  alone.q(1, 4) = -0.3;
  EXPECT_EQ(solve(alone).frame.support.status, Status::kUnsupported);
}

TEST(SpringSupport, AllFeetAtOneHeight) {
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 100; ++trial) {
    Scene s = random_supported(rng, 3 + static_cast<int>(rng() % 30));
    s.q.row(2).setConstant(-0.15);
    const auto r = solve(s);
    ASSERT_EQ(r.frame.support.status, Status::kBalanced);
    expect_matches_oracle(s, r.frame, "flat");
    EXPECT_LE(r.frame.support.residual, 1e-10);
  }
}

TEST(SpringSupport, ExactlyTouchingFeetCarryNothing) {
  // Four feet carry Mg at z* = 0 with compression 1; the fifth touches with h = 0 exactly.
  const Scene s = from_feet(
      {{1.0, 1.0, -1.0}, {-1.0, 1.0, -1.0}, {-1.0, -1.0, -1.0}, {1.0, -1.0, -1.0}, {0.5, 0.3, 0.0}},
      {1.0}, 4.0);
  const auto r = solve(s);
  const Frame& f = r.frame;
  EXPECT_EQ(f.support.status, Status::kBalanced);
  EXPECT_EQ(f.z, 0.0);
  EXPECT_EQ(foot_height(f, 4, f.alpha, f.beta, f.z), 0.0);
  EXPECT_EQ(f.contact[4], 0);
  EXPECT_EQ(f.Fz(4), 0.0);
  for (int j = 0; j < 4; ++j) {
    EXPECT_EQ(f.contact[j], 1);
    EXPECT_NEAR(f.Fz(j), 1.0, 1e-15);
  }
  // Random robots with one foot moved to touch the balance plane exactly: the same state.
  std::mt19937_64 rng(17);
  for (int trial = 0; trial < 100; ++trial) {
    Scene t = random_supported(rng, 4 + static_cast<int>(rng() % 10));
    const auto first = solve(t);
    ASSERT_EQ(first.frame.support.status, Status::kBalanced);
    int air = -1;
    for (int j = 0; j < t.legs(); ++j) {
      air = first.frame.contact[j] == 0 ? j : air;
    }
    if (air < 0) {
      continue;
    }
    const Frame& g = first.frame;
    t.q(2, air) -= foot_height(g, air, g.alpha, g.beta, g.z);
    const auto second = solve(t);
    ASSERT_EQ(second.frame.support.status, Status::kBalanced);
    const double Z = height_scale(t, g);
    EXPECT_NEAR(second.frame.z, g.z, 1e-9 * Z);
    EXPECT_NEAR(second.frame.alpha, g.alpha, 1e-9 * Z / size_of(t));
    EXPECT_NEAR(second.frame.beta, g.beta, 1e-9 * Z / size_of(t));
    EXPECT_NEAR(second.frame.Fz(air), 0.0, 1e-9 * t.K(air) * Z);
  }
}

// ---- invariances --------------------------------------------------------------------------------

TEST(SpringSupport, YawOfTheSceneRotatesTheTiltAndKeepsHeightAndLoads) {
  std::mt19937_64 rng(23);
  for (int trial = 0; trial < 100; ++trial) {
    const Scene s = random_supported(rng, 3 + static_cast<int>(rng() % 30));
    const double phi = uniform(rng, -kPi, kPi);
    Scene t = s;
    const Eigen::Rotation2Dd R(phi);
    for (int j = 0; j < s.legs(); ++j) {
      t.q.col(j).head<2>() = R * s.q.col(j).head<2>();
    }
    const auto a = solve(s);
    const auto b = solve(t);
    ASSERT_EQ(a.frame.support.status, Status::kBalanced);
    ASSERT_EQ(b.frame.support.status, Status::kBalanced);
    const double Z = height_scale(s, a.frame);
    const double L = size_of(s);
    // The ground's gradient in the body frame, (−β, α), turns with the feet.
    const Eigen::Vector2d w = R * Eigen::Vector2d(-a.frame.beta, a.frame.alpha);
    EXPECT_NEAR(-b.frame.beta, w(0), 1e-9 * Z / L);
    EXPECT_NEAR(b.frame.alpha, w(1), 1e-9 * Z / L);
    EXPECT_NEAR(b.frame.z, a.frame.z, 1e-9 * Z);
    for (int j = 0; j < s.legs(); ++j) {
      EXPECT_NEAR(b.frame.Fz(j), a.frame.Fz(j), 1e-9 * s.K(j) * Z + 1e-12 * s.Mg);
    }
  }
}

TEST(SpringSupport, ScalingTheStiffnessesScalesTheCompressions) {
  // With all feet at one height every foot height scales by 1/c when K scales by c: the same
  // contacts and loads, tilt / c, compressions / c.
  std::mt19937_64 rng(29);
  for (int trial = 0; trial < 100; ++trial) {
    Scene s = random_supported(rng, 3 + static_cast<int>(rng() % 30));
    s.q.row(2).setConstant(-0.1);
    const double c = std::pow(10.0, uniform(rng, -2.0, 2.0));
    Scene t = s;
    t.K *= c;
    const auto a = solve(s);
    const auto b = solve(t);
    ASSERT_EQ(a.frame.support.status, Status::kBalanced);
    ASSERT_EQ(b.frame.support.status, Status::kBalanced);
    const double Z = height_scale(s, a.frame);
    for (int j = 0; j < s.legs(); ++j) {
      const double ha = foot_height(a.frame, j, a.frame.alpha, a.frame.beta, a.frame.z);
      const double hb = foot_height(b.frame, j, b.frame.alpha, b.frame.beta, b.frame.z);
      EXPECT_NEAR(hb, ha / c, 1e-9 * Z / std::min(c, 1.0));
      EXPECT_NEAR(b.frame.Fz(j), a.frame.Fz(j), 1e-9 * s.K(j) * Z + 1e-12 * s.Mg);
    }
    EXPECT_NEAR(b.frame.alpha, a.frame.alpha / c, 1e-9 * Z / size_of(s) / std::min(c, 1.0));
    EXPECT_NEAR(b.frame.beta, a.frame.beta / c, 1e-9 * Z / size_of(s) / std::min(c, 1.0));
  }
}

TEST(SpringSupport, PermutingTheLegsPermutesTheOutputs) {
  std::mt19937_64 rng(31);
  for (int trial = 0; trial < 100; ++trial) {
    const Scene s = random_supported(rng, 3 + static_cast<int>(rng() % 40));
    std::vector<int> perm(s.legs());
    for (int j = 0; j < s.legs(); ++j) {
      perm[j] = j;
    }
    std::shuffle(perm.begin(), perm.end(), rng);
    Scene t = s;
    for (int j = 0; j < s.legs(); ++j) {
      t.q.col(j) = s.q.col(perm[j]);
      t.K(j) = s.K(perm[j]);
    }
    const auto a = solve(s);
    const auto b = solve(t);
    const double Z = height_scale(s, a.frame);
    EXPECT_NEAR(b.frame.z, a.frame.z, 1e-9 * Z);
    EXPECT_NEAR(b.frame.alpha, a.frame.alpha, 1e-9 * Z / size_of(s));
    EXPECT_NEAR(b.frame.beta, a.frame.beta, 1e-9 * Z / size_of(s));
    for (int j = 0; j < s.legs(); ++j) {
      EXPECT_NEAR(b.frame.Fz(j), a.frame.Fz(perm[j]), 1e-9 * s.K(j) * Z + 1e-12 * s.Mg);
    }
  }
}

// ---- the path: start, monotone potential, tilt directions ---------------------------------------

// z* of §3.3.1 by bisection on the vertical force at zero tilt (independent of the scan).
double initial_height_by_bisection(const Scene& s) {
  auto force = [&s](double z) {
    double f = 0.0;
    for (int j = 0; j < s.legs(); ++j) {
      f += s.K(j) * std::max(-(s.q(2, j) + z), 0.0);
    }
    return f;
  };
  double hi = -s.q.row(2).minCoeff();  // force 0
  double lo = hi - s.Mg / s.K.minCoeff() - 1.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (force(mid) > s.Mg ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

void expect_path_descends(const Scene& s, const Solved& r) {
  ASSERT_GE(r.path.size(), 2U);
  EXPECT_EQ(r.path.front().alpha, 0.0);
  EXPECT_EQ(r.path.front().beta, 0.0);
  EXPECT_NEAR(r.path.front().z, initial_height_by_bisection(s),
              1e-12 * (1.0 + std::abs(r.frame.z)));
  EXPECT_EQ(r.path.front().changed, -1);
  double prev = potential(s, 0.0, 0.0, r.path.front().z);
  const double tol = 1e-12 * (std::abs(prev) + s.Mg * height_scale(s, r.frame));
  for (std::size_t i = 1; i < r.path.size(); ++i) {
    const SupportStep& p = r.path[i];
    const double U = potential(s, p.alpha, p.beta, p.z);
    EXPECT_LE(U, prev + tol) << "step " << i;
    prev = U;
  }
  if (r.frame.support.status != Status::kUnsupported) {
    EXPECT_EQ(r.path.back().alpha, r.frame.alpha);
    EXPECT_EQ(r.path.back().beta, r.frame.beta);
    EXPECT_EQ(r.path.back().z, r.frame.z);
  }
  EXPECT_EQ(static_cast<int>(r.path.size()), r.frame.support.iterations + 2);
}

TEST(SpringSupport, PathStartsAtZStarAndThePotentialDecreasesAlongIt) {
  std::mt19937_64 rng(37);
  for (int trial = 0; trial < 200; ++trial) {
    const Scene s = random_supported(rng, 3 + static_cast<int>(rng() % 30));
    const auto r = solve(s, true);
    SCOPED_TRACE("trial " + std::to_string(trial));
    expect_path_descends(s, r);
  }
}

// Eq. 3.11 as used: one contact at q_1 tilts along (q_y,1, −q_x,1, −r²) in (α, β, z), a positive
// multiple, so the CoM goes down. Eq. 3.12 as used: two contacts rotate along −sign(c)(δx, δy, c).
TEST(SpringSupport, TiltStepsFollowTheCorrectedEquations311And312) {
  std::mt19937_64 rng(41);
  for (int trial = 0; trial < 100; ++trial) {
    // One low foot beside the CoM, three higher feet around it.
    Scene one = random_supported(rng, 4);
    one.K.setConstant(1000.0);
    one.Mg = 10.0;
    one.q.row(2).setConstant(-0.1);
    one.q(2, 0) = -0.2;
    auto r = solve(one, true);
    ASSERT_GE(r.path.size(), 3U);
    ASSERT_EQ(r.path[0].contacts, 1);
    Eigen::Vector3d d(r.path[1].alpha - r.path[0].alpha, r.path[1].beta - r.path[0].beta,
                      r.path[1].z - r.path[0].z);
    const double qx = one.q(0, 0);
    const double qy = one.q(1, 0);
    const Eigen::Vector3d e311(qy, -qx, -(qx * qx + qy * qy));
    EXPECT_NEAR(d.normalized().dot(e311.normalized()), 1.0, 1e-12);
    expect_path_descends(one, r);

    // Two low feet, the CoM off their line, two higher feet.
    Scene two = random_supported(rng, 4);
    two.K.setConstant(1000.0);
    two.Mg = 10.0;
    two.q.row(2).setConstant(-0.1);
    two.q(2, 0) = -0.2;
    two.q(2, 1) = -0.2;
    r = solve(two, true);
    ASSERT_GE(r.path.size(), 3U);
    ASSERT_EQ(r.path[0].contacts, 2);
    d = Eigen::Vector3d(r.path[1].alpha - r.path[0].alpha, r.path[1].beta - r.path[0].beta,
                        r.path[1].z - r.path[0].z);
    const double dx = two.q(0, 0) - two.q(0, 1);
    const double dy = two.q(1, 0) - two.q(1, 1);
    const double c = two.q(1, 0) * two.q(0, 1) - two.q(1, 1) * two.q(0, 0);
    const Eigen::Vector3d e312 = -std::copysign(1.0, c) * Eigen::Vector3d(dx, dy, c);
    EXPECT_NEAR(d.normalized().dot(e312.normalized()), 1.0, 1e-12);
    expect_path_descends(two, r);
  }
}

// ---- never hangs, never crashes -----------------------------------------------------------------

TEST(SpringSupport, FuzzEveryCallReturnsWithAStatus) {
  std::mt19937_64 rng(43);
  int counts[5] = {0, 0, 0, 0, 0};
  for (int trial = 0; trial < 5000; ++trial) {
    const int n = trial % 50 == 0 ? 60 : 1 + static_cast<int>(rng() % 12);
    Scene s;
    s.q.resize(3, n);
    s.K.resize(n);
    s.Mg = std::pow(10.0, uniform(rng, -2.0, 3.0));
    const int kind = static_cast<int>(rng() % 4);
    for (int j = 0; j < n; ++j) {
      s.K(j) = std::pow(10.0, uniform(rng, -1.0, 5.0));
      if (kind == 0) {  // continuous positions
        s.q(0, j) = uniform(rng, -1.0, 1.0);
        s.q(1, j) = uniform(rng, -1.0, 1.0);
        s.q(2, j) = uniform(rng, -1.0, 0.0);
      } else {  // a coarse grid: exact ties, rows, feet on top of each other and under the CoM
        s.q(0, j) = 0.25 * static_cast<double>(static_cast<int>(rng() % 7) - 3);
        s.q(1, j) = 0.25 * static_cast<double>(static_cast<int>(rng() % 7) - 3);
        s.q(2, j) = kind == 1 ? -0.5 : -0.125 * static_cast<double>(rng() % 4);
      }
      if (kind == 3) {
        s.K(j) = 1.0;
      }
    }
    const auto r = solve(s, trial % 10 == 0);
    const Frame& f = r.frame;
    const Status st = f.support.status;
    counts[static_cast<int>(st)]++;
    SCOPED_TRACE("trial " + std::to_string(trial) + " kind " + std::to_string(kind));
    ASSERT_NE(st, Status::kIterationLimit);
    ASSERT_TRUE(std::isfinite(f.alpha) && std::isfinite(f.beta) && std::isfinite(f.z));
    ASSERT_TRUE(f.Fz.allFinite());
    EXPECT_GE(f.Fz.minCoeff(), 0.0);
    const int hull = com_in_hull(s.q);
    if (st == Status::kUnsupported) {
      EXPECT_NE(hull, 1) << "supported robot reported as tipping";
    } else {
      EXPECT_NE(hull, -1) << "balance reported with the CoM outside the support";
      EXPECT_LE(f.support.residual, 1e-10 + 100.0 * rounding_floor(s, f));
    }
    if (hull == 1) {
      EXPECT_NE(st, Status::kUnsupported);
    }
  }
  std::printf("balanced %d, line %d, point %d, unsupported %d, limit %d\n", counts[0], counts[1],
              counts[2], counts[3], counts[4]);
}

TEST(SpringSupport, IterationLimitIsReportedNotExceeded) {
  std::mt19937_64 rng(47);
  for (int trial = 0; trial < 50; ++trial) {
    const Scene s = random_supported(rng, 30);
    const auto full = solve(s, false, false);  // Alg. 1: the limit counts its contact changes
    if (full.frame.support.iterations < 2) {
      continue;
    }
    Solved r{s.robot(), Frame(s.robot()), {}};
    r.frame.q = s.q;
    SupportOptions opt;
    opt.newton = false;
    opt.max_iterations = 1;
    spring_support(r.robot, r.frame, opt);
    EXPECT_EQ(r.frame.support.status, Status::kIterationLimit);
    EXPECT_EQ(r.frame.support.iterations, 1);
    EXPECT_FALSE(r.frame.support.message.empty());
    EXPECT_TRUE(r.frame.Fz.allFinite());
  }
  EXPECT_EQ(slipwalk::contact::default_support_iterations(6), 1 + 6 + 15 + 20);
}

TEST(SpringSupport, MalformedFramesThrowInputError) {
  const Robot robot = slipwalk::contact::uniform_robot(3);
  Frame frame(robot);
  frame.q << 1.0, 0.0, -1.0, 0.0, 1.0, -1.0, -0.1, -0.1, std::nan("");
  EXPECT_THROW(spring_support(robot, frame), std::runtime_error);
}

}  // namespace
