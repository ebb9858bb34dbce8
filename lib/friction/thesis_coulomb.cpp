// The thesis' Coulomb solver (§3.5.1.3): MINPACK's Levenberg–Marquardt on the ε-law's balance,
// ε shrinking. The oracle in tests: each ε solve balances to MINPACK's tolerance, so it agrees
// with solve_epsilon's Newton on the same ε; the sequence ends where consecutive solutions
// change by less than rel_change, near solve_coulomb's certified velocity. Termination: each
// LM solve is bounded by MINPACK's evaluation budget (maxfev = 200 (n + 1)), the sequence by
// max_eps_steps.
#include "friction/thesis_coulomb.hpp"

#include <cmath>
#include <unsupported/Eigen/NonLinearOptimization>
#include <unsupported/Eigen/NumericalDiff>

#include "friction/planar_forces.hpp"

namespace slipwalk::friction {

namespace {

/// (Σ F_x, Σ F_y, Σ M_z) of the ε-law at (v_x, v_y, ω), in MINPACK's functor form.
struct ThesisEpsilonBalance {
  using Scalar = double;
  using InputType = Eigen::VectorXd;
  using ValueType = Eigen::VectorXd;
  using JacobianType = Eigen::MatrixXd;
  enum { InputsAtCompileTime = Eigen::Dynamic, ValuesAtCompileTime = Eigen::Dynamic };

  const contact::Robot* robot;
  const contact::Frame* frame;
  double epsilon;
  mutable int evaluations = 0;

  [[nodiscard]] int inputs() const { return 3; }
  [[nodiscard]] int values() const { return 3; }
  int operator()(const Eigen::VectorXd& x, Eigen::VectorXd& f) const {
    ++evaluations;
    const PlanarSum s =
        planar_forces(*robot, *frame, x.head<2>(), x(2), ForceLaw::kEpsilon, epsilon);
    f << s.force, s.moment;
    return 0;
  }
};

/// The feet's forces at the velocity found, and the balance residual relative to the size of
/// the forces that cancel.
void write_thesis_forces(const contact::Robot& robot, contact::Frame& frame, double epsilon) {
  const Eigen::Vector3d v = frame.v_body;
  double scale = 0.0;
  for (int k = 0; k < frame.legs(); ++k) {
    frame.Fxy.col(k).setZero();
    if (!frame.contact[k]) {
      continue;
    }
    const Eigen::Vector2d u = v.head<2>() + v(2) * Eigen::Vector2d(-frame.q(1, k), frame.q(0, k)) +
                              frame.qdot.col(k).head<2>();
    frame.Fxy.col(k) = foot_force(robot, frame, k, u, ForceLaw::kEpsilon, epsilon);
    scale += frame.Fxy.col(k).norm();
  }
  const PlanarSum s = planar_forces(robot, frame, v.head<2>(), v(2), ForceLaw::kEpsilon, epsilon);
  double lever = 0.0;
  for (int k = 0; k < frame.legs(); ++k) {
    if (frame.contact[k]) {
      lever = std::max(lever, frame.q.col(k).head<2>().norm());
    }
  }
  frame.friction.residual =
      scale > 0.0 ? std::max(s.force.norm(), std::abs(s.moment) / std::max(lever, 1e-300)) / scale
                  : 0.0;
}

}  // namespace

void solve_epsilon_thesis(const contact::Robot& robot, contact::Frame& frame, double epsilon,
                          const Eigen::Vector3d& start) {
  ThesisEpsilonBalance balance{&robot, &frame, epsilon};
  Eigen::NumericalDiff<ThesisEpsilonBalance> diff(balance);
  Eigen::LevenbergMarquardt<Eigen::NumericalDiff<ThesisEpsilonBalance>> lm(diff);
  Eigen::VectorXd x = start;
  const auto status = lm.minimize(x);
  frame.v_body = x;
  auto& s = frame.friction;
  s.iterations = static_cast<int>(lm.nfev);
  s.converged = status == Eigen::LevenbergMarquardtSpace::RelativeReductionTooSmall ||
                status == Eigen::LevenbergMarquardtSpace::RelativeErrorTooSmall ||
                status == Eigen::LevenbergMarquardtSpace::RelativeErrorAndReductionTooSmall ||
                status == Eigen::LevenbergMarquardtSpace::CosinusTooSmall;
  s.certificate = 0.0;
  s.message = s.converged ? "" : "Levenberg-Marquardt stopped without converging";
  write_thesis_forces(robot, frame, epsilon);
  s.converged = s.converged && frame.v_body.allFinite();
}

void solve_coulomb_thesis(const contact::Robot& robot, contact::Frame& frame,
                          const Eigen::Vector3d& start, const ThesisCoulombOptions& options) {
  Eigen::Vector3d last = start;
  double eps = options.eps_start;
  bool settled = false;
  int steps = 0;
  while (!settled && steps < options.max_eps_steps) {
    solve_epsilon_thesis(robot, frame, eps, last);
    ++steps;
    if (!frame.friction.converged) {
      break;
    }
    const Eigen::Vector3d v = frame.v_body;
    settled = steps > 1 && (v - last).norm() <= options.rel_change * v.norm();
    last = v;
    eps *= options.eps_factor;
  }
  frame.friction.converged = settled;
  frame.friction.iterations = steps;
  if (!settled && frame.friction.message.empty()) {
    frame.friction.message = "the sequence of epsilon solves did not settle";
  }
}

}  // namespace slipwalk::friction
