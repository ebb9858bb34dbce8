// compose(): a scene to a simulator, assembled once. The walker comes from the gait's table entry
// (gaits.hpp); the trajectory kernel is connection::integrate for one Effects bundle, picked here
// by the effects the scene names: each effect becomes a std::variant of its policies (the first
// one is "off"; the friction law's come from its table entry, friction_laws.hpp), and one
// std::visit over all of them instantiates every bundle a scene can name, in this file only, and
// keeps the one this scene names. The per-step code then has no branch for an
// effect that is off (DESIGN.md: Only the effects a scene calls for).
#include <utility>
#include <variant>

#include "connection/trajectory_kernel.hpp"
#include "core/error.hpp"
#include "scene/friction_laws.hpp"
#include "scene/scene.hpp"

namespace slipwalk::scene {

namespace {

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
      friction_law_of(scene.friction).policy(scene.friction), filter_policy(scene.filter),
      residual_policy(scene.residual), noise_policy(scene.noise), ground_policy(scene.terrain));
}

std::string kernel_name(const Scene& scene) {
  std::string name(friction_law_of(scene.friction).name);
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
  friction_law_of(scene.friction).fit_robot(scene.friction, sim.walker.robot);
  sim.options.dt = scene.dt;
  sim.options.steps = scene.steps;
  connection::validate(sim.options);
  sim.kernel = compose_kernel(scene);
  sim.kernel_name = kernel_name(scene);
  return sim;
}

}  // namespace slipwalk::scene
