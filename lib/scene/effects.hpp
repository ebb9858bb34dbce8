#pragma once
// Readers of some effects of a scene (scene.hpp has the format): anisotropic friction's w,
// the residual B of §5.3.1 from its file, and the measurement noise. Used by scene.cpp; the
// residual file reader is public for tests and other users of B files.
#include <Eigen/Core>
#include <string>
#include <string_view>

#include "scene/scene.hpp"
#include "scene/toml_reader.hpp"

namespace slipwalk::scene {

/// [friction] w with law = "anisotropic" or "coulomb" (eq. 3.19, H ∝ I + w wᵀ in the body frame):
/// one pair [wx, wy] for every leg (2 x 1), or one pair per leg [[wx, wy], ...] (2 x legs).
[[nodiscard]] Eigen::Matrix2Xd read_anisotropy(const TableReader& friction, const toml::node& node,
                                               int legs);

/// A residual file (format in scene.hpp): 3 rows (v_x, v_y, ω) of 2·legs comma-separated numbers
/// (columns 2k, 2k + 1: leg k's q̇_x, q̇_y); '#' starts a comment, blank lines are skipped. Errors
/// name file:line (file:line:col for a bad number).
[[nodiscard]] Eigen::Matrix<double, 3, Eigen::Dynamic> parse_residual(std::string_view text,
                                                                      const std::string& file,
                                                                      int legs);

/// [residual] file = "B.csv" (relative to the scene's folder): reads and parses it.
[[nodiscard]] ResidualEffect read_residual(const TableReader& residual,
                                           const std::string& scene_path, int legs);

/// [noise] sigma (m, required), sigma_theta (rad, default 0), seed (integer ≥ 0, default 0).
[[nodiscard]] NoiseEffect read_noise(const TableReader& noise);

}  // namespace slipwalk::scene
