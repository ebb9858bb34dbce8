// slipwalk calibrate --geometry G.toml --hanging H.csv [H2.csv ...] --poses P.csv --out params.json
//   [--model select|full|...] [--solver ceres|alternating] [--errors-in-variables estimate|off]
//   [--target chassis|thesis]
//   [--com smoother|pointwise] [--harmonics H] [--folds F] [--seed S]:
// the in-situ F/T calibration of thesis ch. 4 (lib/calibration/calibrate.hpp) from the hanging
// records and the standing poses. Every file is read and checked whole first — the columns, the
// orientations and their pairing, the number of poses, the quaternions (formats at the head of
// lib/calibration/files.cpp; bad input: exit 2 naming file:line[:col], nothing written) — then the
// estimates are written as one JSON file (calibration_json, with the command, its inputs, the wall
// time and provenance) and a summary is printed.
//
// slipwalk calibrate synth --out DIR [--seed S] [--noise-scale X] [--poses P]
//   [--samples-per-cycle N] [--cycles C] [--force]:
// a synthetic BigANT with known truth (lib/calibration/synthetic.hpp): DIR/geometry.toml,
// DIR/hanging.csv (+x, −x, +z, −z), DIR/poses.csv — the inputs of the command above — and
// DIR/truth.json (truth_json with provenance). The four files are written whole, and renamed only
// once all four are complete; a folder that already holds any of them is refused unless --force.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "calibration/calibrate.hpp"
#include "calibration/files.hpp"
#include "calibration/synthetic.hpp"
#include "core/atomic_file.hpp"
#include "core/csv.hpp"
#include "core/error.hpp"
#include "core/provenance.hpp"
#include "sweeps/cli/commands.hpp"

namespace slipwalk::cli {

namespace {

using core::InputError;
namespace cal = calibration;

/// --model: "select" (Table 4.2 by BIC) or one of the four models, with its DOF per K legs as
/// standing.hpp states it (checked against model_label/model_dof in the command's tests).
struct ModelChoice {
  std::string_view name;
  cal::MountingModel model;
  int dof_per_leg;
  int dof_shared;
};
constexpr std::array<ModelChoice, 4> kModels = {{
    {"full", cal::MountingModel::full, 6, 0},
    {"shared_translation", cal::MountingModel::shared_translation, 3, 3},
    {"translations_only", cal::MountingModel::translations_only, 3, 0},
    {"com_only", cal::MountingModel::com_only, 0, 3},
}};
/// The largest number of harmonics of the CoM fit (hanging.hpp's validate).
constexpr int kMaxHarmonics = 16;
/// The files of `calibrate synth`, in the order they are written.
constexpr std::array<std::string_view, 4> kSynthFiles = {"geometry.toml", "hanging.csv",
                                                         "poses.csv", "truth.json"};

/// Estimates are shown to 4 significant digits unless a call says otherwise.
std::string format(double x, int digits = 4) { return core::format_approx(x, digits); }

/// The fewest poses a model's fit takes: DOF / 6 + 1 (standing.hpp's fit_mounting).
Eigen::Index min_poses(const ModelChoice& m, int legs) {
  return (m.dof_per_leg * legs + m.dof_shared) / 6 + 1;
}

struct CalibrateCommand {
  std::string geometry_file;
  std::vector<std::string> hanging_files;
  std::string poses_file;
  std::string out;
  std::string model = "select";
  std::string solver = "ceres";
  std::string errors_in_variables = "estimate";
  std::string target = "chassis";
  std::string com = "smoother";
  int harmonics = cal::HangingOptions{}.harmonics;
  int folds = cal::CalibrationOptions{}.folds;
  std::uint64_t seed = 1;

  void run() const {
    const auto start = std::chrono::steady_clock::now();
    // Options and the output first: nothing is read before they are known to be usable.
    std::vector<std::filesystem::path> inputs{geometry_file, poses_file};
    inputs.insert(inputs.end(), hanging_files.begin(), hanging_files.end());
    core::check_output_path(out, "--out", inputs);
    if (harmonics < 0 || harmonics > kMaxHarmonics) {
      throw InputError("--harmonics", "must be an integer in 0.." + std::to_string(kMaxHarmonics) +
                                          ", got " + std::to_string(harmonics));
    }
    if (folds < 2) {
      throw InputError("--folds", "must be at least 2, got " + std::to_string(folds));
    }
    cal::CalibrationOptions options;
    options.seed = seed;
    options.folds = folds;
    options.hanging.harmonics = harmonics;
    options.hanging.com =
        com == "pointwise" ? cal::ComEstimator::pointwise : cal::ComEstimator::smoother;
    options.mounting.solver =
        solver == "ceres" ? cal::MountingSolver::ceres_so3 : cal::MountingSolver::alternating;
    options.mounting.target =
        target == "thesis" ? cal::BalanceTarget::thesis_literal : cal::BalanceTarget::chassis;
    if (errors_in_variables == "off") {
      options.mounting.force_noise_variance = 0.0;
    }
    options.select_model = model == "select";
    const ModelChoice* chosen = &kModels.front();  // select: the full model needs the most poses
    for (const ModelChoice& m : kModels) {
      if (m.name == model) {
        chosen = &m;
      }
    }
    options.mounting.model = chosen->model;

    // Every input, read and checked before any work.
    const cal::Geometry geometry = cal::read_geometry(geometry_file);
    std::vector<cal::HangingRecord> records;
    for (const std::string& file : hanging_files) {
      std::vector<cal::HangingRecord> read = cal::read_hanging(file, geometry);
      std::move(read.begin(), read.end(), std::back_inserter(records));
    }
    cal::check_hanging_pairs(records, options.hanging.max_phi_mismatch,
                             Eigen::Index{3} + Eigen::Index{2} * harmonics);
    const cal::StandingPoses poses = cal::read_poses(poses_file, geometry);
    const Eigen::Index needed = min_poses(*chosen, geometry.size());
    const Eigen::Index p = poses.poses();
    if (p < needed) {
      throw InputError(poses.source, std::to_string(p) + " poses; the " +
                                         std::string(chosen->name) + " model of " +
                                         std::to_string(geometry.size()) +
                                         " transducers needs at least " + std::to_string(needed));
    }
    if (options.select_model) {
      const Eigen::Index training = p - (p + folds - 1) / folds;
      if (folds > p || training < needed) {
        throw InputError("--folds", std::to_string(folds) + " folds of " + std::to_string(p) +
                                        " poses leave " + std::to_string(training) +
                                        " poses to fit the full model, which needs " +
                                        std::to_string(needed));
      }
    }

    const cal::Calibration c = cal::calibrate(geometry, records, poses, options);

    const double wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    nlohmann::json json = cal::calibration_json(c);
    json["command"] = "calibrate";
    json["inputs"] = {{"geometry", geometry_file},
                      {"hanging", hanging_files},
                      {"poses", poses_file},
                      {"hanging_records", records.size()},
                      {"poses_count", p}};
    json["options"] = {
        {"model", model},   {"solver", solver}, {"errors_in_variables", errors_in_variables},
        {"target", target}, {"com", com},       {"harmonics", harmonics},
        {"folds", folds},   {"seed", seed}};
    json["wall_s"] = wall_s;
    json["provenance"] = core::build_provenance();
    core::write_file_atomically(out, json.dump(1) + "\n");

    std::ostringstream s;
    s << "slipwalk calibrate: " << geometry.size() << " transducers, " << records.size()
      << " hanging records, " << p << " poses\n";
    for (int k = 0; k < geometry.size(); ++k) {
      const auto ks = static_cast<std::size_t>(k);
      const cal::LegEstimate& e = c.hanging.legs[ks];
      s << "  " << geometry.legs[ks] << ": weight " << format(e.weight) << " ± "
        << format(e.weight_se, 2) << " N; offset f (" << format(e.offset(0)) << ", "
        << format(e.offset(1)) << ", " << format(e.offset(2)) << ") N, τ (" << format(e.offset(3))
        << ", " << format(e.offset(4)) << ", " << format(e.offset(5)) << ") N·m\n";
    }
    s << "mounting: model " << cal::model_label(c.mounting.model)
      << (options.select_model ? " (selected by BIC)" : "") << ", solver "
      << cal::solver_label(c.mounting.solver) << ", RSS " << format(c.mounting.rss) << " over "
      << c.mounting.poses << " poses" << (c.mounting.converged ? "" : " (not converged)") << "\n"
      << "time: hanging " << format(c.seconds_hanging, 3) << " s, standing "
      << format(c.seconds_standing, 3) << " s\n"
      << "wrote " << out << "\n";
    std::cout << s.str();
  }
};

struct SynthCommand {
  std::string out;
  cal::SynthOptions options;
  bool force = false;

  void run() const {
    const std::filesystem::path dir(out);
    core::check_output_dir(dir, "--out");
    std::vector<std::filesystem::path> targets;
    std::vector<std::string> present;
    for (std::string_view name : kSynthFiles) {
      targets.push_back(dir / name);
      std::error_code ec;
      if (std::filesystem::exists(targets.back(), ec)) {
        present.emplace_back(name);
      }
      core::check_output_path(targets.back(), "--out", {}, true);
    }
    if (!present.empty() && !force) {
      std::string list;
      for (const std::string& name : present) {
        list.append(list.empty() ? "" : ", ").append(name);
      }
      throw InputError("--out", out + " already holds " + list + "; --force replaces them");
    }
    try {
      cal::validate(options);
    } catch (const InputError& e) {
      // synth.<field> is the option --<field> here.
      std::string where = e.where();
      if (where.rfind("synth.", 0) == 0) {
        where = "--" + where.substr(6);
        std::replace(where.begin(), where.end(), '_', '-');
      }
      const std::string what = std::string(e.what()).substr(e.where().size() + 2);
      throw InputError(where, what);
    }
    const auto start = std::chrono::steady_clock::now();
    const cal::SyntheticTruth truth = cal::synthetic_truth(options);
    const std::vector<cal::HangingRecord> hanging = cal::synthetic_hanging(truth, options);
    const cal::StandingPoses poses = cal::synthetic_poses(truth, options);

    std::vector<std::unique_ptr<core::AtomicFile>> files;
    files.reserve(targets.size());
    for (const std::filesystem::path& t : targets) {
      files.push_back(std::make_unique<core::AtomicFile>(t));
    }
    cal::write_geometry(files[0]->stream(), truth.geometry);
    cal::write_hanging(files[1]->stream(), hanging, truth.geometry);
    cal::write_poses(files[2]->stream(), poses, truth.geometry);
    nlohmann::json json = cal::truth_json(truth, options);
    json["command"] = "calibrate synth";
    json["wall_s"] =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    json["provenance"] = core::build_provenance();
    files[3]->stream() << json.dump(1) << "\n";
    // All four complete before any is renamed: a failure leaves none of them.
    for (const auto& f : files) {
      f->finish();
    }
    for (const auto& f : files) {
      f->commit();
    }
    Eigen::Index samples = 0;
    for (const cal::HangingRecord& r : hanging) {
      samples += r.samples();
    }
    std::cout << "slipwalk calibrate synth: seed " << options.seed << ", noise scale "
              << format(options.noise_scale) << "; " << hanging.size() << " hanging records ("
              << samples << " samples), " << poses.poses() << " poses; chassis CoM torque bias "
              << format(truth.com_torque_bias(), 3) << " N·m\n"
              << "wrote " << (dir / "geometry.toml").string() << ", hanging.csv, poses.csv, "
              << "truth.json\n";
  }
};

}  // namespace

void add_calibrate_command(CLI::App& app) {
  auto* sub = app.add_subcommand(
      "calibrate",
      "the in-situ F/T calibration of thesis ch. 4: transducer offsets, leg weights and centres "
      "of mass from the hanging records (§4.3.1), mounting errors from standing poses (§4.3.2, "
      "Table 4.2); writes the estimates as JSON and prints a summary");
  sub->require_subcommand(0, 1);
  auto cmd = std::make_shared<CalibrateCommand>();
  std::vector<CLI::Option*> own;
  own.push_back(sub->add_option("--geometry", cmd->geometry_file,
                                "the design geometry (TOML; format at the head of "
                                "lib/calibration/files.cpp)"));
  own.push_back(sub->add_option("--hanging", cmd->hanging_files,
                                "hanging-experiment CSV files (one or more; together at least two "
                                "opposite pairs, e.g. +x -x +z -z)")
                    ->expected(1, -1));
  own.push_back(sub->add_option("--poses", cmd->poses_file, "standing-poses CSV file"));
  own.push_back(sub->add_option("--out", cmd->out,
                                "the estimates' JSON file to write (whole or not at all)"));
  own.push_back(sub->add_option("--model", cmd->model,
                                "select: Table 4.2's model with the smallest BIC (default); or "
                                "full, shared_translation, translations_only, com_only")
                    ->check(CLI::IsMember({"select", "full", "shared_translation",
                                           "translations_only", "com_only"})));
  own.push_back(sub->add_option("--solver", cmd->solver,
                                "ceres (joint, on SO(3); default) or alternating (the thesis')")
                    ->check(CLI::IsMember({"alternating", "ceres"})));
  own.push_back(sub->add_option("--errors-in-variables", cmd->errors_in_variables,
                                "estimate: correct the force noise's bias on the displacements "
                                "with σ_f² estimated (default); off: the thesis' plain least "
                                "squares (lib/calibration/standing.hpp)")
                    ->check(CLI::IsMember({"estimate", "off"})));
  own.push_back(sub->add_option("--target", cmd->target,
                                "chassis: the exact balance of the chassis (default); thesis: "
                                "eq. 4.8 as printed")
                    ->check(CLI::IsMember({"chassis", "thesis"})));
  own.push_back(sub->add_option("--com", cmd->com,
                                "the CoM estimator: smoother (the thesis' RTS, default) or "
                                "pointwise")
                    ->check(CLI::IsMember({"smoother", "pointwise"})));
  own.push_back(sub->add_option("--harmonics", cmd->harmonics,
                                "harmonics of the periodic CoM fit, 0..16 (default 4)"));
  own.push_back(sub->add_option("--folds", cmd->folds,
                                "cross-validation folds of the model selection (default 5)"));
  own.push_back(sub->add_option("--seed", cmd->seed, "the folds' shuffle (default 1)"));

  auto synth = std::make_shared<SynthCommand>();
  auto* syn = sub->add_subcommand(
      "synth",
      "a synthetic BigANT with known truth: writes DIR/geometry.toml, hanging.csv, poses.csv "
      "(the inputs of `slipwalk calibrate`) and truth.json");
  syn->add_option("--out", synth->out, "the folder to write (created if missing)")->required();
  syn->add_option("--seed", synth->options.seed, "the draws of the truth, records and poses (1)");
  syn->add_option("--noise-scale", synth->options.noise_scale,
                  "multiplies every noise σ (0: noiseless; default 1)");
  syn->add_option("--poses", synth->options.poses, "standing poses, 1..729 (default 543)");
  syn->add_option("--samples-per-cycle", synth->options.samples_per_cycle,
                  "hanging samples per shaft turn (default 900)");
  syn->add_option("--cycles", synth->options.cycles, "shaft turns per hanging record (default 10)");
  syn->add_flag("--force", synth->force, "replace the files of an earlier synth in DIR");
  // CLI11 runs the subcommand's callback before its parent's: the check comes first here.
  syn->callback([synth, own] {
    for (const CLI::Option* o : own) {
      if (o->count() > 0) {
        throw InputError(o->get_name(),
                         "is an option of `slipwalk calibrate`, not of `calibrate synth`");
      }
    }
    synth->run();
  });

  sub->callback([sub, syn, cmd] {
    if (syn->parsed()) {
      return;
    }
    for (const char* name : {"--geometry", "--hanging", "--poses", "--out"}) {
      if (sub->get_option(name)->count() == 0) {
        throw InputError(name, "is required (or `slipwalk calibrate synth --out DIR`)");
      }
    }
    cmd->run();
  });
}

}  // namespace slipwalk::cli
