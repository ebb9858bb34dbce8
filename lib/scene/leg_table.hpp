#pragma once
// A robot given as a leg table in a scene: each leg's hip position in the body frame,
// its spring stiffness K and friction coefficient μ, and its phase in a parametric foot path that
// every leg follows about its hip. It is for robots the built-in walkers (robots/robots.hpp) do
// not cover; the foot path is the simplest honest gait: a fore-aft sweep with a lifted swing.
//
//   [robot]
//   name = "legs"
//   mass = 8.18              # kg, > 0: Mg = mass · 9.81 m/s² is carried by the legs
//   [[robot.leg]]            # one table per leg, at least 3
//   name = "FL"              # optional, unique (default: the leg's index)
//   hip = [0.3, 0.2, 0.0]    # m, body frame (x forward, y left, z up), required
//   K = 2675.0               # N/m, > 0, required
//   mu = 1.0                 # >= 0, default 1
//   phase = 0.0              # cycles, [0, 1), default 0
//
//   [gait]
//   kind = "foot_path"       # the gait of a leg table
//   frequency = 0.5          # Hz, > 0
//   stride = 0.1             # m, > 0: the fore-aft sweep of each foot
//   height = 0.1             # m, > 0: the stance foot this far below its hip
//   lift = 0.03              # m, >= 0: the swing's highest lift
//
// Foot path of leg k, φ = 2π (f t + phase_k): q = hip + (−(stride/2) cos φ, 0,
// −height + lift · max(0, sin φ)). In stance (sin φ ≤ 0, half a cycle) the foot moves backward
// (q̇_x = (stride/2) 2πf sin φ ≤ 0) and the body forward; in swing it lifts and returns. q̇ is
// the exact derivative (q̇_z jumps at touchdown and lift-off, where q_z has a kink).
#include <string>
#include <vector>

#include "robots/walker.hpp"
#include "scene/toml_reader.hpp"

namespace slipwalk::scene {

struct LegSpec {
  std::string name;
  Eigen::Vector3d hip = Eigen::Vector3d::Zero();  ///< m, body frame
  double K = 1.0;                                 ///< N/m, > 0
  double mu = 1.0;                                ///< ≥ 0
  double phase = 0.0;                             ///< cycles, [0, 1)
};

/// The leg table and its foot path (one gait, so the table and the gait are one struct).
struct LegTableGait {
  std::vector<LegSpec> legs;
  double mass = 1.0;       ///< kg, > 0
  double frequency = 0.5;  ///< Hz, > 0
  double stride = 0.1;     ///< m, > 0
  double height = 0.1;     ///< m, > 0
  double lift = 0.03;      ///< m, ≥ 0
};

inline constexpr double kGravity = 9.81;  ///< m/s², as robots/ uses for Mg

/// The walker of a leg table: K, μ per leg, isotropic, Mg = mass · g, the foot path above, the
/// phase (f t + phase_k) mod 1. Throws core::InputError("leg_table.<field>", ...) for values out
/// of range (the scene reader checks them first, at their keys).
[[nodiscard]] robots::Walker leg_table_walker(const LegTableGait& gait);

/// Reads [robot] mass and its [[robot.leg]] tables and the foot path's keys of [gait]; every
/// error at its key (file:line:col).
[[nodiscard]] LegTableGait read_leg_table(const TableReader& robot, const TableReader& gait,
                                          const std::string& path,
                                          const std::vector<TableSchema>& all);

}  // namespace slipwalk::scene
