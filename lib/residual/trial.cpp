// Motion trials of the Multipod (thesis §5.3.2): the trial file's reader and writer, and B's
// residual file (trial.hpp has the formats).
#include "residual/trial.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <optional>
#include <set>
#include <sstream>

#include "contact/robot.hpp"
#include "core/csv.hpp"
#include "core/error.hpp"
#include "core/input_file.hpp"
#include "core/json_input.hpp"
#include "core/range.hpp"

namespace slipwalk::residual {

namespace {

using core::InputError;

constexpr int kMinModules = 3;
constexpr int kMaxModules = 6;
/// The joint columns of module i are <prefix>i, in this order (θ_y1, θ_r, θ_y2).
constexpr std::array<std::string_view, 3> kJointPrefix = {"yaw1_", "roll_", "yaw2_"};
/// The pose columns, in the file's order.
constexpr std::array<std::string_view, 4> kPoseColumn = {"t", "x", "y", "theta"};

std::string label_of(const MotionTrial& trial) {
  return trial.label.empty() ? std::string("the trial") : trial.label;
}

/// Module number of a joint column name "<prefix>i" (1-based), 0 when the name is not one;
/// −1 when it starts like one but the number is not 1..kMaxModules.
int joint_module(std::string_view name, std::string_view prefix) {
  if (name.substr(0, prefix.size()) != prefix) {
    return 0;
  }
  const std::string_view digits = name.substr(prefix.size());
  int i = 0;
  const auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), i);
  if (digits.empty() || digits.front() == '0' || ec != std::errc() ||
      ptr != digits.data() + digits.size() || i < 1 || i > kMaxModules) {
    return -1;
  }
  return i;
}

/// Where each needed column is in a row (cell indices), read from the header line.
struct Layout {
  std::array<int, 4> pose{-1, -1, -1, -1};  // t, x, y, theta
  std::vector<int> joints;                  // 3M: module i's yaw1, roll, yaw2 at 3i, 3i+1, 3i+2
  int id = -1;
  std::size_t cells = 0;
  [[nodiscard]] int modules() const { return static_cast<int>(joints.size() / 3); }
};

Layout read_header(std::string_view content, const std::string& where,
                   std::vector<std::string_view>& cells, std::vector<int>& starts) {
  core::split_cells(content, cells, starts);
  Layout layout;
  layout.cells = cells.size();
  std::array<std::array<int, 3>, kMaxModules> joint{};
  for (auto& m : joint) {
    m.fill(-1);
  }
  std::vector<std::pair<std::string_view, int>> seen;  // name, column: duplicates
  const auto place = [&](std::size_t c, std::string_view name) {
    return where + ":" +
           std::to_string(starts[c] + static_cast<int>(name.data() - cells[c].data()));
  };
  for (std::size_t c = 0; c < cells.size(); ++c) {
    const std::string_view name = core::trim_blanks(cells[c]);
    int* slot = nullptr;
    for (std::size_t p = 0; p < kPoseColumn.size(); ++p) {
      if (name == kPoseColumn[p]) {
        slot = &layout.pose[p];
      }
    }
    if (name == "id") {
      slot = &layout.id;
    }
    for (std::size_t k = 0; k < kJointPrefix.size() && slot == nullptr; ++k) {
      const int i = joint_module(name, kJointPrefix[k]);
      if (i < 0) {
        throw InputError(place(c, name), "column '" + core::text_excerpt(name) +
                                             "': joint columns are numbered 1.." +
                                             std::to_string(kMaxModules) +
                                             " (module 1 at the head)");
      }
      if (i > 0) {
        slot = &joint[static_cast<std::size_t>(i - 1)][k];
      }
    }
    if (slot == nullptr) {
      continue;  // another column: ignored
    }
    if (*slot >= 0) {
      throw InputError(place(c, name),
                       "column '" + std::string(name) + "' appears twice (first at column " +
                           std::to_string(starts[static_cast<std::size_t>(*slot)]) + ")");
    }
    *slot = static_cast<int>(c);
  }
  const std::string needs =
      " (a trial file needs t, x, y, theta and yaw1_i, roll_i, yaw2_i of every module i = 1..M)";
  for (std::size_t p = 0; p < kPoseColumn.size(); ++p) {
    if (layout.pose[p] < 0) {
      throw InputError(where, "no column '" + std::string(kPoseColumn[p]) + "'" + needs);
    }
  }
  int modules = 0;
  for (int i = 0; i < kMaxModules; ++i) {
    for (int k = 0; k < 3; ++k) {
      if (joint[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)] >= 0) {
        modules = i + 1;
      }
    }
  }
  if (modules < kMinModules) {
    throw InputError(where, "joint columns for " + std::to_string(modules) +
                                " modules; a Multipod has " + std::to_string(kMinModules) + " to " +
                                std::to_string(kMaxModules) + " (6 to 12 legs)" + needs);
  }
  for (int i = 0; i < modules; ++i) {
    for (int k = 0; k < 3; ++k) {
      const int c = joint[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)];
      if (c < 0) {
        throw InputError(
            where, "no column '" + std::string(kJointPrefix[static_cast<std::size_t>(k)]) +
                       std::to_string(i + 1) + "', though the joint columns go up to module " +
                       std::to_string(modules) + needs);
      }
      layout.joints.push_back(c);
    }
  }
  return layout;
}

/// A trial being read: its rows as they come, row-major.
struct Pending {
  std::string id;
  std::vector<double> t;
  std::vector<double> pose;       // 3 per sample
  std::vector<double> joints;     // 3M per sample
  std::vector<std::string> rows;  // file:line per sample
  long long last_line = 0;
};

MotionTrial finish(Pending& p, const Layout& layout, const std::string& file,
                   const std::string& header_at) {
  MotionTrial trial;
  trial.label = layout.id >= 0 ? file + ", id " + p.id : file;
  trial.id = p.id;
  trial.source = header_at;
  trial.rows = std::move(p.rows);
  const auto n = static_cast<Eigen::Index>(p.t.size());
  if (n < kMinTrialSamples) {
    throw InputError(file + ":" + std::to_string(p.last_line),
                     trial.label + " has " + std::to_string(n) +
                         " samples; a trial needs at least " + std::to_string(kMinTrialSamples) +
                         " (central differences)");
  }
  const Eigen::Index m = Eigen::Index{3} * layout.modules();
  trial.t = Eigen::Map<const Eigen::VectorXd>(p.t.data(), n);
  trial.pose = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
      p.pose.data(), n, 3);
  trial.joints =
      Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
          p.joints.data(), n, m);
  return trial;
}

}  // namespace

std::string MotionTrial::where(Eigen::Index j) const {
  if (j >= 0 && static_cast<std::size_t>(j) < rows.size()) {
    return rows[static_cast<std::size_t>(j)];
  }
  const std::string at = j >= 0 && j < t.size() ? " (t = " + core::format_double(t(j)) + " s)" : "";
  return (label.empty() ? std::string("the trial") : label) + ", sample " + std::to_string(j) + at;
}

void validate(const MotionTrial& trial) {
  const std::string where = label_of(trial);
  const Eigen::Index n = trial.t.size();
  if (trial.pose.rows() != n || trial.joints.rows() != n) {
    throw InputError(where, "sizes disagree: " + std::to_string(n) + " times, " +
                                std::to_string(trial.pose.rows()) + " poses, " +
                                std::to_string(trial.joints.rows()) + " rows of joint angles");
  }
  if (trial.joints.cols() % 3 != 0 || trial.modules() < kMinModules ||
      trial.modules() > kMaxModules) {
    throw InputError(where, std::to_string(trial.joints.cols()) +
                                " joint columns; a Multipod of 3 to 6 modules has 3 per module "
                                "(9 to 18)");
  }
  if (n < kMinTrialSamples) {
    throw InputError(where, std::to_string(n) + " samples; a trial needs at least " +
                                std::to_string(kMinTrialSamples) + " (central differences)");
  }
  if (!trial.t.allFinite() || !trial.pose.allFinite() || !trial.joints.allFinite()) {
    throw InputError(where, "an entry is not finite");
  }
  for (Eigen::Index j = 1; j < n; ++j) {
    if (!(trial.t(j) > trial.t(j - 1))) {
      throw InputError(where, "time does not increase at sample " + std::to_string(j) +
                                  " (t = " + core::format_double(trial.t(j)) + " after " +
                                  core::format_double(trial.t(j - 1)) + ")");
    }
  }
}

std::vector<std::string> trial_columns(int modules) {
  std::vector<std::string> cols(kPoseColumn.begin(), kPoseColumn.end());
  for (int i = 1; i <= modules; ++i) {
    for (std::string_view prefix : kJointPrefix) {
      cols.push_back(std::string(prefix) + std::to_string(i));
    }
  }
  return cols;
}

std::vector<MotionTrial> parse_trials(std::string_view text, const std::string& file) {
  std::vector<MotionTrial> trials;
  std::vector<std::string_view> cells;
  std::vector<int> starts;
  std::optional<Layout> layout;
  std::string header_at;
  std::set<std::string, std::less<>> done;  // ids of finished trials
  Pending pending;
  bool open = false;
  core::LineReader lines(text);
  for (std::string_view line; lines.next(line);) {
    const std::string_view content = line.substr(0, line.find('#'));
    if (core::trim_blanks(content).empty()) {
      continue;
    }
    const std::string where = file + ":" + std::to_string(lines.line_number());
    if (!layout) {
      layout = read_header(content, where, cells, starts);
      header_at = where;
      continue;
    }
    core::split_cells(content, cells, starts);
    if (cells.size() != layout->cells) {
      throw InputError(where, "the row has " + std::to_string(cells.size()) +
                                  " cells, the header " + std::to_string(layout->cells));
    }
    const auto at = [&](int c, std::string_view cell) {
      const auto i = static_cast<std::size_t>(c);
      return where + ":" +
             std::to_string(starts[i] + static_cast<int>(cell.data() - cells[i].data()));
    };
    const auto number = [&](int c, std::string_view name) {
      const std::string_view cell = core::trim_blanks(cells[static_cast<std::size_t>(c)]);
      double x = 0.0;
      const auto [ptr, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), x);
      if (cell.empty() || ec != std::errc() || ptr != cell.data() + cell.size() ||
          !std::isfinite(x)) {
        throw InputError(at(c, cell), std::string(name) + ": '" + core::text_excerpt(cell) +
                                          "' is not a finite number");
      }
      return x;
    };
    if (layout->id >= 0) {
      const std::string_view id = core::trim_blanks(cells[static_cast<std::size_t>(layout->id)]);
      if (id.empty()) {
        throw InputError(at(layout->id, id), "id: empty");
      }
      if (!open || id != pending.id) {
        if (done.find(id) != done.end()) {
          throw InputError(at(layout->id, id), "id " + core::text_excerpt(id) +
                                                   " comes back after id " +
                                                   core::text_excerpt(pending.id) +
                                                   " (the rows of one trial must be together)");
        }
        if (open) {
          trials.push_back(finish(pending, *layout, file, header_at));
          done.insert(pending.id);
        }
        pending = Pending{};
        pending.id = std::string(id);
      }
    }
    open = true;
    const double t = number(layout->pose[0], "t");
    if (!pending.t.empty() && !(t > pending.t.back())) {
      const std::string_view cell =
          core::trim_blanks(cells[static_cast<std::size_t>(layout->pose[0])]);
      throw InputError(at(layout->pose[0], cell),
                       "t must increase strictly within a trial; the row before has t = " +
                           core::format_double(pending.t.back()));
    }
    pending.t.push_back(t);
    pending.rows.push_back(where);
    for (std::size_t p = 1; p < kPoseColumn.size(); ++p) {
      const double v = number(layout->pose[p], kPoseColumn[p]);
      const std::string_view cell =
          core::trim_blanks(cells[static_cast<std::size_t>(layout->pose[p])]);
      core::require_in(at(layout->pose[p], cell), v,
                       p == 3 ? contact::limits::kYaw : contact::limits::kPosition);
      pending.pose.push_back(v);
    }
    for (std::size_t k = 0; k < layout->joints.size(); ++k) {
      const std::string name = std::string(kJointPrefix[k % 3]) + std::to_string(k / 3 + 1);
      const double v = number(layout->joints[k], name);
      const std::string_view cell =
          core::trim_blanks(cells[static_cast<std::size_t>(layout->joints[k])]);
      core::require_in(at(layout->joints[k], cell), v, contact::limits::kYaw);
      pending.joints.push_back(v);
    }
    pending.last_line = lines.line_number();
  }
  if (!layout) {
    throw InputError(file + ":" + std::to_string(std::max(lines.line_number(), 1LL)),
                     "no header line (t, x, y, theta, yaw1_1, roll_1, yaw2_1, ...)");
  }
  if (!open) {
    throw InputError(header_at, "no samples after the header");
  }
  trials.push_back(finish(pending, *layout, file, header_at));
  return trials;
}

std::vector<MotionTrial> read_trials(const std::filesystem::path& file) {
  return parse_trials(core::read_input_file(file, "a motion-trial CSV file", kMaxTrialFileBytes),
                      file.string());
}

void write_trial(std::ostream& out, const MotionTrial& trial) {
  validate(trial);
  core::CsvWriter csv(out, trial_columns(trial.modules()));
  for (Eigen::Index j = 0; j < trial.samples(); ++j) {
    csv.cell(trial.t(j));
    for (int c = 0; c < 3; ++c) {
      csv.cell(trial.pose(j, c));
    }
    for (Eigen::Index c = 0; c < trial.joints.cols(); ++c) {
      csv.cell(trial.joints(j, c));
    }
    csv.end_row();
  }
}

std::string residual_file_text(const Eigen::Matrix<double, 3, Eigen::Dynamic>& B,
                               std::string_view comment) {
  if (!B.allFinite()) {
    throw InputError("B", "an entry is not finite");
  }
  std::string text;
  std::size_t begin = 0;
  while (begin < comment.size()) {
    const std::size_t end = comment.find('\n', begin);
    const std::string_view line =
        comment.substr(begin, end == std::string_view::npos ? std::string_view::npos : end - begin);
    text.append(line.empty() ? "#" : "# ").append(line).append("\n");
    begin = end == std::string_view::npos ? comment.size() : end + 1;
  }
  for (Eigen::Index r = 0; r < 3; ++r) {
    for (Eigen::Index c = 0; c < B.cols(); ++c) {
      text.append(c == 0 ? "" : ",").append(core::format_double(B(r, c)));
    }
    text.append("\n");
  }
  return text;
}

}  // namespace slipwalk::residual
