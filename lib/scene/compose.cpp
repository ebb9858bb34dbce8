// compose(): a scene to a simulator, assembled once. The walker comes from the robot factories;
// the trajectory kernel is connection::integrate for one Effects bundle, picked here by the
// effects the scene names: each effect becomes a std::variant of its policies (the first one is
// "off"), and one std::visit over all of them instantiates every bundle a scene can name, in this
// file only, and keeps the one this scene names. The per-step code then has no branch for an
// effect that is off (DESIGN.md: Only the effects a scene calls for).
#include <utility>
#include <variant>

#include "connection/trajectory_kernel.hpp"
#include "core/error.hpp"
#include "scene/scene.hpp"

namespace slipwalk::scene {

namespace {

using LawPolicy = std::variant<connection::ViscousCoulombKernel, connection::CoulombKernel>;
using FilterPolicy = std::variant<connection::NoFilter, connection::IirFilter>;
using ResidualPolicy = std::variant<connection::NoResidual, connection::LinearResidual>;
using NoisePolicy = std::variant<connection::NoNoise, connection::PoseNoise>;
using GroundPolicy =
    std::variant<connection::FlatGround, connection::SlopeGround, connection::StairsGround>;

GroundPolicy ground_policy(const terrain::Terrain& terrain) {
  if (const auto* slope = std::get_if<terrain::Slope>(&terrain)) {
    return connection::SlopeGround{*slope, {}, {}};
  }
  if (const auto* stairs = std::get_if<terrain::Stairs>(&terrain)) {
    return connection::StairsGround{*stairs, {}, {}};
  }
  return connection::FlatGround{};
}

LawPolicy law_policy(const FrictionEffect& friction) {
  if (friction.law == connection::FrictionLaw::kCoulomb) {
    return connection::CoulombKernel{friction.coulomb};
  }
  // Isotropic and anisotropic viscous-Coulomb are one solver: anisotropy is the robot's w.
  return connection::ViscousCoulombKernel{};
}

FilterPolicy filter_policy(const std::optional<FilterEffect>& filter) {
  if (filter) {
    return connection::IirFilter{filter->gamma};
  }
  return connection::NoFilter{};
}

ResidualPolicy residual_policy(const std::optional<ResidualEffect>& residual) {
  if (residual) {
    return connection::LinearResidual{residual->B};
  }
  return connection::NoResidual{};
}

NoisePolicy noise_policy(const std::optional<NoiseEffect>& noise) {
  if (noise) {
    connection::PoseNoise p;
    p.sigma_xy = noise->sigma;
    p.sigma_theta = noise->sigma_theta;
    p.seed = noise->seed;
    return p;
  }
  return connection::NoNoise{};
}

/// The kernel of one bundle: the policies are copied in, and integrate() copies them per run
/// (their state starts fresh every run).
template <class E>
Simulator::Kernel kernel_of(E effects) {
  return [effects](const robots::Walker& w, const connection::TrajectoryOptions& options,
                   connection::TrajectoryData& data, const connection::TrajectorySink& sink) {
    return connection::integrate(w.robot, w.feet, options, effects, data, sink);
  };
}

}  // namespace

Simulator::Kernel compose_kernel(const Scene& scene) {
  return std::visit(
      [](auto law, auto filter, auto residual, auto noise, auto ground) {
        return kernel_of(connection::Effects<decltype(law), decltype(filter), decltype(residual),
                                             decltype(noise), decltype(ground)>{
            law, filter, residual, noise, ground});
      },
      law_policy(scene.friction), filter_policy(scene.filter), residual_policy(scene.residual),
      noise_policy(scene.noise), ground_policy(scene.terrain));
}

std::string kernel_name(const Scene& scene) {
  std::string name = scene.friction.law == connection::FrictionLaw::kCoulomb ? "coulomb"
                     : scene.friction.anisotropic                            ? "anisotropic"
                                                                             : "viscous";
  if (scene.filter) {
    name.append("+filter");
  }
  if (scene.residual) {
    name.append("+residual");
  }
  if (scene.noise) {
    name.append("+noise");
  }
  if (scene.terrain.index() != 0) {
    name.append("+").append(terrain::kind_name(scene.terrain));
  }
  return name;
}

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
        } else if constexpr (std::is_same_v<G, LegTableGait>) {
          return leg_table_walker(g);
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
  if (scene.friction.anisotropic) {
    // One w for every leg, or one per leg (the reader checked the count).
    contact::Robot& r = sim.walker.robot;
    if (scene.friction.w.cols() == 1) {
      r.w = scene.friction.w.replicate(1, r.legs());
    } else {
      r.w = scene.friction.w;
    }
    contact::validate(r);
  }
  sim.options.dt = scene.dt;
  sim.options.steps = scene.steps;
  connection::validate(sim.options);
  sim.kernel = compose_kernel(scene);
  sim.kernel_name = kernel_name(scene);
  return sim;
}

}  // namespace slipwalk::scene
