// slipwalk model: the frame format end to end, the CSV batch, and bad input (exit 2, a message
// naming file and place, nothing written).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli/command.hpp"
#include "connection/local_connection.hpp"
#include "contact/frame_json.hpp"

namespace slipwalk::cli {
namespace {

using namespace slipwalk::testing;  // NOLINT(google-build-using-namespace): test helpers

const char* kHexapod = R"({"q": [[0.3, 0.2, -0.1], [-0.3, 0.2, -0.1], [0.0, -0.25, -0.1],
  [0.3, -0.2, -0.05], [-0.3, -0.2, -0.1], [0.0, 0.25, -0.08]],
 "qdot": [[-0.1, 0, 0], [-0.1, 0.01, 0], [-0.12, 0, 0], [0.05, 0, 0], [-0.1, 0, 0], [0.02, 0, 0]],
 "Mg": 9.81, "K": [100, 100, 100, 100, 100, 100]})";

TEST(CliModel, JsonFrameMatchesTheLibrary) {
  const ScratchDir dir;
  const auto in = dir / "frame.json";
  write_text(in, kHexapod);
  for (const char* law : {"viscous", "coulomb"}) {
    const CommandResult r = run_slipwalk({"model", "--friction", law, "--in", in.string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto out = nlohmann::json::parse(r.out);
    contact::FrameInput expected = contact::parse_frame_json(kHexapod, "x");
    connection::evaluate(expected.robot, expected.frame,
                         std::string(law) == "viscous" ? connection::FrictionLaw::kViscousCoulomb
                                                       : connection::FrictionLaw::kCoulomb);
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(out.at("v_body")[static_cast<std::size_t>(i)].get<double>(),
                expected.frame.v_body(i));
    }
    EXPECT_EQ(out.at("contact").size(), 6U);
    EXPECT_EQ(out.at("Fz").size(), 6U);
    EXPECT_EQ(out.at("support").at("status"), "balanced");
    EXPECT_TRUE(out.at("friction").at("converged").get<bool>());
  }
}

TEST(CliModel, CsvBatchOneFramePerRow) {
  const ScratchDir dir;
  write_text(dir / "robot.json", R"({"K": [100, 100, 100], "Mg": 9.81})");
  write_text(dir / "frames.csv",
             "theta,q0x,q0y,q0z,qd0x,qd0y,qd0z,q1x,q1y,q1z,qd1x,qd1y,qd1z,q2x,q2y,q2z,qd2x,qd2y,"
             "qd2z\n"
             "0,0.2,0.1,-0.1,0.1,0,0,-0.2,0.1,-0.1,0.1,0,0,0,-0.15,-0.1,-0.2,0,0\n"
             "0.5,0.2,0.1,-0.1,0,0,0,-0.2,0.1,-0.1,0,0,0,0,-0.15,-0.1,0,0,0\n");
  const auto out = dir / "out.csv";
  const CommandResult r = run_slipwalk({"model", "--robot", (dir / "robot.json").string(), "--in",
                                        (dir / "frames.csv").string(), "--out", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string text = read_text(out);
  EXPECT_EQ(text.rfind("frame,alpha,beta,z,vx,vy,wz,", 0), 0U);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 3);  // header + 2 frames
}

TEST(CliModel, BadInputExits2NamingThePlaceAndWritesNothing) {
  const ScratchDir dir;
  const auto out = dir / "out.json";
  struct Case {
    std::string text;
    std::string where;
  };
  const std::vector<Case> cases = {
      {"{\"q\": [[0,0,-1]],\n \"qdot\": [[0,0,0]] oops}", "frame.json:2:20"},
      {R"({"q": [[0,0,-1],[1,0,-1]], "qdot": [[0,0,0]]})", "frame.json:1:36: qdot: has 1"},
      {R"({"q": [[0,0,-1]], "qdot": [[0,0,0]], "K": [-1]})",
       "frame.json:1:44: K[0]: must be in [0.001, 1000000000] N/m, got -1"},
      {R"({"q": [[0,0,-1]], "qdot": [[0,0,0]], "mu": [-0.5]})",
       "frame.json:1:45: mu[0]: must be 0 or in [1e-06, 100], got -0.5"},
      {R"({"q": [[0,0,-1]], "qdot": [[0,0,0]], "Mg": 0})", "frame.json:1:44: Mg: must be in"},
      {R"({"q": [[0,0,NaN]], "qdot": [[0,0,0]]})", "frame.json:1:"},
      // The issue's example: an anisotropy that would overflow I + w wᵀ.
      {"{\"q\": [[0,0,-1]], \"qdot\": [[0,0,0]],\n \"w\": [[1e308, 0]]}",
       "frame.json:2:9: w[0][0]: must be in [-1000, 1000], got 1e+308"},
  };
  for (const Case& c : cases) {
    write_text(dir / "frame.json", c.text);
    const CommandResult r =
        run_slipwalk({"model", "--in", (dir / "frame.json").string(), "--out", out.string()});
    EXPECT_EQ(r.exit_code, 2) << c.text;
    EXPECT_NE(r.err.find(c.where), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
  }
  write_text(dir / "frame.json", kHexapod);
  const CommandResult bad_law =
      run_slipwalk({"model", "--friction", "stiction", "--in", (dir / "frame.json").string()});
  EXPECT_EQ(bad_law.exit_code, 2);
  EXPECT_NE(bad_law.err.find("--friction"), std::string::npos);
  // A CSV batch with a non-number names row and column.
  write_text(dir / "robot.json", R"({"legs": 1})");
  write_text(dir / "frames.csv", "theta,q0x,q0y,q0z,qd0x,qd0y,qd0z\n0,0,0,-1,x,0,0\n");
  const CommandResult bad_cell =
      run_slipwalk({"model", "--robot", (dir / "robot.json").string(), "--in",
                    (dir / "frames.csv").string(), "--out", out.string()});
  EXPECT_EQ(bad_cell.exit_code, 2);
  EXPECT_NE(bad_cell.err.find("frames.csv:2:10"), std::string::npos) << bad_cell.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

// Inputs that are not readable files, as --in or --robot, are bad input naming the path; so is a
// robot file out of range, at its place.
TEST(CliModel, FoldersMissingFilesAndBadRobotsExit2NamingThePath) {
  const ScratchDir dir;
  const auto out = dir / "out.csv";
  const auto frames = dir / "frames.csv";
  const auto robot = dir / "robot.json";
  write_text(frames, "theta,q0x,q0y,q0z,qd0x,qd0y,qd0z\n0,0,0,-1,0,0,0\n");
  write_text(robot, R"({"legs": 1})");
  std::filesystem::create_directory(dir / "folder.json");
  const std::string folder = (dir / "folder.json").string();
  const std::string missing = (dir / "missing.json").string();
  const std::vector<std::vector<std::string>> runs = {
      {"model", "--in", folder, "--out", out.string()},
      {"model", "--in", missing, "--out", out.string()},
      {"model", "--robot", folder, "--in", frames.string(), "--out", out.string()},
      {"model", "--robot", missing, "--in", frames.string(), "--out", out.string()},
      {"model", "--robot", robot.string(), "--in", folder, "--out", out.string()},
  };
  for (const auto& args : runs) {
    const CommandResult r = run_slipwalk(args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    const std::string& path = args[2] == folder || args[2] == missing ? args[2] : args[4];
    EXPECT_NE(r.err.find("slipwalk: error: " + path + ": "), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
  }
  write_text(robot, "{\"legs\": 2,\r\n \"K\": [100, 1e308]}\r\n");
  const CommandResult r = run_slipwalk(
      {"model", "--robot", robot.string(), "--in", frames.string(), "--out", out.string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(robot.string() + ":2:13: K[1]: must be in [0.001, 1000000000] N/m"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

// A CRLF batch (as a spreadsheet writes it) gives the LF batch's output byte for byte.
TEST(CliModel, CrlfBatchGivesTheLfOutput) {
  const ScratchDir dir;
  write_text(dir / "robot.json", "{\"K\": [100, 100, 100],\r\n \"Mg\": 9.81}\r\n");
  const std::string lf =
      "theta,q0x,q0y,q0z,qd0x,qd0y,qd0z,q1x,q1y,q1z,qd1x,qd1y,qd1z,q2x,q2y,q2z,qd2x,qd2y,qd2z\n"
      "0,0.2,0.1,-0.1,0.1,0,0,-0.2,0.1,-0.1,0.1,0,0,0,-0.15,-0.1,-0.2,0,0\n"
      "0.5,0.2,0.1,-0.1,0,0,0,-0.2,0.1,-0.1,0,0,0,0,-0.15,-0.1,0,0,0\n";
  std::string crlf;
  for (const char c : lf) {
    crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  }
  write_text(dir / "lf.csv", lf);
  write_text(dir / "crlf.csv", crlf);
  std::vector<std::string> outputs;
  for (const char* name : {"lf.csv", "crlf.csv"}) {
    const CommandResult r =
        run_slipwalk({"model", "--friction", "coulomb", "--robot", (dir / "robot.json").string(),
                      "--in", (dir / name).string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    outputs.push_back(r.out);
  }
  EXPECT_EQ(outputs[0], outputs[1]);
  EXPECT_EQ(std::count(outputs[0].begin(), outputs[0].end(), '\n'), 3);
}

TEST(CliModel, DeepOrDuplicatedJsonExits2NamingTheFileAndWritesNothing) {
  const ScratchDir dir;
  const auto out = dir / "out.json";
  const auto frame = dir / "deep.json";
  // Nesting under "q" (the value the frame reader looks into first), of every depth class.
  for (const int depth : {65, 1000, 70000, 100000}) {
    for (const bool objects : {false, true}) {
      std::string text = R"({"qdot": [[0, 0, 0]], "q": )";
      for (int i = 0; i < depth; ++i) {
        text += objects ? R"({"a": )" : "[";
      }
      text += "0";
      for (int i = 0; i < depth; ++i) {
        text += objects ? '}' : ']';
      }
      text += "}";
      write_text(frame, text);
      const CommandResult r =
          run_slipwalk({"model", "--in", frame.string(), "--out", out.string()});
      EXPECT_EQ(r.exit_code, 2) << depth << r.err;
      EXPECT_NE(r.err.find(frame.string() + ":1:"), std::string::npos) << r.err;
      EXPECT_NE(r.err.find("nested deeper than"), std::string::npos) << r.err;
      EXPECT_LT(r.err.size(), 400U);
      EXPECT_FALSE(std::filesystem::exists(out));
    }
  }
  // A robot file (batch mode) and a frame file with a key given twice, on line 2 or deeper.
  const auto robot = dir / "robot.json";
  write_text(dir / "frames.csv", "theta,q0x,q0y,q0z,qd0x,qd0y,qd0z\n0,0,0,-1,0,0,0\n");
  const auto csv_out = dir / "out.csv";
  struct Case {
    std::string text;
    std::string where;
  };
  for (const Case& c :
       std::vector<Case>{{"{\"K\": [1],\n \"Mg\": 2, \"K\": [3]}", ":2:11"},
                         {"{\"legs\": 1,\n\n   \"legs\": 2}", ":3:4"},
                         {"{\"K\": [1], \"w\": [{\"x\": 1, \"x\": 2}]}", ":1:27"}}) {
    write_text(robot, c.text);
    const CommandResult r =
        run_slipwalk({"model", "--robot", robot.string(), "--in", (dir / "frames.csv").string(),
                      "--out", csv_out.string()});
    EXPECT_EQ(r.exit_code, 2) << c.text;
    EXPECT_NE(r.err.find(robot.string() + c.where + ": duplicate key"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(csv_out));
  }
  write_text(frame, "{\"q\": [[0, 0, -1]], \"qdot\": [[0, 0, 0]],\n \"q\": [[0, 0, -2]]}");
  const CommandResult dup = run_slipwalk({"model", "--in", frame.string(), "--out", out.string()});
  EXPECT_EQ(dup.exit_code, 2);
  EXPECT_NE(dup.err.find(frame.string() + ":2:2: duplicate key \"q\" (first at 1:2)"),
            std::string::npos)
      << dup.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace slipwalk::cli
