// The calibration's files (calibration/files.hpp): what a writer writes its reader reads back
// (bit for bit for numbers; rotations to rounding), whatever the order of the columns; every
// class of bad input is refused at the file:line:col that holds it; the pairing checks refuse
// records that §4.3.1 cannot pair; the JSON of the estimates holds the estimates.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "calibration/files.hpp"
#include "calibration/standing.hpp"
#include "core/error.hpp"

namespace slipwalk::calibration {
namespace {

Geometry two_legs() {
  Geometry g;
  g.legs = {"L1", "R1"};
  g.transducer.push_back({Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.3, 0.2, 0.04)});
  g.transducer.push_back(
      {rotation_from_vector(Eigen::Vector3d(0.0, 0.0, 3.0)), Eigen::Vector3d(0.3, -0.2, 0.04)});
  g.robot_weight = 80.2458;
  return g;
}

/// Numbers with every digit used, so that a round trip that loses one shows.
Eigen::MatrixXd noise(Eigen::Index rows, Eigen::Index cols, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  Eigen::MatrixXd m(rows, cols);
  for (Eigen::Index i = 0; i < m.size(); ++i) {
    m.data()[i] = (static_cast<double>(rng() >> 11) * 0x1.0p-53 - 0.5) * 20.0;
  }
  return m;
}

HangingRecord record(BodyAxis down, Eigen::Index n, std::uint64_t seed) {
  HangingRecord r;
  r.down = down;
  r.phi.resize(n, 2);
  for (Eigen::Index i = 0; i < n; ++i) {
    r.phi.row(i).setConstant(static_cast<double>(i) / 7.0);
  }
  r.wrench = noise(n, 12, seed);
  return r;
}

std::vector<HangingRecord> four_records(Eigen::Index n = 5) {
  return {record(BodyAxis::plus_x, n, 1), record(BodyAxis::minus_x, n, 2),
          record(BodyAxis::plus_z, n, 3), record(BodyAxis::minus_z, n, 4)};
}

std::string hanging_text(const std::vector<HangingRecord>& records, const Geometry& g) {
  std::ostringstream out;
  write_hanging(out, records, g);
  return out.str();
}

StandingPoses some_poses(Eigen::Index n) {
  StandingPoses p;
  p.phi = noise(n, 2, 11);
  p.wrench = noise(n, 12, 12);
  const Eigen::MatrixXd v = noise(n, 3, 13) * 0.3;
  for (Eigen::Index i = 0; i < n; ++i) {
    p.attitude.push_back(rotation_from_vector(v.row(i).transpose()));
  }
  return p;
}

std::string poses_text(const StandingPoses& p, const Geometry& g) {
  std::ostringstream out;
  write_poses(out, p, g);
  return out.str();
}

/// The InputError's place, or "" when `f` does not throw one.
template <typename F>
std::string error_place(F&& f) {
  try {
    f();
  } catch (const core::InputError& e) {
    return e.where();
  }
  return "";
}

template <typename F>
std::string error_message(F&& f) {
  try {
    f();
  } catch (const core::InputError& e) {
    return e.what();
  }
  return "";
}

/// The text with its first line replaced.
std::string with_header(const std::string& text, const std::string& header) {
  return header + text.substr(text.find('\n'));
}

TEST(CalibrationFiles, HangingRecordsReadBackBitForBitWithTheirRowsAndOrientations) {
  const Geometry g = two_legs();
  const std::vector<HangingRecord> written = four_records();
  const std::vector<HangingRecord> read = parse_hanging(hanging_text(written, g), "h.csv", g);
  ASSERT_EQ(read.size(), written.size());
  for (std::size_t r = 0; r < read.size(); ++r) {
    EXPECT_EQ(read[r].down, written[r].down);
    EXPECT_EQ(read[r].phi, written[r].phi);
    EXPECT_EQ(read[r].wrench, written[r].wrench);
    ASSERT_EQ(read[r].rows.size(), 5U);
    // The header is line 1; record r's rows are lines 2 + 5r ...
    EXPECT_EQ(read[r].rows.front(), "h.csv:" + std::to_string(2 + 5 * r));
    EXPECT_EQ(read[r].source, read[r].rows.front());
  }
}

TEST(CalibrationFiles, PosesReadBackWithTheirAttitudesToRounding) {
  const Geometry g = two_legs();
  const StandingPoses written = some_poses(9);
  const StandingPoses read = parse_poses(poses_text(written, g), "p.csv", g);
  ASSERT_EQ(read.poses(), 9);
  EXPECT_EQ(read.phi, written.phi);
  EXPECT_EQ(read.wrench, written.wrench);
  for (std::size_t i = 0; i < 9; ++i) {
    EXPECT_LT((read.attitude[i] - written.attitude[i]).norm(), 1e-15);
  }
  EXPECT_EQ(read.rows.front(), "p.csv:2");
  EXPECT_EQ(read.source, "p.csv:1");
}

TEST(CalibrationFiles, TheGeometryReadsBackWithItsFramesToRounding) {
  const Geometry g = two_legs();
  std::ostringstream out;
  write_geometry(out, g);
  const Geometry read = parse_geometry(out.str(), "g.toml");
  EXPECT_EQ(read.legs, g.legs);
  EXPECT_EQ(read.robot_weight, g.robot_weight);
  ASSERT_EQ(read.size(), 2);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(read.transducer[k].p, g.transducer[k].p);
    EXPECT_LT((read.transducer[k].R - g.transducer[k].R).norm(), 1e-14);
  }
}

TEST(CalibrationFiles, ColumnsReadInAnyOrderWithCommentsBlankLinesCrlfAndExtraColumns) {
  const Geometry g = two_legs();
  const std::vector<HangingRecord> written = {record(BodyAxis::plus_x, 2, 5)};
  const HangingRecord& r = written.front();
  // Leg R1 first, its columns reversed, an extra column in the middle, the orientation last.
  std::string text = "# a hanging file written by hand\r\n\r\n";
  text +=
      "tz_R1,ty_R1,tx_R1,fz_R1,fy_R1,fx_R1,phi_R1,temperature,phi_L1,fx_L1,fy_L1,fz_L1,"
      "tx_L1,ty_L1,tz_L1, orientation \r\n";
  for (Eigen::Index i = 0; i < 2; ++i) {
    std::ostringstream row;
    row.precision(17);
    for (int j = 5; j >= 0; --j) {
      row << r.wrench(i, 6 + j) << ",";
    }
    row << r.phi(i, 1) << ",21.5," << r.phi(i, 0);
    for (int j = 0; j < 6; ++j) {
      row << "," << r.wrench(i, j);
    }
    row << ", +x  # a comment\r\n";
    text += row.str();
  }
  const std::vector<HangingRecord> read = parse_hanging(text, "h.csv", g);
  ASSERT_EQ(read.size(), 1U);
  EXPECT_EQ(read[0].phi, r.phi);
  EXPECT_EQ(read[0].wrench, r.wrench);
  EXPECT_EQ(read[0].rows.front(), "h.csv:4");
}

TEST(CalibrationFiles, ATypographicMinusReadsAsAMinus) {
  const Geometry g = two_legs();
  std::string text = hanging_text({record(BodyAxis::minus_z, 1, 1)}, g);
  text.replace(text.find("\n-z") + 1, 1, "\xE2\x88\x92");
  EXPECT_EQ(parse_hanging(text, "h.csv", g).front().down, BodyAxis::minus_z);
}

TEST(CalibrationFiles, EachBadCellOrColumnIsRefusedAtItsLineAndColumn) {
  const Geometry g = two_legs();
  const std::string text = hanging_text(four_records(2), g);
  const std::string header = text.substr(0, text.find('\n'));
  const auto place = [&](const std::string& t) {
    return error_place([&] { (void)parse_hanging(t, "h.csv", g); });
  };
  // A leg of the geometry without its columns: the header's line, the leg named.
  const std::string no_leg = with_header(text, header.substr(0, header.find(",phi_R1")));
  EXPECT_EQ(place(no_leg), "h.csv:1");
  EXPECT_NE(error_message([&] { (void)parse_hanging(no_leg, "h.csv", g); }).find("leg R1"),
            std::string::npos);
  // A duplicated column: where its second copy starts.
  EXPECT_EQ(place(with_header(text, header + ",fx_L1")),
            "h.csv:1:" + std::to_string(header.size() + 2));
  // A cell that is not a number: its own column.
  std::string bad = text;
  const std::size_t line3 = bad.find('\n', bad.find('\n') + 1) + 1;  // line 3 starts here
  const std::size_t cell = bad.find(',', line3) + 1;                 // phi_L1 of line 3
  bad.replace(cell, bad.find(',', cell) - cell, "x1");
  EXPECT_EQ(place(bad), "h.csv:3:" + std::to_string(cell - line3 + 1));
  // An unknown orientation, at column 1.
  std::string unknown = text;
  unknown.replace(line3, 2, "+w");
  EXPECT_EQ(place(unknown), "h.csv:3:1");
  // An orientation that comes back after another.
  const std::string split =
      text + text.substr(text.find('\n') + 1, text.find('\n', line3) + 1 - text.find('\n') - 1);
  EXPECT_EQ(place(split), "h.csv:10:1");
  // A row of the wrong length; no header; no rows.
  EXPECT_EQ(place(text + "+x,1,2\n"), "h.csv:10");
  EXPECT_EQ(place("# nothing\n"), "h.csv:1");
  EXPECT_EQ(place(header + "\n"), "h.csv:1");
}

TEST(CalibrationFiles, AQuaternionOffUnitLengthIsRefusedAtItsRow) {
  const Geometry g = two_legs();
  std::string text = poses_text(some_poses(3), g);
  const std::size_t line3 = text.find('\n', text.find('\n') + 1) + 1;
  text.replace(line3, text.find(',', line3) - line3, "0.9");
  EXPECT_EQ(error_place([&] { (void)parse_poses(text, "p.csv", g); }), "p.csv:3:1");
  // A missing quaternion column names the header line.
  const std::string t2 = poses_text(some_poses(3), g);
  EXPECT_EQ(error_place([&] { (void)parse_poses(t2.substr(3), "p.csv", g); }), "p.csv:1");
}

TEST(CalibrationFiles, BadGeometryIsRefusedAtTheKeyOrValue) {
  const auto place = [](const std::string& t) {
    return error_place([&] { (void)parse_geometry(t, "g.toml"); });
  };
  const std::string leg =
      "[[transducer]]\nleg = \"HL\"\nposition = [0.1, 0.2, 0.0]\n"
      "rotation = [0.0, 0.0, 0.0]\n";
  EXPECT_EQ(place("robot_weight = 80.0\n" + leg), "");
  EXPECT_EQ(place("robot_wieght = 80.0\n" + leg), "g.toml:1:1");
  EXPECT_NE(error_message([&] {
              (void)parse_geometry("robot_wieght = 80.0\n" + leg, "g");
            }).find("did you mean 'robot_weight'"),
            std::string::npos);
  EXPECT_EQ(place(leg), "g.toml:1:1");  // no robot_weight
  EXPECT_EQ(place("robot_weight = -1.0\n" + leg), "g.toml:1:16");
  EXPECT_EQ(place("robot_weight = 80.0\n" + leg + leg), "g.toml:7:7");  // HL twice
  EXPECT_EQ(place("robot_weight = 80.0\n[[transducer]]\nleg = \"HL\"\nposition = [0.1, 0.2]\n"
                  "rotation = [0.0, 0.0, 0.0]\n"),
            "g.toml:4:12");
  EXPECT_EQ(place("robot_weight = 80.0\n[[transducer]]\nleg = \"HL\"\nposition = [0.1, \"a\", 0]\n"
                  "rotation = [0.0, 0.0, 0.0]\n"),
            "g.toml:4:18");
  EXPECT_EQ(place("robot_weight = 80.0\n[[transducer]]\nleg = \"HL\"\nposition = [0.1, 0.2, 0]\n"
                  "rotation = [0.0, 0.0, 3.5]\n"),
            "g.toml:5:12");
  EXPECT_EQ(place("robot_weight = 80.0\n[[transducer]]\nleg = \"H L\"\nposition = [0.1, 0.2, 0]\n"
                  "rotation = [0.0, 0.0, 0.0]\n"),
            "g.toml:3:7");
  EXPECT_EQ(place("robot_weight = 80.0\n[[transducer]]\nleg = \"HL\"\nposition = [0.1, 0.2, 0]\n"),
            "g.toml:2:1");                                  // no rotation
  EXPECT_EQ(place("robot_weight = 80.0\n"), "g.toml:1:1");  // no transducer
}

TEST(CalibrationFiles, RecordsThatDoNotPairAreRefusedBeforeCalibrating) {
  const auto place = [](const std::vector<HangingRecord>& r) {
    return error_place([&] { check_hanging_pairs(r, 0.01, 3); });
  };
  std::vector<HangingRecord> r = four_records();
  for (std::size_t i = 0; i < r.size(); ++i) {
    r[i].source = "h.csv:" + std::to_string(2 + 5 * i);
    for (int j = 0; j < 5; ++j) {
      r[i].rows.push_back("h.csv:" + std::to_string(2 + 5 * i + j));
    }
  }
  EXPECT_EQ(place(r), "");
  // The upright record may stand alone (the naive tare's), any other needs its opposite.
  EXPECT_EQ(
      place({r[0], r[1], record(BodyAxis::plus_y, 5, 8), record(BodyAxis::minus_y, 5, 9), r[3]}),
      "");
  EXPECT_EQ(place({r[0], r[1], r[2], r[3], record(BodyAxis::plus_y, 5, 9)}), "");
  std::vector<HangingRecord> lone = {r[0], r[1], r[3]};
  EXPECT_EQ(place(lone), "h.csv:2");  // one pair (±x) and the upright record: too few pairs
  std::vector<HangingRecord> no_opposite = {r[0], r[2], r[3]};
  EXPECT_EQ(place(no_opposite), "h.csv:2");  // +x without −x
  // The same orientation twice (e.g. in two files): the second is named.
  std::vector<HangingRecord> twice = r;
  twice.push_back(r[1]);
  twice.back().source = "h2.csv:2";
  EXPECT_EQ(place(twice), "h2.csv:2");
  // Sample counts and shaft angles must agree across every paired record.
  std::vector<HangingRecord> short_one = r;
  short_one[2] = record(BodyAxis::plus_z, 4, 3);
  short_one[2].source = "h.csv:12";
  EXPECT_EQ(place(short_one), "h.csv:12");
  std::vector<HangingRecord> shifted = r;
  shifted[1].phi(3, 1) += 0.02;
  EXPECT_EQ(place(shifted), "h.csv:10");
  // Too few samples for the fit.
  EXPECT_EQ(error_place([&] { check_hanging_pairs(r, 0.01, 6); }), "h.csv:2");
}

TEST(CalibrationFiles, TheEstimatesJsonHoldsTheEstimates) {
  Calibration c;
  c.geometry = two_legs();
  for (int k = 0; k < 2; ++k) {
    LegEstimate e;
    e.offset << 1.0 + k, 2.0, 3.0, 0.1, 0.2, 0.3;
    e.weight = 6.2 + 0.1 * k;
    e.weight_se = 0.01;
    e.com.coefficients = Eigen::Matrix3Xd::Constant(3, 3, 0.05 * (k + 1));
    c.hanging.legs.push_back(e);
    c.mounting.rotation.push_back(rotation_from_vector(Eigen::Vector3d(0.01 * (k + 1), 0.0, 0.0)));
    c.mounting.displacement.push_back(Eigen::Vector3d(0.001, -0.002, 0.003 * k));
  }
  c.mounting.model = MountingModel::shared_translation;
  c.mounting.rss = 1.5;
  c.models.push_back({MountingModel::full, 12, 1.0, 0.1, -3.0});
  const nlohmann::json j = calibration_json(c);
  ASSERT_EQ(j["legs"].size(), 2U);
  EXPECT_EQ(j["legs"][1]["leg"], "R1");
  EXPECT_EQ(j["legs"][1]["weight"].get<double>(), 6.3);
  EXPECT_EQ(j["legs"][1]["offset"][0].get<double>(), 2.0);
  EXPECT_EQ(j["legs"][0]["com"]["harmonics"], 1);
  EXPECT_NEAR(j["legs"][1]["rotation"][0].get<double>(), 0.02, 1e-15);
  EXPECT_EQ(j["legs"][1]["displacement"][2].get<double>(), 0.003);
  EXPECT_EQ(j["mounting"]["model"], "shared_translation");
  EXPECT_EQ(j["mounting"]["rss"].get<double>(), 1.5);
  EXPECT_EQ(j["models"][0]["model"], "full");
  EXPECT_EQ(j["models"][0]["bic"].get<double>(), -3.0);
}

TEST(CalibrationFiles, TheTruthJsonTabulatesTheLegCentresOfMass) {
  SynthOptions o;
  o.poses = 10;
  o.samples_per_cycle = 16;
  o.cycles = 1;
  const SyntheticTruth truth = synthetic_truth(o);
  const nlohmann::json j = truth_json(truth, o);
  ASSERT_EQ(j["legs"].size(), static_cast<std::size_t>(truth.legs()));
  const auto& phi = j["com_phi"];
  for (int k = 0; k < truth.legs(); ++k) {
    const auto& leg = j["legs"][static_cast<std::size_t>(k)];
    EXPECT_EQ(leg["weight"].get<double>(), truth.weight[static_cast<std::size_t>(k)]);
    for (std::size_t i = 0; i < phi.size(); i += 7) {
      const Eigen::Vector3d r = truth.leg_com(k, phi[i].get<double>());
      for (int a = 0; a < 3; ++a) {
        EXPECT_EQ(leg["com"][i][static_cast<std::size_t>(a)].get<double>(), r(a));
      }
    }
  }
  EXPECT_EQ(j["options"]["poses"], 10);
}

}  // namespace
}  // namespace slipwalk::calibration
