// BigANT (robots/bigant.hpp) and its gaits (thesis §3.5.1.4 tripod, §3.5.1.5 metachronal).
// Oracles: the documented properties of the toe path, the analytic dq/dφ against central
// differences, the spring-support contact sets the gaits are designed for, the mirror symmetry
// of the straight tripod (and that it does not turn), and whether the stance feet's velocities are
// compatible with one rigid planar motion (tripod: yes; metachronal: no, so the feet must slip).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "connection/trajectory.hpp"
#include "contact/spring_support.hpp"
#include "core/error.hpp"
#include "robots/bigant.hpp"
#include "robots/robots.hpp"
#include "support/bigant_toe.hpp"

namespace slipwalk::robots {
namespace {

constexpr double kSweep = kBigAntStanceSweep;  // the tripod's default sweep
const double kMetaSweep = MetachronalGait{}.sweep;

using test_support::toe;

TEST(BigAntLeg, ToePathHasAFlatStanceAndARaisedReturn) {
  const BigAntLegs legs = bigant_legs();
  double zmin = 1e9;
  double zmax = -1e9;
  double vmin = 1e9;
  double vmax = -1e9;
  const int n = 3600;
  for (int k = 0; k <= n; ++k) {
    const double phi = -0.5 * kSweep + kSweep * k / n;
    Eigen::Vector3d d;
    const Eigen::Vector3d q = toe(legs, phi, &d);
    zmin = std::min(zmin, q.z());
    zmax = std::max(zmax, q.z());
    EXPECT_LT(d.x(), 0.0) << "the toe moves backward throughout stance, phi " << phi;
    vmin = std::min(vmin, -d.x());
    vmax = std::max(vmax, -d.x());
  }
  const double stroke = toe(legs, -0.5 * kSweep).x() - toe(legs, 0.5 * kSweep).x();
  EXPECT_NEAR(stroke, 0.145, 0.001);
  EXPECT_LT(zmax - zmin, 0.0035);      // flat-ish: 3.3 mm over the stroke
  EXPECT_NEAR(zmin, -0.1259, 0.0005);  // 12.5 cm below the crank pivot
  EXPECT_LT(vmax / vmin, 1.75);        // the stance speed varies by < 1.75×
  double lift = 0.0;
  double clear5 = 1e9;
  double clear10 = 1e9;
  for (int k = 0; k < n; ++k) {
    const double phi = -0.5 + (k + 0.5) / n;
    const double z = toe(legs, phi).z();
    lift = std::max(lift, z - zmax);
    const double past = std::abs(phi) - 0.5 * kSweep;  // turns past the stance sweep
    if (past >= 0.05) {
      clear5 = std::min(clear5, z - zmax);
    }
    if (past >= 0.1) {
      clear10 = std::min(clear10, z - zmax);
    }
    EXPECT_LT(z, -0.07);  // the whole path is well below the crank pivot
  }
  EXPECT_GT(lift, 0.040);
  EXPECT_GT(clear5, 0.006);
  EXPECT_GT(clear10, 0.013);
}

TEST(BigAntLeg, MidStanceToesSitAtTheStanceCentres) {
  const BigAntLegs legs = bigant_legs();
  const double x[] = {-0.3, 0.0, 0.3, -0.3, 0.0, 0.3};
  for (int j = 0; j < kBigAntLegs; ++j) {
    Eigen::Vector3d q;
    Eigen::Vector3d d;
    bigant_toe(legs, j, 0.0, q, d);
    EXPECT_NEAR(q.x(), x[j], 1e-15) << legs.names[static_cast<std::size_t>(j)];
    EXPECT_EQ(q.y(), j < 3 ? 0.2 : -0.2);
    EXPECT_LT(q.z(), -0.12);
  }
}

TEST(BigAntLeg, ToeDerivativeMatchesCentralDifferences) {
  const BigAntLegs legs = bigant_legs();
  const double h = 1e-7;  // turns
  for (int k = 0; k < 1000; ++k) {
    const double phi = (k + 0.3) / 1000.0;
    Eigen::Vector3d d;
    toe(legs, phi, &d);
    const Eigen::Vector3d fd = (toe(legs, phi + h) - toe(legs, phi - h)) / (2 * h);
    EXPECT_LT((fd - d).norm(), 1e-6 * d.norm()) << "phi " << phi;
  }
}

TEST(BigAntRobot, WeightStiffnessAndFriction) {
  const contact::Robot r = bigant_robot();
  EXPECT_NO_THROW(contact::validate(r));
  ASSERT_EQ(r.legs(), 6);
  EXPECT_DOUBLE_EQ(r.Mg, 8.18 * 9.81);
  for (int j = 0; j < 6; ++j) {
    EXPECT_DOUBLE_EQ(r.K(j), r.Mg / 0.03);  // 1 cm mean compression on one tripod
    EXPECT_EQ(r.mu(j), 1.0);
    EXPECT_EQ(r.w.col(j).norm(), 0.0);
  }
}

TEST(BigAntRobot, SixLegsAreBigAntItselfWhateverTheCallSaysIt) {
  const BigAntLegs a = bigant_legs();
  const BigAntLegs b = bigant_legs(6);
  EXPECT_EQ(a.names, b.names);
  EXPECT_EQ((a.pivot - b.pivot).norm(), 0.0);
  const contact::Robot r = bigant_robot(6);
  EXPECT_EQ(r.Mg, bigant_robot().Mg);
  EXPECT_EQ(r.K, bigant_robot().K);
}

TEST(BigAntRobot, MoreLegsSitHalfPerSideEquallySpacedAndCentredWithOneCentimetreSinkage) {
  for (int n : {2, 8, 10, 12}) {
    const BigAntLegs legs = bigant_legs(n);
    const contact::Robot r = bigant_robot(n);
    ASSERT_EQ(legs.pivot.cols(), n);
    ASSERT_EQ(r.legs(), n);
    const int side = n / 2;
    Eigen::Vector3d toe;
    Eigen::Vector3d d;
    double x_sum = 0.0;
    for (int j = 0; j < n; ++j) {
      bigant_toe(legs, j, 0.0, toe, d);  // mid-stance
      x_sum += toe.x();
      EXPECT_EQ(toe.y(), j < side ? kBigAntFootLateral : -kBigAntFootLateral);
      if (j % side > 0) {
        Eigen::Vector3d behind;
        bigant_toe(legs, j - 1, 0.0, behind, d);
        EXPECT_NEAR(toe.x() - behind.x(), kBigAntLegSpacing, 1e-12);
      }
    }
    EXPECT_NEAR(x_sum / n, 0.0, 1e-12);  // centred on the body origin, the CoM
    EXPECT_NEAR(r.Mg, 8.18 * 9.81 * n / 6.0, 1e-12);
    // Half the legs standing compress by 1 cm: K · (n/2) · 0.01 = Mg.
    EXPECT_NEAR(r.K(0) * side * 0.01, r.Mg, 1e-9);
    EXPECT_EQ(legs.names.front(), "L1");
    EXPECT_EQ(legs.names.back(), "R" + std::to_string(side));
  }
}

TEST(BigAntRobot, RefusesAnOddOrOutOfRangeLegCount) {
  for (int n : {0, 1, 3, 7, kBigAntMaxLegs + 2}) {
    EXPECT_THROW((void)bigant_legs(n), core::InputError) << n;
    EXPECT_THROW((void)bigant_robot(n), core::InputError) << n;
  }
}

// ---- gaits ------------------------------------------------------------------------------------

std::vector<int> contacts_at(const Walker& w, double t, contact::SupportSummary* s = nullptr) {
  contact::Frame f(w.robot);
  w.feet(t, f.q, f.qdot);
  contact::spring_support(w.robot, f);
  if (s != nullptr) {
    *s = f.support;
  }
  std::vector<int> in;
  for (int j = 0; j < w.legs(); ++j) {
    if (f.contact[static_cast<std::size_t>(j)] != 0) {
      in.push_back(j);
    }
  }
  return in;
}

/// Legs whose shaft angle is in the stance sweep at t (the gait's command).
std::vector<int> commanded_stance(const Walker& w, double t, double sweep) {
  Eigen::VectorXd phase(w.legs());
  w.phase(t, phase);
  std::vector<int> in;
  for (int j = 0; j < w.legs(); ++j) {
    if (phase(j) <= 0.5 * sweep || phase(j) >= 1.0 - 0.5 * sweep) {
      in.push_back(j);
    }
  }
  return in;
}

/// Relative residual of fitting one rigid planar motion (v, ω) to the given feet's velocities,
/// q̇_k = −(v + ω S q_k): zero when the feet can all stick, large when some must slip.
double rigid_misfit(const Eigen::Matrix3Xd& q, const Eigen::Matrix3Xd& qdot,
                    const std::vector<int>& feet) {
  const auto m = static_cast<Eigen::Index>(feet.size());
  Eigen::MatrixXd a(2 * m, 3);
  Eigen::VectorXd b(2 * m);
  for (Eigen::Index i = 0; i < m; ++i) {
    const int k = feet[static_cast<std::size_t>(i)];
    a.row(2 * i) << 1.0, 0.0, -q(1, k);
    a.row(2 * i + 1) << 0.0, 1.0, q(0, k);
    b.segment<2>(2 * i) = -qdot.col(k).head<2>();
  }
  const Eigen::Vector3d x = a.colPivHouseholderQr().solve(b);
  return (a * x - b).norm() / b.norm();
}

TEST(BigAntTripod, OneTripodCarriesTheRobotInEachHalfCycle) {
  const Walker w = bigant_tripod();
  const std::vector<int> first = {0, 2, 4};   // HL, FL, MR
  const std::vector<int> second = {1, 3, 5};  // ML, HR, FR
  // Away from the switches (duty 0.55 plus the round corners of the path) one tripod is down.
  for (int k = 0; k <= 30; ++k) {
    const double u = 0.35 + 0.3 * k / 30.0;  // cycles
    contact::SupportSummary s;
    EXPECT_EQ(contacts_at(w, (u - 0.5) * w.period, &s), first) << "t/T " << u - 0.5;
    EXPECT_EQ(s.status, contact::SupportSummary::Status::kBalanced);
    EXPECT_EQ(contacts_at(w, u * w.period, &s), second) << "t/T " << u;
    EXPECT_EQ(s.status, contact::SupportSummary::Status::kBalanced);
    // The commanded stance legs are the same tripods, and they are the three lowest feet.
    EXPECT_EQ(commanded_stance(w, u * w.period, kSweep), second);
  }
  // The stance tripod's feet all move alike: one rigid motion fits them exactly (no slip).
  contact::Frame f(w.robot);
  w.feet(0.1 * w.period, f.q, f.qdot);
  EXPECT_LT(rigid_misfit(f.q, f.qdot, first), 1e-12);
}

TEST(BigAntTripod, LeftAndRightMirrorHalfACycleApart) {
  const Walker w = bigant_tripod();
  Eigen::Matrix3Xd q(3, 6);
  Eigen::Matrix3Xd qd(3, 6);
  Eigen::Matrix3Xd q2(3, 6);
  Eigen::Matrix3Xd qd2(3, 6);
  const Eigen::Vector3d mirror(1.0, -1.0, 1.0);
  for (int k = 0; k < 200; ++k) {
    const double t = w.period * (k + 0.123) / 200.0;
    w.feet(t, q, qd);
    w.feet(t + 0.5 * w.period, q2, qd2);
    for (int j = 0; j < 3; ++j) {  // HL↔HR, ML↔MR, FL↔FR
      EXPECT_LT((q2.col(j + 3) - mirror.cwiseProduct(q.col(j))).norm(), 1e-12);
      EXPECT_LT((qd2.col(j + 3) - mirror.cwiseProduct(qd.col(j))).norm(), 1e-12);
    }
  }
}

double yaw_after_one_cycle(const Walker& w) {
  connection::TrajectoryOptions o;
  o.dt = w.period / 200.0;
  o.steps = 200;
  connection::TrajectoryData data(w.robot);
  const auto s =
      connection::integrate(w.robot, w.feet, o, connection::ViscousCoulombKernel{},
                            connection::NoFilter{}, data, [](const connection::TrajectoryStep&) {});
  EXPECT_EQ(s.unsupported, 0);
  EXPECT_GT(s.end.x, 0.1);  // it walks forward (about a quarter metre per cycle)
  return s.end.theta;
}

TEST(BigAntTripod, StraightDoesNotTurnAndSteerTurnsTowardTheShortSide) {
  EXPECT_NEAR(yaw_after_one_cycle(bigant_tripod()), 0.0, 1e-9);
  TripodGait left;
  left.steer = 0.5;
  EXPECT_GT(yaw_after_one_cycle(bigant_tripod(left)), 0.02);
  TripodGait right;
  right.steer = -0.5;
  EXPECT_LT(yaw_after_one_cycle(bigant_tripod(right)), -0.02);
}

TEST(BigAntMetachronal, FourFeetCommandedDownTwoPerSide) {
  const Walker w = bigant_metachronal();
  for (int k = 0; k < 6000; ++k) {
    const std::vector<int> in = commanded_stance(w, w.period * (k + 0.5) / 6000.0, kMetaSweep);
    ASSERT_EQ(in.size(), 4u) << "sample " << k;
    EXPECT_EQ(std::count_if(in.begin(), in.end(), [](int j) { return j < 3; }), 2);
  }
}

TEST(BigAntMetachronal, SpringSupportFindsTheFourStanceFeet) {
  const Walker w = bigant_metachronal();
  // Legs switch at multiples of 1/6 cycle; between switches the four stance feet carry the robot
  // (close to a switch the lifting foot may still touch: the path's corners are round).
  for (int k = 0; k < 6; ++k) {
    for (const double du : {-1.0 / 48, 0.0, 1.0 / 48}) {
      const double t = w.period * (1.0 / 12 + k / 6.0 + du);
      contact::SupportSummary s;
      const std::vector<int> in = contacts_at(w, t, &s);
      EXPECT_EQ(in, commanded_stance(w, t, kMetaSweep)) << "t/T " << t / w.period;
      EXPECT_EQ(s.status, contact::SupportSummary::Status::kBalanced);
    }
  }
}

TEST(BigAntMetachronal, FourFeetCarryTheRobotMostOfTheCycle) {
  // Over a whole cycle: never fewer than four feet, exactly four ≥ 85 % of the time (five at the
  // hand-overs), and each foot on the ground for about 2/3 of the cycle (robots.hpp).
  const Walker w = bigant_metachronal();
  contact::Frame f(w.robot);
  const int n = 1200;
  int four = 0;
  std::vector<int> down(6, 0);
  for (int k = 0; k < n; ++k) {
    w.feet(w.period * (k + 0.5) / n, f.q, f.qdot);
    contact::spring_support(w.robot, f);
    const auto c = std::count(f.contact.begin(), f.contact.end(), 1);
    EXPECT_GE(c, 4);
    EXPECT_LE(c, 5);
    four += c == 4 ? 1 : 0;
    for (int j = 0; j < 6; ++j) {
      down[static_cast<std::size_t>(j)] += f.contact[static_cast<std::size_t>(j)];
    }
  }
  EXPECT_GT(four, 0.85 * n);
  for (int d : down) {
    EXPECT_NEAR(static_cast<double>(d) / n, 2.0 / 3.0, 0.03);
  }
}

TEST(BigAntMetachronal, StanceFeetMoveIncompatibly) {
  // The cubic stance turns the four stance shafts at different rates: no rigid motion fits their
  // velocities, so some must slip (§3.5.1.5).
  const Walker w = bigant_metachronal();
  contact::Frame f(w.robot);
  for (int k = 0; k < 6; ++k) {
    const double t = w.period * (1.0 / 12 + k / 6.0);
    w.feet(t, f.q, f.qdot);
    EXPECT_GT(rigid_misfit(f.q, f.qdot, commanded_stance(w, t, kMetaSweep)), 0.1);
  }
}

TEST(BigAntGaits, PhaseIsTheShaftAngleOfEachToe) {
  const BigAntLegs legs = bigant_legs();
  for (const Walker& w : {bigant_tripod(), bigant_metachronal()}) {
    Eigen::Matrix3Xd q(3, 6);
    Eigen::Matrix3Xd qd(3, 6);
    Eigen::VectorXd phase(6);
    for (int k = 0; k < 50; ++k) {
      const double t = w.period * k / 50.0;
      w.feet(t, q, qd);
      w.phase(t, phase);
      for (int j = 0; j < 6; ++j) {
        Eigen::Vector3d toe_q;
        Eigen::Vector3d d;
        bigant_toe(legs, j, phase(j), toe_q, d);
        EXPECT_LT((toe_q - q.col(j)).norm(), 1e-15);
      }
    }
  }
  // §5.5's standing pose [0.5, 0, 0.5, 0, 0.5, 0] is the tripod at t = T/2: {HL, FL, MR} up.
  Eigen::VectorXd phase(6);
  const Walker w = bigant_tripod();
  w.phase(0.5 * w.period, phase);
  EXPECT_LT((phase - Eigen::VectorXd{{0.5, 0.0, 0.5, 0.0, 0.5, 0.0}}).norm(), 1e-15);
}

}  // namespace
}  // namespace slipwalk::robots
