#pragma once
// The calibration's files: the two experiments' recordings (CSV), the design geometry (TOML), and
// what `slipwalk calibrate` writes (params JSON) and `slipwalk calibrate synth` adds (truth JSON).
// A user with a real robot writes these formats; files.cpp's head documents each.
//
// CSV (one header line, then one row per sample or pose; '#' starts a comment to the end of its
// line; blank lines skipped; columns in any order; unknown columns ignored):
//   hanging:  orientation, then per leg L of the geometry: phi_L, fx_L, fy_L, fz_L, tx_L, ty_L,
//   tz_L
//             orientation ∈ {+x, −x, +y, −y, +z, −z}: the body axis along gravity; the rows of one
//             orientation together, in sample order; one file may hold several orientations and
//             several files may be given.
//   poses:    qw, qx, qy, qz (the attitude R^W_C as a unit quaternion, |q| within 1e-6 of 1), then
//             the same per-leg columns.
// Errors (a missing or duplicated column, a cell that is not a finite number, an unknown
// orientation, an orientation split over two runs of rows, a quaternion off unit length, a
// file larger than kMaxCalibrationFileBytes) are core::InputError at file:line:col.
#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "calibration/calibrate.hpp"
#include "calibration/model.hpp"
#include "calibration/synthetic.hpp"

namespace slipwalk::calibration {

/// The largest recording read (the thesis' full hanging set, 4 × 90,000 rows, is ≈ 150 MB).
inline constexpr std::size_t kMaxCalibrationFileBytes = std::size_t{512} << 20;

/// The columns of each format, in the order the writers write them (one definition for reader
/// and writer): per leg L of the geometry phi_L, fx_L, fy_L, fz_L, tx_L, ty_L, tz_L.
[[nodiscard]] std::vector<std::string> hanging_columns(const Geometry& geometry);
[[nodiscard]] std::vector<std::string> pose_columns(const Geometry& geometry);

/// The readers on text (`source` names it in errors): what read_hanging, read_poses and
/// read_geometry do after reading the file (the fuzz targets call these).
[[nodiscard]] std::vector<HangingRecord> parse_hanging(std::string_view text,
                                                       const std::string& source,
                                                       const Geometry& geometry);
[[nodiscard]] StandingPoses parse_poses(std::string_view text, const std::string& source,
                                        const Geometry& geometry);
[[nodiscard]] Geometry parse_geometry(std::string_view text, const std::string& source);

/// The checks of §4.3.1's pairing, on records gathered from several files, before calibrating
/// (core::InputError at the record's or the sample's file:line): an orientation given twice; a
/// record without its opposite (except −z, the naive tare's upright record, which may stand
/// alone); fewer than two complete opposite pairs (they are then of different axes, so not
/// parallel); paired records (every record of a complete pair, across pairs too) that differ in
/// sample count or whose shaft angles differ by more than `max_phi_mismatch` turns at a sample;
/// fewer than `min_samples` samples in a paired record.
void check_hanging_pairs(const std::vector<HangingRecord>& records, double max_phi_mismatch,
                         Eigen::Index min_samples);

[[nodiscard]] std::vector<HangingRecord> read_hanging(const std::filesystem::path& path,
                                                      const Geometry& geometry);
void write_hanging(std::ostream& out, const std::vector<HangingRecord>& records,
                   const Geometry& geometry);

[[nodiscard]] StandingPoses read_poses(const std::filesystem::path& path, const Geometry& geometry);
void write_poses(std::ostream& out, const StandingPoses& poses, const Geometry& geometry);

/// The geometry file (TOML; errors at file:line:col):
///   robot_weight = 80.25            # N
///   [[transducer]]
///   leg = "HL"
///   position = [x, y, z]            # m, the transducer's origin in the body frame
///   rotation = [θx, θy, θz]         # rad, rotation vector of its axes in the body frame
[[nodiscard]] Geometry read_geometry(const std::filesystem::path& path);
void write_geometry(std::ostream& out, const Geometry& geometry);

/// Everything the calibration estimated (offsets, weights, CoM fits, mounting, standard errors,
/// Table 4.2, timings), as `slipwalk calibrate` writes it.
[[nodiscard]] nlohmann::json calibration_json(const Calibration& calibration);
/// The truth of a synthetic robot, with its leg CoMs tabulated over φ, as the sidecar of
/// `slipwalk calibrate synth`.
[[nodiscard]] nlohmann::json truth_json(const SyntheticTruth& truth, const SynthOptions& options);

}  // namespace slipwalk::calibration
