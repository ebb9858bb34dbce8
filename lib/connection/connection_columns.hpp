#pragma once
// The columns of the local connection A (eq. 3.20) from an already assembled and factorized
// viscous system, so that connection::evaluate factorizes the system once for both A and the
// viscous-Coulomb velocity (local_connection() and solve_viscous_coulomb() each assemble it).
#include "contact/robot.hpp"
#include "friction/balance.hpp"

namespace slipwalk::connection::detail {

/// Fills frame.A from the factorized system of friction::detail::viscous_balance (c_k in
/// frame.work_n).
void connection_columns(const contact::Robot& robot, contact::Frame& frame,
                        const friction::detail::Psd3& solver, const friction::detail::Contacts& cs);

}  // namespace slipwalk::connection::detail
