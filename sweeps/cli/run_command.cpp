// slipwalk run SCENE.toml --out FILE.csv [--progress]: a trajectory of a scene (thesis §3.5,
// effects §5.2-5.3). The scene is read and checked whole first (bad input: exit 2, nothing
// written), the simulator composed once (scene/scene.hpp), then one CSV row per frame is written to
// a temporary file renamed when complete, with a provenance sidecar FILE.json beside it.
//
// The columns and the sidecar are scene/run_writer.hpp's, shared with the [[scene]] entries of
// the studies (`slipwalk reproduce`).
#include <array>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "core/atomic_file.hpp"
#include "scene/run_writer.hpp"
#include "scene/scene.hpp"
#include "sweeps/cli/commands.hpp"

namespace slipwalk::cli {

namespace {

struct RunCommand {
  std::string scene_file;
  std::string out;
  bool progress = false;

  void run() const {
    // Everything is read and checked before anything is written (write_run also refuses an
    // --out whose sidecar would overwrite it before it opens a file); neither output may be the
    // scene file itself.
    const std::array<std::filesystem::path, 1> inputs{scene_file};
    core::check_output_path(out, "--out", inputs);
    std::filesystem::path sidecar = out;
    sidecar.replace_extension(".json");
    core::check_output_path(sidecar, "--out (its sidecar " + sidecar.string() + ")", inputs);
    const scene::Scene scene = scene::read_scene(scene_file);
    const scene::Simulator sim = scene::compose(scene);
    const nlohmann::json extra = {{"command", "run"}};
    const scene::RunResult result =
        scene::write_run(scene, sim, out, extra, progress ? &std::cerr : nullptr);
    const connection::TrajectorySummary& summary = result.summary;
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
      "a trajectory of a scene (thesis §3.5; effects §5.2-5.3): pose, body velocity and per-leg "
      "contact, forces and slip, one CSV row per step; only the effects the scene names are "
      "simulated");
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
