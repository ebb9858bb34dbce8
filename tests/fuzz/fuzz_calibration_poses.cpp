// Fuzz target: a standing-poses CSV file (calibration::parse_poses against a two-leg geometry).
// An accepted file gives finite poses of the geometry's widths whose attitudes are rotations,
// and reads back the same after writing (the attitudes to rounding).
#include <cmath>
#include <sstream>
#include <string>

#include "calibration/files.hpp"
#include "core/error.hpp"
#include "fuzz/fuzz_calibration_files.hpp"
#include "fuzz/fuzz_target.hpp"

namespace slipwalk::fuzz {

Outcome calibration_poses(std::string_view bytes) {
  const calibration::Geometry g = fuzz_calibration_geometry();
  calibration::StandingPoses poses;
  try {
    poses = calibration::parse_poses(bytes, "fuzz_poses.csv", g);
  } catch (const core::InputError&) {
    return Outcome::kRejected;
  }
  const Eigen::Index n = poses.poses();
  require(n > 0 && poses.phi.cols() == 2 && poses.wrench.cols() == 12 && poses.wrench.rows() == n,
          "accepted poses have the geometry's widths");
  require(static_cast<Eigen::Index>(poses.attitude.size()) == n &&
              static_cast<Eigen::Index>(poses.rows.size()) == n,
          "an attitude and a row per pose");
  require(poses.phi.allFinite() && poses.wrench.allFinite(), "accepted poses are finite");
  for (const Eigen::Matrix3d& R : poses.attitude) {
    require((R.transpose() * R - Eigen::Matrix3d::Identity()).norm() <= 1e-12 &&
                std::abs(R.determinant() - 1.0) <= 1e-12,
            "an accepted attitude is a rotation");
  }
  std::ostringstream out;
  calibration::write_poses(out, poses, g);
  const calibration::StandingPoses back = calibration::parse_poses(out.str(), "written.csv", g);
  require(back.poses() == n && back.phi == poses.phi && back.wrench == poses.wrench,
          "the written file reads back bit for bit");
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    require((back.attitude[k] - poses.attitude[k]).norm() <= 1e-14,
            "a written attitude reads back to rounding");
  }
  return Outcome::kAccepted;
}

}  // namespace slipwalk::fuzz

SLIPWALK_FUZZ_ENTRY(calibration_poses)
