#include "robots/multipod.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "robots/check.hpp"

namespace slipwalk::robots {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

Eigen::Vector2d heading(double psi) { return {std::cos(psi), std::sin(psi)}; }
Eigen::Vector2d normal(double psi) { return {-std::sin(psi), std::cos(psi)}; }

}  // namespace

void validate(const UndulationGait& g) {
  if (g.legs != 6 && g.legs != 8 && g.legs != 10 && g.legs != 12) {
    throw core::InputError("multipod.legs", "must be 6, 8, 10 or 12 (the thesis' Multipods), got " +
                                                std::to_string(g.legs));
  }
  detail::require_in("multipod.dphi", g.dphi, detail::kAngle);
  detail::require_in("multipod.frequency", g.frequency, detail::kFrequency);
  detail::require_in("multipod.roll_amplitude", g.roll_amplitude,
                     core::Range{0.0, std::numbers::pi / 2, false, true, "rad"});
  detail::require_in("multipod.yaw_amplitude", g.yaw_amplitude,
                     core::closed(0.0, std::numbers::pi / 4, "rad"));
  detail::require_in("multipod.stiffness", g.stiffness, contact::limits::kStiffness);
}

void multipod_gait_joints(const UndulationGait& g, double t, Eigen::Ref<MultipodJoints> joints,
                          Eigen::Ref<MultipodJoints> rates) {
  const double omega = kTwoPi * g.frequency;
  for (Eigen::Index i = 0; i < joints.cols(); ++i) {
    const double phase = omega * t + static_cast<double>(i) * g.dphi;
    const double c = std::cos(phase);
    const double s = std::sin(phase);
    joints.col(i) << g.yaw_amplitude * c, g.roll_amplitude * s, g.yaw_amplitude * c;
    rates.col(i) << -g.yaw_amplitude * omega * s, g.roll_amplitude * omega * c,
        -g.yaw_amplitude * omega * s;
  }
}

void multipod_feet(const MultipodGeometry& geo, const UndulationGait& g, double t,
                   Eigen::Matrix3Xd& q, Eigen::Matrix3Xd& qdot) {
  // At most 6 modules (12 legs, validate): fixed capacity, no allocation.
  Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 6> joints(3, g.legs / 2);
  Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 6> rates(3, g.legs / 2);
  multipod_gait_joints(g, t, joints, rates);
  multipod_feet_from_joints(geo, joints, rates, q, qdot);
}

void multipod_feet_from_joints(const MultipodGeometry& geo,
                               const Eigen::Ref<const MultipodJoints>& joints,
                               const Eigen::Ref<const MultipodJoints>& rates, Eigen::Matrix3Xd& q,
                               Eigen::Matrix3Xd& qdot) {
  const auto n = static_cast<int>(joints.cols());
  const double w = geo.foot_lateral;
  const double h = geo.foot_depth;

  // Pass 1: walk the chain from the head (section 0 at the origin, heading 0), writing each foot
  // in this chain frame (planar position and velocity, height and its rate) and summing the
  // section centres and headings for the mean frame.
  double psi = 0.0;                                 // heading of section i
  double dpsi = 0.0;                                // its rate
  Eigen::Vector2d c = Eigen::Vector2d::Zero();      // centre of section i
  Eigen::Vector2d dc = Eigen::Vector2d::Zero();     // its velocity
  Eigen::Vector2d c_sum = Eigen::Vector2d::Zero();  // Σ centres, Σ their velocities
  Eigen::Vector2d dc_sum = Eigen::Vector2d::Zero();
  double psi_sum = 0.0;
  double dpsi_sum = 0.0;
  for (int i = 0; i < n; ++i) {
    if (i > 0) {
      // From the rear yaw axis of section i−1 (reached at the end of the last iteration): back
      // along the connector, through the front yaw joint (section heading = connector + θ_y1,i),
      // back half a section to the centre of section i.
      const double conn_psi = psi;  // heading of the connector (set at the end of i−1)
      const double conn_dpsi = dpsi;
      psi = conn_psi + joints(0, i);  // θ_y1,i
      dpsi = conn_dpsi + rates(0, i);
      c -= geo.connector * heading(conn_psi) + 0.5 * geo.section * heading(psi);
      dc -= geo.connector * conn_dpsi * normal(conn_psi) + 0.5 * geo.section * dpsi * normal(psi);
    }
    c_sum += c;
    dc_sum += dc;
    psi_sum += psi;
    dpsi_sum += dpsi;

    // The leg pair, rolled by θ_r about the section's long axis: in the section frame the left
    // foot is R_x(θ_r)(0, w, −h) = (0, w cos θ_r + h sin θ_r, w sin θ_r − h cos θ_r), the right
    // one the same with w → −w. Lateral offset ℓ along the section normal; ℓ̇ = ∂ℓ/∂θ_r · θ̇_r.
    const double roll = joints(1, i);  // θ_r,i
    const double droll = rates(1, i);
    const double cr = std::cos(roll);
    const double sr = std::sin(roll);
    for (int side = 0; side < 2; ++side) {
      const double ws = side == 0 ? w : -w;
      const int j = side * n + i;
      const double lat = ws * cr + h * sr;
      const double dlat = (-ws * sr + h * cr) * droll;
      const Eigen::Vector2d p = c + lat * normal(psi);
      const Eigen::Vector2d dp = dc + dlat * normal(psi) - lat * dpsi * heading(psi);
      q.col(j) << p, ws * sr - h * cr;
      qdot.col(j) << dp, lat * droll;  // d/dt (ws sin θ_r − h cos θ_r) = ℓ θ̇_r
    }
    if (i + 1 < n) {
      // Leave section i through its rear half and the rear yaw joint (connector heading =
      // section − θ_y2,i), carried into the next iteration in psi.
      c -= 0.5 * geo.section * heading(psi);
      dc -= 0.5 * geo.section * dpsi * normal(psi);
      psi -= joints(2, i);  // θ_y2,i
      dpsi -= rates(2, i);
    }
  }

  // Pass 2: into the mean frame, q = R(−ψ̄)(p − c̄), q̇ = R(−ψ̄)(ṗ − c̄̇) − ψ̄̇ S q.
  const double inv_n = 1.0 / static_cast<double>(n);
  const Eigen::Vector2d cbar = c_sum * inv_n;
  const Eigen::Vector2d dcbar = dc_sum * inv_n;
  const double psibar = psi_sum * inv_n;
  const double dpsibar = dpsi_sum * inv_n;
  const double cb = std::cos(psibar);
  const double sb = std::sin(psibar);
  for (int j = 0; j < 2 * n; ++j) {
    const Eigen::Vector2d d = q.col(j).head<2>() - cbar;
    const Eigen::Vector2d dd = qdot.col(j).head<2>() - dcbar;
    const Eigen::Vector2d qb(cb * d.x() + sb * d.y(), -sb * d.x() + cb * d.y());
    const Eigen::Vector2d rb(cb * dd.x() + sb * dd.y(), -sb * dd.x() + cb * dd.y());
    q.col(j).head<2>() = qb;
    qdot.col(j).head<2>() = rb - dpsibar * Eigen::Vector2d(-qb.y(), qb.x());
  }
}

Walker multipod(const UndulationGait& gait) {
  validate(gait);
  const int n = gait.legs / 2;
  Walker w;
  w.name = "multipod" + std::to_string(gait.legs);
  w.robot = contact::uniform_robot(gait.legs, gait.stiffness, 1.0,
                                   static_cast<double>(gait.legs));  // Mg = N (§3.5.2.1)
  for (int side = 0; side < 2; ++side) {
    for (int i = 1; i <= n; ++i) {
      std::string name(side == 0 ? "L" : "R");
      w.leg_names.push_back(name.append(std::to_string(i)));
    }
  }
  w.period = 1.0 / gait.frequency;
  const MultipodGeometry geometry;
  w.feet = [geometry, gait](double t, Eigen::Matrix3Xd& q, Eigen::Matrix3Xd& qdot) {
    multipod_feet(geometry, gait, t, q, qdot);
  };
  // Oscillator phase (2πft + iΔφ)/2π mod 1, shared by the two legs of module i.
  w.phase = [gait, n](double t, Eigen::VectorXd& phase) {
    for (int i = 0; i < n; ++i) {
      const double s = gait.frequency * t + static_cast<double>(i) * gait.dphi / kTwoPi;
      phase(i) = phase(i + n) = s - std::floor(s);
    }
  };
  return w;
}

}  // namespace slipwalk::robots
