#pragma once
// Terrain (thesis §5.2): what the ground under the robot does to one frame of the ch. 3 model.
// A terrain is a model (constants of a run, DESIGN.md); the functions here are its geometry, and
// connection/terrain_kernels.hpp applies them to a frame around spring support and friction.
//
// Flat: the ch. 3 model as it is.
//
// Slope (§5.2.1): a plane inclined by σ whose uphill direction, in the plane's own coordinates,
// is at heading ψ. The pose (x, y, θ) lives in the plane's coordinates and the body frame is
// parallel to the plane (roll and pitch are small about it, eq. 3.6 with the plane as ground).
// Gravity Mg splits into Mg cos σ along the plane's normal, which the spring support balances,
// and Mg sin σ along the plane, downhill, which the feet's planar friction must balance
// (eq. 5.1: (F_x, F_y, F_z) = R₀ (0, 0, Mg)). In the body frame the downhill unit vector is
// d = −R_θᵀ (cos ψ, sin ψ), so the planar load on the body is f = Mg sin σ d. It acts at the
// centre of mass: with the CoM on the body's normal through its origin (the ch. 3 assumption that
// the support balances moments about the origin), f has no moment about that normal, M_z = 0.
// Above the plane by h_c, though, the CoM's weight crosses the plane h_c tan σ downhill of the
// origin: the normal loads balance about that point (support_offset()). The thesis' eq. 5.1
// puts the weight at the origin (h_c = 0, the default); com_height makes the tipping explicit.
//
// Stairs (§5.2.2): horizontal treads of depth `tread`, rising by `riser` toward heading ψ; tread
// i covers s ∈ [i·tread, (i+1)·tread) of s = p·(cos ψ, sin ψ) and lies at height i·riser (an
// edge belongs to the upper tread). The pose is horizontal (world), the body pitches nose-up by
// the stair slope γ = atan(riser/tread · cos(θ − ψ)) seen along its heading plus a small δβ, and
// each toe's spring is measured from the tread under it, h(p_x, p_y). Derivation of the change of
// coordinates (and the thesis' sign slip) in terrain.cpp.
#include <Eigen/Core>
#include <variant>

#include "contact/robot.hpp"
#include "core/se2.hpp"

namespace slipwalk::terrain {

struct Flat {};

struct Slope {
  double angle = 0.0;       ///< σ, rad; valid: [0, π/2)
  double heading = 0.0;     ///< ψ, rad: the uphill direction in the plane's coordinates
  double com_height = 0.0;  ///< h_c, m: the CoM's height above the plane; valid: ≥ 0, finite
};

struct Stairs {
  double tread = 0.3;    ///< m; valid: > 0, finite
  double riser = 0.12;   ///< m; valid: ≥ 0, finite (0 = flat ground)
  double heading = 0.0;  ///< ψ, rad: the direction in which the stairs rise
};

using Terrain = std::variant<Flat, Slope, Stairs>;

/// "flat", "slope", "stairs".
[[nodiscard]] const char* kind_name(const Terrain& terrain);

/// Throw core::InputError ("terrain.angle", ...) for out-of-range or non-finite values.
void validate(const Slope& slope);
void validate(const Stairs& stairs);
void validate(const Terrain& terrain);

// ---- slope -------------------------------------------------------------------------------------

/// The planar gravity load on the body at yaw θ, (F_x, F_y, M_z) in the body frame:
/// Mg sin σ · (−R_θᵀ (cos ψ, sin ψ)), M_z = 0.
[[nodiscard]] Eigen::Vector3d slope_load(const Slope& slope, double Mg, double theta);

/// Where the weight's line crosses the plane, in the body frame: h_c tan σ downhill of the origin
/// (zero for com_height = 0). The spring support balances the normal loads about this point.
[[nodiscard]] Eigen::Vector2d support_offset(const Slope& slope, double theta);

/// A point of the plane's coordinates (x, y) at height n along the plane's normal, in the world
/// (x, y horizontal, z up; the plane passes through the world origin).
[[nodiscard]] Eigen::Vector3d slope_to_world(const Slope& slope, double x, double y, double n);

// ---- stairs ------------------------------------------------------------------------------------

/// h(p_x, p_y): the height of the tread under a world point.
[[nodiscard]] double step_height(const Stairs& stairs, double px, double py);

/// γ, the stairs' slope seen along yaw θ (nose-up positive): atan(riser/tread · cos(θ − ψ)).
[[nodiscard]] double stair_pitch(const Stairs& stairs, double theta);

/// Rewrites a frame's feet (body frame, from the gait) into the coordinates in which the ch. 3
/// support search applies on stairs (terrain.cpp): q_x ← cos γ q_x − sin γ q_z (horizontal
/// forward), q_y ← cos γ q_y (the roll lever), q_z ← sin γ q_x + cos γ q_z − h(p) (the toe's
/// height above its tread relative to the body's), q̇_x ← cos γ q̇_x − sin γ q̇_z; `height` (N)
/// receives h(p) of each toe. The friction balance afterwards needs q_y itself: stairs_levers().
void to_stairs_support(const Stairs& stairs, const core::Pose2& pose, contact::Frame& frame,
                       Eigen::VectorXd& height);

/// After the support search: q_y ← q_y / cos γ (the horizontal lateral lever), exactly the value
/// the gait wrote when stored in `saved_qy` (N) before to_stairs_support.
void stairs_levers(contact::Frame& frame, const Eigen::VectorXd& saved_qy);

// ---- any terrain -------------------------------------------------------------------------------

/// A toe's world position before compression (for plots), from the frame a trajectory hands its
/// sink: flat and slope read the body-frame q; stairs read the frame after to_stairs_support and
/// stairs_levers (h recomputed from the toe's horizontal position, the same value the run used).
[[nodiscard]] Eigen::Vector3d toe_world(const Terrain& terrain, const core::Pose2& pose,
                                        const contact::Frame& frame, int k);

/// The body origin's world position (flat and stairs: z is the body height; slope: the plane's
/// normal height mapped to the world).
[[nodiscard]] Eigen::Vector3d body_world(const Terrain& terrain, const core::Pose2& pose,
                                         const contact::Frame& frame);

}  // namespace slipwalk::terrain
