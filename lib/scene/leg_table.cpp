// The leg-table walker (leg_table.hpp).
#include "scene/leg_table.hpp"

#include <cmath>
#include <numbers>

#include "core/csv.hpp"
#include "core/error.hpp"
#include "scene/ranges.hpp"

namespace slipwalk::scene {

namespace {

void require(bool ok, const std::string& field, const std::string& what) {
  if (!ok) {
    throw core::InputError("leg_table." + field, what);
  }
}

}  // namespace

robots::Walker leg_table_walker(const LegTableGait& g) {
  const int n = static_cast<int>(g.legs.size());
  require(n >= 3, "leg", "needs at least 3 legs, got " + std::to_string(n));
  require(g.mass > 0.0 && std::isfinite(g.mass), "mass",
          "must be > 0 kg, got " + core::format_double(g.mass));
  require(g.frequency > 0.0 && std::isfinite(g.frequency), "frequency",
          "must be > 0 Hz, got " + core::format_double(g.frequency));
  require(g.stride > 0.0 && std::isfinite(g.stride), "stride",
          "must be > 0 m, got " + core::format_double(g.stride));
  require(g.height > 0.0 && std::isfinite(g.height), "height",
          "must be > 0 m, got " + core::format_double(g.height));
  require(g.lift >= 0.0 && std::isfinite(g.lift), "lift",
          "must be >= 0 m, got " + core::format_double(g.lift));
  robots::Walker w;
  w.name = "leg_table" + std::to_string(n);
  w.robot.K.resize(n);
  w.robot.mu.resize(n);
  w.robot.w = Eigen::Matrix2Xd::Zero(2, n);
  w.robot.Mg = g.mass * kGravity;
  Eigen::Matrix3Xd hips(3, n);
  Eigen::VectorXd phases(n);
  for (int k = 0; k < n; ++k) {
    const LegSpec& leg = g.legs[static_cast<std::size_t>(k)];
    require(leg.phase >= 0.0 && leg.phase < 1.0, "phase",
            "must be in [0, 1), got " + core::format_double(leg.phase));
    w.robot.K(k) = leg.K;
    w.robot.mu(k) = leg.mu;
    hips.col(k) = leg.hip;
    phases(k) = leg.phase;
    w.leg_names.push_back(leg.name.empty() ? std::to_string(k) : leg.name);
  }
  contact::validate(w.robot);
  w.period = 1.0 / g.frequency;
  const double omega = 2.0 * std::numbers::pi * g.frequency;
  const double half = 0.5 * g.stride;
  const double height = g.height;
  const double lift = g.lift;
  const double f = g.frequency;
  w.feet = [hips, phases, omega, half, height, lift](double t, Eigen::Matrix3Xd& q,
                                                     Eigen::Matrix3Xd& qdot) {
    for (Eigen::Index k = 0; k < hips.cols(); ++k) {
      const double phi = omega * t + 2.0 * std::numbers::pi * phases(k);
      const double s = std::sin(phi);
      const double c = std::cos(phi);
      const bool swing = s > 0.0;
      q(0, k) = hips(0, k) - half * c;
      q(1, k) = hips(1, k);
      q(2, k) = hips(2, k) - height + (swing ? lift * s : 0.0);
      qdot(0, k) = half * omega * s;
      qdot(1, k) = 0.0;
      qdot(2, k) = swing ? lift * omega * c : 0.0;
    }
  };
  w.phase = [phases, f](double t, Eigen::VectorXd& phase) {
    for (Eigen::Index k = 0; k < phases.size(); ++k) {
      const double p = f * t + phases(k);
      phase(k) = p - std::floor(p);
    }
  };
  return w;
}

LegTableGait read_leg_table(const TableReader& robot, const TableReader& gait,
                            const std::string& path, const std::vector<TableSchema>& all) {
  static const TableSchema leg_schema = {"robot.leg", {"name", "hip", "K", "mu", "phase"}};
  LegTableGait g;
  const toml::node& mass = robot.required("mass");
  g.mass = robot.number_in(mass, "mass", ranges::kMass);
  const toml::node* legs = robot.find("leg");
  if (legs == nullptr) {
    throw core::InputError(robot.origin(),
                           "missing required [[robot.leg]] tables (one per leg) for name = 'legs'");
  }
  const toml::array* list = legs->as_array();
  if (list == nullptr || !list->is_array_of_tables()) {
    robot.fail(*legs, "leg", std::string("expected [[robot.leg]] tables, got ") + type_name(*legs));
  }
  robot.check(list->size() >= 3 && list->size() <= 1000, *legs, "leg",
              "needs 3 to 1000 legs, got " + std::to_string(list->size()));
  for (const toml::node& node : *list) {
    const TableReader leg(*node.as_table(), leg_schema, path, all);
    LegSpec spec;
    if (const toml::node* n = leg.find("name")) {
      const auto* s = n->as_string();
      if (s == nullptr || s->get().empty()) {
        leg.fail(*n, "name", std::string("expected a non-empty string, got ") + type_name(*n));
      }
      for (const LegSpec& other : g.legs) {
        leg.check(other.name != s->get(), *n, "name", "'" + s->get() + "' names two legs");
      }
      spec.name = s->get();
    } else {
      spec.name = std::to_string(g.legs.size());
    }
    const toml::node& hip = leg.required("hip");
    const toml::array* xyz = hip.as_array();
    if (xyz == nullptr || xyz->size() != 3) {
      leg.fail(
          hip, "hip",
          std::string("expected [x, y, z] in m, got ") +
              (xyz != nullptr ? "an array of " + std::to_string(xyz->size()) : type_name(hip)));
    }
    for (int i = 0; i < 3; ++i) {
      spec.hip(i) =
          leg.number_in(*xyz->get(static_cast<std::size_t>(i)), "hip", ranges::kCoordinate);
    }
    spec.K = leg.number_in(leg.required("K"), "K", ranges::kStiffness);
    if (const toml::node* mu = leg.find("mu")) {
      spec.mu = leg.number_in(*mu, "mu", ranges::kFrictionCoefficient);
      leg.check(spec.mu == 0.0 || contact::limits::kFriction.contains(spec.mu), *mu, "mu",
                "must be 0 or in " + contact::limits::kFriction.describe() + ", got " +
                    core::format_double(spec.mu));
    }
    leg.read_in("phase", ranges::kPhase, spec.phase);
    g.legs.push_back(spec);
  }
  gait.read_in("frequency", ranges::kFrequency, g.frequency);
  gait.read_in("stride", ranges::kLength, g.stride);
  gait.read_in("height", ranges::kLength, g.height);
  gait.read_in("lift", ranges::kLengthOrZero, g.lift);
  return g;
}

}  // namespace slipwalk::scene
