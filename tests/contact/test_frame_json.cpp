// The frame format of DESIGN.md: defaults, and every kind of bad input rejected with a message
// that says what and where.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "connection/local_connection.hpp"
#include "contact/frame_json.hpp"
#include "core/error.hpp"

namespace slipwalk::contact {
namespace {

const char* kTripod = R"({"q": [[0.2, 0.1, -0.1], [-0.2, 0.1, -0.1], [0.0, -0.15, -0.1]],
  "qdot": [[0.1, 0, 0], [0.1, 0, 0], [-0.2, 0, 0]], "Mg": 9.81})";

std::string where_of(const std::string& text) {
  try {
    (void)parse_frame_json(text, "f.json");
  } catch (const core::InputError& e) {
    return e.where();
  }
  return "(accepted)";
}

TEST(FrameJson, ReadsTheFormatWithDefaults) {
  const FrameInput in = parse_frame_json(kTripod, "f.json");
  EXPECT_EQ(in.robot.legs(), 3);
  EXPECT_EQ(in.robot.K, Eigen::VectorXd::Ones(3));
  EXPECT_EQ(in.robot.mu, Eigen::VectorXd::Ones(3));
  EXPECT_TRUE(in.robot.w.isZero());
  EXPECT_DOUBLE_EQ(in.robot.Mg, 9.81);
  EXPECT_DOUBLE_EQ(in.frame.q(1, 2), -0.15);
  EXPECT_DOUBLE_EQ(in.frame.qdot(0, 2), -0.2);
  EXPECT_EQ(in.frame.theta, 0.0);
  EXPECT_EQ(in.frame.A.cols(), 6);
}

TEST(FrameJson, MalformedJsonNamesLineAndColumn) {
  EXPECT_EQ(where_of("{\"q\": [[0,0,-1]],\n \"qdot\": [[0,0,0]] oops}"), "f.json:2:20");
  EXPECT_EQ(where_of("{\"q\": [[NaN, 0, -1]], \"qdot\": [[0,0,0]]}"), "f.json:1:9");
  EXPECT_EQ(where_of("[1, 2]"), "f.json:1:1");
}

std::string what_of(const std::string& text) {
  try {
    (void)parse_frame_json(text, "f.json");
  } catch (const core::InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

// A bad value is named by the place of the value itself (a missing key: of the document; an
// unknown key: of the key), and its message starts with the value's name.
TEST(FrameJson, BadValuesNameTheirPlaceKeyAndLeg) {
  const std::string qd = R"("qdot": [[0,0,0],[0,0,0]])";
  struct Case {
    std::string text;
    std::string what;
  };
  for (const Case& c : std::vector<Case>{
           {R"({"q": [[0,0,-1],[1,0]], )" + qd + "}", "f.json:1:17: q[1]: expected 3 numbers"},
           {R"({"q": [[0,0,-1],[1,0,-1]], "qdot": [[0,0,0]]})", "f.json:1:36: qdot: has 1 "},
           {R"({"q": [[0,0,-1],[1,0,-1]], "K": [1, -2], )" + qd + "}",
            "f.json:1:37: K[1]: must be in [0.001, 1000000000] N/m, got -2"},
           {R"({"q": [[0,0,-1],[1,0,-1]], "mu": [1, -0.1], )" + qd + "}",
            "f.json:1:38: mu[1]: must be 0 or in [1e-06, 100], got -0.1"},
           {R"({"q": [[0,0,-1],[1,0,-1]], "Mg": 0, )" + qd + "}", "f.json:1:34: Mg: must be in"},
           {R"({"q": [[0,0,-1],[1,0,-1]], "Mg": "heavy", )" + qd + "}",
            "f.json:1:34: Mg: expected a number"},
           {R"({"q": [[0,0,-1],[1,"x",-1]], )" + qd + "}", "f.json:1:20: q[1][1]: expected a"},
           {R"({"q": [[0,0,-1],[1,0,-1]], "w": [[0,0]], )" + qd + "}", "f.json:1:33: w: has 1"},
           {R"({"q": [[0,0,-1],[1,0,-1]], "speed": 3, )" + qd + "}",
            "f.json:1:28: speed: unknown key"},
           {R"({"qdot": [[0,0,0]]})", "f.json:1:1: q: missing"},
           {R"({"q": [], "qdot": []})", "f.json:1:7: q: needs 1 to 100000 legs, got 0"},
           {"{\"q\": [[0,0,-1]],\r\n\t\"qdot\": [[0,0,0]], \"theta\": 1e7}",
            "f.json:2:30: theta: must be in [-1000000, 1000000] rad"},
       }) {
    EXPECT_EQ(what_of(c.text).rfind(c.what, 0), 0U) << what_of(c.text);
  }
  EXPECT_EQ(where_of(R"({"q": [[0,0,1e999]], "qdot": [[0,0,0]]})"), "f.json:1:17");  // overflow
}

TEST(FrameJson, RobotAloneForBatches) {
  const Robot r = parse_robot_json(R"({"legs": 6, "Mg": 20})", "r.json");
  EXPECT_EQ(r.legs(), 6);
  EXPECT_DOUBLE_EQ(r.Mg, 20.0);
  EXPECT_THROW((void)parse_robot_json(R"({"legs": 2.5})", "r.json"), core::InputError);
  EXPECT_THROW((void)parse_robot_json(R"({"Mg": 1})", "r.json"), core::InputError);
}

// The output carries the friction summary whole: the number of static feet and the dissipated
// power, which must equal −Σ F_k·u_k recomputed from the written forces and slip velocities.
TEST(FrameJson, WritesTheFrictionSummaryWithStaticFeetAndDissipation) {
  FrameInput in = parse_frame_json(kTripod, "f.json");
  connection::evaluate(in.robot, in.frame, connection::FrictionLaw::kCoulomb);
  const nlohmann::json out = frame_to_json(in.robot, in.frame, false);
  const auto& fr = out.at("friction");
  EXPECT_EQ(fr.at("static_feet").get<int>(), in.frame.friction.static_feet);
  const auto v = out.at("v_body").get<std::vector<double>>();
  double power = 0.0;
  for (int k = 0; k < in.frame.legs(); ++k) {
    const auto F = out.at("Fxy").at(static_cast<std::size_t>(k)).get<std::vector<double>>();
    const double ux = v[0] - v[2] * in.frame.q(1, k) + in.frame.qdot(0, k);
    const double uy = v[1] + v[2] * in.frame.q(0, k) + in.frame.qdot(1, k);
    power -= F[0] * ux + F[1] * uy;
  }
  EXPECT_GT(power, 0.0);
  EXPECT_NEAR(fr.at("dissipation").get<double>(), power, 1e-9 * power);
}

}  // namespace
}  // namespace slipwalk::contact
