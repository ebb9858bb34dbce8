#pragma once
// Scene files (DESIGN.md: "Only the effects a scene calls for"): a TOML file says which robot
// walks with which gait, for how long, and which effects the run simulates. read_scene validates
// the whole file first (errors name file:line:col, nothing runs); compose() then builds the
// simulator once from exactly the named effects. The gaits and the friction laws are read from
// descriptor tables, one entry each (scene/gaits.cpp, scene/friction_laws.cpp): the robot names,
// gait kinds, laws and their keys below are those entries'.
//
// Every number has a range (scene/ranges.hpp, with its unit), checked where it is read; a run
// whose CSV could pass kMaxRunBytes (below) is refused at its dt or steps with the estimate.
//
//   [robot]                  # required
//   name = "bigant"          # "bigant" | "multipod" | "quadruped" | "disk" | "legs" (a leg
//                            # table: mass and [[robot.leg]] tables, gait "foot_path";
//                            # scene/leg_table.hpp has its keys)
//   # legs = 6               # multipod: 6, 8, 10, 12; disk: 3 … 1000
//   # radius = 0.3           # disk only, m
//   # stiffness = 1000.0     # multipod only, N/m (robots/multipod.hpp)
//   # linkage = "standard"   # bigant only: "standard" | "stairs", the legs' linkage
//                            # (robots/robots.hpp: BigAntLinkage)
//
//   [gait]                   # required
//   kind = "tripod"          # bigant: "tripod" | "metachronal"; multipod: "undulation";
//                            # quadruped: "trot"; disk: "disk"; legs: "foot_path"
//   frequency = 0.1          # Hz, > 0 (default: the gait's, robots/robots.hpp)
//   steer = 0.0              # tripod only, [−1, 1]
//   # duty (tripod, trot), sweep (tripod, metachronal), dphi, roll_amplitude, yaw_amplitude
//   # (undulation, rad), stride, swing_height (trot, m): the fields of robots/robots.hpp's gait
//   # options, with their defaults and valid ranges (checked by the robot factories)
//
//   [run]                    # required
//   duration = 20.0          # s, > 0
//   dt = 0.01                # s; or steps = 2000 (exactly one of them)
//
//   [friction]               # required
//   law = "viscous"          # "viscous" (viscous-Coulomb) | "anisotropic" | "coulomb"
//   # tol = 1e-10            # coulomb only: the relative duality gap to reach
//   # max_iterations = 500   # coulomb only
//   # w = [0.5, 0.0]         # anisotropic (required) and coulomb (optional; absent = isotropic):
//                            # eq. 3.19's w (body frame, one pair for every leg) or [[wx, wy],
//                            # ...] one pair per leg; viscous-Coulomb with H_k ∝ I + w_k w_kᵀ, or
//                            # Coulomb with the friction ellipses Fᵀ G_k⁻¹ F ≤ (μ_k F_z,k)²,
//                            # G_k = I + w_k w_kᵀ (the same w, the same ellipse)
//
//   [filter]                 # optional effect: present = on (§3.5.2.2)
//   gamma = 0.15             # [0, 1), per step; default 0.15
//
//   [terrain]                # optional effect (§5.2); absent = flat
//   kind = "slope"           # "flat" | "slope" | "stairs"
//   angle_deg = 17.0         # slope only, [0, 90), required
//   heading_deg = 0.0        # slope: the uphill direction; stairs: the rising direction
//   com_height = 0.0         # slope only, m >= 0: the CoM above the plane (tipping; 0 = eq. 5.1)
//   # tread = 0.3, riser = 0.12   # stairs only, m, required (tread > 0, riser >= 0)
//
//   [residual]               # optional effect (§5.3.1): v_body = (A(q) + B) q̇
//   file = "B.csv"           # relative to the scene's folder: 3 rows (v_x, v_y, ω) of 2N
//                            # comma-separated numbers, columns 2k, 2k+1 = leg k's q̇_x, q̇_y
//                            # (the order of A, eq. 3.20); '#' comments, blank lines skipped
//
//   [noise]                  # optional effect: Gaussian noise on the reported pose (motion
//   sigma = 0.001            # capture, §3.5.1); m on x and y, required, >= 0
//   # sigma_theta = 0.0      # rad on θ, >= 0
//   # seed = 0               # integer >= 0; the same seed gives the same numbers
#include <cstdint>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <variant>

#include "connection/trajectory.hpp"
#include "scene/gaits.hpp"
#include "terrain/terrain.hpp"

namespace slipwalk::scene {

/// [friction]: which entry of the law table (scene/friction_laws.hpp) is the pair (law,
/// anisotropic), and that law's parameters.
struct FrictionEffect {
  connection::FrictionLaw law = connection::FrictionLaw::kViscousCoulomb;
  friction::CoulombOptions coulomb;  ///< used by the coulomb law only
  bool anisotropic = false;          ///< law = "anisotropic": viscous-Coulomb with w (eq. 3.19)
  Eigen::Matrix2Xd w;                ///< (2 x 1): one w for every leg, or (2 x N): per leg;
                                     ///< (2 x 0): none (isotropic; coulomb without w)
};

struct FilterEffect {
  double gamma = 0.15;  ///< per step, [0, 1) (connection::IirFilter)
};

/// The connection residual B of §5.3.1 (connection::LinearResidual), read from a file.
struct ResidualEffect {
  std::string file;                            ///< as resolved (relative to the scene's folder)
  Eigen::Matrix<double, 3, Eigen::Dynamic> B;  ///< (3 x 2N)
};

/// Gaussian measurement noise on the reported pose (connection::PoseNoise).
struct NoiseEffect {
  double sigma = 0.0;        ///< m, on x and y
  double sigma_theta = 0.0;  ///< rad, on θ
  std::uint64_t seed = 0;
};

struct Scene {
  std::string path;         ///< the file, as named to read_scene (messages, provenance)
  std::string robot;        ///< [robot] name: the robot of the gait's table entry
  Gait gait;                ///< the gait's options (legs and radius of multipod/disk included)
  std::string gait_origin;  ///< file:line:col of [gait], for errors the robot factories raise
  double duration = 0.0;    ///< s
  double dt = 0.0;          ///< s
  long long steps = 0;      ///< duration = steps · dt; steps + 1 frames t = 0 … duration
  std::string run_origin;   ///< file:line:col of the value that set the frame count ([run] dt
                            ///< or steps, or a study's override), for the size limit's error
  std::string run_key;      ///< that value's key path ("run.dt", "run.steps", "dt", ...)
  FrictionEffect friction;
  std::optional<FilterEffect> filter;      ///< present = the inertia filter is on
  std::optional<ResidualEffect> residual;  ///< present = B is added (§5.3.1)
  std::optional<NoiseEffect> noise;        ///< present = the reported pose is noisy
  terrain::Terrain terrain;                ///< [terrain] (§5.2); flat when absent
};

/// The most steps a scene may ask for (a CSV row each).
inline constexpr long long kMaxSteps = 10'000'000;

/// The largest trajectory CSV a scene may ask for, in bytes (run_writer.hpp estimates it before
/// anything runs: rows × columns × the widest cell). 4 GB is minutes of writing and far beyond
/// what a figure needs; a longer run is split into several scenes or given a larger dt.
inline constexpr double kMaxRunBytes = 4e9;

/// Parses a scene from text; `path` names it in messages. Throws core::InputError naming
/// path:line:col for every error the file can have (syntax, unknown key, wrong type, range,
/// missing field, a parameter of an effect that is not chosen). The gait's options are also
/// checked by building the walker once (a factory's error is re-raised at the key it names).
[[nodiscard]] Scene parse_scene(std::string_view text, const std::string& path);

/// Reads and parses a scene file; an unreadable file is an InputError naming it.
[[nodiscard]] Scene read_scene(const std::filesystem::path& path);

/// The scene as JSON (provenance sidecars): robot, gait and its parameters, run, effects.
[[nodiscard]] nlohmann::json to_json(const Scene& scene);

// ---- composition ------------------------------------------------------------------------------

/// A runnable simulator: the walker and the one trajectory kernel (friction law × filter) the
/// scene calls for, chosen once here; running it never branches on effects that are off.
struct Simulator {
  using Kernel = std::function<connection::TrajectorySummary(
      const robots::Walker&, const connection::TrajectoryOptions&, connection::TrajectoryData&,
      const connection::TrajectorySink&)>;

  robots::Walker walker;
  connection::TrajectoryOptions options;  ///< dt, steps from the scene; t0 = 0, start = identity
  std::string kernel_name;                ///< e.g. "viscous", "coulomb+filter" (provenance)
  Kernel kernel;

  /// Runs the trajectory into `sink` (allocates the run's buffers once).
  connection::TrajectorySummary run(const connection::TrajectorySink& sink) const;
};

/// The trajectory kernel of the scene's effects (one connection::Effects bundle).
[[nodiscard]] Simulator::Kernel compose_kernel(const Scene& scene);

/// The friction law's name (its table entry's), then "+filter", "+residual", "+noise" and
/// "+slope" | "+stairs" as named.
[[nodiscard]] std::string kernel_name(const Scene& scene);

/// Builds the walker (robots/robots.hpp) and picks the kernel. A robot factory's InputError is
/// re-raised naming the scene's [gait] table.
[[nodiscard]] Simulator compose(const Scene& scene);

}  // namespace slipwalk::scene
