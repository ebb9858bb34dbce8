#include "contact/robot.hpp"

#include <cmath>

#include "core/csv.hpp"
#include "core/error.hpp"

namespace slipwalk::contact {

namespace {
std::string at(const char* name, int j) {
  return std::string(name) + "[" + std::to_string(j) + "]";
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
  if (n < 1) {
    throw core::InputError("K", "a robot needs at least one leg");
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
    if (!std::isfinite(robot.K(j)) || robot.K(j) <= 0.0) {
      throw core::InputError(at("K", j),
                             "must be positive, got " + core::format_double(robot.K(j)));
    }
    if (!std::isfinite(robot.mu(j)) || robot.mu(j) < 0.0) {
      throw core::InputError(at("mu", j),
                             "must be non-negative, got " + core::format_double(robot.mu(j)));
    }
    if (!robot.w.col(j).allFinite()) {
      throw core::InputError(at("w", j), "must be finite");
    }
  }
  if (!std::isfinite(robot.Mg) || robot.Mg <= 0.0) {
    throw core::InputError("Mg", "must be positive, got " + core::format_double(robot.Mg));
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
      coulomb(robot.legs()) {}

SupportNewtonScratch::SupportNewtonScratch(int legs)
    : qy(FootRow::Zero(padded_feet(legs))),
      minus_qx(FootRow::Zero(padded_feet(legs))),
      qz(FootRow::Zero(padded_feet(legs))),
      K(FootRow::Zero(padded_feet(legs))),
      on(FootRow::Zero(padded_feet(legs))) {}

CoulombScratch::CoulombScratch(int legs)
    : B(FootRows<6>::Zero(6, padded_feet(legs))),
      d(FootRows<2>::Zero(2, padded_feet(legs))),
      active(FootRow::Zero(padded_feet(legs))),
      sliding(FootRow::Zero(padded_feet(legs))),
      r2(FootRow::Zero(padded_feet(legs))),
      weight(FootRow::Zero(padded_feet(legs))),
      inv_weight2(FootRow::Zero(padded_feet(legs))) {}

void check_frame(const Robot& robot, const Frame& frame) {
  const int n = robot.legs();
  if (frame.q.cols() != n || frame.qdot.cols() != n) {
    throw core::InputError("q", "has " + std::to_string(frame.q.cols()) + " feet, the robot " +
                                    std::to_string(n) + " legs");
  }
  // One vectorized test for the usual case; the loop only to name the culprit.
  if (!frame.q.allFinite() || !frame.qdot.allFinite()) {
    for (int j = 0; j < n; ++j) {
      if (!frame.q.col(j).allFinite()) {
        throw core::InputError(at("q", j), "must be finite");
      }
      if (!frame.qdot.col(j).allFinite()) {
        throw core::InputError(at("qdot", j), "must be finite");
      }
    }
  }
  if (!std::isfinite(frame.theta)) {
    throw core::InputError("theta", "must be finite");
  }
}

}  // namespace slipwalk::contact
