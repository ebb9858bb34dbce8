#pragma once
// Composing a trajectory's steps on SE(2): poses_0 = start, poses_{k+1} = poses_k · inc_k.
//
// The model of ch. 3 has no inertia, so the increments inc_k = exp(v_k dt) of a planned motion
// are known before any pose is (§3.5.3). Composition is associative, so the poses are a prefix
// product and can be computed in parallel (the thesis notes log₂N depth is possible but composed
// linearly). With N processors that is Blelloch's up-/down-sweep, depth 2 log₂N; with P ≪ N
// threads the work-efficient form is a blocked scan:
//   1. each block, in parallel: its local prefix product from the identity;
//   2. serially, over the B block totals: each block's offset (B compositions);
//   3. each block, in parallel: left-multiply its local products by its offset.
// Step 3 is much cheaper than step 1: the offset's rotation is computed once per block, so each
// pose costs four multiply-adds and no trigonometry, while a composition needs cos and sin of
// the running angle. Depth (in compositions) is about N/P + B.
//
// The blocks are fixed by the caller, not by the thread count, so the result is the same to the
// bit on any number of threads. It differs from the sequential product only by rounding (the
// tests hold both to 1e-12 over long random trajectories).
#include <algorithm>
#include <cmath>
#include <span>

#include "core/se2.hpp"
#include "core/worker_pool.hpp"

namespace slipwalk::core {

/// poses[0] = start, poses[k+1] = poses[k] · inc[k]; poses.size() must be inc.size() + 1.
inline void sequential_product(const Pose2& start, std::span<const Pose2> inc,
                               std::span<Pose2> poses) {
  poses[0] = start;
  for (std::size_t k = 0; k < inc.size(); ++k) {
    poses[k + 1] = compose(poses[k], inc[k]);
  }
}

/// The same poses by the blocked parallel prefix product over `blocks` blocks (≥ 1, clamped to
/// the number of increments) on the pool's threads; poses.size() must be inc.size() + 1.
inline void prefix_product(const Pose2& start, std::span<const Pose2> inc, std::span<Pose2> poses,
                           WorkerPool& pool, int blocks) {
  const auto n = static_cast<long long>(inc.size());
  poses[0] = start;
  if (n == 0) {
    return;
  }
  const long long b = std::clamp<long long>(blocks, 1, n);
  const auto first = [n, b](long long i) { return i * n / b; };  // block i: [first(i), first(i+1))
  // 1. Local products: poses[k + 1] = inc[lo] · … · inc[k] within each block.
  pool.run(static_cast<int>(b), [&](int i, int /*worker*/) {
    const long long lo = first(i), hi = first(i + 1);
    Pose2 p = inc[static_cast<std::size_t>(lo)];
    poses[static_cast<std::size_t>(lo + 1)] = p;
    for (long long k = lo + 1; k < hi; ++k) {
      p = compose(p, inc[static_cast<std::size_t>(k)]);
      poses[static_cast<std::size_t>(k + 1)] = p;
    }
  });
  // 2. Serially, block by block: the block's last entry becomes global (offset · local total);
  // it is the offset of the next block. The blocks' other entries are still local.
  Pose2 offset = start;
  for (long long i = 0; i < b; ++i) {
    const auto last = static_cast<std::size_t>(first(i + 1));
    offset = compose(offset, poses[last]);
    poses[last] = offset;
  }
  // 3. Each block's other entries: the global pose before the block times the local product.
  pool.run(static_cast<int>(b), [&](int i, int /*worker*/) {
    const long long lo = first(i), hi = first(i + 1);
    const Pose2 o = poses[static_cast<std::size_t>(lo)];  // global: start or previous block's end
    const double c = std::cos(o.theta), s = std::sin(o.theta);
    for (long long k = lo + 1; k < hi; ++k) {
      Pose2& p = poses[static_cast<std::size_t>(k)];
      p = {o.x + c * p.x - s * p.y, o.y + s * p.x + c * p.y, o.theta + p.theta};
    }
  });
}

}  // namespace slipwalk::core
