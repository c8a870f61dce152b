#include "mocaplink/io/signing_store.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "scoped_env.hpp"

namespace mocaplink::io {
namespace {

class TempDir {
 public:
  /// A new directory with a space in its name, so every test here also covers such paths.
  TempDir() {
    std::random_device seed;
    std::mt19937_64 random(seed());
    do {
      path_ = std::filesystem::temp_directory_path() /
              ("mocaplink io " + std::to_string(random() % 1'000'000'000));
    } while (!std::filesystem::create_directory(path_));
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

using testing_support::ScopedEnv;

TEST(DefaultStateDir, TheOverrideComesFirst) {
  const ScopedEnv state("MOCAPLINK_STATE_DIR", "override dir");
  const ScopedEnv local("LOCALAPPDATA", "C:\\Users\\lab\\AppData\\Local");
  const ScopedEnv systemd("STATE_DIRECTORY", "/var/lib/mocaplink");
  EXPECT_EQ(default_state_dir(), std::filesystem::path("override dir"));
}

#ifdef _WIN32
TEST(DefaultStateDir, WindowsUsesLocalAppData) {
  const ScopedEnv state("MOCAPLINK_STATE_DIR", nullptr);
  const ScopedEnv local("LOCALAPPDATA", "C:\\Users\\lab user\\AppData\\Local");
  EXPECT_EQ(default_state_dir(),
            std::filesystem::path("C:\\Users\\lab user\\AppData\\Local\\mocaplink"));
}
#else
TEST(DefaultStateDir, LinuxUsesSystemdThenXdgThenHome) {
  const ScopedEnv state("MOCAPLINK_STATE_DIR", nullptr);
  const ScopedEnv home("HOME", "/home/lab");
  {
    const ScopedEnv systemd("STATE_DIRECTORY", "/var/lib/mocaplink:/var/lib/other");
    EXPECT_EQ(default_state_dir(), std::filesystem::path("/var/lib/mocaplink"));
  }
  const ScopedEnv systemd("STATE_DIRECTORY", nullptr);
  {
    const ScopedEnv xdg("XDG_STATE_HOME", "/home/lab/state");
    EXPECT_EQ(default_state_dir(), std::filesystem::path("/home/lab/state/mocaplink"));
  }
  const ScopedEnv xdg("XDG_STATE_HOME", nullptr);
  EXPECT_EQ(default_state_dir(), std::filesystem::path("/home/lab/.local/state/mocaplink"));
}
#endif

TEST(SigningTimestampFile, ExactText) {
  EXPECT_EQ(format_signing_timestamp(31557600000000u),
            "mocaplink-signing-timestamp 1 31557600000000\n");
}

TEST(SigningTimestampFile, ParsesWhatItWrites) {
  for (const std::uint64_t v :
       {std::uint64_t{0}, std::uint64_t{1}, std::uint64_t{281474976710655}}) {
    EXPECT_EQ(parse_signing_timestamp(format_signing_timestamp(v)), v);
  }
  EXPECT_EQ(parse_signing_timestamp("mocaplink-signing-timestamp 1 42"), 42u);  // no newline
}

TEST(SigningTimestampFile, RejectsAnythingElse) {
  for (const char* text :
       {"", "42\n", "mocaplink-signing-timestamp 2 42\n", "mocaplink-signing-timestamp 1 \n",
        "mocaplink-signing-timestamp 1 -1\n", "mocaplink-signing-timestamp 1 4x\n",
        "mocaplink-signing-timestamp 1 42\n\n",
        "mocaplink-signing-timestamp 1 281474976710656\n",  // 2^48
        "mocaplink-signing-timestamp 1 99999999999999999999999\n"}) {
    EXPECT_FALSE(parse_signing_timestamp(text).has_value()) << text;
  }
}

TEST(SigningStore, SaveThenLoad) {
  TempDir dir;
  const SigningStore store(dir.path() / "state");  // created on first save
  EXPECT_FALSE(store.load("quad1").has_value());
  std::string problem;
  ASSERT_TRUE(store.save("quad1", 123456789u, &problem)) << problem;
  ASSERT_TRUE(store.save("quad1", 123456790u, &problem)) << problem;
  EXPECT_EQ(store.load("quad1"), 123456790u);
  EXPECT_FALSE(store.load("quad2").has_value());
  EXPECT_FALSE(std::filesystem::exists(store.path_for("quad1").string() + ".tmp"));
}

TEST(SigningStore, CorruptFileIsReportedAndIgnored) {
  TempDir dir;
  const SigningStore store(dir.path());
  std::ofstream(store.path_for("quad1")) << "garbage";
  std::string problem;
  EXPECT_FALSE(store.load("quad1", &problem).has_value());
  EXPECT_NE(problem.find("quad1.signing"), std::string::npos) << problem;
}

TEST(SigningStore, UnwritableDirectoryFailsWithReason) {
  TempDir dir;
  std::ofstream(dir.path() / "file") << "x";
  const SigningStore store(dir.path() / "file" / "sub");  // a path through a regular file
  std::string problem;
  EXPECT_FALSE(store.save("quad1", 1, &problem));
  EXPECT_FALSE(problem.empty());
}

}  // namespace
}  // namespace mocaplink::io
