// The planar friction forces at a prescribed body velocity (friction/planar_forces.hpp) against
// their oracles: the balances of the library's solvers (the sums vanish there and each foot's
// force is the solver's), one foot by hand (Coulomb: the maximum-dissipation force on the
// friction ellipse; viscous-Coulomb: linear in the slip), a rotated body frame, a moved reference
// point, feet at rest in the world, and the ε-law between its two limits.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "contact/robot.hpp"
#include "core/error.hpp"
#include "friction/planar_forces.hpp"
#include "friction/solvers.hpp"

namespace slipwalk::friction {
namespace {

using contact::Frame;
using contact::Robot;
using Eigen::Matrix2d;
using Eigen::Vector2d;
using Eigen::Vector3d;

constexpr ForceLaw kLaws[] = {ForceLaw::kViscousCoulomb, ForceLaw::kCoulomb, ForceLaw::kEpsilon};
constexpr double kEps = 0.05;  // m/s, the ε of the ε-law wherever it is not the point

// ---- fixtures -----------------------------------------------------------------------------

/// A robot with n legs and a frame with every foot in contact (contact and F_z are inputs here).
struct Scene {
  Robot robot;
  Frame frame;
  explicit Scene(int n) : robot(contact::uniform_robot(n)), frame(robot) {
    std::fill(frame.contact.begin(), frame.contact.end(), 1);
    frame.Fz.setConstant(1.0 / n);
  }
  [[nodiscard]] int n() const { return robot.legs(); }
};

/// Feet in a disk of radius 0.3 m, loads and μ varied, optionally anisotropic; every foot moves
/// relative to the body at `common` plus a random velocity of up to `spread` per component.
Scene random_scene(std::mt19937& rng, int n, bool aniso, const Vector2d& common, double spread) {
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  std::uniform_real_distribution<double> P(0.2, 1.0);
  Scene s(n);
  for (int k = 0; k < n; ++k) {
    const double ang = 2.0 * M_PI * k / n + 0.3 * U(rng);
    const double rad = 0.3 * P(rng);
    s.frame.q.col(k) << rad * std::cos(ang), rad * std::sin(ang), -0.1;
    s.frame.qdot.col(k) << common(0) + spread * U(rng), common(1) + spread * U(rng), 0.0;
    s.frame.Fz(k) = P(rng);
    s.robot.mu(k) = 0.5 * P(rng);
    if (aniso) {
      s.robot.w.col(k) << 2.0 * U(rng), 2.0 * U(rng);
    }
  }
  return s;
}

/// u_k = v + ω S q_k + q̇_k, written out here.
Vector2d slip_of(const Frame& f, int k, const Vector2d& v, double omega) {
  return Vector2d(v(0) - omega * f.q(1, k) + f.qdot(0, k), v(1) + omega * f.q(0, k) + f.qdot(1, k));
}

Matrix2d G_of(const Robot& r, int k) {
  return Matrix2d::Identity() + r.w.col(k) * r.w.col(k).transpose();
}

/// Σ ‖F_k‖ at (v, ω): the size of the terms that cancel in a balance.
double force_scale(const Scene& s, const Vector2d& v, double omega, ForceLaw law) {
  double scale = 0.0;
  for (int k = 0; k < s.n(); ++k) {
    scale += foot_force(s.robot, s.frame, k, slip_of(s.frame, k, v, omega), law, kEps).norm();
  }
  return scale;
}

/// At the solver's velocity the sum of `law` vanishes (relative to the cancelling terms, `tol`)
/// and each foot's force is the solver's frame.Fxy.
void expect_balanced(const Scene& s, ForceLaw law, double tol, const char* what) {
  const Vector2d v = s.frame.v_body.head<2>();
  const double omega = s.frame.v_body(2);
  const PlanarSum sum = planar_forces(s.robot, s.frame, v, omega, law, kEps);
  const double scale = force_scale(s, v, omega, law);
  EXPECT_LE(sum.force.norm(), tol * scale) << what;
  EXPECT_LE(std::abs(sum.moment), tol * scale * 0.3) << what;  // lever arms ≤ 0.3 m
  for (int k = 0; k < s.n(); ++k) {
    const Vector2d F = foot_force(s.robot, s.frame, k, slip_of(s.frame, k, v, omega), law, kEps);
    EXPECT_LE((F - s.frame.Fxy.col(k)).norm(), tol * scale) << what << " foot " << k;
  }
}

// ---- the sums vanish at the solvers' balances ----------------------------------------------

TEST(PlanarForces, VanishAtTheViscousCoulombBalance) {
  std::mt19937 rng(1);
  for (int trial = 0; trial < 100; ++trial) {
    Scene s = random_scene(rng, 3 + trial % 8, trial % 2 == 0, Vector2d(0.0, 0.0), 0.1);
    solve_viscous_coulomb(s.robot, s.frame);
    expect_balanced(s, ForceLaw::kViscousCoulomb, 1e-12, "viscous-Coulomb");
  }
}

TEST(PlanarForces, VanishAtTheCoulombBalanceWithTheStickingFeetsForcesAdded) {
  // At a Coulomb balance some feet may stick (u_k = 0): their force is anywhere in their friction
  // ellipse, so the balance is the sum over the sliding feet plus the solver's forces on the
  // sticking ones; each sliding foot's force is the solver's.
  std::mt19937 rng(2);
  int with_sticking = 0;
  int all_sliding = 0;
  for (int trial = 0; trial < 100; ++trial) {
    Scene s = random_scene(rng, 3 + trial % 8, trial % 2 == 0, Vector2d(0.0, 0.0), 0.1);
    solve_coulomb(s.robot, s.frame);
    ASSERT_TRUE(s.frame.friction.converged) << s.frame.friction.message;
    const Vector2d v = s.frame.v_body.head<2>();
    const double omega = s.frame.v_body(2);
    PlanarSum sum = planar_forces(s.robot, s.frame, v, omega, ForceLaw::kCoulomb);
    double scale = 0.0;
    int sticking = 0;
    for (int k = 0; k < s.n(); ++k) {
      const double c = s.robot.mu(k) * s.frame.Fz(k);
      scale += c;
      const Vector2d u = slip_of(s.frame, k, v, omega);
      if (u.norm() <= 1e-9) {  // the feet's speeds are ~0.1 m/s
        ++sticking;
        // Its slip is zero to the solver's accuracy, not exactly: swap the force foot_force()
        // gives it for the solver's.
        const Vector2d F =
            s.frame.Fxy.col(k) - foot_force(s.robot, s.frame, k, u, ForceLaw::kCoulomb);
        sum.force += F;
        sum.moment += s.frame.q(0, k) * F(1) - s.frame.q(1, k) * F(0);
      } else {
        EXPECT_LE(
            (foot_force(s.robot, s.frame, k, u, ForceLaw::kCoulomb) - s.frame.Fxy.col(k)).norm(),
            1e-9 * c)
            << "trial " << trial << " foot " << k;
      }
    }
    EXPECT_EQ(sticking, s.frame.friction.static_feet) << "trial " << trial;
    EXPECT_LE(sum.force.norm(), 1e-9 * scale) << "trial " << trial;
    EXPECT_LE(std::abs(sum.moment), 1e-9 * scale * 0.3) << "trial " << trial;
    (sticking > 0 ? with_sticking : all_sliding) += 1;
  }
  EXPECT_GT(with_sticking, 0);
  EXPECT_GT(all_sliding, 0);
}

TEST(PlanarForces, VanishAtTheEpsilonBalance) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 100; ++trial) {
    Scene s = random_scene(rng, 3 + trial % 8, trial % 2 == 0, Vector2d(0.0, 0.0), 0.1);
    solve_epsilon(s.robot, s.frame, kEps);
    ASSERT_TRUE(s.frame.friction.converged) << s.frame.friction.message;
    expect_balanced(s, ForceLaw::kEpsilon, 1e-10, "epsilon");
  }
}

// ---- one foot by hand -------------------------------------------------------------------------

TEST(FootForce, CoulombHasMagnitudeMuFzOppositeTheSlip) {
  Scene s(1);
  s.robot.mu(0) = 0.7;
  s.frame.Fz(0) = 2.0;
  for (const Vector2d& u : {Vector2d(0.3, -0.4), Vector2d(-5.0, 0.0), Vector2d(1e-9, 2e-9)}) {
    const Vector2d F = foot_force(s.robot, s.frame, 0, u, ForceLaw::kCoulomb);
    EXPECT_NEAR(F.norm(), 1.4, 1e-15);
    EXPECT_NEAR(F.dot(u) / u.norm(), -1.4, 1e-15);  // antiparallel to u
  }
  const Vector2d F = foot_force(s.robot, s.frame, 0, Vector2d(0.3, -0.4), ForceLaw::kCoulomb);
  EXPECT_NEAR(F(0), -0.84, 1e-15);
  EXPECT_NEAR(F(1), 1.12, 1e-15);
}

TEST(FootForce, AnisotropicCoulombIsTheMaximumDissipationForceOnItsEllipse) {
  // The friction set is the ellipse {F : Fᵀ G⁻¹ F ≤ c²} (eq. 3.19's G); the Coulomb force is the
  // one point of it that maximizes the dissipation −F·u, whose maximum is c √(uᵀ G u).
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> U(-2.0, 2.0);
  Scene s(1);
  s.robot.mu(0) = 0.6;
  s.frame.Fz(0) = 1.5;
  const double c = 0.9;
  for (int trial = 0; trial < 50; ++trial) {
    s.robot.w.col(0) << U(rng), U(rng);
    const Vector2d u(U(rng), U(rng));
    const Matrix2d G = G_of(s.robot, 0);
    const Vector2d F = foot_force(s.robot, s.frame, 0, u, ForceLaw::kCoulomb);
    EXPECT_NEAR(F.dot(G.inverse() * F), c * c, 1e-12);
    EXPECT_NEAR(-F.dot(u), c * std::sqrt(u.dot(G * u)), 1e-12);
    // No point of the ellipse's rim dissipates more.
    for (int j = 0; j < 64; ++j) {
      const double a = 2.0 * M_PI * j / 64;
      const Eigen::SelfAdjointEigenSolver<Matrix2d> es(G);
      const Vector2d rim = c * es.operatorSqrt() * Vector2d(std::cos(a), std::sin(a));
      EXPECT_LE(-rim.dot(u), -F.dot(u) + 1e-12);
    }
  }
}

TEST(FootForce, StickingCoulombFootGivesTheCentreOfItsFrictionSet) {
  Scene s(1);
  s.robot.w.col(0) << 1.0, -0.5;
  const Vector2d F = foot_force(s.robot, s.frame, 0, Vector2d::Zero(), ForceLaw::kCoulomb);
  EXPECT_EQ(F, Vector2d::Zero());
}

TEST(FootForce, ViscousCoulombIsLinearInTheSlip) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(-2.0, 2.0);
  Scene s(1);
  s.robot.mu(0) = 0.8;
  s.frame.Fz(0) = 0.5;
  for (int trial = 0; trial < 50; ++trial) {
    s.robot.w.col(0) << U(rng), U(rng);
    const Vector2d u1(U(rng), U(rng));
    const Vector2d u2(U(rng), U(rng));
    const double a = U(rng);
    const double b = U(rng);
    const auto F = [&](const Vector2d& u) {
      return foot_force(s.robot, s.frame, 0, u, ForceLaw::kViscousCoulomb);
    };
    // F = −μ F_z (I + w wᵀ) u, the matrix written out.
    const Matrix2d H = -0.4 * G_of(s.robot, 0);
    EXPECT_LE((F(u1) - H * u1).norm(), 1e-14 * (1.0 + (H * u1).norm()));
    EXPECT_LE((F(a * u1 + b * u2) - (a * F(u1) + b * F(u2))).norm(), 1e-13);
  }
}

// ---- the ε-law between its limits -------------------------------------------------------------

TEST(FootForce, EpsilonLawTendsToCoulombAsEpsilonVanishesAndIsViscousAtInfinity) {
  // A sliding foot at s = ‖W u‖ ≠ 1: φ_ε(s) − 1/s = ε (s − 1)/(s (ε + s²)), so the distance to
  // the Coulomb force is c ‖G u‖ ε |s − 1|/(s (ε + s²)) = O(ε).
  Scene s(1);
  s.robot.mu(0) = 0.5;
  s.frame.Fz(0) = 2.0;
  s.robot.w.col(0) << 0.6, -0.3;
  const double c = 1.0;  // μ F_z
  const Vector2d u(1.8, 1.1);
  const Matrix2d G = G_of(s.robot, 0);
  const double slip = std::sqrt(u.dot(G * u));
  const Vector2d coulomb = foot_force(s.robot, s.frame, 0, u, ForceLaw::kCoulomb);
  double previous = std::numeric_limits<double>::infinity();
  for (double eps : {1.0, 1e-2, 1e-4, 1e-6, 1e-8}) {
    const Vector2d F = foot_force(s.robot, s.frame, 0, u, ForceLaw::kEpsilon, eps);
    const double distance = (F - coulomb).norm();
    const double expected =
        c * (G * u).norm() * eps * std::abs(slip - 1.0) / (slip * (eps + slip * slip));
    EXPECT_NEAR(distance, expected, 1e-14 + 1e-10 * expected) << "eps=" << eps;
    EXPECT_LT(distance, previous);
    previous = distance;
  }
  EXPECT_LE(previous, 1e-8);
  // ε = +∞ is the viscous-Coulomb force exactly; a large ε is close to it.
  const Vector2d viscous = foot_force(s.robot, s.frame, 0, u, ForceLaw::kViscousCoulomb);
  EXPECT_EQ(foot_force(s.robot, s.frame, 0, u, ForceLaw::kEpsilon), viscous);
  EXPECT_LE((foot_force(s.robot, s.frame, 0, u, ForceLaw::kEpsilon, 1e9) - viscous).norm(),
            1e-8 * viscous.norm());
}

TEST(FootForce, EpsilonMustBePositive) {
  Scene s(3);
  const Vector2d u(0.1, 0.2);
  for (double eps : {0.0, -1.0, std::nan("")}) {
    EXPECT_THROW((void)foot_force(s.robot, s.frame, 0, u, ForceLaw::kEpsilon, eps),
                 core::InputError);
    EXPECT_THROW((void)planar_forces(s.robot, s.frame, u, 0.0, ForceLaw::kEpsilon, eps),
                 core::InputError);
    // The other laws do not read ε.
    EXPECT_NO_THROW((void)planar_forces(s.robot, s.frame, u, 0.0, ForceLaw::kCoulomb, eps));
  }
}

// ---- invariances --------------------------------------------------------------------------

TEST(PlanarForces, RotateWithTheBodyFrame) {
  // Rotating feet, their velocities, the anisotropy directions and the body velocity by R rotates
  // the force sum by R and leaves the moment unchanged.
  std::mt19937 rng(6);
  for (int trial = 0; trial < 30; ++trial) {
    Scene s = random_scene(rng, 3 + trial % 6, trial % 2 == 1, Vector2d(0.0, 0.0), 0.3);
    const Vector2d v(0.05 * (trial % 5) - 0.1, 0.03 * (trial % 3));
    const double omega = 0.2 * (trial % 4) - 0.3;
    PlanarSum before[3];
    for (int l = 0; l < 3; ++l) {
      before[l] = planar_forces(s.robot, s.frame, v, omega, kLaws[l], kEps);
    }
    const double a = 0.7 + 0.4 * trial;
    Matrix2d R;
    R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
    for (int k = 0; k < s.n(); ++k) {
      s.frame.q.col(k).head<2>() = R * s.frame.q.col(k).head<2>();
      s.frame.qdot.col(k).head<2>() = R * s.frame.qdot.col(k).head<2>();
      s.robot.w.col(k) = R * s.robot.w.col(k);
    }
    for (int l = 0; l < 3; ++l) {
      const PlanarSum after = planar_forces(s.robot, s.frame, R * v, omega, kLaws[l], kEps);
      const double tol = 1e-13 * (1.0 + force_scale(s, R * v, omega, kLaws[l]));
      EXPECT_LE((after.force - R * before[l].force).norm(), tol) << "law " << l;
      EXPECT_NEAR(after.moment, before[l].moment, tol) << "law " << l;
    }
  }
}

TEST(PlanarForces, MovingTheReferencePointShiftsTheMomentByDCrossF) {
  // Measuring the feet from a point d of the body (q' = q − d) whose velocity is v' = v + ω S d
  // leaves every slip and force unchanged; the moment about the new point is M − d × ΣF.
  std::mt19937 rng(7);
  const Vector2d d(0.12, -0.07);
  for (int trial = 0; trial < 30; ++trial) {
    Scene s = random_scene(rng, 3 + trial % 6, trial % 2 == 0, Vector2d(0.0, 0.0), 0.3);
    const Vector2d v(0.04, -0.02 * (trial % 4));
    const double omega = 0.5 - 0.25 * (trial % 5);
    PlanarSum before[3];
    for (int l = 0; l < 3; ++l) {
      before[l] = planar_forces(s.robot, s.frame, v, omega, kLaws[l], kEps);
    }
    for (int k = 0; k < s.n(); ++k) {
      s.frame.q.col(k).head<2>() -= d;
    }
    const Vector2d v_d = v + omega * Vector2d(-d(1), d(0));
    for (int l = 0; l < 3; ++l) {
      const PlanarSum after = planar_forces(s.robot, s.frame, v_d, omega, kLaws[l], kEps);
      const Vector2d F = before[l].force;
      const double tol = 1e-13 * (1.0 + force_scale(s, v_d, omega, kLaws[l]));
      EXPECT_LE((after.force - F).norm(), tol) << "law " << l;
      EXPECT_NEAR(after.moment, before[l].moment - (d(0) * F(1) - d(1) * F(0)), tol) << "law " << l;
    }
  }
}

TEST(PlanarForces, FeetAtRestInTheWorldCarryNoForce) {
  // A rigid body motion (v, ω) with every foot moving relative to the body at −(v + ω S q_k):
  // no foot slips, so under every law there is no force and no moment.
  std::mt19937 rng(8);
  Scene s = random_scene(rng, 6, true, Vector2d(0.0, 0.0), 0.0);
  const Vector2d v(0.3, -0.2);
  const double omega = 0.8;
  for (int k = 0; k < s.n(); ++k) {
    s.frame.qdot.col(k).head<2>() = -(v + omega * Vector2d(-s.frame.q(1, k), s.frame.q(0, k)));
  }
  for (ForceLaw law : kLaws) {
    const PlanarSum sum = planar_forces(s.robot, s.frame, v, omega, law, kEps);
    EXPECT_LE(sum.force.norm(), 1e-15);
    EXPECT_LE(std::abs(sum.moment), 1e-15);
  }
}

TEST(PlanarForces, FeetInTheAirAreLeftOut) {
  std::mt19937 rng(9);
  Scene s = random_scene(rng, 5, true, Vector2d(0.0, 0.0), 0.3);
  const Vector2d v(0.1, 0.05);
  const double omega = -0.4;
  s.frame.contact[2] = 0;
  for (ForceLaw law : kLaws) {
    Vector2d F = Vector2d::Zero();
    double M = 0.0;
    for (int k : {0, 1, 3, 4}) {
      const Vector2d f = foot_force(s.robot, s.frame, k, slip_of(s.frame, k, v, omega), law, kEps);
      F += f;
      M += s.frame.q(0, k) * f(1) - s.frame.q(1, k) * f(0);
    }
    const PlanarSum sum = planar_forces(s.robot, s.frame, v, omega, law, kEps);
    EXPECT_LE((sum.force - F).norm(), 1e-14);
    EXPECT_NEAR(sum.moment, M, 1e-14);
  }
}

}  // namespace
}  // namespace slipwalk::friction
