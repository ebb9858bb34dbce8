#pragma once
// The trajectory CSV of a scene run and its provenance sidecar, shared by
// `slipwalk run` and the [[scene]] entries of a study (`slipwalk reproduce`).
//
// Columns: t, x, y, theta (world pose; theta unwrapped; with [noise] the measured pose), vx, vy,
// omega (the body velocity that moves the pose, body frame), with the filter or the residual also
// vx_model, vy_model, omega_model (the friction balance's, before residual and filter); then per
// leg L (the walker's leg names): contact_L (0/1), Fz_L, Fx_L, Fy_L (planar force on the foot, body
// frame), slip_x_L, slip_y_L (the foot's velocity over the ground, body frame: the slip velocity
// when in contact), and phase_L when the gait defines phases; last alpha, beta, z: the spring
// support's ground plane (eq. 3.6: roll and pitch slopes, body height, m), from which the roll and
// pitch of Fig. 3.5 follow (appended so the leg columns keep their places); with [noise] last
// x_true, y_true, theta_true (the simulated pose, without noise).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "scene/scene.hpp"

namespace slipwalk::scene {

/// The CSV columns of a run of `walker` (see above).
/// `filtered`: v_body differs from v_model (filter or residual on); `noisy`: [noise] is on.
[[nodiscard]] std::vector<std::string> run_columns(const robots::Walker& walker, bool filtered,
                                                   bool phases, bool noisy = false);

/// Every column of a run of `scene` by `walker`: run_columns() and, on a slope or stairs, the
/// body's and each toe's world position (bx, by, bz, px_L, py_L, pz_L).
[[nodiscard]] std::vector<std::string> scene_columns(const Scene& scene,
                                                     const robots::Walker& walker);

/// The size of a run's CSV, estimated before it runs.
struct RunSize {
  long long rows = 0;     ///< steps + 1 (and the header)
  long long columns = 0;  ///< scene_columns()
  double bytes = 0.0;     ///< an upper bound: every cell as wide as a cell can be
};

/// The widest CSV cell: a double at 17 significant digits ("-1.2345678901234567e-308") and a
/// comma.
inline constexpr double kMaxCellBytes = 25.0;

[[nodiscard]] RunSize estimate_run_size(const Scene& scene, const robots::Walker& walker);

/// Throws core::InputError at scene.run_origin (the [run] dt or steps, or the override that set
/// them) naming the estimate when it passes kMaxRunBytes.
void check_run_size(const Scene& scene, const robots::Walker& walker);

struct RunResult {
  connection::TrajectorySummary summary;
  std::vector<std::string> columns;
  double wall_s = 0.0;  ///< the run and its CSV, s
};

/// Runs `sim` (composed from `scene`) and writes <csv> (a temporary renamed when complete) and
/// its sidecar <csv stem>.json: `extra`'s keys first, then the scene, walker, kernel, columns,
/// the run's summary, wall time and build provenance. `progress`, when given, gets ten lines.
/// Throws core::InputError("--out") when the sidecar would overwrite the CSV (name it .csv).
RunResult write_run(const Scene& scene, const Simulator& sim, const std::filesystem::path& csv,
                    const nlohmann::json& extra, std::ostream* progress);

}  // namespace slipwalk::scene
