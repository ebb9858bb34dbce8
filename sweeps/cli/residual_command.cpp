// slipwalk residual fit --robot multipod --trials A.csv [B.csv ...] --out B.csv [--ids 3,7]
//   [--estimator pinv|ridge] [--lambdas ...] [--skip S]:
// the connection residual B of thesis §5.3.1 fitted from motion trials (§5.3.2). Every trial file
// is read and checked whole first (lib/residual/trial.hpp has the format; bad input: exit 2 naming
// file:line[:col], nothing written); the template Multipod of the trials' leg count predicts
// A(q) q̇ at every interior sample (lib/residual/template.hpp); B is fitted to the residual
// g̊_true − A(q) q̇ by the pseudo-inverse or by ridge regression with λ chosen by leave-one-trial-out
// cross-validation (lib/residual/fit.hpp). B is written as the residual file a scene's [residual]
// reads, with a comment header, and a provenance sidecar <name>.json beside it; the summary is
// printed.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/atomic_file.hpp"
#include "core/csv.hpp"
#include "core/error.hpp"
#include "core/provenance.hpp"
#include "residual/fit.hpp"
#include "residual/template.hpp"
#include "residual/trial.hpp"
#include "scene/ranges.hpp"
#include "sweeps/cli/commands.hpp"

namespace slipwalk::cli {

namespace {

using core::InputError;

/// The default ridge grid, relative to σ_max² of the q̇ matrix: λ = 0 (the pseudo-inverse) and
/// σ_max² · 10^e for e = kGridLow..0 — from no shrinkage to shrinking every direction by half.
constexpr int kGridLow = -12;

std::string three_digits(double x) { return core::format_approx(x); }

std::string components(const Eigen::Vector3d& v) {
  return "v_x " + three_digits(v(0)) + " m/s, v_y " + three_digits(v(1)) + " m/s, ω " +
         three_digits(v(2)) + " rad/s";
}

struct ResidualFitCommand {
  std::string robot = "multipod";
  std::vector<std::string> trial_files;
  std::string out;
  std::vector<std::string> ids;
  std::string estimator = "pinv";
  std::vector<double> lambdas;
  double skip = 0.0;

  void run() const {
    const auto start = std::chrono::steady_clock::now();
    // Options and outputs first: nothing is read before they are known to be usable.
    const std::vector<std::filesystem::path> inputs(trial_files.begin(), trial_files.end());
    std::filesystem::path sidecar = out;
    sidecar.replace_extension(".json");
    if (sidecar == std::filesystem::path(out)) {
      throw InputError("--out", "'" + out + "' would be overwritten by its sidecar; use .csv");
    }
    core::check_output_path(out, "--out", inputs);
    core::check_output_path(sidecar, "--out (its sidecar " + sidecar.string() + ")", inputs);
    if (!std::isfinite(skip) || skip < 0.0) {
      throw InputError("--skip",
                       "must be a number of seconds >= 0, got " + core::format_double(skip));
    }
    const bool ridge = estimator == "ridge";
    if (!lambdas.empty() && !ridge) {
      throw InputError("--lambdas", "a grid of λ is only read with --estimator ridge");
    }
    for (double l : lambdas) {
      if (!std::isfinite(l) || l < 0.0) {
        throw InputError("--lambdas",
                         "every λ must be a number >= 0, got " + core::format_double(l));
      }
    }

    // The trials, all read and checked before any work.
    std::vector<residual::MotionTrial> trials;
    std::set<std::string> matched;
    for (const std::string& file : trial_files) {
      std::vector<residual::MotionTrial> read = residual::read_trials(file);
      if (!ids.empty() && read.front().id.empty()) {
        throw InputError("--ids", "selects trials by id, but " + file + " has no id column");
      }
      for (residual::MotionTrial& t : read) {
        if (ids.empty() || std::find(ids.begin(), ids.end(), t.id) != ids.end()) {
          matched.insert(t.id);
          trials.push_back(std::move(t));
        }
      }
    }
    for (const std::string& id : ids) {
      if (matched.count(id) == 0) {
        throw InputError("--ids", "no trial has id " + id);
      }
    }
    const int legs = trials.front().legs();
    for (const residual::MotionTrial& t : trials) {
      if (t.legs() != legs) {
        throw InputError(t.source, t.label + " is a Multipod of " + std::to_string(t.legs()) +
                                       " legs, " + trials.front().label + " (" +
                                       trials.front().source + ") one of " + std::to_string(legs) +
                                       ": one B fits one robot");
      }
    }

    // The template along every trial, less the first `skip` seconds of each.
    const residual::TemplateRobot model = residual::multipod_template(legs);
    std::vector<residual::ResidualTrial> data;
    nlohmann::json trial_json = nlohmann::json::array();
    Eigen::Index snapshots = 0;
    for (const residual::MotionTrial& t : trials) {
      const residual::TemplatePrediction p = residual::predict(model, t);
      const residual::ResidualTrial all = residual::residual_trial(p);
      Eigen::Index first = 0;
      while (first < p.t.size() && p.t(first) - t.t(0) < skip) {
        ++first;
      }
      const Eigen::Index kept = p.t.size() - first;
      if (kept == 0) {
        throw InputError("--skip", core::format_double(skip) + " s leaves no snapshot of " +
                                       t.label + " (it lasts " +
                                       core::format_double(t.t(t.samples() - 1) - t.t(0)) + " s)");
      }
      data.push_back({all.qdot.bottomRows(kept), all.residual.bottomRows(kept)});
      snapshots += kept;
      trial_json.push_back(
          {{"label", t.label}, {"id", t.id}, {"samples", t.samples()}, {"snapshots", kept}});
    }
    const Eigen::Index columns = Eigen::Index{2} * legs;
    if (snapshots < columns) {
      throw InputError(
          "--trials",
          std::to_string(snapshots) + " snapshots" + (skip > 0.0 ? " (after --skip)" : "") +
              " from " + std::to_string(trials.size()) +
              (trials.size() == 1 ? " trial" : " trials") + "; B of " + std::to_string(legs) +
              " legs has " + std::to_string(columns) + " columns, the fit needs at least " +
              std::to_string(columns) + " snapshots");
    }

    // The fit.
    residual::ResidualFit fit;
    nlohmann::json validation;
    if (ridge) {
      if (data.size() < 2) {
        throw InputError("--estimator",
                         "ridge chooses λ by leaving one trial out: it needs at "
                         "least 2 trials, got 1");
      }
      std::vector<double> grid = lambdas;
      if (grid.empty()) {
        const residual::ResidualFit plain = residual::fit_residual_ridge(data, 0.0);
        const double top = plain.singular_values.size() > 0 ? plain.singular_values(0) : 0.0;
        grid.push_back(0.0);
        for (int e = kGridLow; e <= 0 && top > 0.0; ++e) {
          grid.push_back(top * top * std::pow(10.0, e));
        }
      }
      const residual::RidgeValidation v = residual::validate_ridge(data, grid);
      fit = residual::fit_residual_ridge(data, v.best);
      validation = {{"lambdas", v.lambdas}, {"error", v.error}, {"best", v.best}};
    } else {
      fit = residual::fit_residual(data);
    }
    // A B the scene's reader would refuse is no result.
    for (Eigen::Index i = 0; i < fit.B.size(); ++i) {
      if (!scene::ranges::kResidualEntry.contains(fit.B.data()[i])) {
        throw core::ComputationError(
            "the fitted B has an entry " + core::format_double(fit.B.data()[i]) +
            " outside the residual file's range " + scene::ranges::kResidualEntry.describe() +
            " (the q̇ matrix's condition number is " + three_digits(fit.condition) +
            "; --estimator ridge shrinks B)");
      }
    }

    // B's file with its comment header, and the sidecar.
    std::ostringstream comment;
    comment << "The connection residual B of thesis §5.3.1: g̊ = (A(q) + B) q̇. Rows v_x, v_y, ω;\n"
            << "columns 2k, 2k+1 = leg k's q̇_x, q̇_y (legs L1..L" << legs / 2 << ", R1..R"
            << legs / 2 << ").\n"
            << "slipwalk residual fit: robot " << robot << " (" << legs << " legs), estimator "
            << estimator << ", λ = " << core::format_double(fit.lambda) << ", skip "
            << core::format_double(skip) << " s\n"
            << "trials (" << trials.size() << "):";
    for (const residual::MotionTrial& t : trials) {
      comment << (&t == &trials.front() ? " " : "; ") << t.label;
    }
    comment << "\nsnapshots " << fit.snapshots << ", rank " << fit.rank << " of " << columns
            << ", condition " << three_digits(fit.condition) << "\n"
            << "rms residual before: " << components(fit.rms_before) << "\n"
            << "rms residual after:  " << components(fit.rms_after);
    core::AtomicFile file(out);
    file.stream() << residual::residual_file_text(fit.B, comment.str());
    file.finish();
    const double wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    nlohmann::json json = {
        {"command", "residual fit"},
        {"robot", robot},
        {"legs", legs},
        {"residual", std::filesystem::path(out).filename().string()},
        {"trial_files", trial_files},
        {"ids", ids},
        {"trials", trial_json},
        {"skip", skip},
        {"estimator", estimator},
        {"lambda", fit.lambda},
        {"snapshots", fit.snapshots},
        {"rank", fit.rank},
        {"condition", std::isfinite(fit.condition) ? nlohmann::json(fit.condition) : nullptr},
        {"singular_values",
         std::vector<double>(fit.singular_values.data(),
                             fit.singular_values.data() + fit.singular_values.size())},
        {"rms_before", {fit.rms_before(0), fit.rms_before(1), fit.rms_before(2)}},
        {"rms_after", {fit.rms_after(0), fit.rms_after(1), fit.rms_after(2)}},
        {"wall_s", wall_s},
        {"provenance", core::build_provenance()},
    };
    if (ridge) {
      json["validation"] = validation;
    }
    core::AtomicFile side(sidecar);
    side.stream() << json.dump(1) << "\n";
    core::commit_with_sidecar(file, side);

    std::cout << "slipwalk residual fit: " << trials.size() << " trials, " << fit.snapshots
              << " snapshots, " << legs << " legs\n"
              << "q̇ matrix: rank " << fit.rank << " of " << columns << ", condition "
              << three_digits(fit.condition) << "\n"
              << "estimator " << estimator << ", λ = " << three_digits(fit.lambda) << "\n"
              << "rms residual before: " << components(fit.rms_before) << "\n"
              << "rms residual after:  " << components(fit.rms_after) << "\n";
  }
};

}  // namespace

void add_residual_command(CLI::App& app) {
  auto* residual = app.add_subcommand(
      "residual",
      "the connection residual B of thesis §5.3.1 (g̊ = (A(q) + B) q̇) from motion "
      "trials");
  residual->require_subcommand(1);
  auto cmd = std::make_shared<ResidualFitCommand>();
  auto* fit = residual->add_subcommand(
      "fit",
      "fit B to motion trials (§5.3.2): the template's A(q) q̇ at every interior sample against "
      "the measured body velocity; writes B as a scene's [residual] file and prints the fit's "
      "summary");
  fit->add_option("--robot", cmd->robot, "the template robot (multipod)")
      ->required()
      ->check(CLI::IsMember({"multipod"}));
  fit->add_option("--trials", cmd->trial_files,
                  "trial files (CSV; format in lib/residual/trial.hpp); a file with an id column "
                  "holds one trial per id")
      ->required()
      ->expected(1, -1);
  fit->add_option("--out", cmd->out,
                  "B's residual file to write (whole or not at all), with a provenance sidecar "
                  "<name>.json beside it")
      ->required();
  fit->add_option("--ids", cmd->ids, "only the trials of these ids (comma-separated)")
      ->delimiter(',');
  fit->add_option("--estimator", cmd->estimator,
                  "pinv: the pseudo-inverse (the thesis); ridge: λ by leave-one-trial-out "
                  "cross-validation (at least 2 trials)")
      ->check(CLI::IsMember({"pinv", "ridge"}));
  fit->add_option("--lambdas", cmd->lambdas,
                  "the ridge grid of λ (m²/s², each >= 0); default 0 and σ_max²·10^e, e = -12..0, "
                  "σ_max the q̇ matrix's largest singular value")
      ->delimiter(',');
  fit->add_option("--skip", cmd->skip,
                  "seconds dropped at the start of each trial (a transient), default 0");
  fit->callback([cmd] { cmd->run(); });
}

}  // namespace slipwalk::cli
