// BigANT's stairs leg (robots/bigant.hpp: BigAntLinkage::kStairs) against what it was chosen
// for. Oracles: the toe path's documented properties (the standard leg's stance stroke over the
// same sweep; a return lifted above the thesis' 0.12 m riser, below the crank pivot), the analytic
// dq/dφ against central differences (the crank turns the other way), and whole runs up the
// thesis' stairs (tread 0.3 m, riser 0.12 m): far fewer returning toes that pass an edge below
// the next tread and stand on it than with the standard leg, every cycle gains most of the flat
// stride, height rises at the stairs' rate per forward metre; the standard leg nearly stalls
// there (the check bites).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "connection/terrain_kernels.hpp"
#include "connection/trajectory_kernel.hpp"
#include "robots/bigant.hpp"
#include "robots/robots.hpp"
#include "support/bigant_toe.hpp"
#include "terrain/terrain.hpp"

namespace slipwalk::robots {
namespace {

constexpr double kSweep = kBigAntStanceSweep;

using test_support::toe;

struct StancePath {
  double stroke;     ///< m, backward over the sweep
  double top;        ///< m, the stance line: the highest stance point
  double variation;  ///< m, height variation over the stance
  double speed_ratio;
  bool backward;  ///< the toe moves backward throughout stance
};

StancePath stance(const BigAntLegs& legs) {
  StancePath s{toe(legs, -0.5 * kSweep).x() - toe(legs, 0.5 * kSweep).x(), -1e9, 0.0, 0.0, true};
  double zmin = 1e9;
  double vmin = 1e9;
  double vmax = 0.0;
  for (int k = 0; k <= 3600; ++k) {
    Eigen::Vector3d d;
    const Eigen::Vector3d q = toe(legs, -0.5 * kSweep + kSweep * k / 3600.0, &d);
    s.top = std::max(s.top, q.z());
    zmin = std::min(zmin, q.z());
    s.backward = s.backward && d.x() < 0.0;
    vmin = std::min(vmin, -d.x());
    vmax = std::max(vmax, -d.x());
  }
  s.variation = s.top - zmin;
  s.speed_ratio = vmax / vmin;
  return s;
}

TEST(BigAntStairsLeg, SameStanceStrokeOverTheSameSweepAsTheStandardLeg) {
  const StancePath standard = stance(bigant_legs());
  const StancePath stairs = stance(bigant_legs(kBigAntLegs, BigAntLinkage::kStairs));
  EXPECT_TRUE(stairs.backward);
  EXPECT_NEAR(stairs.stroke, standard.stroke, 0.001);
  EXPECT_LT(stairs.variation, 0.006);
  EXPECT_LT(stairs.speed_ratio, 2.4);
  // Mid-stance toes at the standard leg's stance centres, whatever the linkage.
  const BigAntLegs a = bigant_legs();
  const BigAntLegs b = bigant_legs(kBigAntLegs, BigAntLinkage::kStairs);
  for (int j = 0; j < kBigAntLegs; ++j) {
    Eigen::Vector3d qa;
    Eigen::Vector3d qb;
    Eigen::Vector3d d;
    bigant_toe(a, j, 0.0, qa, d);
    bigant_toe(b, j, 0.0, qb, d);
    EXPECT_NEAR(qa.x(), qb.x(), 1e-12) << j;
    EXPECT_EQ(qa.y(), qb.y()) << j;
  }
}

TEST(BigAntStairsLeg, ReturnLiftsTheToeAboveTheRiserAndStaysBelowTheChassis) {
  const BigAntLegs legs = bigant_legs(kBigAntLegs, BigAntLinkage::kStairs);
  const double line = stance(legs).top;
  double lift = 0.0;
  double highest = -1e9;
  for (int k = 0; k < 3600; ++k) {
    const double z = toe(legs, (k + 0.5) / 3600.0).z();
    lift = std::max(lift, z - line);
    highest = std::max(highest, z + legs.pivot(2, 0));  // body frame
  }
  EXPECT_GT(lift, 0.12 + 0.04);  // the thesis' riser and 4 cm
  EXPECT_LT(highest, 0.0);       // the whole path below the chassis plane
}

TEST(BigAntStairsLeg, ToeDerivativeMatchesCentralDifferences) {
  const BigAntLegs legs = bigant_legs(kBigAntLegs, BigAntLinkage::kStairs);
  const double h = 1e-7;
  for (int k = 0; k < 1000; ++k) {
    const double phi = (k + 0.3) / 1000.0;
    Eigen::Vector3d d;
    toe(legs, phi, &d);
    const Eigen::Vector3d fd = (toe(legs, phi + h) - toe(legs, phi - h)) / (2 * h);
    EXPECT_LT((fd - d).norm(), 1e-6 * d.norm()) << "phi " << phi;
  }
}

/// A run of the tripod (0.1 Hz, 3 cycles, viscous-Coulomb) on stairs with `riser`.
struct Climb {
  double progress = 0.0;     ///< m, forward
  double least_cycle = 1e9;  ///< m, the least forward progress in one gait cycle
  double rate = 0.0;         ///< least-squares slope of the body's height against x
  int edge_contacts = 0;     ///< frames in which a returning toe crosses an edge onto the
                             ///< higher tread and stands on it (it passed the edge below it)
};

Climb climb(BigAntLinkage linkage, double riser) {
  TripodGait gait;
  gait.linkage = linkage;
  const Walker w = bigant_tripod(gait);
  connection::TrajectoryOptions opt;
  opt.dt = 0.01;
  opt.steps = 3000;
  connection::TrajectoryData data(w.robot);
  using E =
      connection::Effects<connection::ViscousCoulombKernel, connection::NoFilter,
                          connection::NoResidual, connection::NoNoise, connection::StairsGround>;
  const terrain::Stairs stairs{0.3, riser, 0.0};
  const E effects{{}, {}, {}, {}, connection::StairsGround{stairs, {}, {}}};
  Eigen::VectorXd tread = Eigen::VectorXd::Zero(6);  // the tread under each toe, last frame
  Climb c;
  Eigen::VectorXd phase(6);
  double cycle_start = 0.0;
  Eigen::Matrix2d normal = Eigen::Matrix2d::Zero();  // least squares z = a + b x
  Eigen::Vector2d rhs = Eigen::Vector2d::Zero();
  integrate(w.robot, w.feet, opt, effects, data, [&](const connection::TrajectoryStep& s) {
    const Eigen::Vector2d row(1.0, s.pose.x);
    normal += row * row.transpose();
    rhs += row * s.frame.z;
    if (s.n % 1000 == 0 && s.n > 0) {
      c.least_cycle = std::min(c.least_cycle, s.pose.x - cycle_start);
      cycle_start = s.pose.x;
    }
    w.phase(s.t, phase);
    for (int j = 0; j < 6; ++j) {
      const double h =
          terrain::step_height(stairs, terrain::toe_world(stairs, s.pose, s.frame, j).x(), 0.0);
      const double phi = std::remainder(phase(j), 1.0);  // φ = 0 mid-stance
      const bool returning = std::abs(phi) > 0.5 * kSweep;
      if (s.n > 0 && returning && s.frame.contact[static_cast<std::size_t>(j)] != 0 &&
          h > tread(j)) {
        ++c.edge_contacts;
      }
      tread(j) = h;
    }
    c.progress = s.pose.x;
  });
  c.rate = normal.ldlt().solve(rhs)(1);
  return c;
}

TEST(BigAntStairsLeg, ClimbsTheThesisStairsWhereTheStandardLegStalls) {
  const Climb flat = climb(BigAntLinkage::kStairs, 0.0);
  const Climb up = climb(BigAntLinkage::kStairs, 0.12);
  const Climb standard = climb(BigAntLinkage::kStandard, 0.12);
  EXPECT_EQ(flat.edge_contacts, 0);
  // Returning toes that pass an edge below the next tread and stand on it: the standard leg
  // (lift 42 mm) has them; the stairs leg far fewer (the last ones near touchdown).
  EXPECT_GT(standard.edge_contacts, 0);
  EXPECT_LE(2 * up.edge_contacts, standard.edge_contacts);
  EXPECT_GT(up.least_cycle, 0.7 * flat.progress / 3.0);
  EXPECT_LT(standard.least_cycle, 0.5 * flat.progress / 3.0);
  EXPECT_NEAR(up.rate, 0.12 / 0.3, 0.15 * 0.4);
}

}  // namespace
}  // namespace slipwalk::robots
