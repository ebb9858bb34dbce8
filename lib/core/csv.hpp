#pragma once
// A small CSV table writer: a header, then rows of numbers or text, doubles printed so that a
// value read back is the value written (round-trip exact).
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace slipwalk::core {

/// Formats a double in the fewest digits (15–17) that read back bit-identical; NaN and inf as
/// nan/inf.
std::string format_double(double value);

class CsvWriter {
 public:
  CsvWriter(std::ostream& out, const std::vector<std::string>& columns);
  /// Appends one cell to the current row; end_row() checks the count against the header.
  CsvWriter& cell(double value);
  CsvWriter& cell(long long value);
  CsvWriter& cell(int value) { return cell(static_cast<long long>(value)); }
  CsvWriter& cell(std::string_view text);
  /// Ends the row; throws ComputationError once the stream has failed (a full disk).
  void end_row();

 private:
  void separator();
  std::ostream& out_;
  std::size_t columns_;
  std::size_t in_row_ = 0;
};

}  // namespace slipwalk::core
