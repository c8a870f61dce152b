// DdsTimeSyncCheck against a scripted PX4 client whose time sync is off by ε: it stamps what it
// sends with its own time plus its offset estimate (PX4 v1.14.3 uORB/ucdr: `t + time_offset`),
// so a sample published at true wall time T carries T + ε and arrives at T + transport.
#include "mocaplink/core/dds_time_sync.hpp"

#include <cmath>
#include <cstdint>
#include <functional>

#include <gtest/gtest.h>

namespace mocaplink::core {
namespace {

using std::chrono::milliseconds;

constexpr std::int64_t kWallAtZeroUs = 1'796'000'000'000'000;  // December 2026

/// Feeds `check` PX4 samples at 50 Hz for `ms`, from host time `start_ms`: published at T, stamped
/// T + error(T), arriving after 0.4–1.6 ms. Returns how often the verdict changed.
int feed(DdsTimeSyncCheck& check, std::int64_t start_ms, std::int64_t ms,
         const std::function<double(std::int64_t)>& error_ms, bool boot_stamps = false) {
  int changes = 0;
  for (std::int64_t t = start_ms; t < start_ms + ms; t += 20) {
    const std::int64_t transport_us = 400 + (t * 37) % 1200;
    const std::int64_t published_us = kWallAtZeroUs + t * 1000;
    const auto stamp = boot_stamps
                           ? static_cast<std::uint64_t>(t * 1000 + 5'000'000)
                           : static_cast<std::uint64_t>(
                                 published_us + static_cast<std::int64_t>(error_ms(t) * 1e3));
    const HostTime arrival{milliseconds(t) + std::chrono::microseconds(transport_us)};
    if (check.on_sample(stamp, published_us + transport_us, arrival)) ++changes;
  }
  return changes;
}

TEST(DdsTimeSync, ARightSyncEarnsCaptureStampsAfterFiveSeconds) {
  DdsTimeSyncCheck check;
  EXPECT_EQ(check.stamps(), DdsPoseStamps::arrival);  // nothing known: arrival
  EXPECT_NE(check.text().find("not judged yet"), std::string::npos) << check.text();
  feed(check, 0, 4000, [](std::int64_t) { return 0.3; });
  EXPECT_EQ(check.stamps(), DdsPoseStamps::arrival);  // 4 windows within: still being confirmed
  EXPECT_NE(check.text().find("being confirmed"), std::string::npos) << check.text();
  EXPECT_EQ(feed(check, 4000, 3000, [](std::int64_t) { return 0.3; }), 1);
  EXPECT_EQ(check.stamps(), DdsPoseStamps::capture);
  ASSERT_TRUE(check.error_ms());
  EXPECT_NEAR(*check.error_ms(), 0.3 - 0.4, 0.05);  // ε less the least transport
  EXPECT_EQ(check.text().rfind("PX4's uXRCE-DDS time sync within ", 0), 0U) << check.text();
  EXPECT_EQ(to_string(check.stamps()), "capture");
}

TEST(DdsTimeSync, ALaggingSyncKeepsArrivalStamps) {
  // PX4 SITL: its lockstep clock drifts, its estimate lags by tens of ms and wanders.
  DdsTimeSyncCheck check;
  EXPECT_EQ(
      feed(check, 0, 60'000,
           [](std::int64_t t) { return 60.0 + 30.0 * std::sin(static_cast<double>(t) / 7e3); }),
      0);
  EXPECT_EQ(check.stamps(), DdsPoseStamps::arrival);
  ASSERT_TRUE(check.error_ms());
  EXPECT_GT(*check.error_ms(), 25.0);
  EXPECT_NE(check.text().find("land that far in its past"), std::string::npos) << check.text();
  // Into its future (PX4 clamps those to their arrival anyway): arrival too, and said so.
  DdsTimeSyncCheck ahead;
  feed(ahead, 0, 10'000, [](std::int64_t) { return -40.0; });
  EXPECT_EQ(ahead.stamps(), DdsPoseStamps::arrival);
  EXPECT_NE(ahead.text().find("in its future"), std::string::npos) << ahead.text();
}

TEST(DdsTimeSync, ASyncThatSlipsLosesCaptureWithinAWindow) {
  DdsTimeSyncCheck check;
  feed(check, 0, 8000, [](std::int64_t) { return 0.0; });
  ASSERT_EQ(check.stamps(), DdsPoseStamps::capture);
  // The estimate slips 20 ms at 10 s: arrival by the end of the window after it.
  feed(check, 8000, 2000, [](std::int64_t) { return 0.0; });
  EXPECT_EQ(check.stamps(), DdsPoseStamps::capture);
  EXPECT_EQ(feed(check, 10'000, 2100, [](std::int64_t) { return 20.0; }), 1);
  EXPECT_EQ(check.stamps(), DdsPoseStamps::arrival);
  EXPECT_NEAR(*check.error_ms(), 20.0 - 0.4, 0.05);
}

TEST(DdsTimeSync, BootTimeStampsAndSilenceStartOver) {
  DdsTimeSyncCheck check;
  feed(
      check, 0, 10'000, [](std::int64_t) { return 0.0; }, /*boot_stamps=*/true);
  EXPECT_EQ(check.stamps(), DdsPoseStamps::arrival);  // PX4's sync not running
  EXPECT_FALSE(check.error_ms());
  feed(check, 10'000, 8000, [](std::int64_t) { return 0.0; });
  ASSERT_EQ(check.stamps(), DdsPoseStamps::capture);
  // Two seconds without a sample (PX4 rebooted, or the Agent): arrival, and five more windows.
  EXPECT_EQ(feed(check, 20'000, 20, [](std::int64_t) { return 0.0; }), 1);
  EXPECT_EQ(check.stamps(), DdsPoseStamps::arrival);
  feed(check, 20'020, 4900, [](std::int64_t) { return 0.0; });
  EXPECT_EQ(check.stamps(), DdsPoseStamps::arrival);
  feed(check, 24'920, 2000, [](std::int64_t) { return 0.0; });
  EXPECT_EQ(check.stamps(), DdsPoseStamps::capture);
}

}  // namespace
}  // namespace mocaplink::core
