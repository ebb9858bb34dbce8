// The readers of a scene's anisotropy, residual file and noise (effects.hpp).
#include "scene/effects.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <vector>

#include "core/csv.hpp"
#include "core/error.hpp"
#include "core/input_file.hpp"
#include "scene/ranges.hpp"

namespace slipwalk::scene {

namespace {

using core::InputError;

/// Reads a pair [wx, wy] (finite numbers) from an array node.
Eigen::Vector2d read_pair(const TableReader& t, const toml::node& node) {
  const toml::array* a = node.as_array();
  if (a == nullptr || a->size() != 2) {
    t.fail(node, "w",
           std::string("expected a pair [wx, wy], got ") +
               (a != nullptr ? "an array of " + std::to_string(a->size()) : type_name(node)));
  }
  return {t.number_in(*a->get(0), "w", ranges::kAnisotropy),
          t.number_in(*a->get(1), "w", ranges::kAnisotropy)};
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r')) {
    s.remove_prefix(1);
  }
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) {
    s.remove_suffix(1);
  }
  return s;
}

}  // namespace

Eigen::Matrix2Xd read_anisotropy(const TableReader& friction, const toml::node& node, int legs) {
  const toml::array* a = node.as_array();
  if (a == nullptr) {
    friction.fail(node, "w",
                  std::string("expected [wx, wy] or one pair per leg, got ") + type_name(node));
  }
  Eigen::Matrix2Xd w;
  if (!a->empty() && !a->get(0)->is_array()) {
    w = read_pair(friction, node);
    return w;
  }
  friction.check(static_cast<int>(a->size()) == legs, node, "w",
                 "one pair per leg: the robot has " + std::to_string(legs) + " legs, got " +
                     std::to_string(a->size()) + " pairs");
  w.resize(2, legs);
  for (int k = 0; k < legs; ++k) {
    w.col(k) = read_pair(friction, *a->get(static_cast<std::size_t>(k)));
  }
  return w;
}

Eigen::Matrix<double, 3, Eigen::Dynamic> parse_residual(std::string_view text,
                                                        const std::string& file, int legs) {
  const int cols = 2 * legs;
  Eigen::Matrix<double, 3, Eigen::Dynamic> B(3, cols);
  int row = 0;
  long long line_no = 0;
  long long last_line = 0;
  core::LineReader lines(text);  // CRLF reads as LF
  for (std::string_view line; lines.next(line);) {
    line_no = lines.line_number();
    const std::string_view content = line.substr(0, line.find('#'));
    if (trim(content).empty()) {
      continue;
    }
    const std::string where = file + ":" + std::to_string(line_no);
    if (row == 3) {
      throw InputError(where, "a fourth row; B has 3 rows (v_x, v_y, omega)");
    }
    int col = 0;
    std::size_t offset = 0;
    while (true) {
      const std::size_t comma = content.find(',', offset);
      const std::string_view field = content.substr(
          offset, comma == std::string_view::npos ? std::string_view::npos : comma - offset);
      const std::string_view value = trim(field);
      const std::size_t column = offset + static_cast<std::size_t>(value.data() - field.data()) + 1;
      double x = 0.0;
      const auto [ptr, ec] = std::from_chars(value.data(), value.data() + value.size(), x);
      if (value.empty() || ec != std::errc() || ptr != value.data() + value.size() ||
          !std::isfinite(x)) {
        throw InputError(where + ":" + std::to_string(column),
                         "'" + std::string(value) + "' is not a finite number");
      }
      core::require_in(where + ":" + std::to_string(column), x, ranges::kResidualEntry);
      if (col < cols) {
        B(row, col) = x;
      }
      ++col;
      if (comma == std::string_view::npos) {
        break;
      }
      offset = comma + 1;
    }
    if (col != cols) {
      throw InputError(where, "row " + std::to_string(row + 1) + " has " + std::to_string(col) +
                                  " values; the robot's " + std::to_string(legs) + " legs need " +
                                  std::to_string(cols) + " (q̇_x, q̇_y of each leg)");
    }
    ++row;
    last_line = line_no;
  }
  if (row != 3) {
    throw InputError(file + ":" + std::to_string(std::max(last_line, 1LL)),
                     "B has 3 rows (v_x, v_y, omega), the file has " + std::to_string(row));
  }
  return B;
}

ResidualEffect read_residual(const TableReader& residual, const std::string& scene_path, int legs) {
  const toml::node& node = residual.required("file");
  const auto* name = node.as_string();
  if (name == nullptr) {
    residual.fail(node, "file",
                  std::string("expected a string (a file name), got ") + type_name(node));
  }
  std::filesystem::path path(name->get());
  if (path.is_relative()) {
    path = std::filesystem::path(scene_path).parent_path() / path;
  }
  std::string text;
  try {
    text = core::read_input_file(path, "a residual-term CSV file");
  } catch (const core::InputError& e) {
    residual.fail(node, "file", std::string("cannot read: ") + e.what());
  }
  ResidualEffect effect;
  effect.file = path.string();
  effect.B = parse_residual(text, effect.file, legs);
  return effect;
}

NoiseEffect read_noise(const TableReader& noise) {
  NoiseEffect effect;
  effect.sigma = noise.number_in(noise.required("sigma"), "sigma", ranges::kNoiseXY);
  noise.read_in("sigma_theta", ranges::kNoiseTheta, effect.sigma_theta);
  if (const toml::node* n = noise.find("seed")) {
    const long long seed = noise.integer(*n, "seed");
    noise.check(seed >= 0, *n, "seed", "must be >= 0, got " + std::to_string(seed));
    effect.seed = static_cast<std::uint64_t>(seed);
  }
  return effect;
}

}  // namespace slipwalk::scene
