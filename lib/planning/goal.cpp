#include "planning/goal.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace slipwalk::planning {

namespace {

void require_finite(const std::string& where, double value) {
  if (!std::isfinite(value)) {
    throw core::InputError(where, "must be a finite number");
  }
}

void require_finite(const std::string& where, const core::Pose2& p) {
  require_finite(where + ".x", p.x);
  require_finite(where + ".y", p.y);
  require_finite(where + ".theta", p.theta);
}

}  // namespace

void validate(const Goal& goal) {
  require_finite("goal.start", goal.start);
  for (int k = 0; k < 3; ++k) {
    require_finite("goal.twist[" + std::to_string(k) + "]", goal.twist(k));
  }
  if (goal.times.empty() && goal.waypoints.empty()) {
    return;
  }
  if (goal.times.size() != goal.waypoints.size()) {
    throw core::InputError("goal.waypoints", std::to_string(goal.times.size()) + " times but " +
                                                 std::to_string(goal.waypoints.size()) + " poses");
  }
  if (goal.times.size() < 2) {
    throw core::InputError("goal.waypoints", "needs at least two waypoints");
  }
  for (std::size_t k = 0; k < goal.times.size(); ++k) {
    const std::string where = "goal.waypoints[" + std::to_string(k) + "]";
    require_finite(where + ".t", goal.times[k]);
    require_finite(where, goal.waypoints[k]);
    if (k > 0 && !(goal.times[k] > goal.times[k - 1])) {
      throw core::InputError(where + ".t", "times must increase strictly");
    }
  }
}

Goal thesis_goal(std::string_view name) {
  for (const NamedTwist& g : kThesisGoals) {
    if (g.name == name) {
      Goal goal;
      goal.twist = {g.vx, g.vy, g.omega};
      return goal;
    }
  }
  throw core::InputError("goal",
                         "expected straight, turn or diagonal, got '" + std::string(name) + "'");
}

core::Pose2 target_at(const Goal& goal, double t) {
  if (goal.times.empty()) {
    return core::advance(goal.start, goal.twist, t);
  }
  const auto& ts = goal.times;
  if (t <= ts.front()) {
    return goal.waypoints.front();
  }
  if (t >= ts.back()) {
    return goal.waypoints.back();
  }
  const auto hi = static_cast<std::size_t>(std::upper_bound(ts.begin(), ts.end(), t) - ts.begin());
  const std::size_t lo = hi - 1;
  const double u = (t - ts[lo]) / (ts[hi] - ts[lo]);
  const core::Pose2& a = goal.waypoints[lo];
  const core::Pose2& b = goal.waypoints[hi];
  return {a.x + u * (b.x - a.x), a.y + u * (b.y - a.y), a.theta + u * (b.theta - a.theta)};
}

}  // namespace slipwalk::planning
