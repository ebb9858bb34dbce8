// Terrain geometry (terrain.hpp).
//
// Stairs: the change of coordinates of §5.2.2, derived. With R = R_z(θ) R_y(β) R_x(α) and the
// thesis' own R_y (first row (cos β, 0, sin β), last row (−sin β, 0, cos β)), a positive β turns
// the body's x axis down (nose-down). Expanding around β = β₀ to first order in δβ = β − β₀ and α,
// the last row of R q is
//   p_z − p_z0 = (−sin β₀ − cos β₀ δβ) q_x + cos β₀ α q_y + (cos β₀ − sin β₀ δβ) q_z
//              = −δβ (cos β₀ q_x + sin β₀ q_z) + α cos β₀ q_y + (−sin β₀ q_x + cos β₀ q_z).
// The thesis prints the constant part as +sin β₀ q_x (and q'_z = sin β₀ q_x + cos β₀ q_z), which
// matches its q'_x = cos β₀ q_x + sin β₀ q_z only with opposite signs of β₀: one of the two is a
// sign slip. Written with the nose-up stair slope γ = −β₀ > 0 used here:
//   q'_x = cos γ q_x − sin γ q_z,   q'_y = cos γ q_y,   q'_z = sin γ q_x + cos γ q_z − h(p),
// and the toe's height above its tread is −δβ q'_x + α q'_y + q'_z + p_z0: eq. 3.6 in q', so the
// spring-support search of §3.3 applies unchanged and returns (α, δβ, p_z0) (p_z0 the body's
// world height). Check: a foot straight below the body (q = (0, 0, −ℓ)) of a nose-up body lies
// ahead of it, q'_x = ℓ sin γ > 0. The friction balance is planar in the world's horizontal plane
// (treads are horizontal, gravity is normal to them, so no planar load): its levers are the toes'
// horizontal positions (q'_x, q_y) and velocities (cos γ q̇_x − sin γ q̇_z, q̇_y) (first order).
#include "terrain/terrain.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "core/csv.hpp"
#include "core/error.hpp"

namespace slipwalk::terrain {

namespace {

void require(bool ok, const char* where, const std::string& what, double value) {
  if (!ok) {
    throw core::InputError(where, what + ", got " + core::format_double(value));
  }
}

}  // namespace

const char* kind_name(const Terrain& terrain) {
  constexpr const char* kNames[] = {"flat", "slope", "stairs"};
  return kNames[terrain.index()];
}

void validate(const Slope& slope) {
  require(slope.angle >= 0.0 && slope.angle < std::numbers::pi / 2, "terrain.angle",
          "must be in [0, 90) degrees", slope.angle * 180.0 / std::numbers::pi);
  require(std::isfinite(slope.heading), "terrain.heading", "must be finite", slope.heading);
  require(slope.com_height >= 0.0 && std::isfinite(slope.com_height), "terrain.com_height",
          "must be >= 0 m and finite", slope.com_height);
}

void validate(const Stairs& stairs) {
  require(stairs.tread > 0.0 && std::isfinite(stairs.tread), "terrain.tread",
          "must be > 0 m and finite", stairs.tread);
  require(stairs.riser >= 0.0 && std::isfinite(stairs.riser), "terrain.riser",
          "must be >= 0 m and finite", stairs.riser);
  require(std::isfinite(stairs.heading), "terrain.heading", "must be finite", stairs.heading);
}

void validate(const Terrain& terrain) {
  if (const auto* s = std::get_if<Slope>(&terrain)) {
    validate(*s);
  } else if (const auto* st = std::get_if<Stairs>(&terrain)) {
    validate(*st);
  }
}

// ---- slope -----------------------------------------------------------------------------------

namespace {

/// The downhill unit vector in the body frame: −R_θᵀ (cos ψ, sin ψ) = −(cos(ψ − θ), sin(ψ − θ)).
Eigen::Vector2d downhill(const Slope& slope, double theta) {
  const double a = slope.heading - theta;
  return {-std::cos(a), -std::sin(a)};
}

}  // namespace

Eigen::Vector3d slope_load(const Slope& slope, double Mg, double theta) {
  const Eigen::Vector2d d = downhill(slope, theta);
  const double f = Mg * std::sin(slope.angle);
  return {f * d(0), f * d(1), 0.0};
}

Eigen::Vector2d support_offset(const Slope& slope, double theta) {
  return slope.com_height * std::tan(slope.angle) * downhill(slope, theta);
}

Eigen::Vector3d slope_to_world(const Slope& slope, double x, double y, double n) {
  // s along the uphill direction u, the rest across it; the plane turns s into s cos σ
  // horizontally and s sin σ up, and the normal (−sin σ u, cos σ) carries n.
  const Eigen::Vector2d u(std::cos(slope.heading), std::sin(slope.heading));
  const Eigen::Vector2d p(x, y);
  const double s = p.dot(u);
  const double cs = std::cos(slope.angle);
  const double sn = std::sin(slope.angle);
  const Eigen::Vector2d horizontal = p - s * u + (s * cs - n * sn) * u;
  return {horizontal(0), horizontal(1), s * sn + n * cs};
}

// ---- stairs ----------------------------------------------------------------------------------

double step_height(const Stairs& stairs, double px, double py) {
  const double s = px * std::cos(stairs.heading) + py * std::sin(stairs.heading);
  return stairs.riser * std::floor(s / stairs.tread);
}

double stair_pitch(const Stairs& stairs, double theta) {
  return std::atan(stairs.riser / stairs.tread * std::cos(theta - stairs.heading));
}

void to_stairs_support(const Stairs& stairs, const core::Pose2& pose, contact::Frame& frame,
                       Eigen::VectorXd& height) {
  const double gamma = stair_pitch(stairs, pose.theta);
  const double cg = std::cos(gamma);
  const double sg = std::sin(gamma);
  const double ct = std::cos(pose.theta);
  const double st = std::sin(pose.theta);
  for (int k = 0; k < frame.legs(); ++k) {
    const double qx = frame.q(0, k);
    const double qy = frame.q(1, k);
    const double qz = frame.q(2, k);
    const double hx = cg * qx - sg * qz;  // horizontal, forward
    const double h = step_height(stairs, pose.x + ct * hx - st * qy, pose.y + st * hx + ct * qy);
    height(k) = h;
    frame.q(0, k) = hx;
    frame.q(1, k) = cg * qy;
    frame.q(2, k) = sg * qx + cg * qz - h;
    frame.qdot(0, k) = cg * frame.qdot(0, k) - sg * frame.qdot(2, k);
  }
}

void stairs_levers(contact::Frame& frame, const Eigen::VectorXd& saved_qy) {
  frame.q.row(1) = saved_qy.transpose();
}

// ---- any terrain -----------------------------------------------------------------------------

Eigen::Vector3d toe_world(const Terrain& terrain, const core::Pose2& pose,
                          const contact::Frame& frame, int k) {
  const double ct = std::cos(pose.theta);
  const double st = std::sin(pose.theta);
  const double qx = frame.q(0, k);
  const double qy = frame.q(1, k);
  const double x = pose.x + ct * qx - st * qy;
  const double y = pose.y + st * qx + ct * qy;
  if (const auto* stairs = std::get_if<Stairs>(&terrain)) {
    // The frame holds (q'_x, q_y, q'_z) with q'_z relative to the tread: add the tread back.
    const double cg = std::cos(stair_pitch(*stairs, pose.theta));
    const double rel = contact::foot_height(frame, k, frame.alpha * cg, frame.beta, frame.z);
    return {x, y, rel + step_height(*stairs, x, y)};
  }
  const double n = contact::foot_height(frame, k, frame.alpha, frame.beta, frame.z);
  if (const auto* slope = std::get_if<Slope>(&terrain)) {
    return slope_to_world(*slope, x, y, n);
  }
  return {x, y, n};
}

Eigen::Vector3d body_world(const Terrain& terrain, const core::Pose2& pose,
                           const contact::Frame& frame) {
  if (const auto* slope = std::get_if<Slope>(&terrain)) {
    return slope_to_world(*slope, pose.x, pose.y, frame.z);
  }
  return {pose.x, pose.y, frame.z};
}

}  // namespace slipwalk::terrain
