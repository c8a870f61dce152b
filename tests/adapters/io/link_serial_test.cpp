#include "mocaplink/io/link_serial.hpp"

#include <fcntl.h>
#include <stdlib.h>
#include <unistd.h>

#include <array>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "link_test_support.hpp"

namespace mocaplink::io {
namespace {

using test::kHeartbeat;
using test::run_until;

/// A pseudo-terminal pair: the link opens the slave path like a USB serial device; the test
/// plays the vehicle on the master side.
class Pty {
 public:
  Pty() {
    master_ = ::posix_openpt(O_RDWR | O_NOCTTY);
    if (master_ >= 0 && ::grantpt(master_) == 0 && ::unlockpt(master_) == 0) {
      slave_path_ = ::ptsname(master_);
    }
  }
  ~Pty() {
    if (master_ >= 0) ::close(master_);
  }
  [[nodiscard]] int master() const { return master_; }
  [[nodiscard]] const std::string& slave_path() const { return slave_path_; }

 private:
  int master_ = -1;
  std::string slave_path_;
};

TEST(SerialLink, RawBytesBothWaysThroughAPty) {
  Pty pty;
  ASSERT_FALSE(pty.slave_path().empty());
  asio::io_context loop;
  SerialLink link(loop, pty.slave_path(), 921600, test::options());
  std::vector<std::uint32_t> msgids;
  link.start([&](const mavlink::FrameView& f, core::HostTime) { msgids.push_back(f.msgid); }, {});
  ASSERT_TRUE(run_until(loop, [&] { return link.state() == TransportState::up; }));
  EXPECT_EQ(link.url(), "serial://" + pty.slave_path() + "?baud=921600");

  // Out: raw mode means 0x0a/0x0d and every other byte pass unchanged.
  ASSERT_TRUE(link.send(kHeartbeat));
  ASSERT_TRUE(run_until(loop, [&] { return link.counters().frames_sent == 1; }));
  std::vector<std::uint8_t> got;
  std::array<std::uint8_t, 256> buffer{};
  while (got.size() < kHeartbeat.size()) {
    const ssize_t n = ::read(pty.master(), buffer.data(), buffer.size());
    ASSERT_GT(n, 0);
    got.insert(got.end(), buffer.begin(), buffer.begin() + n);
  }
  EXPECT_EQ(got, kHeartbeat);

  // In: garbage, then a frame in two writes.
  const std::array<std::uint8_t, 3> garbage{0x0d, 0x0a, 0x55};
  ASSERT_EQ(::write(pty.master(), garbage.data(), garbage.size()), 3);
  ASSERT_EQ(::write(pty.master(), kHeartbeat.data(), 7), 7);
  ASSERT_EQ(::write(pty.master(), kHeartbeat.data() + 7, kHeartbeat.size() - 7),
            static_cast<ssize_t>(kHeartbeat.size() - 7));
  ASSERT_TRUE(run_until(loop, [&] { return msgids.size() == 1; }));
  EXPECT_EQ(link.counters().parser.garbage_bytes, 3u);
  link.close(std::chrono::milliseconds(0));
}

TEST(SerialLink, MissingDeviceStaysDownAndRetries) {
  asio::io_context loop;
  SerialLink link(loop, "/dev/mocaplink-no-such-tty", 57600,
                  test::options(std::chrono::milliseconds(5)));
  int downs = 0;
  link.start({}, [&](TransportState s, const std::string&) {
    downs += s == TransportState::down ? 1 : 0;
  });
  ASSERT_TRUE(run_until(loop, [&] { return link.state() == TransportState::down; }));
  EXPECT_FALSE(link.send(kHeartbeat));
  EXPECT_EQ(link.counters().dropped_down, 1u);
  EXPECT_EQ(link.counters().connects, 0u);
  EXPECT_EQ(downs, 1);  // retries do not re-announce the same state
}

}  // namespace
}  // namespace mocaplink::io
