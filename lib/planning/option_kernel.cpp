#include "planning/option_kernel.hpp"

#include <cmath>

#include "contact/spring_support.hpp"
#include "friction/solvers.hpp"
#include "planning/fast_kernel.hpp"

namespace slipwalk::planning {

namespace {

using core::wrap_turns;

bool support_ok(const contact::SupportSummary& s) {
  using Status = contact::SupportSummary::Status;
  return s.status == Status::kBalanced || s.status == Status::kLine || s.status == Status::kPoint;
}

}  // namespace

double advanced_phi(double phi, double speed, int substeps, double h) {
  return wrap_turns(phi + speed * (static_cast<double>(substeps) * h));
}

void size_node(const PlanRobot& robot, const PlanOptions& options, NodeTable& table) {
  table.legs = robot.legs();
  table.columns = static_cast<int>(options.speeds.size()) + 1;
  table.substeps = options.substeps;
  table.h = options.horizon / static_cast<double>(options.substeps);
  const Eigen::Index n = table.at(options.substeps + 1, 0, 0);
  table.q.resize(3, n);
  table.qdot.resize(3, n);
  table.chooses.assign(static_cast<std::size_t>(table.legs), 1);
  table.free_legs.clear();
  table.free_legs.reserve(static_cast<std::size_t>(table.legs));
  table.start_contact.assign(static_cast<std::size_t>(table.legs), 0);
  table.start_Fz = Eigen::VectorXd::Zero(table.legs);
  table.isotropic = robot.robot.isotropic();
}

void build_node(const PlanRobot& robot, const PlanOptions& options, const Eigen::VectorXd& phi,
                NodeTable& table, contact::Frame& scratch) {
  const int m = table.columns - 1;
  Eigen::Vector3d q;
  Eigen::Vector3d dq;
  for (int s = 0; s <= table.substeps; ++s) {
    for (int c = 0; c < table.columns; ++c) {
      const double speed =
          c < m ? options.speeds[static_cast<std::size_t>(c)] : options.swing_speed;
      for (int i = 0; i < table.legs; ++i) {
        robot.toe(i, advanced_phi(phi(i), speed, s, table.h), q, dq);
        table.q.col(table.at(s, c, i)) = q;
        table.qdot.col(table.at(s, c, i)) = dq * speed;
      }
    }
  }
  // The bounds of the fast route: the largest lever arm and coordinates over the table.
  table.lever = std::sqrt(table.q.topRows<2>().colwise().squaredNorm().maxCoeff());
  if (!(table.lever > 0.0)) {
    table.lever = 1.0;
  }
  table.size_x = table.q.row(0).cwiseAbs().maxCoeff();
  table.size_y = table.q.row(1).cwiseAbs().maxCoeff();
  table.size_z = table.q.row(2).cwiseAbs().maxCoeff();
  // Substep 0 is the node's configuration for every option: its spring support, once.
  for (int i = 0; i < table.legs; ++i) {
    scratch.q.col(i) = table.q.col(table.at(0, 0, i));
  }
  contact::spring_support(robot.robot, scratch);
  detail::store_start_support(robot, scratch, table);
  // Which legs choose: the rule, at the node's configuration (substep 0, any column).
  switch (options.contact) {
    case ContactRule::kSupport:
      for (int i = 0; i < table.legs; ++i) {
        table.chooses[static_cast<std::size_t>(i)] = scratch.contact[static_cast<std::size_t>(i)];
      }
      break;
    case ContactRule::kStanceWindow:
      for (int i = 0; i < table.legs; ++i) {
        const double from_mid = std::min(phi(i), 1.0 - phi(i));  // distance to φ = 0 (mod 1)
        table.chooses[static_cast<std::size_t>(i)] = from_mid <= robot.stance_half_width ? 1 : 0;
      }
      break;
    case ContactRule::kAll:
      for (int i = 0; i < table.legs; ++i) {
        table.chooses[static_cast<std::size_t>(i)] = 1;
      }
      break;
  }
  table.free_legs.clear();
  for (int i = 0; i < table.legs; ++i) {
    if (table.chooses[static_cast<std::size_t>(i)] != 0) {
      table.free_legs.push_back(i);
    }
  }
}

void option_columns(const NodeTable& table, const int* digits, int* columns) {
  const int swing = table.columns - 1;
  for (int i = 0; i < table.legs; ++i) {
    columns[i] = table.chooses[static_cast<std::size_t>(i)] != 0 ? digits[i] : swing;
  }
}

bool integrate_option(const PlanRobot& robot, const PlanOptions& options, const NodeTable& table,
                      const int* columns, int substeps, core::Pose2& pose, contact::Frame& frame) {
  bool ok = false;
  integrate_options(robot, options, table, &columns, 1, substeps, &pose, &ok, frame);
  return ok;
}

static_assert(kOptionBatch == detail::kBatch);

void integrate_options(const PlanRobot& robot, const PlanOptions& options, const NodeTable& table,
                       const int* const* columns, int count, int substeps, core::Pose2* poses,
                       bool* ok, contact::Frame& frame) {
  if (options.law == connection::FrictionLaw::kViscousCoulomb) {
    detail::integrate_batch(robot, options, table, columns, count, substeps, poses, ok, frame);
    return;
  }
  for (int l = 0; l < count; ++l) {
    ok[l] =
        integrate_option_reference(robot, options, table, columns[l], substeps, poses[l], frame);
  }
}

bool integrate_option_reference(const PlanRobot& robot, const PlanOptions& options,
                                const NodeTable& table, const int* columns, int substeps,
                                core::Pose2& pose, contact::Frame& frame) {
  for (int s = 0; s < substeps; ++s) {
    for (int i = 0; i < table.legs; ++i) {
      const Eigen::Index col = table.at(s, columns[i], i);
      frame.q.col(i) = table.q.col(col);
      frame.qdot.col(i) = table.qdot.col(col);
    }
    // §3.3 then §3.4, as connection::integrate's kernels (trajectory.hpp).
    contact::spring_support(robot.robot, frame);
    if (!support_ok(frame.support)) {
      return false;
    }
    if (options.law == connection::FrictionLaw::kViscousCoulomb) {
      friction::solve_viscous_coulomb(robot.robot, frame);
    } else {
      friction::solve_coulomb(robot.robot, frame, options.coulomb);
    }
    if (!frame.friction.converged) {
      return false;
    }
    pose = core::advance(pose, frame.v_body, table.h);
  }
  return std::isfinite(pose.x + pose.y + pose.theta);
}

}  // namespace slipwalk::planning
