#pragma once
// A small CSV table writer: a header, then rows of numbers or text, doubles printed so that a
// value read back is the value written (round-trip exact); and the line splitting that every
// reader of our plain CSV inputs shares (frame batches, residual terms).
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace slipwalk::core {

/// Formats a double in the fewest digits (15–17) that read back bit-identical; NaN and inf as
/// nan/inf.
std::string format_double(double value);

/// Formats a double to `digits` significant digits (%.*g), for a message or a summary line.
std::string format_approx(double value, int digits = 3);

/// The lines of a text, one at a time, with line numbers for messages. A line ends at '\n'; one
/// '\r' before it (or at the end of the text) is part of the line end, so CRLF files read as
/// their LF twins; a UTF-8 byte-order mark before the first line is dropped (spreadsheets write
/// both). Views point into the text, which must outlive the reader.
class LineReader {
 public:
  explicit LineReader(std::string_view text);
  /// The next line without its end; false once the text is used up.
  bool next(std::string_view& line);
  /// The 1-based number of the line last returned (0 before the first).
  [[nodiscard]] long long line_number() const { return line_; }

 private:
  std::string_view rest_;
  long long line_ = 0;
};

/// Splits a line at every ',' (no quoting: our inputs are numbers) into `cells`, views into
/// `line`, and `starts`, the 1-based column where each cell starts. Reuses both vectors.
void split_cells(std::string_view line, std::vector<std::string_view>& cells,
                 std::vector<int>& starts);

/// The cell without the spaces and tabs around it (a view into `s`).
[[nodiscard]] std::string_view trim_blanks(std::string_view s);

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
