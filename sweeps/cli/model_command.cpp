// slipwalk model: one frame of the multi-legged model (thesis ch. 3) in the frame format of
// DESIGN.md, or a CSV batch of frames (one per row) for trajectories; the work is
// connection/frame_model.hpp's, this file parses the options and writes the text.
// Exit codes: 2 for bad input, named at its place (a path that is missing or a folder, via
// core::read_input_file; malformed or duplicated JSON, via core::parse_json; a value outside
// contact::limits, at its file:line:col or CSV row:col); 1 for a result that is not finite
// (core::ComputationError from frame_to_json / write_batch_row); 0 for finite output, which says
// in "support"."status", "friction"."converged" and "friction"."unique" how far it holds.
#include <array>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <string>

#include "connection/frame_model.hpp"
#include "contact/frame_json.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/input_file.hpp"
#include "core/json_input.hpp"
#include "scene/friction_laws.hpp"
#include "sweeps/cli/commands.hpp"

namespace slipwalk::cli {

namespace {

using core::InputError;

std::string read_all(const std::string& path) {
  if (path == "-") {
    return core::read_input_stream(std::cin, "<stdin>", "the frame JSON");
  }
  return core::read_input_file(path, "a frame JSON file");
}

/// The isotropic laws of the scene format's table (a frame's own `w` makes either anisotropic).
connection::FrictionLaw friction_law(const std::string& name) {
  const scene::FrictionLawEntry* entry = scene::find_friction_law(name);
  if (entry != nullptr && !entry->anisotropic) {
    return entry->law;
  }
  std::string message = "unknown friction law '";
  message.append(name).append("'; expected ");
  bool first = true;
  for (const scene::FrictionLawEntry& e : scene::friction_laws()) {
    if (!e.anisotropic) {
      message.append(first ? "" : "|").append(e.name);
      first = false;
    }
  }
  throw InputError("--friction", message);
}

/// Writes `text` to --out (atomically) or stdout.
void emit(const std::string& out, const std::string& text) {
  if (out == "-") {
    std::cout << text;
    return;
  }
  core::write_file_atomically(out, text);
}

struct ModelCommand {
  std::string friction = "viscous";
  std::string in = "-";
  std::string robot;  // a robot file switches to CSV batch mode
  std::string out = "-";

  void run() const {
    const connection::FrictionLaw law = friction_law(friction);
    if (out != "-") {
      const std::array<std::filesystem::path, 2> inputs{in, robot};
      core::check_output_path(out, "--out", inputs);
    }
    const std::string source = in == "-" ? "<stdin>" : in;
    if (robot.empty()) {
      const std::string text = in == "-" ? core::read_json_text(std::cin, source)
                                         : core::read_json_text(std::filesystem::path(in));
      emit(out, connection::evaluate_frame_json(text, source, law));
      return;
    }
    // A robot file switches to the CSV batch form; the robot is read first.
    const contact::Robot r =
        contact::parse_robot_json(core::read_json_text(std::filesystem::path(robot)), robot);
    emit(out, connection::evaluate_frame_batch(r, read_all(in), source, law));
  }
};

}  // namespace

void add_model_command(CLI::App& app) {
  auto cmd = std::make_shared<ModelCommand>();
  auto* sub = app.add_subcommand(
      "model",
      "one frame of the multi-legged model (thesis ch. 3): contacts, loads, body "
      "velocity, foot forces, local connection");
  sub->add_option("--friction", cmd->friction,
                  "viscous (viscous-Coulomb ansatz, eq. 3.19; default) | coulomb (classical)");
  sub->add_option("--in", cmd->in,
                  "frame JSON (DESIGN.md frame format), or a CSV batch with "
                  "--robot; - for stdin (default)");
  sub->add_option("--robot", cmd->robot,
                  "robot JSON {K, mu, w, Mg | legs}: read --in as a CSV batch, one frame a row");
  sub->add_option("--out", cmd->out,
                  "write here instead of stdout (written whole or not at all; - for stdout)");
  sub->callback([cmd] { cmd->run(); });
}

}  // namespace slipwalk::cli
