// The friction solvers with an external planar load (§5.2.1: gravity along a slope). Oracles: the
// balance Σ F_k + f = 0, Σ M_k + M = 0 recomputed here from the returned forces; the affine
// velocity v = A q̇ + M⁻¹ f against the 3 × 3 system assembled here and against A from
// connection::local_connection; linearity in the load; the Coulomb duality gap recomputed here
// from the forces (feasible and balanced, so the gap proves optimality); zero load = the flat
// solvers bit for bit (viscous) or to the certificate (Coulomb); sliding certified by a direction
// of unbounded descent past the holding load, and held statically just below it.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "connection/local_connection.hpp"
#include "contact/robot.hpp"
#include "friction/solvers.hpp"

namespace slipwalk::friction {
namespace {

using contact::Frame;
using contact::Robot;
using Eigen::Vector2d;
using Eigen::Vector3d;

/// n feet in contact on a ring of radius ~0.3 with random loads and velocities (seeded).
struct Case {
  Robot robot;
  Frame frame;
  Case(int n, unsigned seed) : robot(contact::uniform_robot(n, 1.0, 0.7, 9.81)), frame(robot) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int k = 0; k < n; ++k) {
      const double a = 6.283185307179586 * k / n + 0.2 * u(rng);
      frame.q.col(k) << 0.3 * std::cos(a) + 0.02 * u(rng), 0.3 * std::sin(a), -0.1;
      frame.qdot.col(k) << 0.05 * u(rng), 0.05 * u(rng), 0.0;
      frame.contact[static_cast<std::size_t>(k)] = 1;
      frame.Fz(k) = 9.81 / n * (1.0 + 0.3 * u(rng));
    }
  }
};

/// max(‖Σ F + f‖, |Σ q × F + M| / L) / (Σ c_k + ‖f‖) of the frame's forces.
double balance_residual(const Case& c, const Vector3d& load) {
  Vector2d force = load.head<2>();
  double moment = load(2);
  double csum = 0.0;
  for (int k = 0; k < c.frame.legs(); ++k) {
    const Vector2d F = c.frame.Fxy.col(k);
    force += F;
    moment += c.frame.q(0, k) * F(1) - c.frame.q(1, k) * F(0);
    csum += c.robot.mu(k) * c.frame.Fz(k);
  }
  const double scale = csum + load.norm();
  return std::max(force.norm(), std::abs(moment) / 0.3) / scale;
}

/// The viscous-Coulomb balance assembled directly (unscaled): M x = f − Σ c_k J_kᵀ q̇_k.
Vector3d viscous_by_hand(const Case& c, const Vector3d& load) {
  Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
  Vector3d rhs = load;
  for (int k = 0; k < c.frame.legs(); ++k) {
    const double ck = c.robot.mu(k) * c.frame.Fz(k);
    Eigen::Matrix<double, 2, 3> J;
    J << 1.0, 0.0, -c.frame.q(1, k), 0.0, 1.0, c.frame.q(0, k);
    M += ck * J.transpose() * J;
    rhs -= ck * J.transpose() * c.frame.qdot.col(k).head<2>();
  }
  return M.ldlt().solve(rhs);
}

TEST(ViscousLoaded, ZeroLoadIsTheFlatSolverBitForBit) {
  Case a(6, 1);
  Case b(6, 1);
  solve_viscous_coulomb(a.robot, a.frame);
  solve_viscous_coulomb_loaded(b.robot, b.frame, Vector3d::Zero());
  EXPECT_EQ(a.frame.v_body, b.frame.v_body);
  EXPECT_EQ(a.frame.Fxy, b.frame.Fxy);
}

TEST(ViscousLoaded, BalancesTheLoadAndMatchesTheSystemByHand) {
  for (unsigned seed = 0; seed < 20; ++seed) {
    Case c(3 + static_cast<int>(seed % 5), seed);
    const Vector3d load(2.0 * std::cos(seed), 2.0 * std::sin(seed), 0.3 * std::sin(3.0 * seed));
    solve_viscous_coulomb_loaded(c.robot, c.frame, load);
    EXPECT_LE(balance_residual(c, load), 1e-12) << seed;
    EXPECT_LE(c.frame.friction.residual, 1e-12) << seed;
    EXPECT_TRUE(c.frame.friction.converged);
    EXPECT_LE((c.frame.v_body - viscous_by_hand(c, load)).norm(), 1e-12 * (1.0 + load.norm()));
  }
}

TEST(ViscousLoaded, AffineInQdotWithTheFlatConnectionAndLinearInTheLoad) {
  // v = A q̇ + v(q̇ = 0): A from local_connection (eq. 3.20), the constant from a frame at rest.
  Case c(6, 7);
  const Vector3d load(-1.5, 0.4, 0.05);
  solve_viscous_coulomb_loaded(c.robot, c.frame, load);
  const Vector3d v = c.frame.v_body;
  connection::local_connection(c.robot, c.frame);
  Eigen::VectorXd qd(2 * c.frame.legs());
  for (int k = 0; k < c.frame.legs(); ++k) {
    qd.segment<2>(2 * k) = c.frame.qdot.col(k).head<2>();
  }
  const Vector3d linear = c.frame.A * qd;
  Case rest(6, 7);
  rest.frame.qdot.setZero();
  solve_viscous_coulomb_loaded(rest.robot, rest.frame, load);
  const Vector3d affine = rest.frame.v_body;
  EXPECT_LE((v - (linear + affine)).norm(), 1e-13);
  // Linear in the load: twice the load, twice the constant.
  solve_viscous_coulomb_loaded(rest.robot, rest.frame, 2.0 * load);
  EXPECT_LE((rest.frame.v_body - 2.0 * affine).norm(), 1e-13);
}

TEST(ViscousLoaded, NoFrictionCannotHoldALoad) {
  Case c(4, 3);
  std::fill(c.frame.contact.begin(), c.frame.contact.end(), 0);
  solve_viscous_coulomb_loaded(c.robot, c.frame, Vector3d(1.0, 0.0, 0.0));
  EXPECT_FALSE(c.frame.friction.converged);
  EXPECT_EQ(c.frame.friction.message.rfind("sliding", 0), 0U);
}

/// The Coulomb duality gap recomputed from the frame: forces in the disks, balanced, and
/// Σ c‖u‖ − fᵀx − Σ −F·q̇ relative to max(Σ c ‖u‖, Σ c ‖q̇‖, c_sum · max ‖q̇‖).
double coulomb_gap(const Case& c, const Vector3d& load) {
  const Vector3d x = c.frame.v_body;
  double primal = -load.dot(x);
  double dual = 0.0;
  double at_rest = 0.0;
  double vmax = 0.0;
  double csum = 0.0;
  for (int k = 0; k < c.frame.legs(); ++k) {
    const double ck = c.robot.mu(k) * c.frame.Fz(k);
    const Vector2d qd = c.frame.qdot.col(k).head<2>();
    const Vector2d u(x(0) - x(2) * c.frame.q(1, k) + qd(0), x(1) + x(2) * c.frame.q(0, k) + qd(1));
    const Vector2d F = c.frame.Fxy.col(k);
    EXPECT_LE(F.norm(), ck * (1.0 + 1e-12)) << "foot " << k << " outside its disk";
    primal += ck * u.norm();
    dual -= F.dot(qd);
    at_rest += ck * qd.norm();
    vmax = std::max(vmax, qd.norm());
    csum += ck;
  }
  const double pos = primal + load.dot(x);
  return (primal - dual) / std::max({pos, at_rest, csum * vmax});
}

TEST(CoulombLoaded, CertifiedAndBalanced) {
  for (unsigned seed = 0; seed < 30; ++seed) {
    Case c(3 + static_cast<int>(seed % 6), seed);
    // Loads up to ~60 % of what the feet can hold (Σ c ≈ 0.7 · 9.81).
    const double a = 0.7 * seed;
    const Vector3d load(4.0 * std::cos(a), 4.0 * std::sin(a), 0.2 * std::cos(2.0 * a));
    solve_coulomb_loaded(c.robot, c.frame, load);
    ASSERT_TRUE(c.frame.friction.converged) << seed << ": " << c.frame.friction.message;
    EXPECT_LE(c.frame.friction.certificate, 1e-10) << seed;
    EXPECT_LE(balance_residual(c, load), 1e-10) << seed;
    EXPECT_LE(coulomb_gap(c, load), 1e-9) << seed;
  }
}

TEST(CoulombLoaded, ZeroLoadIsTheFlatProblem) {
  for (unsigned seed = 0; seed < 10; ++seed) {
    Case a(5, seed);
    Case b(5, seed);
    solve_coulomb(a.robot, a.frame);
    solve_coulomb_loaded(b.robot, b.frame, Vector3d(1e-300, 0.0, 0.0));
    ASSERT_TRUE(b.frame.friction.converged);
    // Same convex problem, two algorithms: velocities agree to the certified accuracy.
    EXPECT_LE((a.frame.v_body - b.frame.v_body).norm(), 1e-6 * 0.05) << seed;
  }
}

TEST(CoulombLoaded, ExactlyZeroLoadIsTheFlatSolverBitForBit) {
  Case a(6, 5);
  Case b(6, 5);
  solve_coulomb(a.robot, a.frame);
  solve_coulomb_loaded(b.robot, b.frame, Vector3d::Zero());
  EXPECT_EQ(a.frame.v_body, b.frame.v_body);
  EXPECT_EQ(a.frame.Fxy, b.frame.Fxy);
}

TEST(CoulombLoaded, HoldsAtRestBelowTheFrictionLimitAndSlidesAbove) {
  // Feet at rest (q̇ = 0) on a centred ring: a pure force f holds iff ‖f‖ ≤ Σ μ F_z.
  Case c(6, 11);
  c.frame.qdot.setZero();
  for (int k = 0; k < 6; ++k) {
    const double a = 6.283185307179586 * k / 6;
    c.frame.q.col(k) << 0.3 * std::cos(a), 0.3 * std::sin(a), -0.1;
    c.frame.Fz(k) = 9.81 / 6;
  }
  const double hold = 0.7 * 9.81;
  solve_coulomb_loaded(c.robot, c.frame, Vector3d(0.98 * hold, 0.0, 0.0));
  ASSERT_TRUE(c.frame.friction.converged) << c.frame.friction.message;
  EXPECT_LE(c.frame.v_body.norm(), 1e-9);
  EXPECT_EQ(c.frame.friction.static_feet, 6);
  EXPECT_LE(balance_residual(c, Vector3d(0.98 * hold, 0.0, 0.0)), 1e-10);
  solve_coulomb_loaded(c.robot, c.frame, Vector3d(1.02 * hold, 0.0, 0.0));
  EXPECT_FALSE(c.frame.friction.converged);
  EXPECT_EQ(c.frame.friction.message.rfind("sliding", 0), 0U);
  EXPECT_LT(c.frame.friction.certificate, 0.0);  // the recession slope along the load
  // A moment beyond Σ c_k ‖q_k‖ = Σc · 0.3 cannot be held either (found by the runaway test).
  solve_coulomb_loaded(c.robot, c.frame, Vector3d(0.0, 0.0, 1.05 * hold * 0.3));
  EXPECT_FALSE(c.frame.friction.converged);
  EXPECT_EQ(c.frame.friction.message.rfind("sliding", 0), 0U);
  solve_coulomb_loaded(c.robot, c.frame, Vector3d(0.0, 0.0, 0.95 * hold * 0.3));
  EXPECT_TRUE(c.frame.friction.converged) << c.frame.friction.message;
}

TEST(CoulombLoaded, TwoGroupsNearTheHoldingLimit) {
  // A frame of BigANT's tripod on 42° at a gait transition (rounded from a run): the tripod
  // 0, 2, 4 cannot hold the load alone, so it slides and the other group's feet 3 and 5 stick,
  // with foot 3's force near its rim; pure translation with both sticking needs more than foot 3
  // can give, so the body also turns a little. Wrong static sets fail the polish; the right one
  // certifies.
  Case c(6, 0);
  const double q[6][2] = {{-0.35607, 0.2},  {0.078692, 0.2},   {0.24393, 0.2},
                          {-0.22131, -0.2}, {-0.056069, -0.2}, {0.37869, -0.2}};
  const double fz[6] = {12.9899, 0.0, 16.8272, 1.94464, 22.0905, 5.78197};
  const double qd[6] = {-0.026084, -0.023398, -0.026084, -0.023398, -0.026084, -0.023398};
  for (int k = 0; k < 6; ++k) {
    c.frame.q.col(k) << q[k][0], q[k][1], -0.1;
    c.frame.qdot.col(k) << qd[k], 0.0, 0.0;
    c.frame.Fz(k) = fz[k];
    c.frame.contact[static_cast<std::size_t>(k)] = fz[k] > 0.0 ? 1 : 0;
    c.robot.mu(k) = 1.0;
  }
  const Vector3d load(-53.6949, -0.00776542, 0.0);
  solve_coulomb_loaded(c.robot, c.frame, load);
  ASSERT_TRUE(c.frame.friction.converged) << c.frame.friction.message;
  EXPECT_LE(balance_residual(c, load), 1e-12);
  EXPECT_LE(coulomb_gap(c, load), 1e-10);
}

}  // namespace
}  // namespace slipwalk::friction
