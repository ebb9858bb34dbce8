// Viscous-Coulomb friction (eqs. 3.14 with ε → ∞ and 3.19): the body-frame balance M x = −b of
// friction/balance.hpp, one 3 × 3 solve. Two passes over the feet: the system (with the contact
// summary, detail::viscous_balance; the ViscousSystem of viscous_system.hpp) and the forces; both
// in scalars, since per foot there is only a handful of multiply-adds and any temporary or
// repeated lookup is a visible share.
#include "friction/balance.hpp"
#include "friction/solvers.hpp"
#include "friction/viscous_system.hpp"

namespace slipwalk::friction {

namespace {

/// The solve with (kLoaded) or without an external wrench f = (F_x, F_y, M_z) on the body: the
/// balance Σ J_kᵀ F_k + f = 0 reads M x = f − b, so x = M⁻¹ f − M⁻¹ b: the same matrix and the
/// same A as eq. 3.20, plus the constant M⁻¹ f (terrain/terrain.hpp derives f for a slope). The
/// unloaded instantiation is the flat path, with no code for f.
/// finish() takes the assembled and factorized system (solve() below, or a ViscousSystem that
/// connection::evaluate also builds A from).
// The forces of any robot, foot by foot (the anisotropic metric G = I + w wᵀ included).
detail::ForceSums viscous_forces(const contact::Robot& robot, contact::Frame& frame, double v0,
                                 double v1, double om) {
  detail::ForceSums s;
  for (int k = 0; k < frame.legs(); ++k) {
    const double c = frame.work_n(k);
    const double qx = frame.q(0, k);
    const double qy = frame.q(1, k);
    const double u0 = v0 - om * qy + frame.qdot(0, k);
    const double u1 = v1 + om * qx + frame.qdot(1, k);
    const double w0 = robot.w(0, k);
    const double w1 = robot.w(1, k);
    const double wu = w0 * u0 + w1 * u1;  // G u = u + w (w·u)
    const double F0 = -c * (u0 + w0 * wu);
    const double F1 = -c * (u1 + w1 * wu);
    frame.Fxy(0, k) = F0;  // zero for a foot without friction (c = 0)
    frame.Fxy(1, k) = F1;
    s.fx += F0;
    s.fy += F1;
    s.mz += qx * F1 - qy * F0;
    s.dissipation -= F0 * u0 + F1 * u1;  // c uᵀG u
    // c ‖G‖ (‖q̇‖ + ‖J x‖), in 1-norms (a magnitude, no square roots needed).
    s.scale +=
        c * (1.0 + w0 * w0 + w1 * w1) *
        (std::abs(frame.qdot(0, k)) + std::abs(frame.qdot(1, k)) + std::abs(u0) + std::abs(u1));
  }
  return s;
}

template <bool kLoaded>
void finish(const contact::Robot& robot, contact::Frame& frame, const detail::Psd3& solver,
            const detail::Contacts& cs, const Eigen::Vector3d& b, const Eigen::Vector3d& load) {
  // ---- the 3 × 3 balance, unscaled where definite, else least norm in scaled coordinates -----
  Eigen::Vector3d rhs = -b;
  if constexpr (kLoaded) {
    // Scaled coordinates y = (v, L ω): the moment row is divided by L like b's (balance.hpp).
    rhs += cs.unscaled ? load : Eigen::Vector3d(load(0), load(1), load(2) * cs.inv_L);
  }
  const Eigen::Vector3d y = solver.solve(rhs);
  if (cs.unscaled) {
    frame.v_body = y;
  } else {
    detail::set_velocity(frame, y, cs.L);
  }

  // ---- forces F_k = −c_k G_k u_k, dissipation, balance and the size of the cancelling terms --
  // u_k = v + ω S q_k + q̇_k in body coordinates (v_body as just written).
  const double v0 = frame.v_body(0);
  const double v1 = frame.v_body(1);
  const double om = frame.v_body(2);
  const detail::ForceSums forces = cs.rows ? detail::viscous_forces_rows(frame, v0, v1, om)
                                           : viscous_forces(robot, frame, v0, v1, om);
  const double fx = forces.fx;
  const double fy = forces.fy;
  const double dissipation = forces.dissipation;
  double scale = forces.scale;
  detail::BalanceSum sum;
  sum.force << fx, fy;
  sum.moment = forces.mz;
  if constexpr (kLoaded) {
    // The load is one of the cancelling terms: Σ F_k + f = 0 and Σ M_k + M_f = 0.
    sum.force += load.head<2>();
    sum.moment += load(2);
    const double inv_L = cs.unscaled ? 1.0 / std::sqrt(cs.L2) : cs.inv_L;
    scale += std::abs(load(0)) + std::abs(load(1)) + std::abs(load(2)) * inv_L;
  }

  auto& s = frame.friction;
  s.converged = true;
  s.iterations = 0;
  s.certificate = 0.0;
  s.static_feet = 0;
  s.dissipation = dissipation;
  s.residual =
      cs.unscaled ? sum.residual_from_squared_lever(scale, cs.L2) : sum.residual(scale, cs.L);
  s.unique = solver.rank() == 3;
  s.message.clear();
  if (cs.active == 0) {
    s.message = "no foot with friction in contact: body velocity undetermined, set to 0";
    if constexpr (kLoaded) {
      // Nothing holds the load: there is no quasi-static balance (the body falls or slides).
      if (load.squaredNorm() > 0.0) {
        s.converged = false;
        s.message = "sliding: no foot with friction in contact holds the external load";
      }
    }
  } else if (!s.unique) {
    s.message = "all contacts at one point: rotation about it undetermined (least-norm solution)";
    if constexpr (kLoaded) {
      // A load with a part the contacts cannot feel (a moment about their common point) is not
      // balanced by any velocity.
      const Eigen::Vector3d f(load(0), load(1), load(2) * cs.inv_L);
      if ((solver.project_to_range(f) - f).norm() > 1e-12 * f.norm()) {
        s.converged = false;
        s.message = "sliding: the contacts (all at one point) cannot hold the external moment";
      }
    }
  }
  // The end-of-solve check (balance.hpp's flag_non_finite) on values at hand: fx + fy covers
  // every force written and v0, v1, om the velocity (sums: no pass over the feet).
  if (!std::isfinite(fx + fy + v0 + v1 + om + s.residual + dissipation)) [[unlikely]] {
    detail::mark_non_finite(frame);
  }
}

template <bool kLoaded>
void solve(const contact::Robot& robot, contact::Frame& frame, const Eigen::Vector3d& load) {
  Eigen::Matrix3d M;
  Eigen::Vector3d b;
  detail::Contacts cs = detail::viscous_balance(robot, frame, M, b);
  detail::Psd3 solver;
  detail::factorize_system(solver, cs, M, b);
  finish<kLoaded>(robot, frame, solver, cs, b, load);
}

}  // namespace

ViscousSystem::ViscousSystem(const contact::Robot& robot, contact::Frame& frame, FeetSource feet)
    : weights_(frame.work_n.data()) {
  Eigen::Matrix3d M;
  contacts_ = detail::viscous_balance(robot, frame, M, b_, feet == FeetSource::kSupportRows);
  if (contacts_.rows) {
    weights_ = frame.viscous.rows.row(contact::ViscousScratch::Row::kC).data();
  }
  detail::factorize_system(solver_, contacts_, M, b_);
}

Eigen::Matrix3d ViscousSystem::inverse() const {
  Eigen::Matrix3d P = solver_.inverse();
  if (contacts_.unscaled) {
    return P;
  }
  P.row(2) *= contacts_.inv_L;
  P.col(2) *= contacts_.inv_L;
  return P;
}

void solve_viscous_coulomb(const contact::Robot& robot, contact::Frame& frame,
                           const ViscousSystem& system) {
  finish<false>(robot, frame, system.solver_, system.contacts_, system.b_, Eigen::Vector3d::Zero());
}

void solve_viscous_coulomb(const contact::Robot& robot, contact::Frame& frame) {
  solve<false>(robot, frame, Eigen::Vector3d::Zero());
}

void solve_viscous_coulomb_loaded(const contact::Robot& robot, contact::Frame& frame,
                                  const Eigen::Vector3d& load) {
  solve<true>(robot, frame, load);
}

}  // namespace slipwalk::friction
