#pragma once
// A trajectory kernel written by hand for one case only: flat ground, isotropic viscous-Coulomb
// friction, no filter, no residual, no noise. It is the yardstick of the "unused effects cost
// nothing" benchmark (tests/bench/bench_scene.cpp, the scene_cost point kind): the composed
// simulator of such a scene must run as fast as this, and must give the same numbers (the
// steps are connection::integrate's with every policy call replaced by what the off policy does).
#include "connection/trajectory.hpp"
#include "robots/walker.hpp"

namespace slipwalk::scene {

/// The plain loop: feet → spring support → viscous-Coulomb balance → slip → sink → advance.
connection::TrajectorySummary run_flat_viscous(const robots::Walker& walker,
                                               const connection::TrajectoryOptions& options,
                                               connection::TrajectoryData& data,
                                               const connection::TrajectorySink& sink);

}  // namespace slipwalk::scene
