#pragma once
// Scenes and checks shared by the spring-support tests (tests/contact/test_spring_support.cpp,
// test_support_newton.cpp): random supported robots, hand-made feet, the comparison with the
// convex-potential oracle (spring_support_oracle.hpp) and the balance residuals of the outputs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "contact/robot.hpp"
#include "contact/spring_support.hpp"
#include "support/spring_support_oracle.hpp"

namespace slipwalk::testing::support_scenes {

using contact::Frame;
using contact::Robot;
using contact::SupportOptions;
using contact::SupportStep;

inline constexpr double kPi = std::numbers::pi;

struct Scene {
  Eigen::Matrix3Xd q;
  Eigen::VectorXd K;
  double Mg = 1.0;

  [[nodiscard]] int legs() const { return static_cast<int>(q.cols()); }
  [[nodiscard]] Robot robot() const {
    Robot r = slipwalk::contact::uniform_robot(legs(), 1.0, 1.0, Mg);
    r.K = K;
    return r;
  }
  [[nodiscard]] SupportProblem problem() const { return {q, K, Mg}; }
};

struct Solved {
  Robot robot;
  Frame frame;
  std::vector<SupportStep> path;
};

inline Solved solve(const Scene& s, bool record = false, bool newton = true) {
  Solved out{s.robot(), Frame(s.robot()), {}};
  out.frame.q = s.q;
  SupportOptions opt;
  opt.newton = newton;
  if (record) {
    opt.path = &out.path;
  }
  spring_support(out.robot, out.frame, opt);
  return out;
}

inline double size_of(const Scene& s) { return slipwalk::testing::support_size(s.problem()); }

// The vertical length scale of a problem: feet heights and the compressions.
inline double height_scale(const Scene& s, const Frame& f) {
  double z = s.q.row(2).cwiseAbs().maxCoeff();
  for (int j = 0; j < s.legs(); ++j) {
    z = std::max(z, f.Fz(j) / s.K(j));
  }
  return std::max(z, 1e-300);
}

inline double potential(const Scene& s, double alpha, double beta, double z) {
  return support_potential(s.problem(), alpha, beta, z);
}

// Balance residuals computed here from the outputs (not from frame.support).
struct Balance {
  double force;   // |ΣF_z − Mg| / Mg
  double moment;  // max(|M_x|, |M_y|) / (Mg L)
};
inline Balance balance(const Scene& s, const Frame& f) {
  double fz = 0.0;
  double mx = 0.0;
  double my = 0.0;
  for (int j = 0; j < s.legs(); ++j) {
    fz += f.Fz(j);
    mx -= s.q(1, j) * f.Fz(j);
    my += s.q(0, j) * f.Fz(j);
  }
  return {std::abs(fz - s.Mg) / s.Mg, std::max(std::abs(mx), std::abs(my)) / (s.Mg * size_of(s))};
}

// The balance residual that rounding alone can cause: each height is known to about
// ε (|q_z| + |z| + L |α| + L |β|), each load to K times that (relative to Mg).
inline double rounding_floor(const Scene& s, const Frame& f) {
  double floor = 0.0;
  for (int j = 0; j < s.legs(); ++j) {
    floor += s.K(j) * (std::abs(s.q(2, j)) + std::abs(f.z) +
                       size_of(s) * (std::abs(f.alpha) + std::abs(f.beta)));
  }
  return 2.2e-16 * floor / s.Mg;
}

// Where the origin (the CoM) lies relative to the convex hull of the feet's xy positions:
// +1 strictly inside, −1 strictly outside, 0 on the boundary or undecided (a foot at the origin).
inline int com_in_hull(const Eigen::Matrix3Xd& q) {
  std::vector<double> angles;
  for (int j = 0; j < q.cols(); ++j) {
    if (std::hypot(q(0, j), q(1, j)) < 1e-12) {
      return 0;
    }
    angles.push_back(std::atan2(q(1, j), q(0, j)));
  }
  std::sort(angles.begin(), angles.end());
  double gap = angles.front() + 2.0 * kPi - angles.back();
  for (std::size_t i = 1; i < angles.size(); ++i) {
    gap = std::max(gap, angles[i] - angles[i - 1]);
  }
  if (gap < kPi - 1e-9) {
    return 1;
  }
  if (gap > kPi + 1e-9) {
    return -1;
  }
  return 0;
}

inline double uniform(std::mt19937_64& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

// A random robot of n legs: stiffnesses over `decades` decades, feet scattered around a random
// polygon that contains the CoM, heights spread over a few compressions so that some feet are
// in the air and the contact set changes along the search.
inline Scene random_supported(std::mt19937_64& rng, int n, double decades = 2.0) {
  Scene s;
  s.q.resize(3, n);
  s.K.resize(n);
  s.Mg = uniform(rng, 5.0, 50.0);
  const double k0 = uniform(rng, 200.0, 5000.0);
  for (int j = 0; j < n; ++j) {
    s.K(j) = k0 * std::pow(10.0, uniform(rng, 0.0, decades));
  }
  const double R = uniform(rng, 0.1, 0.5);
  do {
    const double c_r = R * uniform(rng, 0.0, 0.4);
    const double c_a = uniform(rng, 0.0, 2.0 * kPi);
    const double phase = uniform(rng, 0.0, 2.0 * kPi);
    for (int j = 0; j < n; ++j) {
      const double a = phase + 2.0 * kPi * (j + uniform(rng, -0.35, 0.35)) / n;
      const double r = R * uniform(rng, 0.6, 1.4);
      s.q(0, j) = c_r * std::cos(c_a) + r * std::cos(a);
      s.q(1, j) = c_r * std::sin(c_a) + r * std::sin(a);
    }
  } while (com_in_hull(s.q) != 1);
  // Typical compression when about a third of the legs carry the weight.
  const double delta = s.Mg / (s.K.sum() / 3.0);
  const double spread = delta * std::vector<double>{0.3, 1.0, 3.0, 10.0}[rng() % 4];
  const double h0 = uniform(rng, 0.05, 0.2);
  for (int j = 0; j < n; ++j) {
    s.q(2, j) = -h0 + uniform(rng, 0.0, spread);
  }
  // Shuffle the legs so that the order carries no geometry.
  std::vector<int> perm(n);
  for (int j = 0; j < n; ++j) {
    perm[j] = j;
  }
  std::shuffle(perm.begin(), perm.end(), rng);
  Scene t = s;
  for (int j = 0; j < n; ++j) {
    t.q.col(j) = s.q.col(perm[j]);
    t.K(j) = s.K(perm[j]);
  }
  return t;
}

// Compares a solved frame with the oracle: state to 1e-9 of the height scale, loads, contact sets
// away from ties, equal potential.
inline void expect_matches_oracle(const Scene& s, const Frame& f, const char* what,
                                  double rel = 1e-9) {
  const auto o = minimize_support_potential(s.problem());
  const double Z = height_scale(s, f);
  const double L = size_of(s);
  EXPECT_NEAR(f.z, o.z, rel * Z) << what;
  EXPECT_NEAR(L * f.alpha, L * o.alpha, rel * Z) << what;
  EXPECT_NEAR(L * f.beta, L * o.beta, rel * Z) << what;
  const double U = potential(s, f.alpha, f.beta, f.z);
  EXPECT_NEAR(U, o.U, 1e-12 * (std::abs(o.U) + s.Mg * Z)) << what;
  for (int j = 0; j < s.legs(); ++j) {
    EXPECT_NEAR(f.Fz(j), o.Fz(j), rel * s.K(j) * Z + 1e-12 * s.Mg) << what << " leg " << j;
    if (std::abs(o.h(j)) > 1e-7 * Z) {
      EXPECT_EQ(f.contact[j] != 0, o.h(j) < 0.0) << what << " leg " << j << " h " << o.h(j);
    }
  }
}

// The same as expect_matches_oracle for states whose tilt is not unique (kLine, kPoint, see-saws):
// height, loads and potential only.
inline void expect_matches_oracle_loads(const Scene& s, const Frame& f, const char* what) {
  const auto o = minimize_support_potential(s.problem());
  const double Z = height_scale(s, f);
  EXPECT_NEAR(f.z, o.z, 1e-9 * Z) << what;
  EXPECT_NEAR(potential(s, f.alpha, f.beta, f.z), o.U, 1e-12 * (std::abs(o.U) + s.Mg * Z)) << what;
  for (int j = 0; j < s.legs(); ++j) {
    EXPECT_NEAR(f.Fz(j), o.Fz(j), 1e-9 * s.K(j) * Z + 1e-12 * s.Mg) << what << " leg " << j;
  }
}

inline Scene from_feet(const std::vector<Eigen::Vector3d>& feet, const std::vector<double>& K,
                       double Mg) {
  Scene s;
  const int n = static_cast<int>(feet.size());
  s.q.resize(3, n);
  s.K.resize(n);
  for (int j = 0; j < n; ++j) {
    s.q.col(j) = feet[j];
    s.K(j) = K.size() == 1 ? K[0] : K[j];
  }
  s.Mg = Mg;
  return s;
}

// A level hexapod (BigANT-like: three pairs of feet 0.25 m apart, 0.3–0.4 m wide), every foot
// 0.12 m below the body, K = 2000 N/m, Mg = 30 N.
inline Scene flat_hexapod() {
  return from_feet({{0.25, 0.15, -0.12},
                    {0.0, 0.2, -0.12},
                    {-0.25, 0.15, -0.12},
                    {0.25, -0.15, -0.12},
                    {0.0, -0.2, -0.12},
                    {-0.25, -0.15, -0.12}},
                   {2000.0}, 30.0);
}
}  // namespace slipwalk::testing::support_scenes
