// core: CSV values read back bit-identical; atomic files appear whole or not at all.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "core/atomic_file.hpp"
#include "core/csv.hpp"
#include "core/error.hpp"
#include "core/provenance.hpp"

namespace slipwalk::core {
namespace {

TEST(Csv, DoublesRoundTripExactly) {
  for (double v : {0.1, 1.0 / 3.0, 1.1113692880861064, 4.9e-324, 1.7976931348623157e308, -0.0}) {
    EXPECT_EQ(std::strtod(format_double(v).c_str(), nullptr), v) << format_double(v);
  }
  EXPECT_EQ(format_double(9.81), "9.81");  // the shortest form, not 9.8100000000000005
  EXPECT_EQ(format_double(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(format_double(std::numeric_limits<double>::quiet_NaN()), "nan");
  EXPECT_EQ(format_double(-std::numeric_limits<double>::infinity()), "-inf");
}

// Every line-end convention a CSV input may come with reads as the same lines: LF, CRLF, a final
// line without an end, and a spreadsheet's byte-order mark. Generated over random lines.
TEST(Csv, LineReaderReadsCrlfAndByteOrderMarkAsLf) {
  std::uint32_t state = 12345;
  const auto next = [&state] { return state = state * 1664525U + 1013904223U; };
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<std::string> lines(1 + next() % 6);
    for (auto& line : lines) {
      for (std::uint32_t k = next() % 8; k > 0; --k) {
        line += "ab,1.5 \t"[next() % 8];
      }
    }
    const bool bom = trial % 3 == 0;
    const bool last_ended = trial % 2 == 0;
    for (const std::string eol : {"\n", "\r\n"}) {
      std::string text = bom ? "\xEF\xBB\xBF" : "";
      for (std::size_t i = 0; i < lines.size(); ++i) {
        text += lines[i];
        text += i + 1 < lines.size() || last_ended ? eol : "";
      }
      LineReader reader(text);
      std::vector<std::string> read;
      for (std::string_view line; reader.next(line);) {
        read.emplace_back(line);
        EXPECT_EQ(reader.line_number(), static_cast<long long>(read.size()));
      }
      // An empty last line without an end is no line at all.
      std::vector<std::string> expected = lines;
      if (!last_ended && expected.back().empty()) {
        expected.pop_back();
      }
      EXPECT_EQ(read, expected) << trial;
    }
  }
  // Only one '\r' belongs to the line end; another one is content.
  LineReader reader("a\r\r\nb\r");
  std::string_view line;
  ASSERT_TRUE(reader.next(line));
  EXPECT_EQ(line, "a\r");
  ASSERT_TRUE(reader.next(line));
  EXPECT_EQ(line, "b");
  EXPECT_FALSE(reader.next(line));
}

TEST(Csv, SplitCellsGivesEachCellAndItsColumn) {
  std::vector<std::string_view> cells;
  std::vector<int> starts;
  split_cells("1,,22,x y", cells, starts);
  EXPECT_EQ(cells, (std::vector<std::string_view>{"1", "", "22", "x y"}));
  EXPECT_EQ(starts, (std::vector<int>{1, 3, 4, 7}));
  split_cells("", cells, starts);
  EXPECT_EQ(cells, (std::vector<std::string_view>{""}));
  EXPECT_EQ(starts, (std::vector<int>{1}));
}

TEST(Csv, WritesHeaderRowsAndQuotesText) {
  std::ostringstream out;
  CsvWriter csv(out, {"a", "b", "c"});
  csv.cell(1.5).cell(2).cell("x,y");
  csv.end_row();
  EXPECT_EQ(out.str(), "a,b,c\n1.5,2,\"x,y\"\n");
  csv.cell(1.0);
  EXPECT_THROW(csv.end_row(), std::logic_error);  // a short row is a bug, not data
}

class AtomicFileTest : public ::testing::Test {
 protected:
  std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("slipwalk_atomic_" + std::to_string(::getpid()));
  void SetUp() override { std::filesystem::create_directories(dir); }
  void TearDown() override { std::filesystem::remove_all(dir); }
};

TEST_F(AtomicFileTest, CommitRenamesOntoTheTarget) {
  const auto target = dir / "out.csv";
  {
    AtomicFile f(target);
    f.stream() << "hello\n";
    EXPECT_FALSE(std::filesystem::exists(target));  // nothing visible before commit
    f.commit();
  }
  std::ifstream in(target);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "hello");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 1);  // no temp left
}

TEST_F(AtomicFileTest, AbandonedFileLeavesNothing) {
  const auto target = dir / "partial.csv";
  try {
    AtomicFile f(target);
    f.stream() << "half a row";
    throw std::runtime_error("computation failed");
  } catch (const std::runtime_error&) {
  }
  EXPECT_FALSE(std::filesystem::exists(target));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 0);
}

TEST_F(AtomicFileTest, UnwritableFolderIsAnInputError) {
  EXPECT_THROW(AtomicFile("/proc/slipwalk_no_such_dir/x.csv"), InputError);
}

TEST(Provenance, NamesCommitCompilerAndLibraries) {
  const auto p = build_provenance();
  EXPECT_FALSE(p.at("git_commit").get<std::string>().empty());
  EXPECT_FALSE(p.at("compiler").get<std::string>().empty());
  for (const char* lib : {"eigen", "sundials", "gsl", "boost"}) {
    EXPECT_FALSE(p.at("libraries").at(lib).get<std::string>().empty()) << lib;
  }
}

}  // namespace
}  // namespace slipwalk::core
