// The template model along a motion trial (thesis §5.3.1; template.hpp).
#include "residual/template.hpp"

#include <string>

#include "connection/local_connection.hpp"
#include "contact/spring_support.hpp"
#include "core/csv.hpp"
#include "core/error.hpp"
#include "core/se2.hpp"
#include "robots/robots.hpp"

namespace slipwalk::residual {

TemplateRobot multipod_template(int legs) {
  robots::UndulationGait gait;
  gait.legs = legs;
  // The gait's other fields are only validated here: the template's legs (K, μ = 1, Mg = N) do
  // not depend on them (§3.5.2.1).
  return {robots::multipod(gait).robot, robots::MultipodGeometry{}};
}

TemplatePrediction predict(const TemplateRobot& model, const MotionTrial& trial) {
  validate(trial);
  const int legs = model.robot.legs();
  if (trial.legs() != legs) {
    throw core::InputError(trial.label.empty() ? std::string("the trial") : trial.label,
                           "the trial's robot has " + std::to_string(trial.legs()) + " legs (" +
                               std::to_string(trial.modules()) + " modules), the template " +
                               std::to_string(legs));
  }
  const Eigen::Index n = trial.samples();
  const Eigen::Index m = n - 2;
  const int modules = trial.modules();
  TemplatePrediction out;
  out.t = trial.t.segment(1, m);
  out.v_true.resize(m, 3);
  out.v_model.resize(m, 3);
  out.qdot.resize(m, 2 * legs);
  out.contacts.resize(m);

  // Everything a sample needs is allocated once here; the loop does not allocate.
  contact::Frame frame(model.robot);
  robots::MultipodJoints joints(3, modules);
  robots::MultipodJoints rates(3, modules);
  const auto pose = [&](Eigen::Index j) {
    return core::Pose2{trial.pose(j, 0), trial.pose(j, 1), trial.pose(j, 2)};
  };
  for (Eigen::Index j = 1; j + 1 < n; ++j) {
    const Eigen::Index row = j - 1;
    const double span = trial.t(j + 1) - trial.t(j - 1);
    // Measured body twist: the constant twist that carries g_{j−1} to g_{j+1} (§5.3.1's g̊_true,
    // in the body frame, as A(q) q̇ is).
    out.v_true.row(row) =
        (core::log(core::compose(core::inverse(pose(j - 1)), pose(j + 1))) / span).transpose();
    // Joint angles at t_j and their rates by the same central difference.
    for (int i = 0; i < modules; ++i) {
      for (int k = 0; k < 3; ++k) {
        const Eigen::Index c = 3 * i + k;
        joints(k, i) = trial.joints(j, c);
        rates(k, i) = (trial.joints(j + 1, c) - trial.joints(j - 1, c)) / span;
      }
    }
    robots::multipod_feet_from_joints(model.geometry, joints, rates, frame.q, frame.qdot);
    // The template's body velocity A(q) q̇ (eq. 3.20) from its spring support (§3.3).
    contact::spring_support(model.robot, frame);
    connection::local_connection(model.robot, frame);
    if (frame.support.status == contact::SupportSummary::Status::kNonFinite ||
        !frame.A.allFinite()) {
      throw core::ComputationError(trial.label +
                                   ": the template's spring support has no finite "
                                   "result at t = " +
                                   core::format_double(trial.t(j)) + " s");
    }
    Eigen::Vector3d v = Eigen::Vector3d::Zero();
    int on = 0;
    for (int k = 0; k < legs; ++k) {
      const double qx = frame.qdot(0, k);
      const double qy = frame.qdot(1, k);
      v += frame.A.col(2 * k) * qx + frame.A.col(2 * k + 1) * qy;
      out.qdot(row, 2 * k) = qx;
      out.qdot(row, 2 * k + 1) = qy;
      on += frame.contact[static_cast<std::size_t>(k)] != 0 ? 1 : 0;
    }
    out.v_model.row(row) = v.transpose();
    out.contacts(row) = on;
  }
  return out;
}

ResidualTrial residual_trial(const TemplatePrediction& prediction) {
  return {prediction.qdot, prediction.v_true - prediction.v_model};
}

Eigen::MatrixX3d with_residual(const TemplatePrediction& prediction,
                               const Eigen::Matrix<double, 3, Eigen::Dynamic>& B) {
  if (B.cols() != prediction.qdot.cols()) {
    throw core::InputError("B", "has " + std::to_string(B.cols()) + " columns; the trial's " +
                                    std::to_string(prediction.qdot.cols() / 2) + " legs need " +
                                    std::to_string(prediction.qdot.cols()));
  }
  return prediction.v_model + prediction.qdot * B.transpose();
}

}  // namespace slipwalk::residual
