// compose(): a scene to a simulator, assembled once. The walker comes from the robot factories;
// the trajectory kernel is one of the template instantiations of connection::integrate, picked
// here by the effects the scene names, so the per-step code has no branch for an effect that is
// off (DESIGN.md: Only the effects a scene calls for).
#include <utility>

#include "core/error.hpp"
#include "scene/scene.hpp"

namespace slipwalk::scene {

namespace {

/// The kernel for a law and a filter, both fixed from here on.
template <class Law, class Filter>
Simulator::Kernel kernel(Law law, Filter filter) {
  return [law, filter](const robots::Walker& w, const connection::TrajectoryOptions& options,
                       connection::TrajectoryData& data, const connection::TrajectorySink& sink) {
    return connection::integrate(w.robot, w.feet, options, law, filter, data, sink);
  };
}

template <class Law>
Simulator::Kernel with_filter(const Law& law, const std::optional<FilterEffect>& filter) {
  if (filter) {
    return kernel(law, connection::IirFilter{filter->gamma});
  }
  return kernel(law, connection::NoFilter{});
}

}  // namespace

robots::Walker make_walker(const Gait& gait) {
  return std::visit(
      [](const auto& g) -> robots::Walker {
        using G = std::decay_t<decltype(g)>;
        if constexpr (std::is_same_v<G, robots::TripodGait>) {
          return robots::bigant_tripod(g);
        } else if constexpr (std::is_same_v<G, robots::MetachronalGait>) {
          return robots::bigant_metachronal(g);
        } else if constexpr (std::is_same_v<G, robots::UndulationGait>) {
          return robots::multipod(g);
        } else if constexpr (std::is_same_v<G, robots::TrotGait>) {
          return robots::quadruped_trot(g);
        } else {
          return robots::disk_robot(g);
        }
      },
      gait);
}

connection::TrajectorySummary Simulator::run(const connection::TrajectorySink& sink) const {
  connection::TrajectoryData data(walker.robot);
  return kernel(walker, options, data, sink);
}

Simulator compose(const Scene& scene) {
  Simulator sim;
  try {
    sim.walker = make_walker(scene.gait);
  } catch (const core::InputError& e) {
    throw core::InputError(scene.gait_origin, e.what());
  }
  sim.options.dt = scene.dt;
  sim.options.steps = scene.steps;
  connection::validate(sim.options);
  if (scene.friction.law == connection::FrictionLaw::kCoulomb) {
    sim.kernel = with_filter(connection::CoulombKernel{scene.friction.coulomb}, scene.filter);
    sim.kernel_name = "coulomb";
  } else {
    sim.kernel = with_filter(connection::ViscousCoulombKernel{}, scene.filter);
    sim.kernel_name = "viscous";
  }
  if (scene.filter) {
    sim.kernel_name.append("+filter");
  }
  return sim;
}

}  // namespace slipwalk::scene
