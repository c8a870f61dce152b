#include "mocaplink/io/rotating_file.hpp"

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

namespace mocaplink::io {
namespace {

std::string read(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

class RotatingFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::random_device seed;
    // A space and a name outside ASCII (UTF-8 here, UTF-16 on Windows), as a user name can be.
    dir_ = std::filesystem::temp_directory_path() /
           std::filesystem::u8path("mocaplink logs J\xC3\xBCrgen " + std::to_string(seed()));
  }
  void TearDown() override {
    std::error_code ignored;
    std::filesystem::remove_all(dir_, ignored);
  }
  std::filesystem::path dir_;
};

TEST_F(RotatingFileTest, CreatesItsDirectoryAndAppendsAcrossOpens) {
  const auto path = dir_ / "logs" / "mocaplink.log";
  {
    RotatingFile file(path, 1000, 2);
    ASSERT_TRUE(file.ok()) << file.error();
    file.write("one\n");
  }
  {
    RotatingFile file(path, 1000, 2);
    file.write("two\n");
  }
  EXPECT_EQ(read(path), "one\ntwo\n");
  EXPECT_EQ(RotatingFile(path, 1000, 2).older(1), dir_ / "logs" / "mocaplink.1.log");
}

TEST_F(RotatingFileTest, RotatesBeforeALineWouldNotFitAndKeepsTheNewestOldFiles) {
  const auto path = dir_ / "mocaplink.log";
  RotatingFile file(path, 10, 2);
  ASSERT_TRUE(file.ok()) << file.error();
  for (const char* line : {"aaaa\n", "bbbb\n", "cccc\n", "dddd\n", "eeee\n", "ffff\n", "gggg\n"}) {
    file.write(line);
  }
  file.flush();
  EXPECT_EQ(read(path), "gggg\n");
  EXPECT_EQ(read(file.older(1)), "eeee\nffff\n");
  EXPECT_EQ(read(file.older(2)), "cccc\ndddd\n");
  EXPECT_FALSE(std::filesystem::exists(file.older(3)));  // a b went with the oldest
}

TEST_F(RotatingFileTest, ALineLongerThanTheLimitIsWrittenWhole) {
  const auto path = dir_ / "mocaplink.log";
  RotatingFile file(path, 4, 1);
  file.write("ab\n");
  file.write("a long line\n");
  file.flush();
  EXPECT_EQ(read(path), "a long line\n");
  EXPECT_EQ(read(file.older(1)), "ab\n");
}

TEST_F(RotatingFileTest, AnUnusableDirectoryIsReportedNotFatal) {
  std::filesystem::create_directories(dir_);
  const auto blocker = dir_ / "a file";
  std::ofstream(blocker) << "x";
  RotatingFile file(blocker / "logs" / "mocaplink.log", 100, 1);
  EXPECT_FALSE(file.ok());
  EXPECT_EQ(file.error().rfind("cannot create ", 0), 0u) << file.error();
  file.write("nothing happens\n");
  file.flush();
}

}  // namespace
}  // namespace mocaplink::io
