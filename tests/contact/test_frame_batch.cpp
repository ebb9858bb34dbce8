// The CSV batch form of the frame format: CRLF line ends (and a spreadsheet's byte-order mark)
// read exactly as LF, for every generated batch; a wrong header names its first wrong cell;
// cells outside contact::limits are refused at row:col with the range.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "connection/frame_model.hpp"
#include "connection/local_connection.hpp"
#include "contact/frame_batch.hpp"
#include "core/csv.hpp"
#include "core/error.hpp"
#include "scene/effects.hpp"

namespace slipwalk::contact {
namespace {

/// A batch of `rows` random frames of a robot with `legs` legs on a circle, with line end `eol`.
std::string batch(int legs, int rows, const std::string& eol, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::string text;
  const auto columns = batch_input_columns(legs);
  for (std::size_t c = 0; c < columns.size(); ++c) {
    text.append(c ? "," : "").append(columns[c]);
  }
  text += eol;
  for (int r = 0; r < rows; ++r) {
    text += core::format_double(u(rng));
    for (int j = 0; j < legs; ++j) {
      const double a = 6.283185307179586 * j / legs;
      const double q[6] = {0.3 * std::cos(a), 0.3 * std::sin(a), -0.1 + 0.02 * u(rng),
                           0.1 * u(rng),      0.1 * u(rng),      0.0};
      for (const double x : q) {
        text.append(",").append(core::format_double(x));
      }
    }
    text += eol;
    if (r % 3 == 1) {
      text += eol;  // an empty line, skipped
    }
  }
  return text;
}

TEST(FrameBatch, CrlfAndByteOrderMarkReadExactlyAsLf) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 40; ++trial) {
    const int legs = 3 + trial % 6;
    const int rows = 1 + trial % 7;
    std::mt19937 a = rng;
    std::mt19937 b = rng;
    std::mt19937 c = rng;
    const std::string lf = batch(legs, rows, "\n", a);
    const std::string crlf = batch(legs, rows, "\r\n", b);
    std::string bom = "\xEF\xBB\xBF";
    bom.append(batch(legs, rows, "\r\n", c));
    bom.pop_back();  // a last line ended by '\r' alone
    rng.discard(1000);
    const Robot robot = uniform_robot(legs, 100.0, 0.7, 9.81);
    for (const auto law :
         {connection::FrictionLaw::kViscousCoulomb, connection::FrictionLaw::kCoulomb}) {
      const std::string expected = connection::evaluate_frame_batch(robot, lf, "f.csv", law);
      EXPECT_EQ(std::count(expected.begin(), expected.end(), '\n'), rows + 1);
      EXPECT_EQ(connection::evaluate_frame_batch(robot, crlf, "f.csv", law), expected);
      EXPECT_EQ(connection::evaluate_frame_batch(robot, bom, "f.csv", law), expected);
    }
  }
}

// The batch goes four rows per call of connection::evaluate_batch; each output row must be what
// connection::evaluate gives for that row's frame alone: the same contacts, status and
// certificate flag, the numbers to rounding.
TEST(FrameBatch, EveryRowIsThatFrameEvaluatedAloneToRounding) {
  std::mt19937 rng(13);
  for (const int legs : {3, 6, 7}) {
    for (const int rows : {1, 4, 9}) {
      const std::string text = batch(legs, rows, "\n", rng);
      const Robot robot = uniform_robot(legs, 100.0, 0.7, 9.81);
      const std::string got = connection::evaluate_frame_batch(
          robot, text, "f.csv", connection::FrictionLaw::kViscousCoulomb);
      FrameBatchReader reader(text, "f.csv", legs);
      core::LineReader lines(got);
      std::string_view line;
      ASSERT_TRUE(lines.next(line));  // the header
      Frame f(robot);
      std::vector<std::string_view> cells;
      std::vector<int> starts;
      int count = 0;
      while (reader.next(f)) {
        connection::evaluate(robot, f, connection::FrictionLaw::kViscousCoulomb);
        ASSERT_TRUE(lines.next(line));
        core::split_cells(line, cells, starts);
        ASSERT_EQ(cells.size(), 9U + 4U * static_cast<std::size_t>(legs));
        const auto cell = [&cells](std::size_t i) { return std::stod(std::string(cells[i])); };
        std::vector<double> expected = {static_cast<double>(reader.frame_number()),
                                        f.alpha,
                                        f.beta,
                                        f.z,
                                        f.v_body(0),
                                        f.v_body(1),
                                        f.v_body(2),
                                        static_cast<double>(f.support.status),
                                        f.friction.converged ? 1.0 : 0.0};
        for (int j = 0; j < legs; ++j) {
          expected.insert(expected.end(),
                          {static_cast<double>(f.contact[j]), f.Fz(j), f.Fxy(0, j), f.Fxy(1, j)});
        }
        for (std::size_t i = 0; i < expected.size(); ++i) {
          const bool exact = i == 0 || i == 7 || i == 8 || (i >= 9 && (i - 9) % 4 == 0);
          if (exact) {
            EXPECT_EQ(cell(i), expected[i]) << "row " << count << " column " << i;
          } else {
            EXPECT_NEAR(cell(i), expected[i], 1e-11 * (std::abs(expected[i]) + 1e-3))
                << "row " << count << " column " << i;
          }
        }
        ++count;
      }
      EXPECT_EQ(count, rows);
      EXPECT_FALSE(lines.next(line));
    }
  }
}

std::string error_of(const std::string& text, int legs) {
  try {
    (void)connection::evaluate_frame_batch(uniform_robot(legs), text, "f.csv",
                                           connection::FrictionLaw::kViscousCoulomb);
  } catch (const core::InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(FrameBatch, AWrongHeaderNamesItsFirstWrongCell) {
  EXPECT_EQ(error_of("theta,q0x,q0Y,q0z,qd0x,qd0y,qd0z\r\n", 1).rfind("f.csv:1:11: ", 0), 0U);
  EXPECT_NE(
      error_of("theta,q0x,q0Y,q0z,qd0x,qd0y,qd0z\n", 1).find("expected 'q0y' here, got 'q0Y'"),
      std::string::npos);
  EXPECT_EQ(error_of("theta,q0x,q0y\n", 1).rfind("f.csv:1:14: ", 0), 0U);
  EXPECT_EQ(error_of("theta,q0x,q0y,q0z,qd0x,qd0y,qd0z,x\n", 1).rfind("f.csv:1:34: ", 0), 0U);
  EXPECT_EQ(error_of("", 1).rfind("f.csv: empty", 0), 0U);
}

TEST(FrameBatch, CellsOutsideTheRangesAreRefusedAtRowAndColumn) {
  const std::string header = "theta,q0x,q0y,q0z,qd0x,qd0y,qd0z\r\n";
  struct Case {
    std::string row;
    std::string start;
    std::string range;
  };
  for (const Case& c : std::vector<Case>{
           {"0,0,0,-1e308,0,0,0", "f.csv:2:7: must be in ", limits::kPosition.describe()},
           {"0,0,0,-1,0,inf,0", "f.csv:2:12: expected a finite number", ""},
           {"0,0,0,-1,0,0,nan", "f.csv:2:14: expected a finite number", ""},
           {"1e30,0,0,-1,0,0,0", "f.csv:2:1: must be in ", limits::kYaw.describe()},
           {"0,0,0,-1,-2e3,0,0", "f.csv:2:10: must be in ", limits::kVelocity.describe()},
           {"0,0,0,-1,0,0,0\r", "f.csv:2:14: expected a finite number", ""},  // "\r\r\n"
       }) {
    std::string text = header;
    text.append(c.row).append("\r\n");
    const std::string what = error_of(text, 1);
    EXPECT_EQ(what.rfind(c.start, 0), 0U) << what;
    EXPECT_NE(what.find(c.range), std::string::npos) << what;
  }
  // Subnormal and tiny cells are values, not errors.
  EXPECT_EQ(error_of(header + "4.9e-324,1e-320,0,-1,1e-30,0,0\r\n", 1), "(accepted)");
}

TEST(ResidualCsv, CrlfReadsExactlyAsLf) {
  const std::string lf = "# B\n1,2,3,4\n\n5,6,7,8 # row 2\n9,10,11,12\n";
  std::string crlf;
  for (const char ch : lf) {
    crlf += ch == '\n' ? std::string("\r\n") : std::string(1, ch);
  }
  EXPECT_EQ(scene::parse_residual(crlf, "b.csv", 2), scene::parse_residual(lf, "b.csv", 2));
  try {
    (void)scene::parse_residual("1,2,3,4\r\n5,x,7,8\r\n", "b.csv", 2);
    ADD_FAILURE() << "accepted";
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.where(), "b.csv:2:3");
  }
}

}  // namespace
}  // namespace slipwalk::contact
