// The Coulomb solver's reported forces checked against the law itself, from frame.v_body and
// frame.Fxy alone (no solver internals): every force in its friction ellipse (eq. 3.19's G_k),
// the forces balanced (eqs. 3.16–3.18), and the complementarity Σ_k (c_k ‖W_k u_k‖ + F_k·u_k) —
// a sum of terms each ≥ 0 inside the ellipses, zero for a foot exactly at the law (static, or
// sliding with the full force against its slip) — within the certificate's tolerance of
// max(D(v), D(0)) (the duality gap of friction/coulomb.cpp written per foot). Walks along which
// the warm starts hold static feet over from frame to frame (the active-set polish and the
// final pass that builds the static feet's forces apart from the sliding ones), cold solves of
// the same frames (the fast path's kink foot), isotropic and anisotropic feet.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "contact/robot.hpp"
#include "contact/spring_support.hpp"
#include "friction/solvers.hpp"
#include "robots/robots.hpp"

namespace slipwalk::friction {
namespace {

using contact::Frame;
using contact::Robot;
using Eigen::Matrix2d;
using Eigen::Vector2d;

constexpr double kTol = 1e-9;  // the ch3_legged cost study's tolerance

/// W_k = G_k^{1/2} = I + α w wᵀ, α = 1/(1 + √(1 + ‖w‖²)) (eq. 3.19's metric, G = I + w wᵀ).
Matrix2d W_of(const Robot& robot, int k) {
  const Vector2d w = robot.w.col(k);
  const double alpha = 1.0 / (1.0 + std::sqrt(1.0 + w.squaredNorm()));
  return Matrix2d::Identity() + alpha * w * w.transpose();
}

/// u_k = v_b + ω S q_xy,k + q̇_xy,k (solvers.hpp).
Vector2d slip(const Frame& f, int k) {
  const double omega = f.v_body(2);
  return Vector2d(f.v_body(0) - omega * f.q(1, k) + f.qdot(0, k),
                  f.v_body(1) + omega * f.q(0, k) + f.qdot(1, k));
}

/// The law checked on one certified answer, from its velocity and forces.
void expect_law(const Robot& robot, const Frame& f, const char* what, int frame) {
  ASSERT_TRUE(f.friction.converged) << what << " frame " << frame << ": " << f.friction.message;
  double D = 0.0;
  double D0 = 0.0;
  double gap = 0.0;
  double scale = 0.0;
  double L = 0.0;
  Vector2d force = Vector2d::Zero();
  double moment = 0.0;
  for (int k = 0; k < f.legs(); ++k) {
    const Vector2d F = f.Fxy.col(k);
    const double c = robot.mu(k) * f.Fz(k);
    if (f.contact[static_cast<std::size_t>(k)] == 0 || !(c > 0.0)) {
      EXPECT_EQ(F.norm(), 0.0) << what << " frame " << frame << " leg " << k;
      continue;
    }
    const Matrix2d W = W_of(robot, k);
    const Matrix2d G = W * W;
    EXPECT_LE(F.dot(G.inverse() * F), c * c * (1.0 + 1e-12))
        << what << " frame " << frame << " leg " << k;
    const Vector2d u = slip(f, k);
    const double dk = c * (W * u).norm();
    D += dk;
    D0 += c * (W * f.qdot.col(k).head<2>()).norm();
    gap += dk + F.dot(u);  // ≥ 0 up to rounding: F inside the ellipse
    EXPECT_GE(dk + F.dot(u), -1e-12 * c * (1.0 + u.norm())) << what << " frame " << frame;
    scale += c * W.norm();
    L = std::max(L, f.q.col(k).head<2>().norm());
    force += F;
    moment += f.q(0, k) * F(1) - f.q(1, k) * F(0);
  }
  EXPECT_LE(force.norm(), 1e-10 * scale) << what << " frame " << frame;
  EXPECT_LE(std::abs(moment), 1e-10 * scale * L) << what << " frame " << frame;
  // The balance's rounding enters Σ F·u through the body's motion: ≤ 1e-10 scale ‖v‖ (L ω).
  const double motion = std::abs(f.v_body(0)) + std::abs(f.v_body(1)) + L * std::abs(f.v_body(2));
  EXPECT_LE(gap, kTol * std::max(D, D0) + 2e-10 * scale * motion + 1e-15 * scale)
      << what << " frame " << frame;
  EXPECT_NEAR(f.friction.dissipation, D, 1e-12 * std::max(D, D0)) << what << " frame " << frame;
}

/// Successive 100 Hz frames of the walk, the spring support's loads in each (frames it cannot
/// balance left out).
std::vector<Frame> walk(const robots::Walker& walker, int count) {
  std::vector<Frame> frames;
  Frame f(walker.robot);
  for (int i = 0; static_cast<int>(frames.size()) < count; ++i) {
    walker.feet(0.01 * i, f.q, f.qdot);
    contact::spring_support(walker.robot, f);
    if (f.support.status == contact::SupportSummary::Status::kBalanced) {
      frames.push_back(f);
    }
  }
  return frames;
}

/// Warm solves along the walk (one working frame, as a trajectory runs) and cold solves of each
/// frame, all checked against the law; returns how many warm answers had static feet.
int check_walk(const robots::Walker& walker, int count) {
  const std::vector<Frame> frames = walk(walker, count);
  CoulombOptions cold;
  cold.tol = kTol;
  CoulombOptions warm = cold;
  warm.warm_start = true;
  Frame g(walker.robot);
  int with_static = 0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    Frame f = frames[i];
    solve_coulomb(walker.robot, f, cold);
    expect_law(walker.robot, f, "cold", static_cast<int>(i));
    g.q = f.q;
    g.qdot = f.qdot;
    g.contact = f.contact;
    g.Fz = f.Fz;
    solve_coulomb(walker.robot, g, warm);
    expect_law(walker.robot, g, "warm", static_cast<int>(i));
    with_static += g.friction.static_feet > 0 ? 1 : 0;
  }
  return with_static;
}

TEST(CoulombForces, AlongATurningWalkTheForcesAreTheLawsToTheCertificate) {
  const robots::Walker walker = robots::bigant_tripod({.frequency = 0.38, .steer = 0.3});
  EXPECT_GT(check_walk(walker, 600), 300);  // static feet held over in most frames
}

TEST(CoulombForces, FeetOnALineWithAFootAtItsKinkGiveTheMedianIntervalAndFiniteForces) {
  // Fig. 3.1's 1-D example in 2-D (sweeps/points/legged_laws.cpp): N feet on the body's x axis,
  // equal loads, foot i sliding at (v_i, 0). Coulomb balances at v_x = −median(v_i); for even N
  // anywhere between minus the two middle speeds, where the solver ends with a foot exactly at
  // its kink (r = 0): its slip direction is 0/0, and no NaN of it may reach the forces.
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> speed(-1.0, 1.0);
  for (const int n : {2, 3, 4, 6, 8, 10, 32}) {
    const Robot robot = contact::uniform_robot(n);
    Frame f(robot);
    for (int i = 0; i < n; ++i) {
      f.q.col(i) = Eigen::Vector3d(-1.0 + 2.0 * i / (n - 1), 0.0, -0.1);
      f.contact[static_cast<std::size_t>(i)] = 1;
      f.Fz(i) = robot.Mg / n;
    }
    for (int trial = 0; trial < 60; ++trial) {
      std::vector<double> v(static_cast<std::size_t>(n));
      for (int i = 0; i < n; ++i) {
        v[static_cast<std::size_t>(i)] = speed(rng);
        f.qdot.col(i) = Eigen::Vector3d(v[static_cast<std::size_t>(i)], 0.0, 0.0);
      }
      std::sort(v.begin(), v.end());
      const std::size_t h = v.size() / 2;
      const double lo = -v[h];
      const double hi = n % 2 == 1 ? -v[h] : -v[h - 1];
      solve_coulomb(robot, f, CoulombOptions{kTol});
      expect_law(robot, f, "line", trial);
      EXPECT_GE(f.v_body(0), lo - 1e-7) << n << " feet, trial " << trial;
      EXPECT_LE(f.v_body(0), hi + 1e-7) << n << " feet, trial " << trial;
    }
  }
}

TEST(CoulombForces, WithAnisotropicFeetTheForcesAreTheLawsToTheCertificate) {
  // Enhanced traction along a different direction per leg: W_k is not diagonal, so the static
  // feet's forces (W_k⁻¹ applied in closed form) and the non-uniqueness test see full matrices.
  robots::Walker walker = robots::bigant_tripod({.frequency = 0.38, .steer = 0.3});
  for (int k = 0; k < walker.robot.legs(); ++k) {
    const double a = 0.7 * k;
    walker.robot.w.col(k) << 0.8 * std::cos(a), 0.8 * std::sin(a);
  }
  EXPECT_GT(check_walk(walker, 400), 100);
}

}  // namespace
}  // namespace slipwalk::friction
