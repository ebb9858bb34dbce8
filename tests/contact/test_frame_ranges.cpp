// The frame format's physical ranges (contact::limits), generated: every numeric field of a frame
// file takes every magnitude class (subnormal, tiny, zero, negative, huge, the largest doubles,
// numbers that overflow a double) and seeded random magnitudes 10^-320..10^308. Each value is
// either refused with an InputError at the value's own file:line:col whose message names the
// field and states the range, or the frame is solved with finite outputs under both friction
// laws; never a non-finite result reported as a balance or as converged.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "connection/local_connection.hpp"
#include "contact/frame_json.hpp"
#include "contact/robot.hpp"
#include "contact/spring_support.hpp"
#include "core/csv.hpp"
#include "core/error.hpp"

namespace slipwalk::contact {
namespace {

using Status = SupportSummary::Status;

/// One numeric field of the frame format: its key, how many numbers a leg has (0: one number
/// for the whole frame), its range and whether 0 is admitted besides (μ).
struct Field {
  const char* key;
  int width;
  core::Range range;
  bool zero_too = false;
};

const std::vector<Field> kFields = {
    {"q", 3, limits::kPosition},   {"qdot", 3, limits::kVelocity},
    {"K", 1, limits::kStiffness},  {"mu", 1, limits::kFriction, true},
    {"w", 2, limits::kAnisotropy}, {"Mg", 0, limits::kWeight},
    {"theta", 0, limits::kYaw},
};

/// A good four-legged frame, with `token` written for entry (leg, axis) of `field`; `offset`
/// receives the byte where the token starts.
std::string frame_with(const Field& field, int leg, int axis, const std::string& token,
                       std::size_t& offset) {
  const double base[4][3] = {
      {0.3, 0.2, -0.1}, {0.3, -0.2, -0.1}, {-0.3, 0.2, -0.1}, {-0.3, -0.2, -0.12}};
  const double vel[4][3] = {{-0.1, 0.02, 0}, {-0.12, 0, 0}, {-0.1, -0.01, 0}, {0.05, 0, 0}};
  std::string text = "{\n";
  const auto put = [&](const std::string& s) { text += s; };
  const auto number = [&](const char* key, int j, int i, double v) {
    if (field.key == std::string(key) && (field.width == 0 || (j == leg && i == axis))) {
      offset = text.size();
      put(token);
    } else {
      put(core::format_double(v));
    }
  };
  const auto per_leg = [&](const char* key, int width, auto value) {
    put(std::string("  \"") + key + "\": [");
    for (int j = 0; j < 4; ++j) {
      put(j ? ", " : "");
      if (width > 1) {
        put("[");
      }
      for (int i = 0; i < width; ++i) {
        put(i ? ", " : "");
        number(key, j, i, value(j, i));
      }
      if (width > 1) {
        put("]");
      }
    }
    put("],\n");
  };
  per_leg("q", 3, [&](int j, int i) { return base[j][i]; });
  per_leg("qdot", 3, [&](int j, int i) { return vel[j][i]; });
  per_leg("K", 1, [](int, int) { return 100.0; });
  per_leg("mu", 1, [](int j, int) { return 0.5 + 0.2 * j; });
  per_leg("w", 2, [](int j, int i) { return i == 0 ? 0.1 * j : 0.0; });
  put("  \"theta\": ");
  number("theta", 0, 0, 0.25);
  put(",\n  \"Mg\": ");
  number("Mg", 0, 0, 9.81);
  put("\n}\n");
  return text;
}

/// "line:col" of byte `offset` in `text` (1-based).
std::string line_col(const std::string& text, std::size_t offset) {
  int line = 1;
  int col = 1;
  for (std::size_t i = 0; i < offset; ++i) {
    col = text[i] == '\n' ? 1 : col + 1;
    line += text[i] == '\n' ? 1 : 0;
  }
  return std::to_string(line) + ":" + std::to_string(col);
}

/// Every output a caller reads, finite.
bool outputs_finite(const Frame& f) {
  return std::isfinite(f.alpha) && std::isfinite(f.beta) && std::isfinite(f.z) &&
         f.Fz.allFinite() && f.v_body.allFinite() && f.Fxy.allFinite() &&
         std::isfinite(f.support.residual) && std::isfinite(f.friction.residual);
}

/// The magnitude classes, as JSON tokens, and seeded random ones.
std::vector<std::string> tokens() {
  std::vector<std::string> t = {
      "4.9e-324", "-1e-320", "1e-30", "0",     "-0",    "-1",     "-2.5",
      "1e-7",     "3",       "1e30",  "-1e30", "1e308", "-1e308", "1.7976931348623157e308"};
  std::mt19937_64 rng(15);
  std::uniform_int_distribution<int> exponent(-320, 308);
  std::uniform_real_distribution<double> mantissa(1.0, 9.99);
  for (int k = 0; k < 24; ++k) {
    const double x = mantissa(rng) * std::pow(10.0, exponent(rng));
    t.push_back(core::format_double(k % 2 ? -x : x));
  }
  return t;
}

TEST(FrameRanges, EveryFieldTimesEveryMagnitudeIsRefusedAtItsPlaceOrSolvedFinite) {
  std::mt19937 rng(7);
  int refused = 0;
  int solved = 0;
  for (const Field& field : kFields) {
    for (const std::string& token : tokens()) {
      const int leg = static_cast<int>(rng() % 4);
      const int axis = field.width > 1 ? static_cast<int>(rng() % field.width) : 0;
      std::size_t offset = 0;
      const std::string text = frame_with(field, leg, axis, token, offset);
      const double x = std::strtod(token.c_str(), nullptr);
      const bool admissible = field.range.contains(x) || (field.zero_too && x == 0.0);
      try {
        FrameInput in = parse_frame_json(text, "f.json");
        EXPECT_TRUE(admissible) << field.key << " = " << token << " was accepted";
        for (const auto law :
             {connection::FrictionLaw::kViscousCoulomb, connection::FrictionLaw::kCoulomb}) {
          connection::evaluate(in.robot, in.frame, law);
          EXPECT_TRUE(outputs_finite(in.frame)) << field.key << " = " << token;
          EXPECT_NE(in.frame.support.status, Status::kNonFinite) << field.key << " = " << token;
          EXPECT_NO_THROW((void)frame_to_json(in.robot, in.frame, true));
        }
        ++solved;
      } catch (const core::InputError& e) {
        ++refused;
        EXPECT_FALSE(admissible) << field.key << " = " << token << ": " << e.what();
        EXPECT_EQ(e.where(), "f.json:" + line_col(text, offset)) << e.what();
        const std::string what = e.what();
        EXPECT_NE(what.find(std::string(": ") + field.key), std::string::npos) << what;
        EXPECT_NE(what.find("must be "), std::string::npos) << what;
        EXPECT_NE(what.find(field.range.describe()), std::string::npos) << what;
      }
    }
  }
  EXPECT_GT(refused, 50);  // both outcomes are exercised
  EXPECT_GT(solved, 50);
}

TEST(FrameRanges, NumbersBeyondDoublesAndNonNumbersAreRefusedAtTheirPlace) {
  for (const Field& field : kFields) {
    for (const std::string token : {"1e999", "-1e400", "NaN", "\"3\"", "null", "[1]"}) {
      std::size_t offset = 0;
      const std::string text = frame_with(field, 1, 0, token, offset);
      try {
        (void)parse_frame_json(text, "f.json");
        ADD_FAILURE() << field.key << " = " << token << " was accepted";
      } catch (const core::InputError& e) {
        // A syntax or overflow error points at (or just past) the token's first byte.
        const std::string where = e.where();
        EXPECT_EQ(where.rfind("f.json:" + line_col(text, offset).substr(0, 1), 0), 0U) << where;
      }
    }
  }
}

TEST(FrameRanges, LegCountsOutsideOneToTheLimitAreRefused) {
  for (const std::size_t n : {std::size_t{0}, std::size_t{limits::kMaxLegs} + 1}) {
    std::string q;
    std::string qd;
    for (std::size_t j = 0; j < n; ++j) {
      q += j ? ",[0,0,-1]" : "[0,0,-1]";
      qd += j ? ",[0,0,0]" : "[0,0,0]";
    }
    const std::string text = "{\"q\": [" + q + "], \"qdot\": [" + qd + "]}";
    try {
      (void)parse_frame_json(text, "f.json");
      ADD_FAILURE() << n << " legs accepted";
    } catch (const core::InputError& e) {
      EXPECT_EQ(e.where(), "f.json:1:7") << e.what();
      EXPECT_NE(std::string(e.what()).find("100000"), std::string::npos) << e.what();
    }
  }
  for (const char* legs : {"0", "-3", "100001", "1e308", "2.5", "\"six\""}) {
    try {
      (void)parse_robot_json(std::string("{\"Mg\": 2,\n \"legs\": ") + legs + "}", "r.json");
      ADD_FAILURE() << legs << " legs accepted";
    } catch (const core::InputError& e) {
      EXPECT_EQ(e.where(), "r.json:2:10") << e.what();
    }
  }
  EXPECT_EQ(parse_robot_json(R"({"legs": 100000})", "r.json").legs(), limits::kMaxLegs);
}

// Every entry of q and q̇ of an admitted frame set in turn to each value outside their ranges (both
// ±1e3: NaN, ±infinity, just beyond, far beyond): `call` must refuse each with core::InputError.
template <class Call>
void expect_every_entry_refused(const Frame& admitted, Call call) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const double bad[] = {std::nan(""), kInf, -kInf, 1.0000001e3, -2e3, 1e300};
  for (Eigen::Index at = 0; at < admitted.q.size(); ++at) {
    for (const double x : bad) {
      for (const bool position : {true, false}) {
        Frame frame = admitted;
        (position ? frame.q : frame.qdot).data()[at] = x;
        EXPECT_THROW(call(frame), core::InputError)
            << admitted.legs() << " legs, " << (position ? "q" : "qdot") << " entry " << at << " = "
            << x;
      }
    }
  }
}

TEST(FrameRanges, CheckFrameRefusesEveryOutOfRangeEntryAtEveryPlaceAndEveryLegCount) {
  // check_frame tests four values at a time with an overlapping last group: every entry of q and
  // q̇, at every leg count up to nine (3N from 3 to 27 values: every remainder), is tested, and
  // the bounds themselves are admitted.
  for (int n = 1; n <= 9; ++n) {
    const Robot robot = uniform_robot(n);
    Frame frame(robot);
    frame.q.setConstant(-0.1);
    frame.qdot.setZero();
    frame.q(0, n - 1) = limits::kPosition.hi;
    frame.q(1, 0) = limits::kPosition.lo;
    frame.qdot(2, n - 1) = limits::kVelocity.lo;
    ASSERT_NO_THROW(check_frame(robot, frame)) << n << " legs";
    expect_every_entry_refused(frame, [&robot](const Frame& f) { check_frame(robot, f); });
  }
}

TEST(FrameRanges, SpringSupportRefusesEveryOutOfRangeFootAtEveryPlaceAndEveryLegCount) {
  // The support tests q's range in its Newton route's first pass (check_frame after it only where
  // that route does not certify): every entry of q and q̇ at every leg count, on frames that route
  // certifies when they are in range (feet on a circle, all down).
  for (int n = 3; n <= 9; ++n) {
    const Robot robot = uniform_robot(n);
    Frame frame(robot);
    for (int j = 0; j < n; ++j) {
      const double a = 2.0 * M_PI * j / n;
      frame.q.col(j) << 0.3 * std::cos(a), 0.3 * std::sin(a), -0.1;
    }
    frame.qdot.setZero();
    Frame solved = frame;
    ASSERT_NO_THROW(spring_support(robot, solved)) << n << " legs";
    ASSERT_EQ(solved.support.route, SupportSummary::Route::kNewton) << n << " legs";
    expect_every_entry_refused(frame, [&robot](Frame& f) { spring_support(robot, f); });
    // Warm-started from its own balance: the start cell is the feet below the plane there, and a
    // foot out of it must still carry its NaN into the sums (weight 0 times NaN).
    SupportOptions warm;
    warm.warm_start = true;
    ASSERT_NO_THROW(spring_support(robot, solved, warm)) << n << " legs";
    ASSERT_EQ(solved.support.newton_steps, 1) << n << " legs";  // it was the warm route
    expect_every_entry_refused(solved, [&](Frame& f) { spring_support(robot, f, warm); });
  }
}

TEST(FrameRanges, ValidateStatesTheRangeOfEveryRobotField) {
  const auto message = [](const Robot& r) {
    try {
      validate(r);
    } catch (const core::InputError& e) {
      return std::string(e.what());
    }
    return std::string("(valid)");
  };
  Robot r = uniform_robot(3, 100.0, 0.5, 9.81);
  EXPECT_EQ(message(r), "(valid)");
  r.w(1, 2) = 1e308;
  EXPECT_EQ(message(r), "w[2][1]: must be in [-1000, 1000], got 1e+308");
  r = uniform_robot(3, 100.0, 0.5, 9.81);
  r.K(1) = std::nan("");
  EXPECT_EQ(message(r), "K[1]: must be in [0.001, 1000000000] N/m, got nan");
  r = uniform_robot(3, 100.0, 1e-320, 9.81);
  EXPECT_EQ(message(r), "mu[0]: must be 0 or in [1e-06, 100], got " + core::format_double(1e-320));
  r = uniform_robot(3, 100.0, 0.0, 1e308);  // μ = 0 (no friction) is admitted
  EXPECT_EQ(message(r), "Mg: must be in [1e-06, 10000000] N, got 1e+308");
  r = uniform_robot(limits::kMaxLegs + 1);
  EXPECT_EQ(message(r), "K: a robot needs 1 to 100000 legs, got 100001");
}

// The issue's example, below the readers: a robot never validated (w = 1e308, a library caller)
// must not come out balanced or converged with values that are not finite.
TEST(FrameRanges, OutOfRangeRobotsNeverComeOutConvergedWithNonFiniteValues) {
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<int> exponent(-320, 308);
  int flagged = 0;
  for (int trial = 0; trial < 300; ++trial) {
    Robot r = uniform_robot(4, 100.0, 0.8, 9.81);
    const double x = std::pow(10.0, exponent(rng)) * (trial % 3 == 0 ? -1.0 : 1.0);
    const double special[] = {std::nan(""), INFINITY, 1e308, 1e-320};
    const double v = trial < 16 ? special[trial % 4] : x;
    switch (trial % 4) {
      case 0:
        r.w(0, trial % 4) = v;
        break;
      case 1:
        r.K(1) = v;
        break;
      case 2:
        r.mu(2) = v;
        break;
      default:
        r.Mg = v;
    }
    Frame f(r);
    f.q << 0.3, 0.3, -0.3, -0.3, 0.2, -0.2, 0.2, -0.2, -0.1, -0.1, -0.1, -0.12;
    f.qdot << -0.1, -0.12, -0.1, 0.05, 0.02, 0.0, -0.01, 0.0, 0.0, 0.0, 0.0, 0.0;
    for (const auto law :
         {connection::FrictionLaw::kViscousCoulomb, connection::FrictionLaw::kCoulomb}) {
      connection::evaluate(r, f, law);
      const bool finite_support = std::isfinite(f.alpha) && std::isfinite(f.beta) &&
                                  std::isfinite(f.z) && f.Fz.allFinite() &&
                                  std::isfinite(f.support.residual);
      if (!finite_support) {
        EXPECT_EQ(f.support.status, Status::kNonFinite) << trial;
      }
      const bool finite_friction =
          f.v_body.allFinite() && f.Fxy.allFinite() && std::isfinite(f.friction.residual);
      if (!finite_friction) {
        EXPECT_FALSE(f.friction.converged)
            << trial << " v = " << v << " law " << static_cast<int>(law) << " res "
            << f.friction.residual << " v_body " << f.v_body.transpose() << " F " << f.Fxy.sum();
        ++flagged;
      }
      if (!finite_support || !finite_friction) {
        EXPECT_THROW((void)frame_to_json(r, f, false), core::ComputationError);
      }
    }
  }
  EXPECT_GT(flagged, 0);  // the class is reached: some of these robots do overflow
}

}  // namespace
}  // namespace slipwalk::contact
