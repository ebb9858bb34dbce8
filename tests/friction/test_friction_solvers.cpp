// The friction solvers of §3.4 against their oracles: balance residuals, the 1-D example of
// §3.1.2 (mean / median), a brute-force minimization of the dissipation, the dual certificate
// recomputed here from the returned forces, the ε limits, invariances, anisotropy by hand and the
// hard cases (static, one foot, one point, many feet).
#include <gsl/gsl_multimin.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "contact/robot.hpp"
#include "core/error.hpp"
#include "friction/coulomb_solver.hpp"
#include "friction/solvers.hpp"

namespace slipwalk::friction {
namespace {

using contact::Frame;
using contact::Robot;
using Eigen::Matrix2d;
using Eigen::Vector2d;
using Eigen::Vector3d;

// ---- fixtures -----------------------------------------------------------------------------

/// A robot with n legs and a frame with every foot in contact (the spring support is not used:
/// contact and F_z are inputs here).
struct Scene {
  Robot robot;
  Frame frame;
  explicit Scene(int n) : robot(contact::uniform_robot(n)), frame(robot) {
    std::fill(frame.contact.begin(), frame.contact.end(), 1);
    frame.Fz.setConstant(1.0 / n);
  }
  [[nodiscard]] int n() const { return robot.legs(); }
};

/// Random scene: feet in a disk of radius 0.3 m, velocities ~0.1 m/s, loads and μ varied,
/// optionally anisotropic.
Scene random_scene(std::mt19937& rng, int n, bool aniso = false) {
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  std::uniform_real_distribution<double> P(0.2, 1.0);
  Scene s(n);
  for (int k = 0; k < n; ++k) {
    const double ang = 2.0 * M_PI * k / n + 0.3 * U(rng);
    const double rad = 0.3 * P(rng);
    s.frame.q.col(k) << rad * std::cos(ang), rad * std::sin(ang), -0.1;
    s.frame.qdot.col(k) << 0.1 * U(rng), 0.1 * U(rng), 0.0;
    s.frame.Fz(k) = P(rng);
    s.robot.mu(k) = 0.5 * P(rng);
    if (aniso) {
      s.robot.w.col(k) << 2.0 * U(rng), 2.0 * U(rng);
    }
  }
  return s;
}

Matrix2d G_of(const Robot& r, int k) {
  return Matrix2d::Identity() + r.w.col(k) * r.w.col(k).transpose();
}
Matrix2d W_of(const Robot& r, int k) {
  const Eigen::SelfAdjointEigenSolver<Matrix2d> es(G_of(r, k));
  return es.operatorSqrt();
}

Vector2d slip_of(const Frame& f, int k, const Vector3d& x) {
  return x.head<2>() + x(2) * Vector2d(-f.q(1, k), f.q(0, k)) + f.qdot.col(k).head<2>();
}

/// The Coulomb dissipation D(x) = Σ μ F_z ‖W u‖ (independent of the library).
double dissipation(const Scene& s, const Vector3d& x) {
  double D = 0.0;
  for (int k = 0; k < s.n(); ++k) {
    if (s.frame.contact[static_cast<std::size_t>(k)] != 0) {
      D += s.robot.mu(k) * s.frame.Fz(k) * (W_of(s.robot, k) * slip_of(s.frame, k, x)).norm();
    }
  }
  return D;
}

/// Planar force and moment of frame.Fxy.
Vector3d wrench(const Frame& f) {
  Vector3d w = Vector3d::Zero();
  for (int k = 0; k < f.legs(); ++k) {
    w.head<2>() += f.Fxy.col(k);
    w(2) += f.q(0, k) * f.Fxy(1, k) - f.q(1, k) * f.Fxy(0, k);
  }
  return w;
}

/// The viscous-Coulomb balance written independently, in the WORLD frame of the thesis (eqs.
/// 3.15–3.19 with H_k = −c R_θ G R_θᵀ and the moment p̄ × F), solved with Eigen's LU.
Vector3d viscous_world(const Scene& s) {
  const double th = s.frame.theta;
  Matrix2d R;
  R << std::cos(th), -std::sin(th), std::sin(th), std::cos(th);
  Matrix2d S;
  S << 0, -1, 1, 0;
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Vector3d rhs = Vector3d::Zero();
  for (int k = 0; k < s.n(); ++k) {
    if (s.frame.contact[static_cast<std::size_t>(k)] == 0) {
      continue;
    }
    const Matrix2d H = -s.robot.mu(k) * s.frame.Fz(k) * R * G_of(s.robot, k) * R.transpose();
    const Vector2d pbar = R * s.frame.q.col(k).head<2>();
    const Vector2d qd = R * s.frame.qdot.col(k).head<2>();
    // F = H (pdot0 + θ̇ S p̄ + R q̇); rows: ΣF = 0 and Σ (p̄ × F) = 0.
    A.block<2, 2>(0, 0) += H;
    A.block<2, 1>(0, 2) += H * S * pbar;
    const Eigen::RowVector2d cross(-pbar(1), pbar(0));  // p̄ × a = (−p̄_y, p̄_x)·a
    A.block<1, 2>(2, 0) += cross * H;
    A(2, 2) += cross * H * S * pbar;
    rhs.head<2>() -= H * qd;
    rhs(2) -= cross * H * qd;
  }
  const Vector3d world = A.lu().solve(rhs);
  Vector3d body;
  body.head<2>() = R.transpose() * world.head<2>();
  body(2) = world(2);
  return body;
}

/// Brute force: GSL Nelder–Mead on D from several starts, each restarted until it stops
/// improving; returns the best point.
Vector3d brute_force_coulomb(const Scene& s, const Vector3d& hint) {
  struct Ctx {
    const Scene* s;
  } ctx{&s};
  gsl_multimin_function fn;
  fn.n = 3;
  fn.params = &ctx;
  fn.f = [](const gsl_vector* v, void* p) {
    const auto* c = static_cast<const Ctx*>(p);
    return dissipation(*c->s,
                       Vector3d(gsl_vector_get(v, 0), gsl_vector_get(v, 1), gsl_vector_get(v, 2)));
  };
  std::mt19937 rng(7);
  std::normal_distribution<double> N01(0.0, 1.0);
  Vector3d best = hint;
  double fbest = dissipation(s, hint);
  gsl_vector* x = gsl_vector_alloc(3);
  gsl_vector* step = gsl_vector_alloc(3);
  gsl_multimin_fminimizer* m = gsl_multimin_fminimizer_alloc(gsl_multimin_fminimizer_nmsimplex2, 3);
  for (int start = 0; start < 4; ++start) {
    Vector3d x0 = start == 0 ? Vector3d::Zero()
                             : Vector3d(best + 0.05 * Vector3d(N01(rng), N01(rng), N01(rng)));
    double size = 0.05;
    for (int restart = 0; restart < 8; ++restart) {
      for (int i = 0; i < 3; ++i) {
        gsl_vector_set(x, static_cast<std::size_t>(i), x0(i));
        gsl_vector_set(step, static_cast<std::size_t>(i), size);
      }
      gsl_multimin_fminimizer_set(m, &fn, x, step);
      for (int it = 0; it < 5000; ++it) {
        if (gsl_multimin_fminimizer_iterate(m) != 0) {
          break;
        }
        if (gsl_multimin_test_size(gsl_multimin_fminimizer_size(m), 1e-14) == GSL_SUCCESS) {
          break;
        }
      }
      for (int i = 0; i < 3; ++i) {
        x0(i) = gsl_vector_get(m->x, static_cast<std::size_t>(i));
      }
      size = std::max(size * 0.1, 1e-9);
    }
    const double f0 = dissipation(s, x0);
    if (f0 < fbest) {
      fbest = f0;
      best = x0;
    }
  }
  gsl_multimin_fminimizer_free(m);
  gsl_vector_free(step);
  gsl_vector_free(x);
  return best;
}

/// The optimality certificate recomputed from the returned forces: balanced (relative 1e-10), in
/// the friction ellipses, and D(v) − Σ F_k·(−q̇_k) ≤ tol · max(D(v), D(0)).
void expect_certified(const Scene& s, double tol, const char* what) {
  const Frame& f = s.frame;
  double scale = 0.0;
  double dual = 0.0;
  double L = 0.0;
  for (int k = 0; k < s.n(); ++k) {
    const double c = s.robot.mu(k) * s.frame.Fz(k);
    if (f.contact[static_cast<std::size_t>(k)] == 0) {
      EXPECT_EQ(f.Fxy.col(k).norm(), 0.0) << what;
      continue;
    }
    scale += c * W_of(s.robot, k).norm();
    L = std::max(L, f.q.col(k).head<2>().norm());
    // ellipse Fᵀ G⁻¹ F ≤ c²
    const Vector2d F = f.Fxy.col(k);
    EXPECT_LE(F.dot(G_of(s.robot, k).inverse() * F), c * c * (1.0 + 1e-12)) << what << " leg " << k;
    dual += -F.dot(f.qdot.col(k).head<2>());
  }
  const Vector3d w = wrench(f);
  EXPECT_LE(w.head<2>().norm(), 1e-10 * scale) << what;
  EXPECT_LE(std::abs(w(2)), 1e-10 * scale * L) << what;
  const double D = dissipation(s, f.v_body);
  const double D0 = dissipation(s, Vector3d::Zero());
  EXPECT_LE(D - dual, tol * std::max(D, D0) + 1e-15 * scale) << what;
  EXPECT_LE(f.friction.certificate, tol) << what;
  EXPECT_TRUE(f.friction.converged) << what << ": " << f.friction.message;
  EXPECT_LE(f.friction.residual, 1e-10) << what;
  EXPECT_TRUE(f.v_body.allFinite()) << what;
}

/// Feet on the x axis moving along x with equal loads (the 1-D example of §3.1.2).
Scene line_scene(const std::vector<double>& qdx) {
  const int n = static_cast<int>(qdx.size());
  Scene s(n);
  for (int k = 0; k < n; ++k) {
    s.frame.q.col(k) << -0.3 + 0.6 * k / std::max(n - 1, 1), 0.0, -0.1;
    s.frame.qdot.col(k) << qdx[static_cast<std::size_t>(k)], 0.0, 0.0;
  }
  return s;
}

// ---- balance residuals ----------------------------------------------------------------------

TEST(FrictionBalance, ViscousEpsilonAndCoulombBalanceOnRandomFrames) {
  std::mt19937 rng(1);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 3 + trial % 10;
    Scene s = random_scene(rng, n, trial % 3 == 0);
    solve_viscous_coulomb(s.robot, s.frame);
    EXPECT_LE(s.frame.friction.residual, 1e-10);
    EXPECT_TRUE(s.frame.friction.unique);
    double scale = 0.0;
    for (int k = 0; k < n; ++k) {
      scale += s.frame.Fxy.col(k).norm();
    }
    const Vector3d w = wrench(s.frame);
    EXPECT_LE(w.head<2>().norm(), 1e-12 * scale);
    EXPECT_LE(std::abs(w(2)), 1e-12 * scale * 0.3);

    solve_epsilon(s.robot, s.frame, 0.01);
    EXPECT_TRUE(s.frame.friction.converged) << s.frame.friction.message;
    EXPECT_LE(s.frame.friction.residual, 1e-10);

    solve_coulomb(s.robot, s.frame);
    expect_certified(s, 1e-10, "random");
  }
}

TEST(FrictionBalance, ViscousMatchesTheThesisWorldFrameFormulation) {
  std::mt19937 rng(2);
  for (int trial = 0; trial < 100; ++trial) {
    Scene s = random_scene(rng, 3 + trial % 6, trial % 2 == 0);
    s.frame.theta = 3.0 * (trial % 7) - 9.0;
    solve_viscous_coulomb(s.robot, s.frame);
    const Vector3d ref = viscous_world(s);
    EXPECT_LE((s.frame.v_body - ref).norm(), 1e-12 * (1.0 + ref.norm()));
  }
}

// ---- the 1-D example of §3.1.2 --------------------------------------------------------------

TEST(Friction1D, ViscousIsMinusTheMean) {
  const std::vector<double> qd = {0.3, -0.1, 0.05, 0.2, -0.4, 0.7};
  Scene s = line_scene(qd);
  solve_viscous_coulomb(s.robot, s.frame);
  double mean = 0.0;
  for (double v : qd) {
    mean += v / static_cast<double>(qd.size());
  }
  EXPECT_NEAR(s.frame.v_body(0), -mean, 1e-15);
  EXPECT_EQ(s.frame.v_body(1), 0.0);
  EXPECT_EQ(s.frame.v_body(2), 0.0);
}

TEST(Friction1D, CoulombIsMinusTheMedianForOddN) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int n : {1, 3, 5, 7, 9, 51}) {
    std::vector<double> qd(static_cast<std::size_t>(n));
    for (double& v : qd) {
      v = U(rng);
    }
    Scene s = line_scene(qd);
    solve_coulomb(s.robot, s.frame);
    std::vector<double> sorted = qd;
    std::sort(sorted.begin(), sorted.end());
    const double median = sorted[sorted.size() / 2];
    EXPECT_NEAR(s.frame.v_body(0), -median, 1e-14) << "n=" << n;
    EXPECT_NEAR(s.frame.v_body(1), 0.0, 1e-14);
    EXPECT_NEAR(s.frame.v_body(2), 0.0, 1e-13);
    EXPECT_EQ(s.frame.friction.static_feet, 1) << "n=" << n;
    EXPECT_EQ(s.frame.friction.unique, n > 1) << "n=" << n << " " << s.frame.friction.message;
    if (n > 1) {
      expect_certified(s, 1e-10, "odd median");
    }
  }
}

TEST(Friction1D, CoulombIsInTheMedianIntervalAndNotUniqueForEvenN) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int n : {2, 4, 6, 10, 50}) {
    std::vector<double> qd(static_cast<std::size_t>(n));
    for (double& v : qd) {
      v = U(rng);
    }
    Scene s = line_scene(qd);
    solve_coulomb(s.robot, s.frame);
    std::vector<double> sorted = qd;
    std::sort(sorted.begin(), sorted.end());
    const double lo = -sorted[sorted.size() / 2];
    const double hi = -sorted[sorted.size() / 2 - 1];
    EXPECT_GE(s.frame.v_body(0), lo - 1e-14) << "n=" << n;
    EXPECT_LE(s.frame.v_body(0), hi + 1e-14) << "n=" << n;
    EXPECT_NEAR(s.frame.v_body(2), 0.0, 1e-13);
    EXPECT_FALSE(s.frame.friction.unique) << "n=" << n;
    expect_certified(s, 1e-10, "even median");
  }
}

TEST(Friction1D, CoulombWithUnequalLoadsIsTheWeightedMedian) {
  Scene s = line_scene({0.1, 0.2, 0.3, 0.4});
  s.frame.Fz << 0.1, 0.1, 0.1, 0.35;  // foot 3 carries more than half the load: it holds
  solve_coulomb(s.robot, s.frame);
  EXPECT_NEAR(s.frame.v_body(0), -0.4, 1e-14);
  EXPECT_TRUE(s.frame.friction.unique);
  expect_certified(s, 1e-10, "weighted median");
}

// ---- Coulomb against brute force --------------------------------------------------------------

TEST(Coulomb, AgreesWithBruteForceMinimizationOfTheDissipation) {
  std::mt19937 rng(5);
  int unique_cases = 0;
  for (int trial = 0; trial < 40; ++trial) {
    Scene s = random_scene(rng, 3 + trial % 4, trial % 4 == 3);
    solve_coulomb(s.robot, s.frame);
    const Vector3d v = s.frame.v_body;
    const Vector3d bf = brute_force_coulomb(s, Vector3d::Zero());
    const double D = dissipation(s, v);
    const double Dbf = dissipation(s, bf);
    // Nothing beats our minimum, and the brute force gets as low to its own accuracy.
    EXPECT_LE(D, Dbf * (1.0 + 1e-12)) << "trial " << trial;
    EXPECT_LE(Dbf - D, 1e-9 * D) << "trial " << trial;
    if (s.frame.friction.unique) {
      ++unique_cases;
      EXPECT_LE((v - bf).norm(), 1e-5 * (1.0 + v.norm())) << "trial " << trial;
    }
  }
  EXPECT_GT(unique_cases, 30);
}

TEST(Coulomb, ReportedUniqueMinimaRiseInEveryDirection) {
  std::mt19937 rng(6);
  for (int trial = 0; trial < 100; ++trial) {
    Scene s = random_scene(rng, 3 + trial % 8, trial % 5 == 0);
    solve_coulomb(s.robot, s.frame);
    const Vector3d v = s.frame.v_body;
    const double D = dissipation(s, v);
    for (int i = 0; i < 3; ++i) {
      for (double h : {-1e-4, 1e-4}) {
        Vector3d e = Vector3d::Zero();
        e(i) = h * (i == 2 ? 3.0 : 0.1);
        EXPECT_GE(dissipation(s, v + e), D * (1.0 - 1e-14));
        if (s.frame.friction.unique) {
          EXPECT_GT(dissipation(s, v + e), D + 1e-14 * D) << "trial " << trial;
        }
      }
    }
  }
}

// ---- ε limits -------------------------------------------------------------------------------

TEST(Epsilon, LargeEpsilonIsViscousCoulomb) {
  std::mt19937 rng(8);
  for (int trial = 0; trial < 50; ++trial) {
    Scene s = random_scene(rng, 3 + trial % 6, trial % 2 == 0);
    solve_viscous_coulomb(s.robot, s.frame);
    const Vector3d visc = s.frame.v_body;
    solve_epsilon(s.robot, s.frame, std::numeric_limits<double>::infinity());
    EXPECT_EQ((s.frame.v_body - visc).norm(), 0.0);
    double prev = 1.0;
    for (double eps : {1e2, 1e4, 1e6, 1e8}) {
      solve_epsilon(s.robot, s.frame, eps);
      EXPECT_TRUE(s.frame.friction.converged);
      EXPECT_LE(s.frame.friction.residual, 1e-10);
      const double err = (s.frame.v_body - visc).norm() / (visc.norm() + 1e-3);
      EXPECT_LE(err, 10.0 / eps) << "eps=" << eps;  // φ − 1 = O(s/ε) with s ≲ 0.3
      EXPECT_LE(err, prev);
      prev = err;
    }
  }
}

TEST(Epsilon, SmallEpsilonTendsToCoulomb) {
  std::mt19937 rng(9);
  for (int trial = 0; trial < 30; ++trial) {
    Scene s = random_scene(rng, 3 + trial % 6, trial % 3 == 0);
    solve_coulomb(s.robot, s.frame);
    if (!s.frame.friction.unique) {
      continue;
    }
    const Vector3d coul = s.frame.v_body;
    std::vector<double> err;
    for (double eps : {1e-6, 1e-8, 1e-10, 1e-12}) {
      solve_epsilon(s.robot, s.frame, eps);
      EXPECT_TRUE(s.frame.friction.converged) << "eps=" << eps << " " << s.frame.friction.message;
      EXPECT_LE(s.frame.friction.residual, 1e-10);
      err.push_back((s.frame.v_body - coul).norm() / (coul.norm() + 1e-3));
      // A sliding foot sees φ = 1/s + O(ε/s²); a static one holding a fraction t of its friction
      // limit sticks with slip s = √(ε t/(1 − t)): the error falls like √ε (or faster), with a
      // constant that grows for feet near the rim of their disk.
      EXPECT_LE(err.back(), 1e3 * std::sqrt(eps)) << "trial " << trial << " eps=" << eps;
    }
    // Asymptotically ×0.1 per ε/100: over ε = 1e-8 → 1e-12, at least ×0.02.
    EXPECT_LE(err[3], 0.02 * err[1] + 1e-11) << "trial " << trial;
  }
}

TEST(Epsilon, RejectsNonPositiveEpsilon) {
  Scene s = line_scene({0.1, 0.2, 0.3});
  EXPECT_THROW(solve_epsilon(s.robot, s.frame, 0.0), core::InputError);
  EXPECT_THROW(solve_epsilon(s.robot, s.frame, -1.0), core::InputError);
  EXPECT_THROW(solve_epsilon(s.robot, s.frame, std::nan("")), core::InputError);
}

// ---- invariances ----------------------------------------------------------------------------

template <class Solve>
void check_invariances(Solve solve, const char* what) {
  std::mt19937 rng(10);
  for (int trial = 0; trial < 30; ++trial) {
    Scene s = random_scene(rng, 3 + trial % 7, trial % 2 == 1);
    solve(s);
    const Vector3d v0 = s.frame.v_body;
    const Eigen::Matrix2Xd F0 = s.frame.Fxy;
    // Yaw: body-frame outputs do not depend on θ.
    s.frame.theta = 1.234 + trial;
    solve(s);
    EXPECT_LE((s.frame.v_body - v0).norm(), 1e-14 * (1.0 + v0.norm())) << what;
    EXPECT_LE((s.frame.Fxy - F0).norm(), 1e-14 * (1.0 + F0.norm())) << what;
    // Rotating the whole scene (feet, velocities and anisotropy directions) by R rotates v and
    // the forces, ω unchanged.
    const double a = 0.7 + 0.4 * trial;
    Matrix2d R;
    R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
    for (int k = 0; k < s.n(); ++k) {
      s.frame.q.col(k).head<2>() = R * s.frame.q.col(k).head<2>();
      s.frame.qdot.col(k).head<2>() = R * s.frame.qdot.col(k).head<2>();
      s.robot.w.col(k) = R * s.robot.w.col(k);
    }
    solve(s);
    const double tol = 1e-9 * (1.0 + v0.norm());
    EXPECT_LE((s.frame.v_body.head<2>() - R * v0.head<2>()).norm(), tol) << what;
    EXPECT_NEAR(s.frame.v_body(2), v0(2), tol) << what;
    EXPECT_LE((s.frame.Fxy - R * F0).norm(), 1e-8 * (1.0 + F0.norm())) << what;
  }
}

TEST(FrictionInvariance, YawAndSceneRotation) {
  check_invariances([](Scene& s) { solve_viscous_coulomb(s.robot, s.frame); }, "viscous");
  check_invariances([](Scene& s) { solve_epsilon(s.robot, s.frame, 0.05); }, "epsilon");
  check_invariances([](Scene& s) { solve_coulomb(s.robot, s.frame); }, "coulomb");
}

// ---- anisotropy by hand -----------------------------------------------------------------------

TEST(FrictionAnisotropy, TwoFeetOnALineByHand) {
  // Feet at x = ±0.2 on the x axis, moving along x at +1 and −1; foot 0 has w = (√3, 0): its
  // G = diag(4, 1) and W = diag(2, 1). By symmetry v_y = ω = 0.
  Scene s = line_scene({1.0, -1.0});
  s.frame.Fz.setConstant(1.0);
  s.robot.w.col(0) << std::sqrt(3.0), 0.0;
  // Viscous: 4 (v + 1) + (v − 1) = 0 → v = −3/5: the stiffer foot (along x) wins.
  solve_viscous_coulomb(s.robot, s.frame);
  EXPECT_NEAR(s.frame.v_body(0), -0.6, 1e-15);
  EXPECT_NEAR(s.frame.v_body(2), 0.0, 1e-15);
  EXPECT_NEAR(s.frame.Fxy(0, 0), -4.0 * 0.4, 1e-14);
  // Coulomb: D = 2|v + 1| + |v − 1| → v = −1, foot 0 static holding F = −1 (inside its ellipse:
  // the semi-axis along x is 2).
  solve_coulomb(s.robot, s.frame);
  EXPECT_NEAR(s.frame.v_body(0), -1.0, 1e-14);
  EXPECT_EQ(s.frame.friction.static_feet, 1);
  EXPECT_TRUE(s.frame.friction.unique);
  EXPECT_NEAR(s.frame.Fxy(0, 0), -1.0, 1e-14);
  EXPECT_NEAR(s.frame.Fxy(0, 1), 1.0, 1e-14);
  expect_certified(s, 1e-10, "aniso x");
  // ε between them.
  solve_epsilon(s.robot, s.frame, 1.0);
  EXPECT_LT(s.frame.v_body(0), -0.6);
  EXPECT_GT(s.frame.v_body(0), -1.0);

  // The same traction along y (across the motion) changes nothing along x.
  s.robot.w.col(0) << 0.0, std::sqrt(3.0);
  solve_viscous_coulomb(s.robot, s.frame);
  EXPECT_NEAR(s.frame.v_body(0), 0.0, 1e-15);
  solve_coulomb(s.robot, s.frame);
  EXPECT_FALSE(s.frame.friction.unique);  // any v in [−1, 1]
  EXPECT_LE(std::abs(s.frame.v_body(0)), 1.0 + 1e-14);
  expect_certified(s, 1e-10, "aniso y");
}

// ---- hard cases -----------------------------------------------------------------------------

TEST(FrictionHardCases, AllFeetStaticGiveTheRigidMotionExactly) {
  std::mt19937 rng(11);
  for (int n : {2, 3, 6, 12, 60}) {
    Scene s = random_scene(rng, n, n == 6);
    const Vector3d x(0.05, -0.02, 0.3);
    for (int k = 0; k < n; ++k) {
      s.frame.qdot.col(k).head<2>() =
          -(x.head<2>() + x(2) * Vector2d(-s.frame.q(1, k), s.frame.q(0, k)));
    }
    solve_viscous_coulomb(s.robot, s.frame);
    EXPECT_LE((s.frame.v_body - x).norm(), 1e-14);
    solve_coulomb(s.robot, s.frame);
    EXPECT_LE((s.frame.v_body - x).norm(), 1e-14) << "n=" << n;
    EXPECT_TRUE(s.frame.friction.unique);
    EXPECT_EQ(s.frame.friction.static_feet, n);
    EXPECT_LE(s.frame.friction.dissipation, 1e-15);
    // The certificate: zero dissipation is optimal, zero forces balance (the forces themselves
    // are not determined: any balanced set in the disks would do).
    EXPECT_LE(s.frame.friction.certificate, 1e-14);
    EXPECT_EQ(s.frame.Fxy.norm(), 0.0);
    EXPECT_NE(s.frame.friction.message.find("internal force"), std::string::npos);
    expect_certified(s, 1e-14, "static");
    solve_epsilon(s.robot, s.frame, 1e-6);
    EXPECT_LE((s.frame.v_body - x).norm(), 1e-13);
  }
}

TEST(FrictionHardCases, NearlyStaticFeetStayWellPosedInVelocity) {
  // §3.1.2.3: with noise of size η on a static gait the Coulomb velocity moves by O(η) (a sharp
  // minimum), only the forces jump.
  std::mt19937 rng(12);
  std::normal_distribution<double> N01(0.0, 1.0);
  Scene s = random_scene(rng, 6);
  const Vector3d x(0.05, -0.02, 0.3);
  for (int k = 0; k < 6; ++k) {
    s.frame.qdot.col(k).head<2>() =
        -(x.head<2>() + x(2) * Vector2d(-s.frame.q(1, k), s.frame.q(0, k)));
  }
  const Eigen::Matrix3Xd qd0 = s.frame.qdot;
  for (double eta : {1e-3, 1e-6, 1e-9}) {
    for (int k = 0; k < 6; ++k) {
      s.frame.qdot.col(k).head<2>() = qd0.col(k).head<2>() + eta * Vector2d(N01(rng), N01(rng));
    }
    solve_coulomb(s.robot, s.frame);
    EXPECT_LE((s.frame.v_body - x).norm(), 50.0 * eta) << "eta=" << eta;
    expect_certified(s, 1e-10, "noisy static");
  }
}

TEST(FrictionHardCases, OneFootIsUndeterminedInRotationButFinite) {
  Scene s(1);
  s.frame.q.col(0) << 0.2, 0.1, -0.1;
  s.frame.qdot.col(0) << 0.3, -0.2, 0.0;
  solve_viscous_coulomb(s.robot, s.frame);
  EXPECT_FALSE(s.frame.friction.unique);
  EXPECT_TRUE(s.frame.v_body.allFinite());
  EXPECT_LE(slip_of(s.frame, 0, s.frame.v_body).norm(), 1e-15);  // the foot does not slip
  const Vector3d visc = s.frame.v_body;
  solve_coulomb(s.robot, s.frame);
  EXPECT_FALSE(s.frame.friction.unique);
  EXPECT_LE((s.frame.v_body - visc).norm(), 1e-15);  // the same least-norm choice
  EXPECT_TRUE(s.frame.friction.converged);
  solve_epsilon(s.robot, s.frame, 1e-3);
  EXPECT_LE((s.frame.v_body - visc).norm(), 1e-15);
  // A foot under the centre: ω = 0 is the least-norm choice.
  s.frame.q.col(0) << 0.0, 0.0, -0.1;
  solve_coulomb(s.robot, s.frame);
  EXPECT_NEAR(s.frame.v_body(0), -0.3, 1e-15);
  EXPECT_NEAR(s.frame.v_body(1), 0.2, 1e-15);
  EXPECT_EQ(s.frame.v_body(2), 0.0);
}

TEST(FrictionHardCases, TwoFeet) {
  std::mt19937 rng(13);
  for (int trial = 0; trial < 20; ++trial) {
    Scene s = random_scene(rng, 2, trial % 2 == 0);
    solve_viscous_coulomb(s.robot, s.frame);
    EXPECT_TRUE(s.frame.friction.unique);
    EXPECT_LE(s.frame.friction.residual, 1e-10);
    solve_coulomb(s.robot, s.frame);
    expect_certified(s, 1e-10, "two feet");
    const Vector3d bf = brute_force_coulomb(s, s.frame.v_body);
    EXPECT_LE(dissipation(s, s.frame.v_body), dissipation(s, bf) * (1.0 + 1e-12));
  }
}

TEST(FrictionHardCases, FeetAtOnePoint) {
  Scene s(3);
  for (int k = 0; k < 3; ++k) {
    s.frame.q.col(k) << 0.1, -0.05, -0.1;
  }
  s.frame.qdot.col(0) << 0.1, 0.0, 0.0;
  s.frame.qdot.col(1) << 0.0, 0.1, 0.0;
  s.frame.qdot.col(2) << -0.1, -0.1, 0.0;
  solve_viscous_coulomb(s.robot, s.frame);
  EXPECT_FALSE(s.frame.friction.unique);
  EXPECT_TRUE(s.frame.v_body.allFinite());
  EXPECT_LE(s.frame.friction.residual, 1e-10);
  solve_coulomb(s.robot, s.frame);
  EXPECT_FALSE(s.frame.friction.unique);
  expect_certified(s, 1e-10, "one point");
  // The common point moves at minus the (Fermat–Weber) geometric median of the three velocities:
  // the minimizer of Σ‖u + q̇_k‖, checked by brute force on D.
  const Vector3d bf = brute_force_coulomb(s, s.frame.v_body);
  EXPECT_LE(dissipation(s, s.frame.v_body), dissipation(s, bf) * (1.0 + 1e-12));
  solve_epsilon(s.robot, s.frame, 0.1);
  EXPECT_FALSE(s.frame.friction.unique);
  EXPECT_TRUE(s.frame.v_body.allFinite());
}

TEST(FrictionHardCases, NoFootInContactGivesZeroAndSaysSo) {
  Scene s = line_scene({0.1, 0.2, 0.3});
  std::fill(s.frame.contact.begin(), s.frame.contact.end(), 0);
  solve_viscous_coulomb(s.robot, s.frame);
  EXPECT_EQ(s.frame.v_body.norm(), 0.0);
  EXPECT_FALSE(s.frame.friction.unique);
  EXPECT_FALSE(s.frame.friction.message.empty());
  solve_coulomb(s.robot, s.frame);
  EXPECT_EQ(s.frame.v_body.norm(), 0.0);
  EXPECT_EQ(s.frame.Fxy.norm(), 0.0);
  EXPECT_FALSE(s.frame.friction.unique);
  solve_epsilon(s.robot, s.frame, 1.0);
  EXPECT_EQ(s.frame.v_body.norm(), 0.0);
}

TEST(FrictionHardCases, FeetInTheAirAreIgnored) {
  std::mt19937 rng(14);
  Scene s = random_scene(rng, 8, true);
  Scene t(5);
  int j = 0;
  for (int k = 0; k < 8; ++k) {
    if (k % 3 == 1) {
      s.frame.contact[static_cast<std::size_t>(k)] = 0;
      continue;
    }
    t.frame.q.col(j) = s.frame.q.col(k);
    t.frame.qdot.col(j) = s.frame.qdot.col(k);
    t.frame.Fz(j) = s.frame.Fz(k);
    t.robot.mu(j) = s.robot.mu(k);
    t.robot.w.col(j) = s.robot.w.col(k);
    ++j;
  }
  ASSERT_EQ(j, 5);
  for (int law = 0; law < 3; ++law) {
    auto run = [law](Scene& x) {
      if (law == 0) {
        solve_viscous_coulomb(x.robot, x.frame);
      } else if (law == 1) {
        solve_epsilon(x.robot, x.frame, 0.1);
      } else {
        solve_coulomb(x.robot, x.frame);
      }
    };
    run(s);
    run(t);
    EXPECT_LE((s.frame.v_body - t.frame.v_body).norm(), 1e-12) << "law " << law;
    for (int k = 0; k < 8; ++k) {
      if (k % 3 == 1) {
        EXPECT_EQ(s.frame.Fxy.col(k).norm(), 0.0);
      }
    }
  }
}

TEST(FrictionHardCases, ManyFeet) {
  std::mt19937 rng(15);
  for (int n : {50, 64, 200}) {
    for (int trial = 0; trial < 5; ++trial) {
      Scene s = random_scene(rng, n, trial % 2 == 1);
      solve_viscous_coulomb(s.robot, s.frame);
      EXPECT_LE(s.frame.friction.residual, 1e-10);
      solve_coulomb(s.robot, s.frame);
      expect_certified(s, 1e-10, "many feet");
      EXPECT_LT(s.frame.friction.iterations, 100);
    }
  }
}

TEST(FrictionHardCases, WildScalesStayFinite) {
  // Tiny and huge robots, loads and speeds: everything finite, certified.
  std::mt19937 rng(16);
  for (double len : {1e-4, 1.0, 1e3}) {
    for (double vel : {1e-6, 1.0, 1e4}) {
      Scene s = random_scene(rng, 6);
      s.frame.q *= len / 0.3;
      s.frame.qdot *= vel / 0.1;
      s.frame.Fz *= 1e3;
      solve_viscous_coulomb(s.robot, s.frame);
      EXPECT_LE(s.frame.friction.residual, 1e-10);
      solve_coulomb(s.robot, s.frame);
      expect_certified(s, 1e-10, "scales");
      solve_epsilon(s.robot, s.frame, 1e-2);
      EXPECT_TRUE(s.frame.v_body.allFinite());
    }
  }
}

// ---- the fast path (kink Newton) against the smoothing path, and its kink model -------------

/// Six feet in mirror pairs about the x axis, moving mirror-symmetrically: two feet come to rest
/// at once, which the fast path hands over to the smoothing path.
Scene mirror_scene(std::mt19937& rng) {
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  Scene s(6);
  for (int k = 0; k < 3; ++k) {
    const Vector2d q(-0.25 + 0.25 * k + 0.05 * U(rng), 0.15 + 0.02 * U(rng));
    const Vector2d qd(0.1 * U(rng), 0.02 * U(rng));
    s.frame.q.col(k) << q, -0.1;
    s.frame.q.col(k + 3) << q(0), -q(1), -0.1;
    s.frame.qdot.col(k) << qd, 0.0;
    s.frame.qdot.col(k + 3) << qd(0), -qd(1), 0.0;
    s.frame.Fz(k) = s.frame.Fz(k + 3) = 0.5 + 0.5 * std::abs(U(rng));
  }
  return s;
}

TEST(Coulomb, FastPathAgreesWithTheSmoothingPath) {
  std::mt19937 rng(18);
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 2 + trial % 11;
    Scene s = trial % 10 == 9 ? mirror_scene(rng) : random_scene(rng, n, trial % 3 == 0);
    CoulombOptions path;
    path.fast_path = false;
    solve_coulomb(s.robot, s.frame, path);
    expect_certified(s, 1e-10, "smoothing path");
    const Vector3d v_path = s.frame.v_body;
    const contact::FrictionSummary ref = s.frame.friction;
    solve_coulomb(s.robot, s.frame);
    expect_certified(s, 1e-10, "fast path");
    EXPECT_NEAR(s.frame.friction.dissipation, ref.dissipation, 1e-10 * ref.dissipation)
        << "trial " << trial;
    EXPECT_EQ(s.frame.friction.unique, ref.unique) << "trial " << trial;
    if (ref.unique) {
      EXPECT_LE((s.frame.v_body - v_path).norm(), 1e-9 * (1.0 + v_path.norm()))
          << "trial " << trial;
      EXPECT_EQ(s.frame.friction.static_feet, ref.static_feet) << "trial " << trial;
    }
  }
}

TEST(Coulomb, MirrorSymmetricFramesGiveSymmetricAnswers) {
  // Mirror symmetry about the x axis maps (v_x, v_y, ω) to (v_x, −v_y, −ω): a unique answer has
  // v_y = ω = 0, to the accuracy of the final Newton step (not only of the certificate).
  std::mt19937 rng(19);
  for (int trial = 0; trial < 30; ++trial) {
    Scene s = mirror_scene(rng);
    solve_coulomb(s.robot, s.frame);
    expect_certified(s, 1e-10, "mirror");
    if (s.frame.friction.unique) {
      EXPECT_LE(std::abs(s.frame.v_body(1)), 1e-13) << "trial " << trial;
      EXPECT_LE(std::abs(s.frame.v_body(2)), 1e-12) << "trial " << trial;
    }
  }
}

TEST(CoulombKinkStep, SatisfiesTheOptimalityConditionsOfItsModel) {
  // m(p) = gᵀp + ½ pᵀHp + ‖r + Bp‖ is convex; p is its minimizer iff g + Hp + Bᵀλ = 0 with
  // λ = u/‖u‖ (u = r + Bp ≠ 0) or ‖λ‖ ≤ 1 (u = 0). Checked on random models, H of rank 3 and 2.
  std::mt19937 rng(20);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  int sticks = 0;
  int slides = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    Eigen::Matrix<double, 3, 3> A;
    for (int i = 0; i < 9; ++i) {
      A(i) = U(rng);
    }
    if (trial % 2 == 1) {
      A.col(2).setZero();  // rank 2: the model is bounded only through the kink foot
    }
    const Eigen::Matrix3d H = A * A.transpose();
    const Vector3d g(U(rng), U(rng), U(rng));
    const double c = 0.2 + std::abs(U(rng));
    const Vector2d w(U(rng), U(rng));
    const Matrix2d W =
        Matrix2d::Identity() + (1.0 / (1.0 + std::sqrt(1.0 + w.squaredNorm()))) * w * w.transpose();
    Eigen::Matrix<double, 2, 3> B;
    B.leftCols<2>() = c * W;
    B.col(2) = c * W * Vector2d(U(rng), U(rng));
    const Vector2d r = std::pow(10.0, -3.0 * std::abs(U(rng))) * Vector2d(U(rng), U(rng));
    coulomb::KinkStep st;
    if (!coulomb::kink_step(g, H, B, r, r.norm(), st)) {
      continue;  // a degenerate model (H flat about the foot, or unbounded): said so
    }
    const Vector2d u = r + B * st.p;
    const double scale = g.norm() + H.norm() * st.p.norm() + B.norm();
    EXPECT_LE((g + H * st.p + B.transpose() * st.lam).norm(), 1e-9 * scale) << trial;
    if (st.stick) {
      ++sticks;
      EXPECT_LE(u.norm(), 1e-12 * (r.norm() + B.norm() * st.p.norm())) << trial;
      EXPECT_LE(st.lam.norm(), 1.0) << trial;
    } else {
      ++slides;
      EXPECT_NEAR(st.lam.norm(), 1.0, 1e-12) << trial;
      EXPECT_LE((st.lam - u.normalized()).norm(), 1e-7) << trial;
    }
    const auto m = [&](const Vector3d& p) {
      return g.dot(p) + 0.5 * p.dot(H * p) + (r + B * p).norm();
    };
    EXPECT_NEAR(st.decrease, m(Vector3d::Zero()) - m(st.p), 1e-12 * (1.0 + std::abs(st.decrease)));
  }
  EXPECT_GT(sticks, 100);
  EXPECT_GT(slides, 100);
}

TEST(Coulomb, ToleranceOptionIsHonoured) {
  std::mt19937 rng(17);
  Scene s = random_scene(rng, 6);
  CoulombOptions opt;
  opt.tol = 1e-4;
  solve_coulomb(s.robot, s.frame, opt);
  EXPECT_LE(s.frame.friction.certificate, 1e-4);
  opt.max_iterations = 0;
  solve_coulomb(s.robot, s.frame, opt);  // must terminate and say whether it certified
  EXPECT_TRUE(s.frame.v_body.allFinite());
  EXPECT_EQ(s.frame.friction.converged, s.frame.friction.certificate <= opt.tol);
}

}  // namespace
}  // namespace slipwalk::friction
