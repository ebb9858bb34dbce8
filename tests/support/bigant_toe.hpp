#pragma once
// The toe of BigANT's leg 0 relative to its crank pivot (every leg shares the linkage), for the
// tests of robots/bigant.hpp's linkages.
#include <Eigen/Core>

#include "robots/bigant.hpp"

namespace slipwalk::test_support {

/// Toe of leg 0 at φ (turns) relative to its crank pivot, m; dq/dφ into *d when given.
inline Eigen::Vector3d toe(const robots::BigAntLegs& legs, double phi,
                           Eigen::Vector3d* d = nullptr) {
  Eigen::Vector3d q;
  Eigen::Vector3d dq;
  robots::bigant_toe(legs, 0, phi, q, dq);
  if (d != nullptr) {
    *d = dq;
  }
  return q - legs.pivot.col(0);
}

}  // namespace slipwalk::test_support
