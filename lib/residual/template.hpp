#pragma once
// The template model along a motion trial (thesis §5.3.1): at every interior sample t_j of a
// trial, what the robot did and what the template says it should have done.
//
//  - measured body velocity g̊_true (body frame): the constant body twist that carries the pose
//    at t_{j−1} to the pose at t_{j+1}, g̊_true,j = log(g_{j−1}⁻¹ g_{j+1}) / (t_{j+1} − t_{j−1})
//    (core/se2.hpp): exact for motion at a constant body twist, second-order accurate
//    otherwise, like a central difference;
//  - joint rates by central differences, the same stencil;
//  - the feet q, q̇ from the joints (robots::multipod_feet_from_joints, the template's rigid
//    legs), then the spring support and the local connection A(q) of eq. 3.20
//    (contact::spring_support, connection::local_connection) for the template robot, and the
//    template's body velocity A(q) q̇.
//
// The first and last samples have no central difference and are left out: a trial of n samples
// gives n − 2 snapshots.
#include <Eigen/Core>

#include "contact/robot.hpp"
#include "residual/fit.hpp"
#include "residual/trial.hpp"
#include "robots/multipod.hpp"

namespace slipwalk::residual {

/// The template robot the residual is fitted against: the thesis' Multipod of §3.5.2.1 (uniform
/// legs K, μ = 1, Mg = N newtons; robots::multipod) and its geometry.
struct TemplateRobot {
  contact::Robot robot;
  robots::MultipodGeometry geometry;
};
/// The template Multipod of `legs` legs (6, 8, 10 or 12) with the defaults of
/// robots::UndulationGait (K = 1000 N/m). Throws core::InputError for another count.
[[nodiscard]] TemplateRobot multipod_template(int legs);

/// The interior samples of a trial, measured and predicted, row j ↔ sample j + 1.
struct TemplatePrediction {
  Eigen::VectorXd t;         ///< (n − 2) s
  Eigen::MatrixX3d v_true;   ///< (n − 2) × 3: measured (v_x, v_y m/s, ω rad/s), body frame
  Eigen::MatrixX3d v_model;  ///< (n − 2) × 3: the template's A(q) q̇
  Eigen::MatrixXd qdot;      ///< (n − 2) × 2K: vec(q̇_xy), columns 2k, 2k + 1 = foot k
  Eigen::VectorXi contacts;  ///< (n − 2) feet in contact in the template's spring support
};

/// Throws core::InputError (the trial's label) when the trial is invalid (validate) or its legs
/// differ from the template's.
[[nodiscard]] TemplatePrediction predict(const TemplateRobot& model, const MotionTrial& trial);

/// The fit's snapshots of one prediction: q̇ rows and r = g̊_true − A(q) q̇ rows.
[[nodiscard]] ResidualTrial residual_trial(const TemplatePrediction& prediction);

/// The body velocity with B: (A(q) + B) q̇ = v_model + q̇ Bᵀ, row by row ((n − 2) × 3).
[[nodiscard]] Eigen::MatrixX3d with_residual(const TemplatePrediction& prediction,
                                             const Eigen::Matrix<double, 3, Eigen::Dynamic>& B);

}  // namespace slipwalk::residual
