#pragma once
// The spring support (thesis §3.3) of many independent frames of one robot: the Newton route of
// support_newton.cpp with four frames side by side in the lanes of a vector, where the one-frame
// route puts four feet there. For a sweep, a batch of frames from a file, a study of random
// frames: anything whose frames do not wait for each other's answers (a trajectory does, and
// takes spring_support with SupportOptions::warm_start).
//
// Why. On a few legs the one-frame route is a serial chain: each step's pass over the feet ends in
// sums across the lanes, a 3 × 3 solve by cofactors and a division, and the next step waits for
// it. With the frames in the lanes each foot is one vector operation for four frames, the sums
// need no reduction across lanes, and one vector division serves four solves.
//
// Same answer. The steps, the contact convention and the certificate are those of
// support_by_newton, and so is the start below 20 legs (the all-feet cell; from 20 legs the
// one-frame route starts from the level body, the batch still from all feet, see
// support_batch.cpp): a frame is certified only when its contact set
// repeats, the balance residual is zero to rounding and the cell is safely definite, so the
// certified state is the unique minimizer of U, and the same frame's one-frame route certifies
// the same contact set and the same state to rounding (the feet are summed in another order,
// so not to the bit). A frame the batched route does not certify (a step from a cell that is
// not definite, where the one-frame route tilts; a foot at its plane; a cycling contact set) is
// solved again by spring_support, whatever route that takes, so every frame's outputs are those
// of spring_support up to rounding.
#include <span>

#include "contact/robot.hpp"

namespace slipwalk::contact {

/// Scratch of the batched model (spring_support_batch, friction::solve_viscous_coulomb_group) for
/// a robot of `legs` legs: the feet of the four frames of a group, column j holding foot j of the
/// four side by side (4 × legs, column-major).
struct BatchScratch {
  explicit BatchScratch(int legs);
  // The spring support's.
  Eigen::Matrix<double, 4, Eigen::Dynamic> qy;        ///< q_y,j of the four frames, m
  Eigen::Matrix<double, 4, Eigen::Dynamic> minus_qx;  ///< −q_x,j, m
  Eigen::Matrix<double, 4, Eigen::Dynamic> qz;        ///< q_z,j, m
  /// All ones (−1) where foot j of that frame was in contact (h_j < 0) at the last pass, else 0.
  Eigen::Matrix<std::int64_t, 4, Eigen::Dynamic> on;
  Eigen::Matrix<double, 4, Eigen::Dynamic> Fz;  ///< F_z,j at the certified lanes' states, N
  // The viscous-Coulomb balance's (the feet read again from the frames, whatever route their
  // support took).
  Eigen::Matrix<double, 4, Eigen::Dynamic> x;   ///< q_x,j, m
  Eigen::Matrix<double, 4, Eigen::Dynamic> y;   ///< q_y,j, m
  Eigen::Matrix<double, 4, Eigen::Dynamic> dx;  ///< q̇_x,j, m/s
  Eigen::Matrix<double, 4, Eigen::Dynamic> dy;  ///< q̇_y,j, m/s
  Eigen::Matrix<double, 4, Eigen::Dynamic> c;  ///< c_j = μ_j F_z,j of a foot in contact, else 0, N

  [[nodiscard]] bool holds(int legs) const {
    for (const auto* rows : {&qy, &minus_qx, &qz, &Fz, &x, &y, &dx, &dy, &c}) {
      if (rows->cols() != legs) {
        return false;
      }
    }
    return on.cols() == legs;
  }
};

/// spring_support(robot, frame) (cold start, Newton route first) for every frame of `frames`, four
/// at a time: the same contact sets and status, the state and loads to rounding (see the top).
/// Every frame must have robot.legs() legs; a malformed frame throws core::InputError from
/// check_frame as spring_support does (the frames of its group and after it are then unspecified).
/// Allocates only to resize a scratch made for another leg count (and where spring_support does).
void spring_support_batch(const Robot& robot, std::span<Frame> frames, BatchScratch& scratch);

}  // namespace slipwalk::contact
