// One frame of the multi-legged model (Alg. 1): spring support, local connection, friction law.
// Kept apart from local_connection.cpp so that code using only the connection does not link the
// spring-support search.
#include <algorithm>

#include "connection/local_connection.hpp"
#include "friction/viscous_batch.hpp"

namespace slipwalk::connection {

namespace {

// Steps 2 and 3 of a frame whose spring support is done.
void connection_and_balance(const contact::Robot& robot, contact::Frame& frame, FrictionLaw law,
                            friction::FeetSource feet) {
  // 2. The viscous system M x = −b of eq. 3.20, assembled and factorized once: it gives the local
  //    connection A whatever the law, and the viscous-Coulomb velocity.
  const friction::ViscousSystem system(robot, frame, feet);
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

}  // namespace

void evaluate(const contact::Robot& robot, contact::Frame& frame, FrictionLaw law,
              const contact::SupportOptions& support) {
  // 1. Which feet touch and what they carry (§3.3).
  contact::spring_support(robot, frame, support);
  // The system reads the feet from the rows the support just left (the same values, padded).
  connection_and_balance(robot, frame, law, friction::FeetSource::kSupportRows);
}

void evaluate_batch(const contact::Robot& robot, std::span<contact::Frame> frames, FrictionLaw law,
                    contact::BatchScratch& scratch) {
  constexpr std::size_t kGroup = 4;
  for (std::size_t at = 0; at < frames.size(); at += kGroup) {
    // Group by group, so that a group's feet are still in the cache for its second stage.
    const std::span<contact::Frame> group =
        frames.subspan(at, std::min(kGroup, frames.size() - at));
    contact::spring_support_batch(robot, group, scratch);
    unsigned solved = 0;
    if (law == FrictionLaw::kViscousCoulomb) {
      contact::Frame* lanes[kGroup];
      for (std::size_t i = 0; i < kGroup; ++i) {
        lanes[i] = &group[std::min(i, group.size() - 1)];
      }
      solved = friction::solve_viscous_coulomb_group(robot, lanes, static_cast<int>(group.size()),
                                                     scratch);
    }
    for (std::size_t i = 0; i < group.size(); ++i) {
      if ((solved >> i & 1U) == 0) {
        // The batched support leaves its rows in the scratch, not in frame.support_newton.
        connection_and_balance(robot, group[i], law, friction::FeetSource::kFrame);
      }
    }
  }
}

}  // namespace slipwalk::connection
