#pragma once
// The CSV batch form of the frame format (DESIGN.md: `slipwalk model --robot`): one frame a row,
// for trajectories. Input columns for N legs: theta, then per leg j q{j}x, q{j}y, q{j}z, qd{j}x,
// qd{j}y, qd{j}z (body frame, SI units, as the JSON form). Output columns: frame (the row's
// number, from 1), alpha, beta, z (eq. 3.6), vx, vy, wz (v_body), support (SupportSummary::Status
// as an integer), friction_converged (0/1), then per leg contact{j} (0/1), Fz{j}, Fx{j}, Fy{j}.
// Cells are plain numbers (no quoting) in the ranges of contact::limits; empty lines are skipped;
// CRLF line ends read as LF (core::LineReader). A row whose result is not finite stops the batch
// (core::ComputationError from write_batch_row).
#include <cstddef>
#include <string>
#include <vector>

#include "contact/robot.hpp"
#include "core/csv.hpp"

namespace slipwalk::contact {

[[nodiscard]] std::vector<std::string> batch_input_columns(int legs);
[[nodiscard]] std::vector<std::string> batch_output_columns(int legs);

/// Reads a batch's rows into a frame, one at a time. Errors are core::InputError naming
/// "<source>" (no header), "<source>:1:<col>" (the first wrong header cell), "<source>:<row>" (a
/// wrong cell count) or "<source>:<row>:<col>" (a cell that is not a number in its range).
class FrameBatchReader {
 public:
  /// Checks the header against batch_input_columns(legs).
  FrameBatchReader(std::string text, std::string source, int legs);
  FrameBatchReader(const FrameBatchReader&) = delete;  // lines_ and cells_ view text_
  FrameBatchReader& operator=(const FrameBatchReader&) = delete;

  /// Reads the next non-empty row into frame.theta, frame.q and frame.qdot; false at the end.
  bool next(Frame& frame);

  /// The frame number of the row last read (its line number minus the header's).
  [[nodiscard]] long long frame_number() const { return row_ - 1; }

 private:
  std::string text_;
  std::string source_;
  int legs_;
  core::LineReader lines_;  // views into text_ (declared after it, so built after it)
  std::size_t expected_cells_ = 0;
  long long row_ = 1;  // line number of the row last read (the header is line 1)
  std::vector<std::string_view> cells_;
  std::vector<int> starts_;  // column (from 1) where each cell starts
};

/// Writes one output row (batch_output_columns) of an evaluated frame; core::ComputationError
/// when its result is not finite.
void write_batch_row(core::CsvWriter& csv, long long frame_number, const Frame& frame);

}  // namespace slipwalk::contact
