#include "contact/frame_batch.hpp"

#include <cmath>
#include <exception>
#include <utility>

#include "core/error.hpp"

namespace slipwalk::contact {

namespace {

using core::InputError;

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

/// The line starting at `pos` (without its '\n'); advances `pos` past it. False at the end.
bool next_line(const std::string& text, std::size_t& pos, std::string& line) {
  if (pos >= text.size()) {
    return false;
  }
  const std::size_t end = text.find('\n', pos);
  line = text.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
  pos = end == std::string::npos ? text.size() : end + 1;
  return true;
}

}  // namespace

std::vector<std::string> batch_input_columns(int legs) {
  std::vector<std::string> cols{"theta"};
  for (int j = 0; j < legs; ++j) {
    for (const char* prefix : {"q", "qd"}) {
      for (const char* axis : {"x", "y", "z"}) {
        std::string name = prefix;
        name.append(std::to_string(j)).append(axis);
        cols.push_back(std::move(name));
      }
    }
  }
  return cols;
}

std::vector<std::string> batch_output_columns(int legs) {
  std::vector<std::string> cols{
      "frame", "alpha", "beta", "z", "vx", "vy", "wz", "support", "friction_converged"};
  for (int j = 0; j < legs; ++j) {
    for (const char* quantity : {"contact", "Fz", "Fx", "Fy"}) {
      cols.push_back(std::string(quantity).append(std::to_string(j)));
    }
  }
  return cols;
}

FrameBatchReader::FrameBatchReader(std::string text, std::string source, int legs)
    : text_(std::move(text)), source_(std::move(source)), legs_(legs) {
  const std::vector<std::string> expected = batch_input_columns(legs);
  expected_cells_ = expected.size();
  std::string line;
  if (!next_line(text_, pos_, line)) {
    throw InputError(source_, "empty; expected a header line");
  }
  split(line, cells_, starts_);
  if (cells_ != expected) {
    throw InputError(source_ + ":1:1",
                     "header must be " + std::to_string(expected.size()) +
                         " columns theta,q0x,q0y,q0z,qd0x,qd0y,qd0z,q1x,... for " +
                         std::to_string(legs) + " legs");
  }
}

bool FrameBatchReader::next(Frame& frame) {
  std::string line;
  do {
    if (!next_line(text_, pos_, line)) {
      return false;
    }
    ++row_;
  } while (line.empty());
  split(line, cells_, starts_);
  const std::string at_row = source_ + ":" + std::to_string(row_);
  if (cells_.size() != expected_cells_) {
    throw InputError(at_row, "has " + std::to_string(cells_.size()) + " cells, expected " +
                                 std::to_string(expected_cells_));
  }
  const auto value = [&](std::size_t c) {
    return cell_number(cells_[c], at_row + ":" + std::to_string(starts_[c]));
  };
  frame.theta = value(0);
  for (int j = 0; j < legs_; ++j) {
    const std::size_t base = 1 + 6 * static_cast<std::size_t>(j);
    for (int i = 0; i < 3; ++i) {
      frame.q(i, j) = value(base + static_cast<std::size_t>(i));
      frame.qdot(i, j) = value(base + 3 + static_cast<std::size_t>(i));
    }
  }
  return true;
}

void write_batch_row(core::CsvWriter& csv, long long frame_number, const Frame& f) {
  csv.cell(frame_number).cell(f.alpha).cell(f.beta).cell(f.z);
  csv.cell(f.v_body(0)).cell(f.v_body(1)).cell(f.v_body(2));
  csv.cell(static_cast<int>(f.support.status)).cell(f.friction.converged ? 1 : 0);
  for (int j = 0; j < f.legs(); ++j) {
    csv.cell(f.contact[static_cast<std::size_t>(j)] != 0 ? 1 : 0).cell(f.Fz(j));
    csv.cell(f.Fxy(0, j)).cell(f.Fxy(1, j));
  }
  csv.end_row();
}

}  // namespace slipwalk::contact
