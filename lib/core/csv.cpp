#include "core/csv.hpp"

#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "core/error.hpp"

namespace slipwalk::core {

std::string_view trim_blanks(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) {
    s.remove_prefix(1);
  }
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) {
    s.remove_suffix(1);
  }
  return s;
}

std::string format_approx(double value, int digits) {
  std::array<char, 48> buffer{};
  (void)std::snprintf(buffer.data(), buffer.size(), "%.*g", digits, value);
  return buffer.data();
}

std::string format_double(double value) {
  if (std::isnan(value)) {
    return "nan";
  }
  if (std::isinf(value)) {
    return value > 0 ? "inf" : "-inf";
  }
  // The shortest of %.15g, %.16g, %.17g that reads back as the same double.
  std::array<char, 32> buffer{};
  for (int digits = 15; digits <= 17; ++digits) {
    std::snprintf(buffer.data(), buffer.size(), "%.*g", digits, value);
    if (std::strtod(buffer.data(), nullptr) == value) {
      break;
    }
  }
  return buffer.data();
}

LineReader::LineReader(std::string_view text) : rest_(text) {
  constexpr std::string_view kBom = "\xEF\xBB\xBF";
  if (rest_.substr(0, kBom.size()) == kBom) {
    rest_.remove_prefix(kBom.size());
  }
}

bool LineReader::next(std::string_view& line) {
  if (rest_.empty()) {
    return false;
  }
  const std::size_t end = rest_.find('\n');
  line = rest_.substr(0, end);
  rest_.remove_prefix(end == std::string_view::npos ? rest_.size() : end + 1);
  if (!line.empty() && line.back() == '\r') {
    line.remove_suffix(1);
  }
  ++line_;
  return true;
}

void split_cells(std::string_view line, std::vector<std::string_view>& cells,
                 std::vector<int>& starts) {
  cells.clear();
  starts.clear();
  std::size_t begin = 0;
  while (true) {
    const std::size_t end = line.find(',', begin);
    cells.push_back(line.substr(begin, end == std::string_view::npos ? end : end - begin));
    starts.push_back(static_cast<int>(begin) + 1);
    if (end == std::string_view::npos) {
      break;
    }
    begin = end + 1;
  }
}

CsvWriter::CsvWriter(std::ostream& out, const std::vector<std::string>& columns)
    : out_(out), columns_(columns.size()) {
  for (std::size_t i = 0; i < columns.size(); ++i) {
    out_ << (i ? "," : "") << columns[i];
  }
  out_ << '\n';
}

void CsvWriter::separator() {
  if (in_row_++ > 0) {
    out_ << ',';
  }
}

CsvWriter& CsvWriter::cell(double value) {
  separator();
  out_ << format_double(value);
  return *this;
}

CsvWriter& CsvWriter::cell(long long value) {
  separator();
  out_ << value;
  return *this;
}

CsvWriter& CsvWriter::cell(std::string_view text) {
  separator();
  // Quote text that would break the row; our own labels never need it, user text might.
  if (text.find_first_of(",\"\n") != std::string_view::npos) {
    out_ << '"';
    for (char c : text) {
      out_ << (c == '"' ? "\"\"" : std::string(1, c));
    }
    out_ << '"';
  } else {
    out_ << text;
  }
  return *this;
}

void CsvWriter::end_row() {
  if (in_row_ != columns_) {
    throw std::logic_error("CsvWriter: row has " + std::to_string(in_row_) + " cells, header " +
                           std::to_string(columns_));
  }
  out_ << '\n';
  in_row_ = 0;
  // A failed write (a full disk, a closed pipe) stops the writer at once rather than after a
  // run's worth of rows into a stream that discards them.
  if (!out_) {
    throw ComputationError(std::string("writing CSV rows failed: ") + std::strerror(errno));
  }
}

}  // namespace slipwalk::core
