#pragma once
// A motion trial of the Multipod (thesis §5.3.2): what motion capture and the motors' encoders
// record while the robot walks one gait — the body pose and the joint angles, sampled together
// (the thesis: 125 Hz, 8–10 cycles). It is all the residual fit needs from a robot: the template
// model turns the joint angles into feet (robots::multipod_feet_from_joints) and the local
// connection A(q) q̇ (template.hpp), the pose gives the measured body velocity g̊_true.
//
// The trial file (CSV, one header line, then one line per sample; '#' starts a comment to the end
// of its line, blank lines are skipped):
//
//   t, x, y, theta, yaw1_1, roll_1, yaw2_1, ..., yaw1_M, roll_M, yaw2_M
//
//   t        s, strictly increasing
//   x, y     m, the body frame's origin in the world (the mean frame of the modules,
//            robots/multipod.hpp: centroid of the module centres)
//   theta    rad, the body frame's heading (mean of the module headings), continuous (not
//            wrapped: a robot that turns twice reads 4π)
//   yaw1_i, roll_i, yaw2_i   rad, module i's joints θ_y1,i, θ_r,i, θ_y2,i (i = 1 at the head;
//            signs as robots/multipod.hpp)
//
// M modules make a robot of 2M legs (M ∈ {3, 4, 5, 6}); x, y must lie in ±1e3 m and theta and
// the joint angles in ±1e6 rad (contact::limits, so that sines and cosines keep their accuracy).
// Columns may come in any order; a name starting yaw1_, roll_ or yaw2_ must end in a module
// number 1..6; other columns are ignored (they may hold text), except `id`: a file with an `id`
// column holds several trials, one per id (rows of one id together, in time order), which is how a
// sweep's CSV of trials (kind multipod_trial) reads as trial files.
#include <Eigen/Core>
#include <cstddef>
#include <filesystem>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace slipwalk::residual {

struct MotionTrial {
  std::string label;       ///< where it came from, for messages ("trials.csv, id 7")
  Eigen::VectorXd t;       ///< (n) s, strictly increasing
  Eigen::MatrixX3d pose;   ///< (n × 3) x, y (m), θ (rad, continuous), world
  Eigen::MatrixXd joints;  ///< (n × 3M) module i's θ_y1, θ_r, θ_y2 in columns 3i, 3i+1, 3i+2
  std::string id;          ///< the trial's `id` cell when read from a file with an id column
  std::string source;      ///< "file:line" of the header that named the columns, when read
  /// (n) "file:line" of each sample's row when read from a file (empty otherwise): where an
  /// error about one sample points.
  std::vector<std::string> rows;
  /// Where sample j came from: its row's file:line, or "<label>, sample j (t = … s)".
  [[nodiscard]] std::string where(Eigen::Index j) const;

  [[nodiscard]] Eigen::Index samples() const { return t.size(); }
  [[nodiscard]] int modules() const { return static_cast<int>(joints.cols() / 3); }
  [[nodiscard]] int legs() const { return 2 * modules(); }
};

/// Fewest samples a trial may have (central differences need three; a fit needs many more,
/// checked by the fit).
inline constexpr Eigen::Index kMinTrialSamples = 3;

/// Throws core::InputError naming the trial's label for sizes that disagree, a module count
/// outside {3, 4, 5, 6}, fewer than kMinTrialSamples samples, a time that does not increase, or an
/// entry that is not finite.
void validate(const MotionTrial& trial);

/// The trial file's column names for M modules, in the order write_trial writes them.
[[nodiscard]] std::vector<std::string> trial_columns(int modules);

/// The largest trial file read: a study's whole set of trials (144 trials of 8 cycles at 125 Hz,
/// ch5_residual's trials.csv, is ~75 MB) fits with room to spare.
inline constexpr std::size_t kMaxTrialFileBytes = std::size_t{512} << 20;

/// Reads a trial file (format above): one trial, or one per id. Throws core::InputError with
/// file:line (file:line:col for a bad number) for a missing or duplicated column, a joint column
/// set that is not complete 1..M, a row of the wrong width, a bad number, a time that does not
/// increase within a trial, an id that comes back after another one, or a trial too short.
[[nodiscard]] std::vector<MotionTrial> read_trials(const std::filesystem::path& file);
/// The same from text; `file` labels the messages.
[[nodiscard]] std::vector<MotionTrial> parse_trials(std::string_view text, const std::string& file);

/// Writes the trial in the file format (header, then the samples with up to 17 significant digits,
/// core::format_double's shortest that round-trips, so reading it back gives the same numbers).
/// Throws core::InputError (validate) for an invalid trial; writes no id column.
void write_trial(std::ostream& out, const MotionTrial& trial);

/// B (3 × 2K) as the residual file a scene's [residual] file reads (scene::parse_residual): three
/// rows v_x, v_y, ω of 2K numbers with up to 17 significant digits (round-trip exact), after
/// `comment` (each of its lines written as a '#' line; may be empty). Throws core::InputError("B")
/// for a non-finite entry.
[[nodiscard]] std::string residual_file_text(const Eigen::Matrix<double, 3, Eigen::Dynamic>& B,
                                             std::string_view comment);

}  // namespace slipwalk::residual
