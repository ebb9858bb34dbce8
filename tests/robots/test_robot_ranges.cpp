// The robot factories' option ranges, generated: every numeric option of every built-in robot
// takes every magnitude class (subnormal, tiny, zero, negative, huge, the largest double, inf,
// NaN) and seeded random magnitudes 10^-320..10^308. Each is either refused with an InputError
// naming the option whose message states the allowed interval, or gives a walker whose robot
// validates and whose feet stay finite and inside contact::limits over a cycle, and whose
// frames the model solves with finite outputs.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "connection/local_connection.hpp"
#include "contact/spring_support.hpp"
#include "core/error.hpp"
#include "robots/robots.hpp"

namespace slipwalk::robots {
namespace {

/// One numeric option: its name in messages and how to build a walker with it set to x.
struct Option {
  std::string name;
  std::function<Walker(double)> make;
};

std::vector<Option> options() {
  std::vector<Option> o;
  const auto tripod = [](double TripodGait::*field) {
    return [field](double x) {
      TripodGait g;
      g.*field = x;
      return bigant_tripod(g);
    };
  };
  o.push_back({"bigant_tripod.frequency", tripod(&TripodGait::frequency)});
  o.push_back({"bigant_tripod.steer", tripod(&TripodGait::steer)});
  o.push_back({"bigant_tripod.duty", tripod(&TripodGait::duty)});
  o.push_back({"bigant_tripod.sweep", tripod(&TripodGait::sweep)});
  const auto meta = [](double MetachronalGait::*field) {
    return [field](double x) {
      MetachronalGait g;
      g.*field = x;
      return bigant_metachronal(g);
    };
  };
  o.push_back({"bigant_metachronal.frequency", meta(&MetachronalGait::frequency)});
  o.push_back({"bigant_metachronal.sweep", meta(&MetachronalGait::sweep)});
  const auto pod = [](double UndulationGait::*field) {
    return [field](double x) {
      UndulationGait g;
      g.*field = x;
      return multipod(g);
    };
  };
  o.push_back({"multipod.dphi", pod(&UndulationGait::dphi)});
  o.push_back({"multipod.frequency", pod(&UndulationGait::frequency)});
  o.push_back({"multipod.roll_amplitude", pod(&UndulationGait::roll_amplitude)});
  o.push_back({"multipod.yaw_amplitude", pod(&UndulationGait::yaw_amplitude)});
  o.push_back({"multipod.stiffness", pod(&UndulationGait::stiffness)});
  const auto trot = [](double TrotGait::*field) {
    return [field](double x) {
      TrotGait g;
      g.*field = x;
      return quadruped_trot(g);
    };
  };
  o.push_back({"quadruped_trot.frequency", trot(&TrotGait::frequency)});
  o.push_back({"quadruped_trot.duty", trot(&TrotGait::duty)});
  o.push_back({"quadruped_trot.stride", trot(&TrotGait::stride)});
  o.push_back({"quadruped_trot.swing_height", trot(&TrotGait::swing_height)});
  const auto disk = [](double DiskGait::*field) {
    return [field](double x) {
      DiskGait g;
      g.*field = x;
      return disk_robot(g);
    };
  };
  o.push_back({"disk_robot.radius", disk(&DiskGait::radius)});
  o.push_back({"disk_robot.frequency", disk(&DiskGait::frequency)});
  return o;
}

std::vector<double> magnitudes() {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> m = {4.9e-324, -1e-320, 1e-30,  0.0, -0.0, -1.0,        0.05,
                           0.3,      0.55,    0.99,   1.0, 1.5,  100.0,       1e30,
                           -1e30,    1e308,   -1e308, inf, -inf, std::nan("")};
  std::mt19937_64 rng(15);
  std::uniform_int_distribution<int> exponent(-320, 308);
  for (int k = 0; k < 16; ++k) {
    m.push_back(std::pow(10.0, exponent(rng)) * (k % 2 ? -1.0 : 1.0));
  }
  return m;
}

TEST(RobotRanges, EveryOptionTimesEveryMagnitudeIsRefusedWithItsRangeOrWalksFinite) {
  int refused = 0;
  int built = 0;
  for (const Option& option : options()) {
    for (const double x : magnitudes()) {
      Walker w;
      try {
        w = option.make(x);
      } catch (const core::InputError& e) {
        ++refused;
        EXPECT_EQ(e.where(), option.name) << e.what();
        const std::string what = e.what();
        EXPECT_NE(what.find("must be in "), std::string::npos) << what;
        continue;
      }
      ++built;
      const std::string at = option.name + " = " + core::format_double(x);
      EXPECT_NO_THROW(contact::validate(w.robot)) << at;
      EXPECT_TRUE(std::isfinite(w.period) && w.period > 0.0) << at;
      contact::Frame f(w.robot);
      for (const double s : {0.0, 0.13, 0.5, 0.77}) {
        w.feet(s * w.period, f.q, f.qdot);
        ASSERT_NO_THROW(contact::check_frame(w.robot, f)) << at << " at " << s;
        connection::evaluate(w.robot, f, connection::FrictionLaw::kViscousCoulomb);
        EXPECT_NE(f.support.status, contact::SupportSummary::Status::kNonFinite) << at;
        EXPECT_TRUE(f.v_body.allFinite() && f.Fz.allFinite() && f.Fxy.allFinite()) << at;
      }
    }
  }
  EXPECT_GT(refused, 100);  // both outcomes are exercised
  EXPECT_GT(built, 50);
}

TEST(RobotRanges, MessagesStateTheIntervalAndTheUnit) {
  const auto message = [](const std::function<void()>& make) {
    try {
      make();
    } catch (const core::InputError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  TripodGait g;
  g.frequency = 1e-320;
  EXPECT_EQ(
      message([&] { (void)bigant_tripod(g); }),
      "bigant_tripod.frequency: must be in [1e-06, 1000] Hz, got " + core::format_double(1e-320));
  UndulationGait u;
  u.stiffness = 1e308;
  EXPECT_EQ(message([&] { (void)multipod(u); }),
            "multipod.stiffness: must be in [0.001, 1000000000] N/m, got 1e+308");
  TrotGait t;
  t.duty = 1.0;
  EXPECT_EQ(message([&] { (void)quadruped_trot(t); }),
            "quadruped_trot.duty: must be in [0.5, 1), got 1");
  DiskGait d;
  d.radius = std::nan("");
  EXPECT_EQ(message([&] { (void)disk_robot(d); }),
            "disk_robot.radius: must be in [0.01, 100] m, got nan");
}

}  // namespace
}  // namespace slipwalk::robots
