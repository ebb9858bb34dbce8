#include "contact/frame_batch.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <utility>

#include "contact/spring_support.hpp"
#include "core/error.hpp"
#include "core/json_input.hpp"
#include "core/range.hpp"

namespace slipwalk::contact {

namespace {

using core::InputError;

/// The cell as a number in `range`; InputError(where) otherwise.
double cell_number(std::string_view cell, const std::string& where, const core::Range& range) {
  const std::string text(cell);
  char* end = nullptr;
  const double v = text.empty() ? 0.0 : std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v)) {
    throw InputError(where, "expected a finite number, got '" + core::text_excerpt(text) + "'");
  }
  core::require_in(where, v, range);  // an underflow (ERANGE) reads as the tiny value it is
  return v;
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
    : text_(std::move(text)), source_(std::move(source)), legs_(legs), lines_(text_) {
  const std::vector<std::string> expected = batch_input_columns(legs);
  expected_cells_ = expected.size();
  std::string_view line;
  if (!lines_.next(line)) {
    throw InputError(source_, "empty; expected a header line");
  }
  core::split_cells(line, cells_, starts_);
  // The first cell that differs names the place; a row too short or too long, its end.
  for (std::size_t c = 0; c < std::max(cells_.size(), expected.size()); ++c) {
    if (c < cells_.size() && c < expected.size() && cells_[c] == expected[c]) {
      continue;
    }
    const int column = c < cells_.size() ? starts_[c] : static_cast<int>(line.size()) + 1;
    std::string what = "header must be " + std::to_string(expected.size()) +
                       " columns theta,q0x,q0y,q0z,qd0x,qd0y,qd0z,q1x,... for " +
                       std::to_string(legs) + " legs; ";
    if (c >= cells_.size()) {
      what += "it ends before column '" + expected[c] + "'";
    } else if (c >= expected.size()) {
      what += "it has " + std::to_string(cells_.size()) + " columns";
    } else {
      what += "expected '" + expected[c] + "' here, got '" + core::text_excerpt(cells_[c]) + "'";
    }
    throw InputError(source_ + ":1:" + std::to_string(column), what);
  }
}

bool FrameBatchReader::next(Frame& frame) {
  std::string_view line;
  do {
    if (!lines_.next(line)) {
      return false;
    }
  } while (line.empty());
  row_ = lines_.line_number();
  core::split_cells(line, cells_, starts_);
  const std::string at_row = source_ + ":" + std::to_string(row_);
  if (cells_.size() != expected_cells_) {
    throw InputError(at_row, "has " + std::to_string(cells_.size()) + " cells, expected " +
                                 std::to_string(expected_cells_));
  }
  const auto value = [&](std::size_t c, const core::Range& range) {
    return cell_number(cells_[c], at_row + ":" + std::to_string(starts_[c]), range);
  };
  frame.theta = value(0, limits::kYaw);
  for (int j = 0; j < legs_; ++j) {
    const std::size_t base = 1 + 6 * static_cast<std::size_t>(j);
    for (int i = 0; i < 3; ++i) {
      frame.q(i, j) = value(base + static_cast<std::size_t>(i), limits::kPosition);
      frame.qdot(i, j) = value(base + 3 + static_cast<std::size_t>(i), limits::kVelocity);
    }
  }
  return true;
}

void write_batch_row(core::CsvWriter& csv, long long frame_number, const Frame& f) {
  // A non-finite result is no result (as frame_to_json): the batch stops with exit 1.
  const double outputs = f.alpha + f.beta + f.z + f.Fz.sum() + f.v_body.sum() + f.Fxy.sum();
  if (!std::isfinite(outputs)) {
    throw core::ComputationError("frame " + std::to_string(frame_number) +
                                 ": the model's result is not finite (spring support: " +
                                 status_name(f.support.status) + ")");
  }
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
