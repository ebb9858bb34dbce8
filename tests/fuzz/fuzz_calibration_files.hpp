#pragma once
// The geometry the calibration files' fuzz targets read against: two legs, L and R, so that a
// short input can name every column.
#include <Eigen/Core>

#include "calibration/model.hpp"
#include "calibration/wrench.hpp"

namespace slipwalk::fuzz {

inline calibration::Geometry fuzz_calibration_geometry() {
  calibration::Geometry g;
  g.legs = {"L", "R"};
  g.transducer.push_back({Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.3, 0.2, 0.04)});
  g.transducer.push_back({calibration::rotation_from_vector(Eigen::Vector3d(0.0, 0.0, 3.0)),
                          Eigen::Vector3d(0.3, -0.2, 0.04)});
  g.robot_weight = 80.0;
  return g;
}

}  // namespace slipwalk::fuzz
