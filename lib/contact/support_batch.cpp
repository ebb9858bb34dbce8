// The batched Newton route of the spring support (support_batch.hpp): support_newton.cpp's
// all-feet start, steps and certificate, four frames at a time with frame i in lane i. The
// arithmetic of a step is that route's, lane by lane; what differs is the order of the sums (foot
// after foot here, four feet per lane and then across the lanes there), hence the last bits.
//
// A lane stops stepping where its frame is certified (its outputs are written at once) or where
// it cannot go on (a cell that is not safely definite: the one-frame route tilts there; a NaN or
// out-of-range start; kMaxSteps steps); the other lanes step on, the stopped lane's state frozen
// (its step masked to zero). A group costs its slowest frame's steps, so the lanes' spare steps
// are the price of the shared ones; frames not certified are solved again by spring_support.
// Termination: at most kMaxSteps passes per group.
//
// The start is the all-feet cell at every leg count, also where the one-frame route starts from
// the level body (from 20 legs, support_newton.cpp): the batch takes more steps there (2.45 per
// frame at 20 legs, 2.9 at 50, against 1.7–1.8) but each costs less. On the cost study's disks
// (three runs) it took 0.54–0.65 of the one-frame support's time at 16 legs, 0.66–0.67 at 20,
// 0.71–0.74 at 24, 0.76–0.89 at 32 and 0.74–1.02 at 50. On bench_friction's disks, whose feet
// are all near the ground (4.0 all-feet steps at 24 legs, 4.7 at 50, against 2.4 from the level
// start), it is on par from 24 legs (one run: 0.98 at 24, 1.00 at 50; 0.64 at 12, 0.58 at 6). A
// level start of its own is left for when the many-legged robots need it.
#include "contact/support_batch.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "contact/spring_support.hpp"
#include "contact/support_newton.hpp"
#include "core/lanes.hpp"

namespace slipwalk::contact {

BatchScratch::BatchScratch(int legs)
    : qy(4, legs),
      minus_qx(4, legs),
      qz(4, legs),
      on(4, legs),
      Fz(4, legs),
      x(4, legs),
      y(4, legs),
      dx(4, legs),
      dy(4, legs),
      c(4, legs) {}

namespace {

using L = core::Lanes<4>;
using V = L::V;
using M = L::M;
using detail::kEps;
using detail::kInf;
using detail::kMaxSteps;
using detail::kNearPlane;
using detail::kPolished;
using detail::kRoundingCap;
constexpr int kLanes = 4;

// The sums of one pass, lane i those of frame i (support_newton.cpp's Sums without the reduction).
struct Sums {
  V k{}, y{}, x{}, yy{}, yx{}, xx{}, gy{}, gx{}, gz{};
  M changes{};  // minus the count of feet whose flag changed
};

[[gnu::always_inline]] inline V max_of(V a, V b) { return a < b ? b : a; }

// The feet of the four frames in the scratch, foot-major (column j: foot j of each lane).
struct Feet {
  const double* qy;
  const double* minus_qx;
  const double* qz;
  std::int64_t* on;
  const double* K;
  int n;
};

// One pass at the lanes' states (v0, v1, v2) = (α, β, z): the feet with h_j < threshold make each
// lane's cell (support_newton.cpp's pass()).
[[gnu::always_inline]] inline Sums pass(const Feet& F, V v0, V v1, V v2, V threshold) {
  Sums s;
  for (std::ptrdiff_t j = 0; j < F.n; ++j) {
    const V y = L::load(F.qy + kLanes * j);
    const V x = L::load(F.minus_qx + kLanes * j);
    const V h = y * v0 + x * v1 + (L::load(F.qz + kLanes * j) + v2);
    const M touching = h < threshold;
    s.changes += touching ^ L::load(F.on + kLanes * j);
    L::store(F.on + kLanes * j, touching);
    detail::accumulate_cell(s, L::select(touching, L::splat(F.K[j])), y, x, h);
  }
  return s;
}

// The Newton step −H⁻¹ g of every lane's cell (support_newton.hpp's cell_newton_step, lane by
// lane), and the lanes whose cell is safely definite.
[[gnu::always_inline]] inline M newton_step(const Sums& s, V Mg, V il, V& d0, V& d1, V& d2) {
  return detail::cell_newton_step(s.yy, s.yx, s.xx, s.y, s.x, s.k, s.gy, s.gx, s.gz + Mg, il, d0,
                                  d1, d2);
}

// The loads of eq. 3.7 at the lanes' states, F_z = −K h for the feet of the last pass's contact
// sets, into Fz (4 × n, foot-major), and the lanes with a foot within `margin` of its plane
// (support_newton.cpp's loads_unless_near: h² ≤ margin², either side).
[[gnu::always_inline]] inline M loads(const Feet& F, V v0, V v1, V v2, V margin, double* Fz) {
  M near{};
  for (std::ptrdiff_t j = 0; j < F.n; ++j) {
    const V h = L::load(F.qy + kLanes * j) * v0 + L::load(F.minus_qx + kLanes * j) * v1 +
                (L::load(F.qz + kLanes * j) + v2);
    near |= h * h <= margin * margin;
    L::store(Fz + kLanes * j, L::select(L::load(F.on + kLanes * j), -L::splat(F.K[j]) * h));
  }
  return near;
}

// What a certified lane writes into its frame: the contact flags, the loads and the summary.
struct LaneResult {
  double alpha, beta, z, residual;
  int changes, steps;
};

void write_lane(const Feet& F, const double* Fz, int lane, const LaneResult& r, Frame& frame) {
  char* const contact = frame.contact.data();
  double* const loads = frame.Fz.data();
  for (std::ptrdiff_t j = 0; j < F.n; ++j) {
    contact[j] = F.on[kLanes * j + lane] != 0 ? 1 : 0;
    loads[j] = Fz[kLanes * j + lane];
  }
  frame.alpha = r.alpha;
  frame.beta = r.beta;
  frame.z = r.z;
  SupportSummary& summary = frame.support;
  summary.status = SupportSummary::Status::kBalanced;
  summary.route = SupportSummary::Route::kNewton;
  summary.iterations = r.changes;
  summary.newton_steps = r.steps;
  summary.residual = r.residual;
  summary.message.clear();
}

// The Newton route of up to four frames (lanes ≥ m repeat frame 0 and write nothing). Returns the
// certified lanes as bits.
SLIPWALK_CLONES unsigned support_group(const Robot& robot, Frame* const* frames, int m,
                                       BatchScratch& S) {
  const int n = robot.legs();
  const Feet F{S.qy.data(), S.minus_qx.data(), S.qz.data(), S.on.data(), robot.K.data(), n};
  const double* q[kLanes];
  for (int i = 0; i < kLanes; ++i) {
    q[i] = frames[i < m ? i : 0]->q.data();
  }
  // ---- the feet into the lanes, and the all-feet start cell at v = 0 (h = q_z, weight K) ------
  double* const qy = S.qy.data();
  double* const minus_qx = S.minus_qx.data();
  double* const qz = S.qz.data();
  Sums start;
  V max_y{};
  V max_x{};
  V max_z{};
  V max_r2{};
  for (std::ptrdiff_t j = 0; j < n; ++j) {
    const std::ptrdiff_t c = 3 * j;
    const V x{q[0][c], q[1][c], q[2][c], q[3][c]};
    const V y{q[0][c + 1], q[1][c + 1], q[2][c + 1], q[3][c + 1]};
    const V z{q[0][c + 2], q[1][c + 2], q[2][c + 2], q[3][c + 2]};
    const V minus_x = -x;
    const V k = L::splat(F.K[j]);
    L::store(qy + kLanes * j, y);
    L::store(minus_qx + kLanes * j, minus_x);
    L::store(qz + kLanes * j, z);
    L::store(F.on + kLanes * j, k > 0.0);
    max_y = max_of(max_y, L::abs(y));
    max_x = max_of(max_x, L::abs(x));
    max_z = max_of(max_z, L::abs(z));
    max_r2 = max_of(max_r2, x * x + y * y);
    detail::accumulate_cell(start, k, y, minus_x, z);
  }
  V size_L{};
  for (int i = 0; i < kLanes; ++i) {
    size_L[i] = max_r2[i] > 0.0 ? std::sqrt(max_r2[i]) : 1.0;
  }
  const V il = 1.0 / size_L;
  const V Mg = L::splat(robot.Mg);
  const double inv_mg = 1.0 / robot.Mg;
  // support_by_newton's range test of q (the outputs are certified only for feet within
  // limits::kPosition) and its NaN test on the start cell's sums (0 · NaN is NaN).
  const V size = max_of(max_of(max_y, max_x), max_z);
  const V sums = start.y + start.x + (start.gz + Mg);
  M active = (size <= limits::kPosition.hi) & (sums == sums) & (M{0, 1, 2, 3} < m);

  // ---- Newton steps, every lane until its contact set repeats and its gradient vanishes -------
  Sums s = start;
  V v0{};
  V v1{};
  V v2{};
  V last = L::splat(kInf);  // the residual after the lane's previous step, if it was settled
  M changes{};
  M steps{};
  unsigned certified = 0;
  for (int step = 1; step <= kMaxSteps && core::any(active); ++step) {
    V d0;
    V d1;
    V d2;
    active &= newton_step(s, Mg, il, d0, d1, d2);  // not definite: spring_support tilts there
    v0 += L::select(active, d0);
    v1 += L::select(active, d1);
    v2 += L::select(active, d2);
    steps -= active;
    const V noise = 4.0 * kEps * (max_z + L::abs(v2) + L::abs(v0) * max_y + L::abs(v1) * max_x);
    s = pass(F, v0, v1, v2, -noise);
    changes += s.changes & active;
    const M settled = s.changes == 0;
    const V g = L::abs(s.gz + Mg);
    const V r = max_of(max_of(g, L::abs(s.gy) * il), L::abs(s.gx) * il) * inv_mg;
    const M done =
        active & settled & ((r <= kPolished) | ((r >= 0.5 * last) & (r <= kRoundingCap)));
    last = settled ? r : L::splat(kInf);
    if (core::any(done)) {
      // A foot at its plane (not strictly complementary): the tie is the path search's.
      const M near = loads(F, v0, v1, v2, kNearPlane * noise, S.Fz.data());
      for (int i = 0; i < m; ++i) {
        if (done[i] != 0 && near[i] == 0) {
          write_lane(F, S.Fz.data(), i,
                     LaneResult{v0[i], v1[i], v2[i], r[i], static_cast<int>(-changes[i]),
                                static_cast<int>(steps[i])},
                     *frames[i]);
          certified |= 1U << static_cast<unsigned>(i);
        }
      }
      active &= ~done;
    }
  }
  return certified;
}

}  // namespace

void spring_support_batch(const Robot& robot, std::span<Frame> frames, BatchScratch& scratch) {
  if (!scratch.holds(robot.legs())) {
    scratch = BatchScratch(robot.legs());
  }
  for (std::size_t at = 0; at < frames.size(); at += kLanes) {
    const int m = static_cast<int>(std::min<std::size_t>(kLanes, frames.size() - at));
    Frame* group[kLanes];
    for (int i = 0; i < kLanes; ++i) {
      group[i] = &frames[at + static_cast<std::size_t>(i < m ? i : 0)];
    }
    for (int i = 0; i < m; ++i) {
      check_frame_except_positions(robot, *group[i]);  // sizes, before the rows are read
    }
    const unsigned certified = support_group(robot, group, m, scratch);
    for (int i = 0; i < m; ++i) {
      if ((certified >> static_cast<unsigned>(i) & 1U) == 0) {
        spring_support(robot, *group[i]);  // the one-frame route: a tilt, a tie, Alg. 1
      }
    }
  }
}

}  // namespace slipwalk::contact
