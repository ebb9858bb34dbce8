// The legged robots of the MuJoCo peer, without MuJoCo (legged_spec.hpp).
#include "peers/mujoco/legged_spec.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "core/error.hpp"

namespace slipwalk::peers::mujoco {

namespace {

using core::InputError;

void check_spec(const PeerSpec& s) {
  const auto bad = [](const std::string& what) { throw InputError("peer spec", what); };
  if (s.legs.empty()) {
    bad("no legs");
  }
  for (std::size_t k = 0; k < s.legs.size(); ++k) {
    const LegSpec& l = s.legs[k];
    const std::string leg = "legs[" + std::to_string(k) + "]";
    if (!l.hip.allFinite() || !std::isfinite(l.direction)) {
      bad(leg + ": hip and direction must be finite");
    }
    if (!(l.length > 0.0) || !std::isfinite(l.length)) {
      bad(leg + ".length: must be positive");
    }
    if (!(l.yaw_range > 0.0 && l.yaw_range < std::numbers::pi / 2)) {
      bad(leg + ".yaw_range: must be in (0, pi/2)");
    }
    if (!(l.pitch_min > 0.0 && l.pitch_min < l.pitch_max && l.pitch_max < std::numbers::pi / 2)) {
      bad(leg + ": need 0 < pitch_min < pitch_max < pi/2");
    }
    if (!(l.slide_range > 0.0) || !std::isfinite(l.slide_range)) {
      bad(leg + ".slide_range: must be positive");
    }
    if (!(l.mu >= 0.0) || !std::isfinite(l.mu)) {
      bad(leg + ".mu: must be >= 0");
    }
  }
  const double leg_mass = 3.0 * s.link_mass * static_cast<double>(s.legs.size());
  if (!(s.link_mass > 0.0) || !(s.total_mass > leg_mass) || !std::isfinite(s.total_mass)) {
    bad("need link_mass > 0 and total_mass > the legs' mass");
  }
  for (double x :
       {s.body_radius, s.foot_radius, s.gravity, s.timestep, s.tolerance, s.kp_slide, s.kp_hinge}) {
    if (!(x > 0.0) || !std::isfinite(x)) {
      bad("body_radius, foot_radius, gravity, timestep, tolerance, kp_*: must be positive");
    }
  }
  if (s.iterations < 1 || !(s.joint_damping >= 0.0)) {
    bad("iterations must be >= 1 and joint_damping >= 0");
  }
}

/// The leg's pitch axis: horizontal, across the leg, oriented so that φ > 0 swings the foot out
/// (p × (−ℓ e_z) = ℓ e_r for p = (sin a, −cos a, 0)).
Eigen::Vector3d pitch_axis(double a) { return {std::sin(a), -std::cos(a), 0.0}; }

}  // namespace

// --- the disk robot of §3.5.3
// ---------------------------------------------------------------------

PeerSpec disk_spec(const contact::Robot& robot, double radius, double reach, double height) {
  contact::validate(robot);
  const int n = robot.legs();
  PeerSpec spec;
  spec.total_mass = robot.Mg / spec.gravity;
  spec.body_radius = radius;
  // A foot moves in a wedge around its nominal point: ±w radially, and tangentially at most 45 %
  // of the distance between neighbouring hips, so no two workspaces overlap (§3.5.3).
  const double w = 0.4 * reach;
  const double chord = 2.0 * radius * std::sin(std::numbers::pi / n);
  const double yaw = std::min(0.5, std::asin(std::min(0.99, 0.45 * chord / (reach + w))));
  const double length = 2.0 * (reach + w);  // pitch stays below 30°, far from the singular 90°
  for (int k = 0; k < n; ++k) {
    LegSpec leg;
    leg.direction = 2.0 * std::numbers::pi * k / n;
    leg.hip << radius * std::cos(leg.direction), radius * std::sin(leg.direction), 0.0;
    leg.length = length;
    leg.yaw_range = yaw;
    leg.pitch_min = std::asin((reach - w) / length);
    leg.pitch_max = std::asin((reach + w) / length);
    leg.slide_range = height;
    leg.mu = robot.mu(k);
    spec.legs.push_back(leg);
  }
  return spec;
}

// --- MJCF
// ------------------------------------------------------------------------------------------

std::string mjcf(const PeerSpec& s) {
  check_spec(s);
  std::ostringstream x;
  x.precision(17);
  const auto v3 = [&x](const Eigen::Vector3d& v) -> std::ostringstream& {
    x << v(0) << ' ' << v(1) << ' ' << v(2);
    return x;
  };
  const double n = static_cast<double>(s.legs.size());
  const double body_mass = s.total_mass - 3.0 * s.link_mass * n;
  // A thin uniform disk: I_xx = I_yy = m r²/4, I_zz = m r²/2.
  const double r2 = s.body_radius * s.body_radius;
  // Link inertias: tiny but positive (MuJoCo rejects massless moving bodies).
  const double link_inertia = s.link_mass * 1e-4;
  x << "<mujoco model=\"slipwalk_peer\">\n"
    << "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n"
    << "  <option timestep=\"" << s.timestep << "\" gravity=\"0 0 " << -s.gravity
    << "\" solver=\"Newton\" iterations=\"" << s.iterations << "\" tolerance=\"" << s.tolerance
    << "\" cone=\"pyramidal\"/>\n"
    // Only feet and floor collide: feet have contype 1, the floor conaffinity 1, the rest 0.
    << "  <default><geom contype=\"0\" conaffinity=\"0\" condim=\"3\"/>"
    << "<joint damping=\"" << s.joint_damping << "\" limited=\"true\"/></default>\n"
    << "  <worldbody>\n"
    << "    <geom name=\"floor\" type=\"plane\" size=\"0 0 1\" pos=\"0 0 " << -s.foot_radius
    << "\" conaffinity=\"1\"/>\n"
    << "    <body name=\"body\" pos=\"0 0 0.2\">\n"
    << "      <freejoint name=\"root\"/>\n"
    << "      <inertial pos=\"0 0 0\" mass=\"" << body_mass << "\" diaginertia=\""
    << body_mass * r2 / 4 << ' ' << body_mass * r2 / 4 << ' ' << body_mass * r2 / 2 << "\"/>\n"
    << "      <geom type=\"cylinder\" size=\"" << s.body_radius << " 0.005\"/>\n";
  // Each link's mass sits at its far end: the slide's and the yaw link's at the hip, the pitch
  // link's at the foot, so the hips' inertia is the foot's (m ℓ²), not a bare numerical floor.
  const auto inertial = [&](double z) {
    x << "<inertial pos=\"0 0 " << z << "\" mass=\"" << s.link_mass << "\" diaginertia=\""
      << link_inertia << ' ' << link_inertia << ' ' << link_inertia << "\"/>";
  };
  for (std::size_t k = 0; k < s.legs.size(); ++k) {
    const LegSpec& l = s.legs[k];
    x << "      <body name=\"slide" << k << "\" pos=\"";
    v3(l.hip) << "\">";
    inertial(0.0);
    x << "<joint name=\"slide" << k << "\" type=\"slide\" axis=\"0 0 1\" range=\"" << -l.slide_range
      << ' ' << l.slide_range << "\"/>\n"
      << "        <body name=\"yaw" << k << "\">";
    inertial(0.0);
    x << "<joint name=\"yaw" << k << "\" type=\"hinge\" axis=\"0 0 1\" range=\"" << -l.yaw_range
      << ' ' << l.yaw_range << "\"/>\n"
      << "          <body name=\"pitch" << k << "\">";
    inertial(-l.length);
    x << "<joint name=\"pitch" << k << "\" type=\"hinge\" axis=\"";
    v3(pitch_axis(l.direction)) << "\" range=\"" << l.pitch_min << ' ' << l.pitch_max << "\"/>\n"
                                << "            <geom type=\"capsule\" fromto=\"0 0 0 0 0 "
                                << -l.length << "\" size=\"0.004\"/>\n"
                                << "            <geom name=\"foot" << k
                                << "\" type=\"sphere\" pos=\"0 0 " << -l.length << "\" size=\""
                                << s.foot_radius << "\" contype=\"1\" friction=\"" << l.mu
                                << " 0.005 0.0001\"/>\n"
                                << "          </body>\n        </body>\n      </body>\n";
  }
  x << "    </body>\n  </worldbody>\n  <actuator>\n";
  for (std::size_t k = 0; k < s.legs.size(); ++k) {
    x << "    <position joint=\"slide" << k << "\" kp=\"" << s.kp_slide << "\"/>"
      << "<position joint=\"yaw" << k << "\" kp=\"" << s.kp_hinge << "\"/>"
      << "<position joint=\"pitch" << k << "\" kp=\"" << s.kp_hinge << "\"/>\n";
  }
  x << "  </actuator>\n</mujoco>\n";
  return x.str();
}

// --- leg kinematics
// ---------------------------------------------------------------------------------

// With Δ = q_xy − hip_xy = ρ e_r(a + ψ): ρ = ℓ sin φ, ψ = angle(Δ) − a, s = q_z − hip_z + ℓ cos φ.
// Rates: ρ̇ = Δ·Δ̇/ρ, ψ̇ = (Δ × Δ̇)_z/ρ², φ̇ = ρ̇/(ℓ cos φ), ṡ = q̇_z − ℓ sin φ φ̇.
bool leg_inverse(const LegSpec& leg, const Eigen::Vector3d& q, const Eigen::Vector3d& qdot,
                 LegJoints& joints, LegJoints& rates) {
  const Eigen::Vector2d d = q.head<2>() - leg.hip.head<2>();
  const double rho = d.norm();
  if (!(rho > 0.0 && rho < leg.length)) {
    return false;
  }
  const double phi = std::asin(rho / leg.length);
  const double c = leg.length * std::cos(phi);
  joints.pitch = phi;
  joints.yaw = std::remainder(std::atan2(d(1), d(0)) - leg.direction, 2.0 * std::numbers::pi);
  joints.slide = q(2) - leg.hip(2) + c;
  const Eigen::Vector2d dd = qdot.head<2>();
  const double rho_dot = d.dot(dd) / rho;
  rates.pitch = rho_dot / c;
  rates.yaw = (d(0) * dd(1) - d(1) * dd(0)) / (rho * rho);
  rates.slide = qdot(2) - rho * rates.pitch;
  return true;
}

Eigen::Vector3d leg_forward(const LegSpec& leg, const LegJoints& j) {
  const double b = leg.direction + j.yaw;
  const double rho = leg.length * std::sin(j.pitch);
  return leg.hip + Eigen::Vector3d(rho * std::cos(b), rho * std::sin(b),
                                   j.slide - leg.length * std::cos(j.pitch));
}

Eigen::Vector3d workspace_point(const LegSpec& leg, double u_reach, double u_yaw, double z) {
  const double lo = leg.length * std::sin(leg.pitch_min);
  const double hi = leg.length * std::sin(leg.pitch_max);
  const double mid = 0.5 * (lo + hi), half = 0.475 * (hi - lo);
  const double rho = mid + half * (2.0 * u_reach - 1.0);
  const double b = leg.direction + 0.95 * leg.yaw_range * (2.0 * u_yaw - 1.0);
  return {leg.hip(0) + rho * std::cos(b), leg.hip(1) + rho * std::sin(b), z};
}

}  // namespace slipwalk::peers::mujoco
