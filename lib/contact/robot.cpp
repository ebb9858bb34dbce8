#include "contact/robot.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/csv.hpp"
#include "core/error.hpp"
#include "core/lanes.hpp"

namespace slipwalk::contact {

namespace {
// Appended piecewise: GCC 12 warns falsely (-Wrestrict) on operator+ chains.
std::string at(const char* name, int j, int i = -1) {
  std::string where(name);
  where.append("[").append(std::to_string(j)).append("]");
  if (i >= 0) {
    where.append("[").append(std::to_string(i)).append("]");
  }
  return where;
}
}  // namespace

Robot uniform_robot(int n, double K, double mu, double Mg) {
  Robot r;
  r.K = Eigen::VectorXd::Constant(n, K);
  r.mu = Eigen::VectorXd::Constant(n, mu);
  r.w = Eigen::Matrix2Xd::Zero(2, n);
  r.Mg = Mg;
  return r;
}

void validate(const Robot& robot) {
  const int n = robot.legs();
  if (n < 1 || n > limits::kMaxLegs) {
    std::string what = "a robot needs 1 to ";
    what.append(std::to_string(limits::kMaxLegs)).append(" legs, got ").append(std::to_string(n));
    throw core::InputError("K", what);
  }
  if (robot.mu.size() != n) {
    throw core::InputError(
        "mu", "has " + std::to_string(robot.mu.size()) + " entries, K has " + std::to_string(n));
  }
  if (robot.w.cols() != n) {
    throw core::InputError(
        "w", "has " + std::to_string(robot.w.cols()) + " entries, K has " + std::to_string(n));
  }
  for (int j = 0; j < n; ++j) {
    core::require_in(at("K", j), robot.K(j), limits::kStiffness);
    require_friction(at("mu", j), robot.mu(j));
    for (int i = 0; i < 2; ++i) {
      core::require_in(at("w", j, i), robot.w(i, j), limits::kAnisotropy);
    }
  }
  core::require_in("Mg", robot.Mg, limits::kWeight);
}

void require_friction(const std::string& where, double mu) {
  if (mu != 0.0 && !limits::kFriction.contains(mu)) {
    std::string what = "must be 0 or in ";
    what.append(limits::kFriction.describe()).append(", got ").append(core::format_double(mu));
    throw core::InputError(where, what);
  }
}

Frame::Frame(const Robot& robot)
    : q(Eigen::Matrix3Xd::Zero(3, robot.legs())),
      qdot(Eigen::Matrix3Xd::Zero(3, robot.legs())),
      contact(static_cast<std::size_t>(robot.legs()), 0),
      Fz(Eigen::VectorXd::Zero(robot.legs())),
      Fxy(Eigen::Matrix2Xd::Zero(2, robot.legs())),
      A(Eigen::MatrixXd::Zero(3, 2 * static_cast<Eigen::Index>(robot.legs()))),
      work_n(Eigen::VectorXd::Zero(robot.legs())),
      work_2n(Eigen::Matrix2Xd::Zero(2, robot.legs())),
      work_idx(static_cast<std::size_t>(robot.legs()), 0),
      support_newton(robot.legs()),
      viscous(robot.legs()),
      coulomb(robot.legs()) {}

ViscousScratch::ViscousScratch(int legs) : rows(FootRows<kRows>::Zero(kRows, padded_feet(legs))) {}

SupportNewtonScratch::SupportNewtonScratch(int legs)
    : qy(FootRow::Zero(padded_feet(legs))),
      minus_qx(FootRow::Zero(padded_feet(legs))),
      qz(FootRow::Zero(padded_feet(legs))),
      K(FootRow::Zero(padded_feet(legs))),
      on(FootFlags::Zero(padded_feet(legs))) {}

CoulombScratch::CoulombScratch(int legs)
    : B(FootRows<6>::Zero(6, padded_pairs(legs))),
      d(FootRows<2>::Zero(2, padded_pairs(legs))),
      active(FootRow::Zero(padded_pairs(legs))),
      sliding(FootRow::Zero(padded_pairs(legs))),
      r2(FootRow::Zero(padded_pairs(legs))),
      weight(FootRow::Zero(padded_pairs(legs))),
      inv_weight2(FootRow::Zero(padded_pairs(legs))) {}

namespace detail {

// Whether |x_i| ≤ bound for all n values of x (core::all_within; cloned here, where it is called
// through check_frame and Robot::isotropic). A short-circuiting test per value was the model's
// largest per-leg cost after the support search.
SLIPWALK_CLONES bool within(const double* x, Eigen::Index n, double bound) {
  return core::all_within(x, n, bound);
}

}  // namespace detail

bool Robot::isotropic() const { return detail::within(w.data(), w.size(), 0.0); }

namespace {

// The cold path of check_frame: names the first value out of its range.
[[gnu::noinline, gnu::cold]] void name_out_of_range(const Frame& frame) {
  for (int j = 0; j < frame.legs(); ++j) {
    for (int i = 0; i < 3; ++i) {
      core::require_in(at("q", j, i), frame.q(i, j), limits::kPosition);
      core::require_in(at("qdot", j, i), frame.qdot(i, j), limits::kVelocity);
    }
  }
  core::require_in("theta", frame.theta, limits::kYaw);
}

// check_frame, with or without the positions' range test.
void check(const Robot& robot, const Frame& frame, bool positions) {
  const int n = robot.legs();
  if (frame.q.cols() != n || frame.qdot.cols() != n) {
    throw core::InputError("q", "has " + std::to_string(frame.q.cols()) + " feet, the robot " +
                                    std::to_string(n) + " legs");
  }
  // One pass per matrix, four values at a time (the ranges are symmetric), and a loop only to
  // name the culprit (the first in the frame's order, whichever test failed).
  const bool inside =
      (!positions || detail::within(frame.q.data(), frame.q.size(), limits::kPosition.hi)) &&
      detail::within(frame.qdot.data(), frame.qdot.size(), limits::kVelocity.hi) &&
      limits::kYaw.contains(frame.theta);
  if (!inside) [[unlikely]] {
    name_out_of_range(frame);
  }
}

}  // namespace

void check_frame(const Robot& robot, const Frame& frame) { check(robot, frame, true); }

void check_frame_except_positions(const Robot& robot, const Frame& frame) {
  check(robot, frame, false);
}

}  // namespace slipwalk::contact
