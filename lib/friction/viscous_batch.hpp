#pragma once
// The viscous-Coulomb balance (eqs. 3.14 with ε → ∞ and 3.19) and the local connection of eq.
// 3.20 of up to four frames of one isotropic robot at once, frame i in lane i of a vector: the
// batched model's second stage (connection::evaluate_batch), as contact::spring_support_batch is
// its first. Both outputs come from the one 3 × 3 system M x = −b of friction/balance.hpp (A is
// −c_k M⁻¹ J_kᵀ per foot), which is why A is computed here and not in connection/.
//
// Same answer. The system, its LDLᵀ, the solve, M⁻¹ and the forces are those of
// solve_viscous_coulomb and connection::local_connection (friction/balance.cpp,
// viscous_coulomb.cpp, connection/local_connection.cpp) lane by lane, with the feet summed one
// after another instead of four per lane and then across: the same values to rounding. A frame
// whose system is not safely definite (no foot with friction, all contacts at one point: the
// least-norm solve of Psd3's eigen path, with its messages) is left to the caller, as is every
// frame of an anisotropic robot.
#include "contact/robot.hpp"
#include "contact/support_batch.hpp"

namespace slipwalk::friction {

/// For frames[0 … m−1] (1 ≤ m ≤ 4, each with robot.legs() legs, its contact and F_z set by the
/// spring support): v_body, Fxy, the friction summary and A as solve_viscous_coulomb and
/// connection::local_connection write them, for the frames it solved; returns those as bits
/// (frame i: bit i). Writes nothing into the other frames, nor into any frame's own scratch (its
/// ViscousScratch rows). Does not allocate
/// once scratch holds robot.legs() (it is resized otherwise).
unsigned solve_viscous_coulomb_group(const contact::Robot& robot, contact::Frame* const* frames,
                                     int m, contact::BatchScratch& scratch);

}  // namespace slipwalk::friction
