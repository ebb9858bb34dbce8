#include "sweeps/points/families.hpp"

#include <utility>

namespace slipwalk::sweeps::points {

std::span<const PointKind> all_kinds() {
  // An explicit list: static self-registration would be dropped by the linker from a static
  // library whose object nothing else references.
  static const std::vector<PointKind> kinds = [] {
    std::vector<PointKind> all;
    for (auto family :
         {inchworm_kinds, legged_law_kinds, legged_frame_kinds, legged_cost_kinds, peer_kinds,
          peer_bigant_kinds, peer_terrain_kinds, plan_replay_kinds, scene_cost_kinds, slope_kinds,
          planning_kinds, planning_cost_kinds, coulomb_long_run_kinds, residual_kinds,
          calibration_kinds, hostile_input_kinds, scale_out_kinds, machine_limit_kinds}) {
      for (PointKind& kind : family()) {
        all.push_back(std::move(kind));
      }
    }
    return all;
  }();
  return kinds;
}

PreparedSweep prepare(Spec spec) { return sweeps::prepare(std::move(spec), all_kinds()); }

}  // namespace slipwalk::sweeps::points
