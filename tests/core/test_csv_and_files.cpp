// core: CSV values read back bit-identical; atomic files appear whole or not at all.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

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
