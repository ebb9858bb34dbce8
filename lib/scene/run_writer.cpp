// The trajectory CSV and sidecar of a scene run (run_writer.hpp has the columns).
#include "scene/run_writer.hpp"

#include <algorithm>
#include <chrono>

#include "core/atomic_file.hpp"
#include "core/clock.hpp"
#include "core/csv.hpp"
#include "core/error.hpp"
#include "core/provenance.hpp"

namespace slipwalk::scene {

std::vector<std::string> run_columns(const robots::Walker& walker, bool filtered, bool phases,
                                     bool noisy) {
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
  cols.insert(cols.end(), {"alpha", "beta", "z"});
  if (noisy) {
    cols.insert(cols.end(), {"x_true", "y_true", "theta_true"});
  }
  return cols;
}

std::vector<std::string> scene_columns(const Scene& scene, const robots::Walker& walker) {
  const bool filtered = scene.filter.has_value() || scene.residual.has_value();
  const bool phases = static_cast<bool>(walker.phase);
  std::vector<std::string> columns = run_columns(walker, filtered, phases, scene.noise.has_value());
  // On a slope or stairs (§5.2): the body origin and each toe (before compression) in the world,
  // x, y horizontal and z up (terrain::body_world, toe_world), for Figs. 5.2 and 5.3.
  if (scene.terrain.index() != 0) {
    columns.insert(columns.end(), {"bx", "by", "bz"});
    const bool named = static_cast<int>(walker.leg_names.size()) == walker.legs();
    for (int k = 0; k < walker.legs(); ++k) {
      const std::string leg =
          named ? walker.leg_names[static_cast<std::size_t>(k)] : std::to_string(k);
      for (const char* c : {"px_", "py_", "pz_"}) {
        columns.push_back(std::string(c).append(leg));
      }
    }
  }
  return columns;
}

RunSize estimate_run_size(const Scene& scene, const robots::Walker& walker) {
  RunSize size;
  size.rows = scene.steps + 1;
  size.columns = static_cast<long long>(scene_columns(scene, walker).size());
  size.bytes =
      static_cast<double>(size.rows + 1) * static_cast<double>(size.columns) * kMaxCellBytes;
  return size;
}

void check_run_size(const Scene& scene, const robots::Walker& walker) {
  const RunSize size = estimate_run_size(scene, walker);
  if (size.bytes > kMaxRunBytes) {
    std::string what = scene.run_key;
    what.append(": the run would write ")
        .append(std::to_string(size.rows))
        .append(" rows of ")
        .append(std::to_string(size.columns))
        .append(" columns, up to ")
        .append(core::format_double(size.bytes / 1e9))
        .append(" GB; at most ")
        .append(core::format_double(kMaxRunBytes / 1e9))
        .append(" GB (a larger dt, fewer steps or a shorter duration)");
    throw core::InputError(scene.run_origin.empty() ? scene.path : scene.run_origin, what);
  }
}

RunResult write_run(const Scene& scene, const Simulator& sim, const std::filesystem::path& csv_path,
                    const nlohmann::json& extra, std::ostream* progress) {
  std::filesystem::path sidecar_path = csv_path;
  sidecar_path.replace_extension(".json");
  if (sidecar_path == csv_path) {
    std::string what = "'";
    what.append(csv_path.string()).append("' would be overwritten by its sidecar; use .csv");
    throw core::InputError("--out", what);
  }
  check_run_size(scene, sim.walker);
  RunResult result;
  const bool filtered = scene.filter.has_value() || scene.residual.has_value();
  const bool phases = static_cast<bool>(sim.walker.phase);
  const bool noisy = scene.noise.has_value();
  const bool terrain_columns = scene.terrain.index() != 0;
  result.columns = scene_columns(scene, sim.walker);

  // One row per frame, into a temporary file renamed when complete.
  core::AtomicFile file(csv_path);
  core::CsvWriter csv(file.stream(), result.columns);
  Eigen::VectorXd phase = Eigen::VectorXd::Zero(sim.walker.legs());
  const long long frames = sim.options.steps + 1;
  const long long every = std::max<long long>(1, frames / 10);
  const auto start = std::chrono::steady_clock::now();
  result.summary = sim.run([&](const connection::TrajectoryStep& s) {
    csv.cell(s.t).cell(s.measured.x).cell(s.measured.y).cell(s.measured.theta);
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
    csv.cell(s.frame.alpha).cell(s.frame.beta).cell(s.frame.z);
    if (noisy) {
      csv.cell(s.pose.x).cell(s.pose.y).cell(s.pose.theta);
    }
    if (terrain_columns) {
      const Eigen::Vector3d b = terrain::body_world(scene.terrain, s.pose, s.frame);
      csv.cell(b(0)).cell(b(1)).cell(b(2));
      for (int k = 0; k < s.frame.legs(); ++k) {
        const Eigen::Vector3d p = terrain::toe_world(scene.terrain, s.pose, s.frame, k);
        csv.cell(p(0)).cell(p(1)).cell(p(2));
      }
    }
    csv.end_row();
    if ((s.n + 1) % every != 0) {
      return;
    }
    file.check();  // a full disk stops the run here, not at its end
    if (progress != nullptr) {
      *progress << "slipwalk run: " << (s.n + 1) << "/" << frames
                << " frames (t = " << core::format_double(s.t) << " s)" << std::endl;
    }
  });
  result.wall_s = core::seconds_since(start);
  if (result.summary.non_finite_step >= 0) {
    // The rows so far are not a result: the temporary goes with `file`.
    throw core::ComputationError(scene.path + ": " + result.summary.non_finite);
  }
  file.finish();

  // The provenance sidecar.
  nlohmann::json sidecar = extra.is_object() ? extra : nlohmann::json::object();
  const connection::TrajectorySummary& summary = result.summary;
  sidecar.update({
      {"scene_file", scene.path},
      {"scene", to_json(scene)},
      {"walker", sim.walker.name},
      {"legs", sim.walker.leg_names},
      {"kernel", sim.kernel_name},
      {"csv", csv_path.filename().string()},
      {"columns", result.columns},
      {"frames", summary.frames},
      {"summary",
       {{"unsupported_frames", summary.unsupported},
        {"not_converged_frames", summary.not_converged},
        {"not_unique_frames", summary.not_unique},
        {"max_friction_residual", summary.max_friction_residual},
        {"message", summary.message}}},
      {"wall_s", result.wall_s},
      {"threads", 1},
      {"provenance", core::build_provenance()},
  });
  // Both files are complete before either is renamed (a failure leaves neither behind), and the
  // CSV is renamed last: it is never seen without its sidecar.
  core::AtomicFile side(sidecar_path);
  side.stream() << sidecar.dump(1) << "\n";
  core::commit_with_sidecar(file, side);
  return result;
}

}  // namespace slipwalk::scene
