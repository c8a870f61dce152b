#include "mocaplink/io/tlog.hpp"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include <gtest/gtest.h>

namespace mocaplink::io {
namespace {

TEST(Tlog, TimePrefixIsBigEndianMicroseconds) {
  // 2026-01-01T00:00:00Z = 1767225600 s = 0x0006474846204000 µs.
  const auto prefix = tlog_time_prefix(1767225600000000);
  EXPECT_EQ(prefix, (std::array<std::uint8_t, 8>{0x00, 0x06, 0x47, 0x48, 0x46, 0x20, 0x40, 0x00}));
}

TEST(Tlog, WritesPrefixedFramesAndFlushesOnClose) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("mocaplink-tlog-test-" + std::to_string(::getpid()) + ".tlog");
  std::string problem;
  auto writer = TlogWriter::create(path, &problem);
  ASSERT_NE(writer, nullptr) << problem;
  // HEARTBEAT from golden-vectors.json ("heartbeat").
  const std::vector<std::uint8_t> frame = {0xfd, 0x09, 0x00, 0x00, 0x00, 0x01, 0xc5,
                                           0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
                                           0x12, 0x08, 0x00, 0x04, 0x03, 0x1e, 0xe4};
  writer->write(1, frame);
  writer->write(2, frame);
  writer->close();
  EXPECT_EQ(writer->records(), 2u);
  EXPECT_FALSE(writer->failed());
  std::vector<std::uint8_t> bytes;
  {
    std::ifstream in(path, std::ios::binary);  // closed before the removal (Windows needs that)
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  ASSERT_EQ(bytes.size(), 2 * (8 + frame.size()));
  EXPECT_EQ(bytes[7], 1);
  EXPECT_EQ(bytes[8], 0xfd);
  EXPECT_EQ(bytes[8 + frame.size() + 7], 2);
  EXPECT_TRUE(std::equal(frame.begin(), frame.end(), bytes.begin() + 8));
  writer->write(3, frame);  // ignored after close
  EXPECT_EQ(writer->records(), 2u);
  std::filesystem::remove(path);
}

TEST(Tlog, AppendKeepsEarlierRecordsAndTruncateDoesNot) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("mocaplink-tlog-append-" + std::to_string(::getpid()) + ".tlog");
  const std::vector<std::uint8_t> frame = {0xfe, 0x00, 0x00, 0x01, 0xc5, 0x00, 0x00, 0x00};
  auto size_after = [&](TlogWriter::Mode mode, int records) {
    std::string problem;
    auto writer = TlogWriter::create(path, &problem, mode);
    EXPECT_NE(writer, nullptr) << problem;
    for (int i = 0; i < records; ++i) writer->write(i, frame);
    writer->close();
    return std::filesystem::file_size(path);
  };
  const std::uintmax_t record = 8 + frame.size();
  EXPECT_EQ(size_after(TlogWriter::Mode::truncate, 2), 2 * record);
  EXPECT_EQ(size_after(TlogWriter::Mode::append, 3), 5 * record);
  EXPECT_EQ(size_after(TlogWriter::Mode::truncate, 1), record);
  std::filesystem::remove(path);
  EXPECT_EQ(size_after(TlogWriter::Mode::append, 1), record);  // created when missing
  std::filesystem::remove(path);
}

TEST(Tlog, CreateFailsWithReason) {
  std::string problem;
  EXPECT_EQ(TlogWriter::create("/nonexistent-dir/x.tlog", &problem), nullptr);
  EXPECT_NE(problem.find("/nonexistent-dir/x.tlog"), std::string::npos);
}

}  // namespace
}  // namespace mocaplink::io
