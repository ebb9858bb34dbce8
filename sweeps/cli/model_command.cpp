// slipwalk model: one frame of the multi-legged model (thesis ch. 3) in the frame format of
// DESIGN.md, or a CSV batch of frames (one per row) for trajectories.
#include <cmath>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "sweeps/cli/commands.hpp"
#include "connection/local_connection.hpp"
#include "contact/frame_json.hpp"
#include "core/atomic_file.hpp"
#include "core/csv.hpp"
#include "core/error.hpp"

namespace slipwalk::cli {

namespace {

using core::InputError;

std::string read_all(const std::string& path) {
  if (path == "-") {
    return {std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>()};
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InputError(path, "cannot read");
  }
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

connection::FrictionLaw friction_law(const std::string& name) {
  if (name == "viscous") {
    return connection::FrictionLaw::kViscousCoulomb;
  }
  if (name == "coulomb") {
    return connection::FrictionLaw::kCoulomb;
  }
  throw InputError("--friction", "unknown friction law '" + name + "'; expected viscous|coulomb");
}

/// Writes `text` to --out (atomically) or stdout.
void emit(const std::string& out, const std::string& text) {
  if (out.empty() || out == "-") {
    std::cout << text;
    return;
  }
  core::write_file_atomically(out, text);
}

/// The per-leg CSV columns of a batch: q{j}x, q{j}y, q{j}z, qd{j}x, qd{j}y, qd{j}z.
std::vector<std::string> batch_input_columns(int n) {
  std::vector<std::string> cols{"theta"};
  for (int j = 0; j < n; ++j) {
    for (const char* c : {"x", "y", "z"}) {
      cols.push_back("q" + std::to_string(j) + c);
    }
    for (const char* c : {"x", "y", "z"}) {
      cols.push_back("qd" + std::to_string(j) + c);
    }
  }
  return cols;
}

std::vector<std::string> batch_output_columns(int n) {
  std::vector<std::string> cols{
      "frame", "alpha", "beta", "z", "vx", "vy", "wz", "support", "friction_converged"};
  for (int j = 0; j < n; ++j) {
    for (const char* c : {"contact", "Fz", "Fx", "Fy"}) {
      cols.push_back(std::string(c) + std::to_string(j));
    }
  }
  return cols;
}

/// Splits one CSV line (no quoting: numbers only) and records where each cell starts.
void split(const std::string& line, std::vector<std::string>& cells, std::vector<int>& starts) {
  cells.clear();
  starts.clear();
  std::size_t begin = 0;
  while (true) {
    const std::size_t end = line.find(',', begin);
    cells.push_back(line.substr(begin, end == std::string::npos ? std::string::npos : end - begin));
    starts.push_back(static_cast<int>(begin) + 1);
    if (end == std::string::npos) {
      break;
    }
    begin = end + 1;
  }
}

double cell_number(const std::string& cell, const std::string& where) {
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(cell, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != cell.size() || !std::isfinite(v)) {
    throw InputError(where, "expected a finite number, got '" + cell + "'");
  }
  return v;
}

struct ModelCommand {
  std::string friction = "viscous";
  std::string in = "-";
  std::string robot;  // a robot file switches to CSV batch mode
  std::string out;

  void run() const {
    const connection::FrictionLaw law = friction_law(friction);
    if (!robot.empty()) {
      run_batch(law);
      return;
    }
    const std::string text = read_all(in);
    contact::FrameInput input = contact::parse_frame_json(text, in == "-" ? "<stdin>" : in);
    connection::evaluate(input.robot, input.frame, law);
    const auto json = contact::frame_to_json(input.robot, input.frame,
                                             law == connection::FrictionLaw::kViscousCoulomb);
    emit(out, json.dump(1) + "\n");
  }

  void run_batch(connection::FrictionLaw law) const {
    const contact::Robot r = contact::parse_robot_json(read_all(robot), robot);
    const int n = r.legs();
    const std::string source = in == "-" ? "<stdin>" : in;
    std::istringstream lines(read_all(in));
    std::string line;
    std::vector<std::string> cells;
    std::vector<int> starts;
    if (!std::getline(lines, line)) {
      throw InputError(source, "empty; expected a header line");
    }
    const std::vector<std::string> expected = batch_input_columns(n);
    split(line, cells, starts);
    if (cells != expected) {
      throw InputError(source + ":1:1",
                       "header must be " + std::to_string(expected.size()) +
                           " columns theta,q0x,q0y,q0z,qd0x,qd0y,qd0z,q1x,... for " +
                           std::to_string(n) + " legs");
    }
    std::ostringstream text;
    core::CsvWriter csv(text, batch_output_columns(n));
    contact::Frame f(r);
    int row = 1;
    while (std::getline(lines, line)) {
      ++row;
      if (line.empty()) {
        continue;
      }
      split(line, cells, starts);
      const std::string at_row = source + ":" + std::to_string(row);
      if (cells.size() != expected.size()) {
        throw InputError(at_row, "has " + std::to_string(cells.size()) + " cells, expected " +
                                     std::to_string(expected.size()));
      }
      auto value = [&](std::size_t c) {
        return cell_number(cells[c], at_row + ":" + std::to_string(starts[c]));
      };
      f.theta = value(0);
      for (int j = 0; j < n; ++j) {
        const std::size_t base = 1 + 6 * static_cast<std::size_t>(j);
        for (int i = 0; i < 3; ++i) {
          f.q(i, j) = value(base + static_cast<std::size_t>(i));
          f.qdot(i, j) = value(base + 3 + static_cast<std::size_t>(i));
        }
      }
      connection::evaluate(r, f, law);
      csv.cell(static_cast<long long>(row - 1)).cell(f.alpha).cell(f.beta).cell(f.z);
      csv.cell(f.v_body(0)).cell(f.v_body(1)).cell(f.v_body(2));
      csv.cell(static_cast<int>(f.support.status)).cell(f.friction.converged ? 1 : 0);
      for (int j = 0; j < n; ++j) {
        csv.cell(f.contact[static_cast<std::size_t>(j)] != 0 ? 1 : 0).cell(f.Fz(j));
        csv.cell(f.Fxy(0, j)).cell(f.Fxy(1, j));
      }
      csv.end_row();
    }
    emit(out, text.str());
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
  sub->add_option("--out", cmd->out, "write here instead of stdout (written whole or not at all)");
  sub->callback([cmd] { cmd->run(); });
}

}  // namespace slipwalk::cli
