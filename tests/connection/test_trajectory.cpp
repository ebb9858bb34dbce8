// connection::integrate: trajectories on SE(2). Oracles: feet moving as one rigid body (the body
// moves exactly opposite, no slip, the pose is the closed-form arc), mirror symmetry (no turning),
// the filter's step response 1 − γ^(j+1), connection::evaluate frame by frame, determinism, and no
// allocation per step.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "connection/trajectory.hpp"
#include "core/error.hpp"
#include "support/count_allocations.hpp"

namespace slipwalk::connection {
namespace {

constexpr double kPi = std::numbers::pi;

/// Six feet on a circle of radius 0.3 m, 0.1 m below the body; K = 100, μ = 0.8, Mg = 9.81.
contact::Robot hexapod() { return contact::uniform_robot(6, 100.0, 0.8, 9.81); }

Eigen::Vector2d circle_foot(int k) {
  const double a = 2.0 * kPi * k / 6.0 + 0.1;
  return {0.3 * std::cos(a), 0.3 * std::sin(a)};
}

/// The feet move as one rigid body with twist −(c, ω0) in the body frame: q̇_k = −(c + ω0 S q_k),
/// i.e. they rotate by −ω0 t about p* = S c / ω0 (a translation by −c t when ω0 = 0). The body
/// must then move with exactly (c, ω0) and no foot slips, whatever the loads.
FootKinematics rigid_feet(Eigen::Vector2d c, double w0) {
  return [c, w0](double t, Eigen::Matrix3Xd& q, Eigen::Matrix3Xd& qdot) {
    for (int k = 0; k < q.cols(); ++k) {
      const Eigen::Vector2d q0 = circle_foot(k);
      Eigen::Vector2d p;
      if (w0 == 0.0) {
        p = q0 - c * t;
      } else {
        const Eigen::Vector2d pstar(-c(1) / w0, c(0) / w0);
        const double a = -w0 * t;
        const Eigen::Vector2d r = q0 - pstar;
        p = pstar + Eigen::Vector2d(std::cos(a) * r(0) - std::sin(a) * r(1),
                                    std::sin(a) * r(0) + std::cos(a) * r(1));
      }
      q.col(k) << p, -0.1;
      qdot.col(k) << -(c(0) - w0 * p(1)), -(c(1) + w0 * p(0)), 0.0;
    }
  };
}

/// Three leg pairs, left feet at y > 0, right feet mirrored. Each foot sweeps in x and lifts for
/// half its cycle; pair i has phase 2πi/3 + (right side only) `right_shift`. With right_shift = 0
/// the gait is mirror-symmetric.
FootKinematics paired_feet(double right_shift) {
  return [right_shift](double t, Eigen::Matrix3Xd& q, Eigen::Matrix3Xd& qdot) {
    const double w = 2.0 * kPi * 0.5;  // 0.5 Hz
    for (int k = 0; k < 6; ++k) {
      const int pair = k % 3;
      const bool right = k >= 3;
      const double side = right ? -1.0 : 1.0;
      const double phase = w * t + 2.0 * kPi * pair / 3.0 + (right ? right_shift : 0.0);
      const double s = std::sin(phase);
      const double c = std::cos(phase);
      q.col(k) << -0.25 + 0.25 * pair + 0.05 * c, side * (0.15 + 0.01 * s),
          -0.1 + 0.03 * std::max(0.0, s);
      qdot.col(k) << -0.05 * w * s, side * 0.01 * w * c, s > 0.0 ? 0.03 * w * c : 0.0;
    }
  };
}

/// One frame as the sink saw it (copies, for comparisons after the run).
struct Record {
  double t;
  core::Pose2 pose;
  Eigen::Vector3d v_body;
  Eigen::Vector3d v_model;
  std::vector<char> contact;
  Eigen::VectorXd Fz;
  Eigen::Matrix2Xd Fxy;
  Eigen::Matrix2Xd slip;
};

template <class Law, class Filter>
std::vector<Record> run(const FootKinematics& feet, const TrajectoryOptions& options, Law law,
                        Filter filter, TrajectorySummary* summary = nullptr) {
  const contact::Robot robot = hexapod();
  TrajectoryData data(robot);
  std::vector<Record> out;
  const TrajectorySummary s =
      integrate(robot, feet, options, law, filter, data, [&](const TrajectoryStep& step) {
        out.push_back(Record{step.t, step.pose, step.v_body, step.v_model, step.frame.contact,
                             step.frame.Fz, step.frame.Fxy, step.slip});
      });
  if (summary != nullptr) {
    *summary = s;
  }
  return out;
}

template <class Law>
void expect_rigid_feet_move_the_body_exactly(const Law& law) {
  const Eigen::Vector2d c(0.05, 0.02);
  for (double w0 : {0.0, 0.3}) {
    TrajectoryOptions options;
    options.dt = 0.01;
    options.steps = 100;
    options.start = {0.5, -0.2, 0.7};
    TrajectorySummary summary;
    const auto records = run(rigid_feet(c, w0), options, law, NoFilter{}, &summary);
    ASSERT_EQ(records.size(), 101u);
    EXPECT_EQ(summary.frames, 101);
    EXPECT_EQ(summary.unsupported, 0);
    EXPECT_EQ(summary.not_converged, 0);
    const Eigen::Vector3d twist(c(0), c(1), w0);
    for (const Record& r : records) {
      EXPECT_NEAR((r.v_model - twist).norm(), 0.0, 1e-12) << "t = " << r.t;
      EXPECT_EQ((r.v_body - r.v_model).norm(), 0.0);
      EXPECT_NEAR(r.slip.norm(), 0.0, 1e-12) << "t = " << r.t;
      // The pose at t_n is the closed form start · exp(n dt (c, ω0)): a straight line for ω0 = 0,
      // a circular arc otherwise.
      const core::Pose2 exact = core::advance(options.start, twist, r.t);
      EXPECT_NEAR(r.pose.x, exact.x, 1e-12);
      EXPECT_NEAR(r.pose.y, exact.y, 1e-12);
      EXPECT_NEAR(r.pose.theta, exact.theta, 1e-12);
    }
    EXPECT_EQ(summary.end.x, records.back().pose.x);
    if (w0 == 0.0) {
      // Straight: x = x0 + t (c_x cos θ0 − c_y sin θ0), y likewise.
      const double T = 1.0;
      EXPECT_NEAR(records.back().pose.x, 0.5 + T * (c(0) * std::cos(0.7) - c(1) * std::sin(0.7)),
                  1e-13);
      EXPECT_NEAR(records.back().pose.y, -0.2 + T * (c(0) * std::sin(0.7) + c(1) * std::cos(0.7)),
                  1e-13);
    }
  }
}

TEST(Trajectory, RigidlyMovingFeetMoveTheBodyExactlyOppositeViscous) {
  expect_rigid_feet_move_the_body_exactly(ViscousCoulombKernel{});
}

TEST(Trajectory, RigidlyMovingFeetMoveTheBodyExactlyOppositeCoulomb) {
  expect_rigid_feet_move_the_body_exactly(CoulombKernel{});
}

template <class Law>
void expect_mirror_symmetric_gait_does_not_turn(const Law& law) {
  TrajectoryOptions options;
  options.dt = 0.02;
  options.steps = 200;  // two gait cycles
  const auto records = run(paired_feet(0.0), options, law, NoFilter{});
  for (const Record& r : records) {
    EXPECT_NEAR(r.v_model(1), 0.0, 1e-12) << "t = " << r.t;
    EXPECT_NEAR(r.v_model(2), 0.0, 1e-12) << "t = " << r.t;
  }
  EXPECT_NEAR(records.back().pose.y, 0.0, 1e-12);
  EXPECT_NEAR(records.back().pose.theta, 0.0, 1e-12);
  EXPECT_GT(std::abs(records.back().pose.x), 0.01);  // it does walk
  // Control: the same gait with the right side out of phase turns or drifts sideways.
  const auto skewed = run(paired_feet(0.7), options, law, NoFilter{});
  EXPECT_GT(std::abs(skewed.back().pose.theta) + std::abs(skewed.back().pose.y), 1e-3);
}

TEST(Trajectory, MirrorSymmetricGaitDoesNotTurnViscous) {
  expect_mirror_symmetric_gait_does_not_turn(ViscousCoulombKernel{});
}

TEST(Trajectory, MirrorSymmetricGaitDoesNotTurnCoulomb) {
  expect_mirror_symmetric_gait_does_not_turn(CoulombKernel{});
}

TEST(Trajectory, FilterStepResponse) {
  // Feet still until t = 0.1 s (step 10), then translating at −c: the model's velocity is a step
  // from 0 to c and the filtered one is y_{10+j} = (1 − γ^(j+1)) c.
  const Eigen::Vector2d c(0.04, -0.01);
  const FootKinematics moving = rigid_feet(c, 0.0);
  const FootKinematics feet = [&](double t, Eigen::Matrix3Xd& q, Eigen::Matrix3Xd& qdot) {
    moving(t < 0.095 ? 0.0 : t - 0.1, q, qdot);
    if (t < 0.095) {
      qdot.setZero();
    }
  };
  TrajectoryOptions options;
  options.dt = 0.01;
  options.steps = 60;
  const double gamma = 0.15;
  for (const auto& law : {0, 1}) {
    const auto records = law == 0 ? run(feet, options, ViscousCoulombKernel{}, IirFilter{gamma})
                                  : run(feet, options, CoulombKernel{}, IirFilter{gamma});
    double x = 0.0;
    double y = 0.0;
    for (std::size_t n = 0; n < records.size(); ++n) {
      const Record& r = records[n];
      const double response = n < 10 ? 0.0 : 1.0 - std::pow(gamma, static_cast<double>(n - 10 + 1));
      EXPECT_NEAR(r.v_body(0), response * c(0), 1e-14) << n;
      EXPECT_NEAR(r.v_body(1), response * c(1), 1e-14) << n;
      EXPECT_NEAR(r.v_body(2), 0.0, 1e-14) << n;
      // The pose integrates the filtered velocity (ω = 0: a sum of straight pieces).
      EXPECT_NEAR(r.pose.x, x, 1e-14) << n;
      EXPECT_NEAR(r.pose.y, y, 1e-14) << n;
      x += options.dt * response * c(0);
      y += options.dt * response * c(1);
    }
  }
}

TEST(Trajectory, FilterWithGammaZeroIsNoFilter) {
  TrajectoryOptions options;
  options.dt = 0.02;
  options.steps = 50;
  const auto a = run(paired_feet(0.3), options, ViscousCoulombKernel{}, NoFilter{});
  const auto b = run(paired_feet(0.3), options, ViscousCoulombKernel{}, IirFilter{0.0});
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t n = 0; n < a.size(); ++n) {
    EXPECT_EQ(a[n].pose.x, b[n].pose.x);
    EXPECT_EQ(a[n].pose.theta, b[n].pose.theta);
    EXPECT_EQ(a[n].v_body, b[n].v_body);
  }
}

TEST(Trajectory, EachFrameIsConnectionEvaluate) {
  const contact::Robot robot = hexapod();
  const FootKinematics feet = paired_feet(0.9);
  TrajectoryOptions options;
  options.dt = 0.05;
  options.steps = 40;
  for (FrictionLaw law : {FrictionLaw::kViscousCoulomb, FrictionLaw::kCoulomb}) {
    const auto records = law == FrictionLaw::kCoulomb
                             ? run(feet, options, CoulombKernel{}, NoFilter{})
                             : run(feet, options, ViscousCoulombKernel{}, NoFilter{});
    contact::Frame f(robot);
    contact::forget_balance(f);  // as a run starts: the first frame's support starts cold
    for (const Record& r : records) {
      feet(r.t, f.q, f.qdot);
      evaluate(robot, f, law, kTrajectorySupport);  // then each from the frame before
      EXPECT_EQ(f.contact, r.contact);
      EXPECT_EQ(f.Fz, r.Fz);
      EXPECT_EQ(f.Fxy, r.Fxy);
      EXPECT_EQ(f.v_body, r.v_model);
      for (int k = 0; k < 6; ++k) {
        const Eigen::Vector2d u = f.v_body.head<2>() +
                                  f.v_body(2) * Eigen::Vector2d(-f.q(1, k), f.q(0, k)) +
                                  f.qdot.col(k).head<2>();
        EXPECT_NEAR((u - r.slip.col(k)).norm(), 0.0, 1e-15);
        if (law == FrictionLaw::kViscousCoulomb && f.contact[static_cast<std::size_t>(k)]) {
          // The viscous law: F_k = −μ F_z,k u_k.
          EXPECT_NEAR((r.Fxy.col(k) + 0.8 * r.Fz(k) * r.slip.col(k)).norm(), 0.0, 1e-12);
        }
      }
    }
  }
}

TEST(Trajectory, Deterministic) {
  TrajectoryOptions options;
  options.dt = 0.02;
  options.steps = 100;
  const auto a = run(paired_feet(0.5), options, CoulombKernel{}, IirFilter{});
  const auto b = run(paired_feet(0.5), options, CoulombKernel{}, IirFilter{});
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t n = 0; n < a.size(); ++n) {
    EXPECT_EQ(a[n].t, b[n].t);
    EXPECT_EQ(a[n].pose.x, b[n].pose.x);
    EXPECT_EQ(a[n].pose.y, b[n].pose.y);
    EXPECT_EQ(a[n].pose.theta, b[n].pose.theta);
    EXPECT_EQ(a[n].v_body, b[n].v_body);
    EXPECT_EQ(a[n].Fxy, b[n].Fxy);
    EXPECT_EQ(a[n].slip, b[n].slip);
  }
}

template <class Law, class Filter>
long long allocations_between_steps(const Law& law, Filter filter) {
  const contact::Robot robot = hexapod();
  TrajectoryData data(robot);
  TrajectoryOptions options;
  options.dt = 0.02;
  options.steps = 100;
  std::vector<long long> counts;
  counts.reserve(200);
  integrate(robot, paired_feet(0.4), options, law, filter, data, [&](const TrajectoryStep&) {
    counts.push_back(slipwalk::testing::allocation_count());
  });
  return counts.back() - counts.front();
}

TEST(Trajectory, StepsDoNotAllocate) {
  EXPECT_EQ(allocations_between_steps(ViscousCoulombKernel{}, NoFilter{}), 0);
  EXPECT_EQ(allocations_between_steps(ViscousCoulombKernel{}, IirFilter{}), 0);
  EXPECT_EQ(allocations_between_steps(CoulombKernel{}, IirFilter{}), 0);
  // The counter works: a run that copies frames allocates.
  const long long before = slipwalk::testing::allocation_count();
  TrajectoryOptions options;
  options.steps = 3;
  run(paired_feet(0.0), options, ViscousCoulombKernel{}, NoFilter{});
  EXPECT_GT(slipwalk::testing::allocation_count(), before);
}

TEST(Trajectory, BadOptionsAreInputErrors) {
  const contact::Robot robot = hexapod();
  TrajectoryData data(robot);
  const TrajectorySink sink = [](const TrajectoryStep&) {};
  const FootKinematics feet = paired_feet(0.0);
  TrajectoryOptions options;
  options.dt = 0.0;
  EXPECT_THROW(integrate(robot, feet, options, ViscousCoulombKernel{}, NoFilter{}, data, sink),
               core::InputError);
  options.dt = 0.01;
  options.steps = -1;
  EXPECT_THROW(integrate(robot, feet, options, ViscousCoulombKernel{}, NoFilter{}, data, sink),
               core::InputError);
  options.steps = 1;
  EXPECT_THROW(integrate(robot, feet, options, ViscousCoulombKernel{}, IirFilter{1.0}, data, sink),
               core::InputError);
  EXPECT_THROW(integrate(robot, feet, options, CoulombKernel{}, NoFilter{}, data, nullptr),
               core::InputError);
  TrajectoryData wrong(contact::uniform_robot(4));
  EXPECT_THROW(integrate(robot, feet, options, ViscousCoulombKernel{}, NoFilter{}, wrong, sink),
               core::InputError);
}

}  // namespace
}  // namespace slipwalk::connection
