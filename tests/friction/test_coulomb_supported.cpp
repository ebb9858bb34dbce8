// The Coulomb solver on spring-supported hexapod frames, as the ch3_legged cost study builds
// them (sweeps/points/legged_cost.cpp): 3–6 feet down with the spring support's loads, often one
// foot that friction holds still. Oracles: the smoothing path (fast_path = false, a second
// route to the same convex minimum) and the certificate; and, for frames whose first Newton
// step must be cut below 1/16, that the fast path certifies them in a few steps.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <random>
#include <vector>

#include "contact/robot.hpp"
#include "contact/spring_support.hpp"
#include "friction/solvers.hpp"

namespace slipwalk::friction {
namespace {

using contact::Frame;
using contact::Robot;

constexpr double kTol = 1e-9;  // the study's tolerance

/// Solves `f` on both routes and checks that they certify the same minimum.
void expect_routes_agree(const Robot& robot, Frame f, const char* what) {
  CoulombOptions path;
  path.tol = kTol;
  path.fast_path = false;
  solve_coulomb(robot, f, path);
  ASSERT_TRUE(f.friction.converged) << what << ": " << f.friction.message;
  const contact::FrictionSummary ref = f.friction;
  const Eigen::Vector3d v_ref = f.v_body;
  solve_coulomb(robot, f, CoulombOptions{kTol});
  EXPECT_TRUE(f.friction.converged) << what << ": " << f.friction.message;
  EXPECT_LE(f.friction.certificate, kTol) << what;
  EXPECT_LE(f.friction.residual, 1e-10) << what;
  EXPECT_NEAR(f.friction.dissipation, ref.dissipation, 1e-8 * ref.dissipation) << what;
  EXPECT_EQ(f.friction.unique, ref.unique) << what;
  if (ref.unique) {
    // Body velocities of ~0.1 m/s: the smoothing path's answer is certified to 1e-9 only.
    EXPECT_LE((f.v_body - v_ref).norm(), 1e-6 * (1e-3 + v_ref.norm())) << what;
    EXPECT_EQ(f.friction.static_feet, ref.static_feet) << what;
  }
}

/// A BigANT-like hexapod frame as the study draws it: feet jittered about x ∈ {−0.3, 0, 0.3},
/// y = ±0.2, about half lifted, the spring support deciding contact and loads; foot velocities
/// around a common backward slide plus a turn.
Frame supported_frame(const Robot& robot, std::mt19937& rng) {
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  std::normal_distribution<double> N(0.0, 1.0);
  Frame f(robot);
  for (int attempt = 0; attempt < 1000; ++attempt) {
    for (int k = 0; k < 6; ++k) {
      f.q.col(k) << 0.3 * (k / 2 - 1) + 0.02 * U(rng), (k % 2 == 0 ? 0.2 : -0.2) + 0.02 * U(rng),
          -0.1 + 0.002 * U(rng);
      if (U(rng) < 0.0) {
        f.q(2, k) += 0.0225 + 0.0175 * U(rng);
      }
    }
    contact::spring_support(robot, f);
    if (f.support.status == contact::SupportSummary::Status::kBalanced) {
      break;
    }
  }
  const double turn = 0.05 * N(rng) / 0.3;
  for (int k = 0; k < 6; ++k) {
    f.qdot.col(k) << 0.1 * (-1.0 + 0.5 * N(rng)) - turn * f.q(1, k),
        0.05 * N(rng) + turn * f.q(0, k), 0.0;
  }
  return f;
}

TEST(CoulombSupported, FastPathAgreesWithTheSmoothingPathOnStudyFrames) {
  const double Mg = 8.18 * 9.81;
  const Robot robot = contact::uniform_robot(6, Mg / (6 * 0.01), 1.0, Mg);
  std::mt19937 rng(5);
  int with_static = 0;
  for (int i = 0; i < 200; ++i) {
    const Frame f = supported_frame(robot, rng);
    ASSERT_EQ(f.support.status, contact::SupportSummary::Status::kBalanced);
    expect_routes_agree(robot, f, "supported frame");
    Frame g = f;
    solve_coulomb(robot, g, CoulombOptions{kTol});
    with_static += g.friction.static_feet > 0 ? 1 : 0;
  }
  EXPECT_GT(with_static, 40);  // the case this file is about is well represented
}

/// Frames of the study (seed 2: frames 224, 389, 282) whose first Newton step is cut to
/// t ≈ 1/64 … 1/1000 by the line search: the Newton model promises more decrease than D itself.
/// Feet in contact: q_x, q_y, q̇_x, q̇_y (m, m/s) and F_z (N), μ = 1.
TEST(CoulombSupported, StronglyCutFirstStepsStayOnTheFastPath) {
  using Foot = std::array<double, 5>;
  const std::vector<std::vector<Foot>> frames = {
      {{-0.31551890553367867, 0.19945661150629906, -0.14217438283839345, 0.025226365104606938,
        27.626439447197722},
       {-0.0050242657775818999, -0.207370741038054, -0.1119948625400464, 0.043410392977719224,
        22.37539033199926},
       {0.28767819249971571, 0.19698286509508561, -0.16607669705196068, -0.022782453180728916,
        13.759852851890205},
       {0.29547679985396552, -0.21722303256373174, -0.10695846995546332, 0.059098342411527144,
        16.484117368912859}},
      {{-0.31061643591319138, 0.19673573272961487, -0.07854302377552802, -0.041083304241039065,
        5.0139162395029313},
       {-0.28849945730874615, -0.20591233353048455, -0.097855129768932653, 0.041112155893070948,
        17.728529053069572},
       {0.008760787570196181, 0.21029602585446566, -0.076684106318683207, 0.047547195702165451,
        13.624260910905942},
       {0.0036380465517393858, -0.21358606896453272, -0.099234244715849684, -0.024634762067004459,
        22.583356570141628},
       {0.30382186294919, 0.21761212495443133, -0.069996094127543401, 0.046020978049614511,
        21.267575746448149},
       {0.31968352371624636, -0.19933681033316369, -0.087061950476426814, 0.010164853980775154,
        0.028161479931693673}},
      {{-0.31468242374432481, 0.18314843550289706, -0.024623841484497359, 0.004978700586496655,
        11.921167356850066},
       {-0.29026665866824941, -0.19369592286833742, 0.016479301217628143, -0.095315638684206033,
        10.885929380511985},
       {0.011900511700225973, 0.1992617384893548, -0.095856320387100069, -0.016345082275710809,
        24.363290810903191},
       {-0.01789001669489405, -0.21802247442286823, -0.13123854674012381, 0.020451550006259138,
        10.023188459366516},
       {0.31744108332345333, 0.19773244479776461, -0.1067086328452026, 0.04312184773149496,
        3.8392136141818267},
       {0.29052497908185121, -0.18234057916985749, -0.10128348122217311, -0.025627967486291904,
        19.213010378186397}}};
  for (const auto& feet : frames) {
    const int n = static_cast<int>(feet.size());
    const Robot robot = contact::uniform_robot(n);
    Frame f(robot);
    std::fill(f.contact.begin(), f.contact.end(), 1);
    for (int k = 0; k < n; ++k) {
      const Foot& foot = feet[static_cast<std::size_t>(k)];
      f.q.col(k) << foot[0], foot[1], -0.1;
      f.qdot.col(k) << foot[2], foot[3], 0.0;
      f.Fz(k) = foot[4];
    }
    expect_routes_agree(robot, f, "cut first step");
    solve_coulomb(robot, f, CoulombOptions{kTol});
    // The smoothing path alone needs 13 or more steps on these frames (the handover to it
    // came after 1–3 fast-path steps); the fast path certifies them in 5–7.
    EXPECT_LE(f.friction.iterations, 8) << n << " feet";
  }
}

}  // namespace
}  // namespace slipwalk::friction
