#pragma once
// The stroke shared by both inchworm models (eqs. 2.1–2.3): the end mass x (mass m) is pushed by
// +F and the loaded end y (mass M) by −F in every stroke (F_t sgn(x − y) = F, §2.3), each with
// Coulomb friction and static friction as a mode; the stroke ends when x − y reaches L_max
// (extension) or −L_min (contraction). Written once here; InstantSwapSystem and MassSwapSystem
// differ only in what happens after the stroke.
#include <cstdint>

#include "events/hybrid_system.hpp"
#include "inchworm/params.hpp"

namespace slipwalk::inchworm {

class StrokeDynamics {
 public:
  /// Guard ids of a stroke, shared by both systems.
  enum GuardId : int {
    kSmallStops = 0,   ///< x's velocity reaches zero
    kLargeStops = 1,   ///< y's velocity reaches zero
    kLengthLimit = 2,  ///< x − y reaches L_max (extension) or −L_min (contraction)
  };

  explicit StrokeDynamics(const Params& p)
      : L_min_(p.L_min),
        L_max_(p.L_max),
        // Differences are formed before dividing so that F close to μmg keeps its digits.
        accel_x_{(p.F + p.mu * p.m * p.g) / p.m, 0.0, (p.F - p.mu * p.m * p.g) / p.m},
        accel_y_{-(p.F - p.mu * p.M * p.g) / p.M, 0.0, -(p.F + p.mu * p.M * p.g) / p.M},
        rest_x_(p.F > p.static_mu() * p.m * p.g ? 1 : 0),
        rest_y_(p.F > p.static_mu() * p.M * p.g ? -1 : 0) {}

  /// Accelerations by friction mode (slide: +1 forward, −1 backward, 0 stuck).
  [[nodiscard]] double accel_x(std::int8_t slide) const { return accel_x_[slide + 1]; }
  [[nodiscard]] double accel_y(std::int8_t slide) const { return accel_y_[slide + 1]; }
  /// The modes of x and y at rest: x breaks away forward if F > μ_s m g, y backward if
  /// F > μ_s M g; otherwise static friction holds them.
  [[nodiscard]] std::int8_t rest_x() const { return rest_x_; }
  [[nodiscard]] std::int8_t rest_y() const { return rest_y_; }
  /// y sliding back is driven back (accelerates backward) when F > μMg: two masses moving.
  [[nodiscard]] bool drives_y_back() const { return accel_y_[0] < 0.0; }

  /// Appends the stroke's guards to `f` from slot n (bodies 0 = x, 1 = y); returns the next slot.
  template <int N, int G>
  int add_guards(events::ModeFlow<N, G>& f, int n, std::int8_t slide_x, std::int8_t slide_y,
                 std::int8_t side) const {
    // A sliding mass's guard: its velocity reaches zero (g = −v·slide rises through 0).
    if (slide_x != 0) {
      auto& g = f.guard[n++];
      g.wv(0) = -slide_x;
      g.id = kSmallStops;
    }
    if (slide_y != 0) {
      auto& g = f.guard[n++];
      g.wv(1) = -slide_y;
      g.id = kLargeStops;
    }
    auto& g = f.guard[n++];
    g.wp(0) = 1.0;
    g.wp(1) = -1.0;
    g.w0 = side > 0 ? -L_max_ : L_min_;
    g.id = kLengthLimit;
    return n;
  }

 private:
  double L_min_;
  double L_max_;
  double accel_x_[3];  ///< x's acceleration when sliding backward, stuck, forward
  double accel_y_[3];  ///< y's acceleration likewise
  std::int8_t rest_x_;
  std::int8_t rest_y_;
};

}  // namespace slipwalk::inchworm
