// Motion-trial files and B's residual file (residual/trial.hpp): a trial written and read back is
// the same trial bit for bit; a file with an id column splits into one trial per id, columns in
// any order and other columns ignored; every kind of bad file is refused naming file:line (and the
// column for a cell); B's residual file reads back through the scene's reader
// (scene::parse_residual) bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "residual/trial.hpp"
#include "scene/effects.hpp"

namespace slipwalk::residual {
namespace {

/// A trial of n samples and M modules with awkward doubles (full 17-digit mantissas, tiny and
/// large magnitudes, negative zero).
MotionTrial random_trial(int modules, Eigen::Index n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  MotionTrial trial;
  trial.label = "random";
  trial.t.resize(n);
  trial.pose.resize(n, 3);
  trial.joints.resize(n, 3 * modules);
  double t = -0.1;
  for (Eigen::Index j = 0; j < n; ++j) {
    t += 1.0 / 125.0 * (1.0 + 0.1 * std::abs(g(rng)));
    trial.t(j) = t;
    trial.pose.row(j) << g(rng), 1e-9 * g(rng), 40.0 * g(rng);
    for (Eigen::Index c = 0; c < trial.joints.cols(); ++c) {
      trial.joints(j, c) = std::ldexp(g(rng), static_cast<int>(c % 7) - 3);
    }
  }
  trial.joints(0, 0) = -0.0;
  trial.pose(1, 1) = 5e-324;  // a subnormal
  return trial;
}

std::string text_of(const MotionTrial& trial) {
  std::ostringstream out;
  write_trial(out, trial);
  return out.str();
}

void expect_bitwise_equal(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  ASSERT_EQ(a.rows(), b.rows());
  ASSERT_EQ(a.cols(), b.cols());
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    EXPECT_EQ(std::memcmp(&a.data()[i], &b.data()[i], sizeof(double)), 0)
        << i << ": " << a.data()[i] << " vs " << b.data()[i];
  }
}

TEST(Trial, WrittenAndReadBackIsTheSameTrialBitForBit) {
  for (int modules : {3, 4, 6}) {
    const MotionTrial trial = random_trial(modules, 40, static_cast<std::uint64_t>(modules));
    const std::string text = text_of(trial);
    const std::vector<MotionTrial> back = parse_trials(text, "a.csv");
    ASSERT_EQ(back.size(), 1u);
    EXPECT_EQ(back[0].label, "a.csv");
    EXPECT_EQ(back[0].source, "a.csv:1");
    EXPECT_EQ(back[0].id, "");
    EXPECT_EQ(back[0].legs(), 2 * modules);
    expect_bitwise_equal(back[0].t, trial.t);
    expect_bitwise_equal(back[0].pose, trial.pose);
    expect_bitwise_equal(back[0].joints, trial.joints);
    EXPECT_EQ(text_of(back[0]), text);  // and written again, the same text
  }
  const std::vector<std::string> cols = trial_columns(4);
  ASSERT_EQ(cols.size(), 16u);
  EXPECT_EQ(cols[0], "t");
  EXPECT_EQ(cols[3], "theta");
  EXPECT_EQ(cols[4], "yaw1_1");
  EXPECT_EQ(cols[5], "roll_1");
  EXPECT_EQ(cols[15], "yaw2_4");
}

/// The file text of `trial` with `id` and an ignored text column added and the columns shuffled.
std::string with_id(const MotionTrial& trial, const std::string& id, bool header) {
  std::vector<std::string> cols = trial_columns(trial.modules());
  std::string text;
  if (header) {
    text = "# a comment line\nfrequency,id";
    for (auto it = cols.rbegin(); it != cols.rend(); ++it) {
      text.append(",").append(*it);
    }
    text.append("\n");
  }
  std::istringstream rows(text_of(trial));
  std::string line;
  std::getline(rows, line);  // the header
  while (std::getline(rows, line)) {
    std::vector<std::string> cells;
    std::istringstream in(line);
    for (std::string c; std::getline(in, c, ',');) {
      cells.push_back(c);
    }
    text.append("high, ").append(id);
    for (auto it = cells.rbegin(); it != cells.rend(); ++it) {
      text.append(", ").append(*it);
    }
    text.append("\r\n");
  }
  return text;
}

TEST(Trial, AFileWithAnIdColumnSplitsIntoOneTrialPerId) {
  const MotionTrial a = random_trial(4, 5, 11);
  const MotionTrial b = random_trial(4, 3, 12);
  const MotionTrial c = random_trial(4, 7, 13);
  const std::string text =
      with_id(a, "7", true) + with_id(b, "3", false) + "\n" + with_id(c, "12", false);
  const std::vector<MotionTrial> trials = parse_trials(text, "trials.csv");
  ASSERT_EQ(trials.size(), 3u);
  const std::vector<const MotionTrial*> truth = {&a, &b, &c};
  const std::vector<std::string> ids = {"7", "3", "12"};
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(trials[i].id, ids[i]);
    EXPECT_EQ(trials[i].label, "trials.csv, id " + ids[i]);
    EXPECT_EQ(trials[i].source, "trials.csv:2");
    expect_bitwise_equal(trials[i].t, truth[i]->t);
    expect_bitwise_equal(trials[i].pose, truth[i]->pose);
    expect_bitwise_equal(trials[i].joints, truth[i]->joints);
  }
}

TEST(Trial, EveryBadFileIsRefusedNamingFileLineAndColumn) {
  const std::string f = "bad.csv";
  auto err = [&](const std::string& text, const std::string& at, const std::string& part) {
    try {
      (void)parse_trials(text, f);
      ADD_FAILURE() << "accepted:\n" << text;
    } catch (const core::InputError& e) {
      EXPECT_EQ(e.where(), at) << e.what();
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  const std::string head =
      "t,x,y,theta,yaw1_1,roll_1,yaw2_1,yaw1_2,roll_2,yaw2_2,yaw1_3,roll_3,yaw2_3";
  const std::string row0 = "0,0,0,0,0,0,0,0,0,0,0,0,0\n";
  const std::string row1 = "0.1,0,0,0,0,0,0,0,0,0,0,0,0\n";
  const std::string row2 = "0.2,0,0,0,0,0,0,0,0,0,0,0,0\n";
  const std::string good = head + "\n" + row0 + row1 + row2;
  ASSERT_EQ(parse_trials(good, f).size(), 1u);

  err("", "bad.csv:1", "no header line");
  err("# only a comment\n\n", "bad.csv:2", "no header line");
  err(head + "\n", "bad.csv:1", "no samples after the header");
  // Columns: missing, duplicated, an incomplete or too small joint set, a bad module number.
  err("t,x,theta,yaw1_1,roll_1,yaw2_1\n", "bad.csv:1", "no column 'y'");
  err(head + ",x\n" + row0, "bad.csv:1:" + std::to_string(head.size() + 2),
      "column 'x' appears twice (first at column 3)");
  err("t,x,y,theta,yaw1_1,roll_1,yaw2_1,yaw1_2,roll_2,yaw2_2\n", "bad.csv:1",
      "joint columns for 2 modules; a Multipod has 3 to 6");
  err("t,x,y,theta,yaw1_1,roll_1,yaw2_1,yaw1_2,yaw2_2,yaw1_3,roll_3,yaw2_3\n", "bad.csv:1",
      "no column 'roll_2'");
  err("t,x,y,theta,yaw1_7\n", "bad.csv:1:13", "joint columns are numbered 1..6");
  err("t,x,y,theta,roll_01\n", "bad.csv:1:13", "joint columns are numbered 1..6");
  // Rows: the wrong width, a bad number (its column), out of range, time not increasing.
  err(head + "\n" + row0 + "0.1,0,0,0,0,0,0,0,0,0,0,0\n", "bad.csv:3",
      "the row has 12 cells, the header 13");
  err(head + "\n" + row0 + "0.1,0, abc,0,0,0,0,0,0,0,0,0,0\n", "bad.csv:3:8",
      "y: 'abc' is not a finite number");
  err(head + "\n" + row0 + "0.1,0,0,0,0,0,0,0,nan,0,0,0,0\n", "bad.csv:3:19",
      "roll_2: 'nan' is not a finite number");
  err(head + "\n" + row0 + "0.1,0,0,0,0,0,0,0,,0,0,0,0\n", "bad.csv:3:19",
      "roll_2: '' is not a finite number");
  err(head + "\n" + row0 + "0.1,2e3,0,0,0,0,0,0,0,0,0,0,0\n", "bad.csv:3:5", "must be in");
  err(head + "\n" + row0 + row1 + "0.1,0,0,0,0,0,0,0,0,0,0,0,0\n", "bad.csv:4:1",
      "t must increase strictly within a trial; the row before has t = 0.1");
  // Too short a trial: at its last row.
  err(head + "\n" + row0 + row1, "bad.csv:3", "has 2 samples; a trial needs at least 3");
  // Ids: an empty id, an id that comes back, a short trial in the middle of the file.
  const std::string idhead = "id," + head + "\n";
  err(idhead + "1," + row0 + "," + row1, "bad.csv:3:1", "id: empty");
  err(idhead + "1," + row0 + "1," + row1 + "1," + row2 + "2," + row0 + "2," + row1 + "2," + row2 +
          "1," + row0,
      "bad.csv:8:1", "id 1 comes back after id 2");
  err(idhead + "1," + row0 + "1," + row1 + "2," + row0 + "2," + row1 + "2," + row2, "bad.csv:3",
      "bad.csv, id 1 has 2 samples");
  // Time restarts with a new id (each trial its own clock) but must increase within one.
  EXPECT_EQ(parse_trials(idhead + "1," + row0 + "1," + row1 + "1," + row2 + "2," + row0 + "2," +
                             row1 + "2," + row2,
                         f)
                .size(),
            2u);
  // A missing file names itself.
  try {
    (void)read_trials("/nonexistent/trial.csv");
    ADD_FAILURE();
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.where(), "/nonexistent/trial.csv");
  }
}

TEST(Trial, ValidateRefusesInconsistentTrialsByLabel) {
  const MotionTrial good = random_trial(3, 5, 21);
  EXPECT_NO_THROW(validate(good));
  auto refused = [](const MotionTrial& t, const std::string& part) {
    try {
      validate(t);
      ADD_FAILURE() << part;
    } catch (const core::InputError& e) {
      EXPECT_EQ(e.where(), "random");
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  MotionTrial t = good;
  t.pose.conservativeResize(4, 3);
  refused(t, "sizes disagree");
  t = good;
  t.joints.conservativeResize(5, 8);
  refused(t, "8 joint columns");
  t = good;
  t.joints.conservativeResize(5, 21);
  refused(t, "21 joint columns");
  t = good;
  t.t(3) = t.t(2);
  refused(t, "time does not increase at sample 3");
  t = good;
  t.joints(1, 1) = std::numeric_limits<double>::infinity();
  refused(t, "not finite");
  t = random_trial(3, 2, 22);
  refused(t, "2 samples");
  std::ostringstream out;
  EXPECT_THROW(write_trial(out, t), core::InputError);
}

TEST(Trial, ResidualFileTextIsReadBackByTheScenesReaderBitForBit) {
  std::mt19937_64 rng(31);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int legs : {6, 8, 12}) {
    Eigen::Matrix<double, 3, Eigen::Dynamic> B(3, 2 * legs);
    for (Eigen::Index i = 0; i < B.size(); ++i) {
      B.data()[i] = std::ldexp(g(rng), static_cast<int>(i % 9) - 6);
    }
    B(0, 0) = -0.0;
    B(2, 1) = 1e3;  // the range's ends
    B(1, 2) = -1e3;
    const std::string text =
        residual_file_text(B, "B of a test\n\nsecond line # with a hash\nlast");
    EXPECT_EQ(text.rfind("# B of a test\n#\n# second line # with a hash\n# last\n", 0), 0u) << text;
    const Eigen::Matrix<double, 3, Eigen::Dynamic> back =
        scene::parse_residual(text, "B.csv", legs);
    expect_bitwise_equal(back, B);
  }
  EXPECT_EQ(residual_file_text(Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, 2), ""),
            "0,0\n0,0\n0,0\n");
  Eigen::Matrix<double, 3, Eigen::Dynamic> bad =
      Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, 12);
  bad(1, 3) = std::nan("");
  EXPECT_THROW((void)residual_file_text(bad, ""), core::InputError);
}

}  // namespace
}  // namespace slipwalk::residual
