// One frame of the multi-legged model (Alg. 1): spring support, local connection, friction law.
// Kept apart from local_connection.cpp so that code using only the connection does not link the
// spring-support search.
#include "connection/local_connection.hpp"

namespace slipwalk::connection {

void evaluate(const contact::Robot& robot, contact::Frame& frame, FrictionLaw law,
              const contact::SupportOptions& support) {
  // 1. Which feet touch and what they carry (§3.3).
  contact::spring_support(robot, frame, support);
  // 2. The viscous system M x = −b of eq. 3.20, assembled and factorized once: it gives the local
  //    connection A whatever the law, and the viscous-Coulomb velocity. It reads the feet from the
  //    rows the support just left (the same values, padded).
  const friction::ViscousSystem system(robot, frame, friction::FeetSource::kSupportRows);
  local_connection(robot, frame, system);
  // 3. The friction law's balance: body velocity, foot forces, summary (§3.4).
  switch (law) {
    case FrictionLaw::kViscousCoulomb:
      friction::solve_viscous_coulomb(robot, frame, system);
      break;
    case FrictionLaw::kCoulomb:
      friction::solve_coulomb(robot, frame);
      break;
  }
}

}  // namespace slipwalk::connection
