// slipwalk run SCENE.toml --out FILE.csv [--progress]: a trajectory of a scene (thesis §3.5;
// issue 6). The scene is read and checked whole first (bad input: exit 2, nothing written), the
// simulator composed once (scene/scene.hpp), then one CSV row per frame is written to a temporary
// file renamed when complete, with a provenance sidecar FILE.json beside it.
//
// Columns: t, x, y, theta (world pose; theta unwrapped), vx, vy, omega (the body velocity that
// moves the pose, body frame), with the filter also vx_model, vy_model, omega_model (before the
// filter); then per leg L (the walker's leg names): contact_L (0/1), Fz_L, Fx_L, Fy_L (planar
// force on the foot, body frame), slip_x_L, slip_y_L (the foot's velocity over the ground, body
// frame: the slip velocity when in contact), and phase_L when the gait defines phases.
#include <algorithm>
#include <chrono>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "core/atomic_file.hpp"
#include "core/csv.hpp"
#include "core/error.hpp"
#include "core/provenance.hpp"
#include "scene/scene.hpp"

namespace slipwalk::cli {

namespace {

std::vector<std::string> columns(const robots::Walker& walker, bool filtered, bool phases) {
  std::vector<std::string> cols{"t", "x", "y", "theta", "vx", "vy", "omega"};
  if (filtered) {
    cols.insert(cols.end(), {"vx_model", "vy_model", "omega_model"});
  }
  const bool named = static_cast<int>(walker.leg_names.size()) == walker.legs();
  for (int k = 0; k < walker.legs(); ++k) {
    const std::string leg =
        named ? walker.leg_names[static_cast<std::size_t>(k)] : std::to_string(k);
    for (const char* c : {"contact_", "Fz_", "Fx_", "Fy_", "slip_x_", "slip_y_"}) {
      cols.push_back(std::string(c).append(leg));
    }
    if (phases) {
      cols.push_back(std::string("phase_").append(leg));
    }
  }
  return cols;
}

struct RunCommand {
  std::string scene_file;
  std::string out;
  bool progress = false;

  void run() const {
    // 1. Read and check everything before writing anything.
    const scene::Scene scene = scene::read_scene(scene_file);
    const scene::Simulator sim = scene::compose(scene);
    const std::filesystem::path csv_path = out;
    std::filesystem::path sidecar_path = csv_path;
    sidecar_path.replace_extension(".json");
    if (sidecar_path == csv_path) {
      std::string what = "'";
      what.append(out).append("' would be overwritten by its sidecar; use .csv");
      throw core::InputError("--out", what);
    }
    const bool filtered = scene.filter.has_value();
    const bool phases = static_cast<bool>(sim.walker.phase);
    const std::vector<std::string> cols = columns(sim.walker, filtered, phases);

    // 2. Run, one row per frame.
    core::AtomicFile file(csv_path);
    core::CsvWriter csv(file.stream(), cols);
    Eigen::VectorXd phase = Eigen::VectorXd::Zero(sim.walker.legs());
    const long long frames = sim.options.steps + 1;
    const long long every = std::max<long long>(1, frames / 10);
    const auto start = std::chrono::steady_clock::now();
    const connection::TrajectorySummary summary = sim.run([&](const connection::TrajectoryStep& s) {
      csv.cell(s.t).cell(s.pose.x).cell(s.pose.y).cell(s.pose.theta);
      csv.cell(s.v_body(0)).cell(s.v_body(1)).cell(s.v_body(2));
      if (filtered) {
        csv.cell(s.v_model(0)).cell(s.v_model(1)).cell(s.v_model(2));
      }
      if (phases) {
        sim.walker.phase(s.t, phase);
      }
      for (int k = 0; k < s.frame.legs(); ++k) {
        csv.cell(static_cast<int>(s.frame.contact[static_cast<std::size_t>(k)]));
        csv.cell(s.frame.Fz(k)).cell(s.frame.Fxy(0, k)).cell(s.frame.Fxy(1, k));
        csv.cell(s.slip(0, k)).cell(s.slip(1, k));
        if (phases) {
          csv.cell(phase(k));
        }
      }
      csv.end_row();
      if (progress && (s.n + 1) % every == 0) {
        std::cerr << "slipwalk run: " << (s.n + 1) << "/" << frames
                  << " frames (t = " << core::format_double(s.t) << " s)" << std::endl;
      }
    });
    const double wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    file.commit();

    // 3. The provenance sidecar.
    const nlohmann::json sidecar = {
        {"command", "run"},
        {"scene_file", scene_file},
        {"scene", scene::to_json(scene)},
        {"walker", sim.walker.name},
        {"legs", sim.walker.leg_names},
        {"kernel", sim.kernel_name},
        {"csv", csv_path.filename().string()},
        {"columns", cols},
        {"frames", summary.frames},
        {"summary",
         {{"unsupported_frames", summary.unsupported},
          {"not_converged_frames", summary.not_converged},
          {"not_unique_frames", summary.not_unique},
          {"max_friction_residual", summary.max_friction_residual},
          {"message", summary.message}}},
        {"wall_s", wall_s},
        {"threads", 1},
        {"provenance", core::build_provenance()},
    };
    core::write_file_atomically(sidecar_path, sidecar.dump(1) + "\n");
    if (!summary.message.empty()) {
      std::cerr << "slipwalk: warning: " << summary.unsupported << " unsupported and "
                << summary.not_converged << " unconverged frames; first at " << summary.message
                << "\n";
    }
  }
};

}  // namespace

void add_run_command(CLI::App& app) {
  auto cmd = std::make_shared<RunCommand>();
  auto* sub = app.add_subcommand(
      "run",
      "a trajectory of a scene (thesis §3.5): pose, body velocity and per-leg contact, forces "
      "and slip, one CSV row per step");
  sub->add_option("SCENE", cmd->scene_file, "scene file (TOML; format in lib/scene/scene.hpp)")
      ->required();
  sub->add_option("--out", cmd->out,
                  "CSV file to write (whole or not at all), with a provenance sidecar "
                  "<name>.json beside it")
      ->required();
  sub->add_flag("--progress", cmd->progress, "print progress to stderr");
  sub->callback([cmd] { cmd->run(); });
}

}  // namespace slipwalk::cli
