#pragma once
// The local connection of thesis eq. 3.20: with the viscous-Coulomb ansatz the body velocity is
// linear in the feet's planar velocities, v_body = A(q) · vec(q̇_xy) with A of size 3 × 2N
// (columns 2k, 2k+1 for foot k; zero for feet in the air). Also the whole per-frame pipeline.
#include <span>

#include "contact/robot.hpp"
#include "contact/spring_support.hpp"
#include "contact/support_batch.hpp"
#include "friction/solvers.hpp"
#include "friction/viscous_system.hpp"

namespace slipwalk::connection {

/// Fills frame.A from frame.q, frame.contact, frame.Fz (needs contact::spring_support first).
void local_connection(const contact::Robot& robot, contact::Frame& frame);

/// Fills frame.A from the frame's already built viscous system (friction/viscous_system.hpp), for
/// a caller that solves the viscous-Coulomb balance from the same system (evaluate).
void local_connection(const contact::Robot& robot, contact::Frame& frame,
                      const friction::ViscousSystem& system);

enum class FrictionLaw { kViscousCoulomb, kCoulomb };

/// One frame of the model: spring support, the local connection A (eq. 3.20 is defined by the
/// viscous-Coulomb ansatz, so A is filled whatever the law), then the friction law's balance
/// (v_body, Fxy, friction summary). The `slipwalk model` command and trajectories call this.
/// support: the spring support's options (its warm start, for a frame that carries the previous
/// frame's balance).
void evaluate(const contact::Robot& robot, contact::Frame& frame, FrictionLaw law,
              const contact::SupportOptions& support = {});

/// evaluate(robot, frame, law) for every frame, four independent frames at a time, frame i of a
/// group in lane i of a vector: the spring support (contact::spring_support_batch) and, with
/// viscous-Coulomb friction on an isotropic robot, the balance and A
/// (friction::solve_viscous_coulomb_group); the same contact sets and statuses, every output to
/// rounding (not to the bit: the feet are summed in another order). For frames that do not wait for
/// each other's answers (a batch from a file, random frames; not a trajectory's warm starts).
/// Every frame must have robot.legs() legs; does not allocate once scratch fits the robot.
void evaluate_batch(const contact::Robot& robot, std::span<contact::Frame> frames, FrictionLaw law,
                    contact::BatchScratch& scratch);

}  // namespace slipwalk::connection
