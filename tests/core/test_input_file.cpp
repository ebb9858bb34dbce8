// core::read_input_file: every kind of path that is not a readable file of bounded size is
// refused as bad input naming the path, and a readable one comes back byte for byte.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "core/error.hpp"
#include "core/input_file.hpp"

namespace slipwalk::core {
namespace {

namespace fs = std::filesystem;

class InputFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("slipwalk_input_file_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// The message of the InputError read_input_file throws for `path`, checked to name it.
  static std::string refusal(const fs::path& path, std::size_t max_bytes = kInputMaxBytes) {
    try {
      (void)read_input_file(path, "a test file", max_bytes);
    } catch (const InputError& e) {
      EXPECT_EQ(e.where(), path.empty() ? "<empty path>" : path.string());
      return e.what();
    }
    ADD_FAILURE() << "no InputError for " << path;
    return {};
  }

  fs::path dir_;
};

TEST_F(InputFile, AnyBytesComeBackExactlyIncludingNulAndCr) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 20; ++trial) {
    std::string bytes(static_cast<std::size_t>(rng() % 200'000), '\0');
    for (char& c : bytes) {
      c = static_cast<char>(rng() & 0xff);
    }
    const fs::path p = dir_ / "bytes.bin";
    std::ofstream(p, std::ios::binary) << bytes;
    EXPECT_EQ(read_input_file(p, "a test file"), bytes) << "trial " << trial;
  }
}

TEST_F(InputFile, AMissingFileIsRefusedAsMissing) {
  EXPECT_NE(refusal(dir_ / "nope.toml").find("no such file"), std::string::npos);
  EXPECT_NE(refusal(dir_ / "no_dir" / "x.toml").find("no such file"), std::string::npos);
}

TEST_F(InputFile, AFolderIsRefusedAsAFolderWhateverItsSpelling) {
  fs::create_directories(dir_ / "sub");
  for (const fs::path& p : {dir_ / "sub", fs::path((dir_ / "sub").string() + "/"),
                            dir_ / "sub" / ".", dir_ / "sub" / ".."}) {
    EXPECT_NE(refusal(p).find("is a folder"), std::string::npos) << p;
  }
}

TEST_F(InputFile, ANamedPipeIsRefusedWithoutWaitingForAWriter) {
  const fs::path p = dir_ / "pipe.toml";
  ASSERT_EQ(::mkfifo(p.c_str(), 0600), 0);
  EXPECT_NE(refusal(p).find("is a named pipe"), std::string::npos);
}

TEST_F(InputFile, AnEmptyPathIsRefused) {
  EXPECT_NE(refusal(fs::path()).find("no file named"), std::string::npos);
}

TEST_F(InputFile, TextBeyondTheLimitIsRefusedAtAnyLimit) {
  const fs::path p = dir_ / "long.txt";
  std::ofstream(p, std::ios::binary) << std::string(1000, 'x');
  for (std::size_t limit : {0UL, 1UL, 999UL}) {
    EXPECT_NE(refusal(p, limit).find("longer than the limit of " + std::to_string(limit)),
              std::string::npos);
  }
  EXPECT_EQ(read_input_file(p, "a test file", 1000).size(), 1000U);
}

TEST_F(InputFile, AnEndlessDeviceStopsAtTheLimit) {
  EXPECT_NE(refusal("/dev/zero", 1 << 20).find("longer than the limit"), std::string::npos);
}

TEST_F(InputFile, AStreamBeyondTheLimitIsRefusedNamingItsSource) {
  std::istringstream in(std::string(100, 'y'));
  try {
    (void)read_input_stream(in, "<stdin>", "the frame JSON", 50);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "<stdin>");
  }
}

}  // namespace
}  // namespace slipwalk::core
