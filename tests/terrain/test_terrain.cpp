// Terrain (§5.2): the geometry of terrain/terrain.hpp and the ground policies of
// connection/terrain_kernels.hpp on single frames and whole trajectories. Oracles: a slope of
// angle 0 and stairs of riser 0 are flat ground bit for bit (both laws); the slope is invariant to
// its heading when the robot turns with it; the slope's balance (Σ F + gravity's planar part = 0,
// moments, Σ F_z = Mg cos σ) recomputed here; sliding past the holding angle tan σ = μ; the stairs'
// change of coordinates against the same support search on hand-transformed feet; a toe exactly
// on a stair edge stands on the upper tread; a toe whose tread changes between frames.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "connection/trajectory_kernel.hpp"
#include "contact/spring_support.hpp"
#include "robots/robots.hpp"
#include "terrain/terrain.hpp"

namespace slipwalk::connection {
namespace {

constexpr double kPi = std::numbers::pi;

/// Six feet on a ring of radius 0.3 m, 0.1 m below the body, walking with a rigid stance of
/// three and a lifted swing of three (a tripod-like frame), at time t.
void ring_frame(contact::Frame& f, double t) {
  for (int k = 0; k < 6; ++k) {
    const double a = 2.0 * kPi * k / 6.0 + 0.1;
    const bool stance = (k % 2) == 0;
    f.q.col(k) << 0.3 * std::cos(a) - (stance ? 0.05 * t : -0.05 * t), 0.3 * std::sin(a),
        stance ? -0.1 : -0.09;
    f.qdot.col(k) << (stance ? -0.05 : 0.05), 0.01 * k, 0.0;
  }
}

contact::Robot hexapod() { return contact::uniform_robot(6, 1000.0, 0.6, 9.81); }

template <class Ground, class Law>
contact::Frame frame_on(Ground ground, const Law& law, const core::Pose2& pose, double t) {
  const contact::Robot robot = hexapod();
  contact::Frame f(robot);
  ring_frame(f, t);
  f.theta = pose.theta;
  ground.reset(robot);
  ground(robot, f, pose, law);
  return f;
}

void expect_same(const contact::Frame& a, const contact::Frame& b) {
  EXPECT_EQ(a.v_body, b.v_body);
  EXPECT_EQ(a.Fxy, b.Fxy);
  EXPECT_EQ(a.Fz, b.Fz);
  EXPECT_EQ(a.z, b.z);
  EXPECT_EQ(a.alpha, b.alpha);
  EXPECT_EQ(a.beta, b.beta);
}

TEST(Slope, AngleZeroIsFlatBitForBitForBothLaws) {
  const core::Pose2 pose{0.3, -0.2, 0.7};
  for (double t : {0.0, 0.3, 1.1}) {
    SlopeGround slope{terrain::Slope{0.0, 1.2, 0.0}, {}, {}};
    expect_same(frame_on(FlatGround{}, ViscousCoulombKernel{}, pose, t),
                frame_on(slope, ViscousCoulombKernel{}, pose, t));
    expect_same(frame_on(FlatGround{}, CoulombKernel{}, pose, t),
                frame_on(slope, CoulombKernel{}, pose, t));
  }
}

TEST(Stairs, ZeroRiserIsFlatBitForBitForBothLaws) {
  const core::Pose2 pose{0.31, -0.2, 0.4};
  for (double t : {0.0, 0.3, 1.1}) {
    StairsGround stairs{terrain::Stairs{0.3, 0.0, 0.5}, {}, {}};
    expect_same(frame_on(FlatGround{}, ViscousCoulombKernel{}, pose, t),
                frame_on(stairs, ViscousCoulombKernel{}, pose, t));
    expect_same(frame_on(FlatGround{}, CoulombKernel{}, pose, t),
                frame_on(stairs, CoulombKernel{}, pose, t));
  }
}

TEST(Slope, InvariantToItsHeadingWhenTheRobotTurnsWithIt) {
  for (double sigma_deg : {5.0, 17.0, 25.0}) {
    const double sigma = sigma_deg * kPi / 180.0;
    for (double psi : {0.4, -2.0, 3.0}) {
      const SlopeGround a{terrain::Slope{sigma, 0.0, 0.05}, {}, {}};
      const SlopeGround b{terrain::Slope{sigma, psi, 0.05}, {}, {}};
      const contact::Frame fa = frame_on(a, ViscousCoulombKernel{}, {0.0, 0.0, 0.3}, 0.2);
      const contact::Frame fb = frame_on(b, ViscousCoulombKernel{}, {1.0, 2.0, 0.3 + psi}, 0.2);
      EXPECT_LE((fa.v_body - fb.v_body).norm(), 1e-12);
      EXPECT_LE((fa.Fxy - fb.Fxy).norm(), 1e-11);
      const contact::Frame ca = frame_on(a, CoulombKernel{}, {0.0, 0.0, 0.3}, 0.2);
      const contact::Frame cb = frame_on(b, CoulombKernel{}, {1.0, 2.0, 0.3 + psi}, 0.2);
      ASSERT_TRUE(ca.friction.converged) << ca.friction.message;
      EXPECT_LE((ca.v_body - cb.v_body).norm(), 1e-9);
    }
  }
}

/// max(‖Σ F + f_g‖, |Σ q × F| / L) / Mg with f_g = −Mg sin σ R_θᵀ (cos ψ, sin ψ) written here.
double slope_residual(const contact::Frame& f, double Mg, double sigma, double psi, double theta) {
  const Eigen::Vector2d up(std::cos(psi - theta), std::sin(psi - theta));
  Eigen::Vector2d force = -Mg * std::sin(sigma) * up;
  double moment = 0.0;
  for (int k = 0; k < f.legs(); ++k) {
    force += f.Fxy.col(k);
    moment += f.q(0, k) * f.Fxy(1, k) - f.q(1, k) * f.Fxy(0, k);
  }
  return std::max(force.norm(), std::abs(moment) / 0.3) / Mg;
}

TEST(Slope, BalanceResidualForBothLaws) {
  const double Mg = 9.81;
  for (double sigma_deg : {3.0, 17.0, 28.0}) {
    const double sigma = sigma_deg * kPi / 180.0;
    const double psi = 0.9;
    const core::Pose2 pose{0.0, 0.0, 0.2};
    const SlopeGround g{terrain::Slope{sigma, psi, 0.0}, {}, {}};
    const contact::Frame v = frame_on(g, ViscousCoulombKernel{}, pose, 0.4);
    EXPECT_LE(slope_residual(v, Mg, sigma, psi, pose.theta), 1e-10) << sigma_deg;
    EXPECT_NEAR(v.Fz.sum(), Mg * std::cos(sigma), 1e-10);
    const contact::Frame c = frame_on(g, CoulombKernel{}, pose, 0.4);
    ASSERT_TRUE(c.friction.converged) << c.friction.message;
    EXPECT_LE(slope_residual(c, Mg, sigma, psi, pose.theta), 1e-10) << sigma_deg;
    EXPECT_LE(c.friction.certificate, 1e-10);
  }
}

TEST(Slope, ViscousVelocityIsAffineWithTheSlopeDrift) {
  // v(σ) − v(0) = M⁻¹ f_g: at rest (q̇ = 0) on a centred ring, the drift is f_g / Σ μ F_z.
  const contact::Robot robot = hexapod();
  contact::Frame f(robot);
  for (int k = 0; k < 6; ++k) {
    const double a = 2.0 * kPi * k / 6.0;
    f.q.col(k) << 0.3 * std::cos(a), 0.3 * std::sin(a), -0.1;
  }
  f.qdot.setZero();
  const double sigma = 0.2;
  SlopeGround g{terrain::Slope{sigma, 0.0, 0.0}, {}, {}};
  g.reset(robot);
  g(robot, f, core::Pose2{}, ViscousCoulombKernel{});
  EXPECT_NEAR(f.v_body(0), -std::tan(sigma) / 0.6, 1e-12);  // Mg sin σ / (μ Mg cos σ)
  EXPECT_NEAR(f.v_body(1), 0.0, 1e-12);
  EXPECT_NEAR(f.v_body(2), 0.0, 1e-12);
}

TEST(Slope, CoulombHoldsBelowTanSigmaEqualsMuAndSlidesAbove) {
  const double mu = 0.6;
  const double limit = std::atan(mu);
  for (double factor : {0.95, 1.05}) {
    const SlopeGround g{terrain::Slope{factor * limit, 0.0, 0.0}, {}, {}};
    contact::Frame f = frame_on(g, CoulombKernel{}, core::Pose2{}, 0.0);
    if (factor < 1.0) {
      EXPECT_TRUE(f.friction.converged) << f.friction.message;
    } else {
      EXPECT_FALSE(f.friction.converged);
      EXPECT_EQ(f.friction.message.rfind("sliding", 0), 0U) << f.friction.message;
      EXPECT_EQ(f.v_body, Eigen::Vector3d::Zero());
    }
  }
}

TEST(Slope, ComHeightShiftsTheLoadsDownhill) {
  // The weight crosses the plane h tan σ downhill: the normal loads' centre moves there.
  const double sigma = 0.3;
  const double h = 0.1;
  const SlopeGround g{terrain::Slope{sigma, 0.0, h}, {}, {}};
  const contact::Robot robot = hexapod();
  contact::Frame f(robot);
  for (int k = 0; k < 6; ++k) {
    const double a = 2.0 * kPi * k / 6.0;
    f.q.col(k) << 0.3 * std::cos(a), 0.3 * std::sin(a), -0.1;
  }
  f.qdot.setZero();
  SlopeGround gg = g;
  gg.reset(robot);
  gg(robot, f, core::Pose2{}, ViscousCoulombKernel{});
  const double cx = (f.Fz.transpose() * f.q.row(0).transpose())(0) / f.Fz.sum();
  EXPECT_NEAR(cx, -h * std::tan(sigma), 1e-9);
  EXPECT_NEAR(f.q(0, 0), 0.3, 1e-15);  // the feet are handed back unshifted
}

TEST(Stairs, StepHeightAtAndAroundAnEdge) {
  const terrain::Stairs s{0.25, 0.12, 0.0};
  EXPECT_EQ(terrain::step_height(s, 0.5, 0.3), 2 * 0.12);  // exactly on the edge: upper tread
  EXPECT_EQ(terrain::step_height(s, std::nextafter(0.5, 0.0), 0.3), 0.12);
  EXPECT_EQ(terrain::step_height(s, -0.01, 0.0), -0.12);
  // Rotated stairs: the same along their heading.
  const terrain::Stairs r{0.25, 0.12, kPi / 2};
  EXPECT_EQ(terrain::step_height(r, 0.0, 0.6), 2 * 0.12);
}

TEST(Stairs, SupportOnHandTransformedFeet) {
  // The policy equals the flat support search on feet transformed by the formulas of §5.2.2
  // (written here again), and its loads balance the weight about the horizontal levers.
  const terrain::Stairs st{0.3, 0.12, 0.0};
  const core::Pose2 pose{0.02, 0.0, 0.0};
  const contact::Robot robot = hexapod();
  contact::Frame f(robot);
  ring_frame(f, 0.1);
  contact::Frame g = f;
  StairsGround ground{st, {}, {}};
  ground.reset(robot);
  ground(robot, f, pose, ViscousCoulombKernel{});
  const double gam = std::atan(0.12 / 0.3);
  for (int k = 0; k < 6; ++k) {
    const double qx = g.q(0, k);
    const double qy = g.q(1, k);
    const double qz = g.q(2, k);
    const double hx = std::cos(gam) * qx - std::sin(gam) * qz;
    const double h = 0.12 * std::floor((pose.x + hx) / 0.3);
    g.q.col(k) << hx, std::cos(gam) * qy, std::sin(gam) * qx + std::cos(gam) * qz - h;
  }
  contact::spring_support(robot, g);
  EXPECT_EQ(f.z, g.z);
  EXPECT_EQ(f.beta, g.beta);
  EXPECT_EQ(f.Fz, g.Fz);
  // Some toes stand on the tread below the body's (a real step), the loads carry Mg.
  EXPECT_GT(ground.height.maxCoeff() - ground.height.minCoeff(), 0.1);
  EXPECT_NEAR(f.Fz.sum(), robot.Mg, 1e-9);
  double mx = 0.0;
  for (int k = 0; k < 6; ++k) {
    mx += f.Fz(k) * f.q(1, k);  // levers restored to the horizontal q_y
  }
  EXPECT_NEAR(mx, 0.0, 1e-9);
}

TEST(Stairs, ToeExactlyOnAnEdgeAndCrossingItBetweenFrames) {
  // One foot sits exactly on the edge of tread 1 (s = 0.25): it stands on the upper tread; with
  // the body 1e-12 m further back (the next frame of a robot sliding back) it stands on the lower
  // one, its spring 0.12 m longer; the support search follows (that foot carries less), both
  // frames stay balanced.
  const terrain::Stairs st{0.25, 0.12, 0.0};
  const contact::Robot robot = hexapod();
  contact::Frame base(robot);
  for (int k = 0; k < 6; ++k) {
    const double a = 2.0 * kPi * k / 6.0;
    base.q.col(k) << 0.25 * std::cos(a), 0.25 * std::sin(a), -0.1;
  }
  base.qdot.setZero();
  StairsGround ground{st, {}, {}};
  ground.reset(robot);
  contact::Frame on = base;
  // Pose chosen so that foot 0 (q_x = 0.25) lands exactly at s = 0.25 after the pitch: shift x by
  // the pitch's change of q_x; cos γ q_x − sin γ q_z is computed the same way here.
  const double gam = terrain::stair_pitch(st, 0.0);
  const double hx = std::cos(gam) * 0.25 - std::sin(gam) * -0.1;
  const core::Pose2 at_edge{0.25 - hx, 0.0, 0.0};
  ASSERT_EQ(at_edge.x + hx, 0.25);
  ground(robot, on, at_edge, ViscousCoulombKernel{});
  EXPECT_EQ(ground.height(0), 0.12);
  const double z_on = on.z;
  const double fz_on = on.Fz(0);
  contact::Frame off = base;
  const core::Pose2 before{at_edge.x - 1e-12, 0.0, 0.0};
  ground(robot, off, before, ViscousCoulombKernel{});
  EXPECT_EQ(ground.height(0), 0.0);
  EXPECT_LT(off.Fz(0), fz_on);  // on the lower tread its spring is less compressed
  EXPECT_NE(off.z, z_on);
  EXPECT_NEAR(on.Fz.sum(), robot.Mg, 1e-9);
  EXPECT_NEAR(off.Fz.sum(), robot.Mg, 1e-9);
}

TEST(Trajectory, SlopeRunIsHeadingInvariantAndStairsZeroRiserIsFlat) {
  const robots::Walker w = robots::bigant_tripod(
      robots::TripodGait{.frequency = 0.5, .steer = 0.0, .duty = 0.55, .sweep = 0.35});
  TrajectoryOptions opt;
  opt.dt = 0.02;
  opt.steps = 100;
  TrajectoryData data(w.robot);
  std::vector<Eigen::Vector3d> a;
  std::vector<Eigen::Vector3d> b;
  const auto run = [&](auto effects, const core::Pose2& start, std::vector<Eigen::Vector3d>& out) {
    opt.start = start;
    out.clear();
    return integrate(w.robot, w.feet, opt, effects, data, [&](const TrajectoryStep& s) {
      out.emplace_back(s.pose.x, s.pose.y, s.pose.theta);
    });
  };
  using E = Effects<ViscousCoulombKernel, NoFilter, NoResidual, NoNoise, SlopeGround>;
  const double sigma = 10.0 * kPi / 180.0;
  const double psi = 1.1;
  run(E{{}, {}, {}, {}, SlopeGround{terrain::Slope{sigma, 0.0, 0.0}, {}, {}}}, {}, a);
  run(E{{}, {}, {}, {}, SlopeGround{terrain::Slope{sigma, psi, 0.0}, {}, {}}}, {0.0, 0.0, psi}, b);
  for (std::size_t i = 0; i < a.size(); ++i) {
    // b is a rotated by ψ about the origin.
    const Eigen::Vector2d ra(std::cos(psi) * a[i](0) - std::sin(psi) * a[i](1),
                             std::sin(psi) * a[i](0) + std::cos(psi) * a[i](1));
    EXPECT_LE((ra - b[i].head<2>()).norm(), 1e-10) << i;
    EXPECT_NEAR(a[i](2) + psi, b[i](2), 1e-10) << i;
  }
  using F = Effects<CoulombKernel, NoFilter, NoResidual, NoNoise, FlatGround>;
  using S = Effects<CoulombKernel, NoFilter, NoResidual, NoNoise, StairsGround>;
  run(F{}, {}, a);
  run(S{{}, {}, {}, {}, StairsGround{terrain::Stairs{0.3, 0.0, 0.2}, {}, {}}}, {}, b);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i], b[i]) << i;
  }
}

}  // namespace
}  // namespace slipwalk::connection
