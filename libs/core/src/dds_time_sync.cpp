// DdsTimeSyncCheck (dds_time_sync.hpp): PX4's uXRCE-DDS time sync, judged from its own stamps.
#include "mocaplink/core/dds_time_sync.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace mocaplink::core {

std::string_view to_string(DdsPoseStamps stamps) {
  return stamps == DdsPoseStamps::capture ? "capture" : "arrival";
}

bool DdsTimeSyncCheck::on_sample(std::uint64_t stamp_us, std::int64_t arrival_unix_us,
                                 HostTime now) {
  const DdsPoseStamps before = stamps_;
  if (last_sample_ && now - *last_sample_ > kDdsSyncWindow) {
    // Silent for a window: whatever PX4's sync was, it may have started again.
    window_start_.reset();
    window_min_us_.reset();
    window_boot_stamps_ = false;
    good_windows_ = 0;
    error_ms_.reset();
    stamps_ = DdsPoseStamps::arrival;
  }
  last_sample_ = now;
  if (!window_start_) {
    window_start_ = now;
  } else if (now - *window_start_ >= kDdsSyncWindow) {
    close_window(now);
  }
  if (stamp_us < kWallClockStampUs) {
    window_boot_stamps_ = true;
  } else {
    const std::int64_t d = arrival_unix_us - static_cast<std::int64_t>(stamp_us);
    window_min_us_ = window_min_us_ ? std::min(*window_min_us_, d) : d;
  }
  return stamps_ != before;
}

void DdsTimeSyncCheck::close_window(HostTime now) {
  if (window_boot_stamps_ || !window_min_us_) {
    error_ms_.reset();
    good_windows_ = 0;
  } else {
    error_ms_ = -static_cast<double>(*window_min_us_) / 1000.0;
    good_windows_ = std::abs(*error_ms_) <= kDdsSyncToleranceMs ? good_windows_ + 1 : 0;
  }
  stamps_ = good_windows_ >= kDdsSyncGoodWindows ? DdsPoseStamps::capture : DdsPoseStamps::arrival;
  window_start_ = now;
  window_min_us_.reset();
  window_boot_stamps_ = false;
}

std::string DdsTimeSyncCheck::text() const {
  char figure[64] = "";
  if (error_ms_) {
    std::snprintf(figure, sizeof figure, "%+.1f ms", *error_ms_);
  }
  if (stamps_ == DdsPoseStamps::capture) {
    return std::string("PX4's uXRCE-DDS time sync within ") + figure +
           " of this host's clock: poses carry their capture time";
  }
  if (!error_ms_) {
    return "PX4's uXRCE-DDS time sync not judged yet (no wall-clock stamps from it): poses "
           "stamped at their arrival (timestamp_sample 0)";
  }
  if (std::abs(*error_ms_) <= kDdsSyncToleranceMs) {
    return std::string("PX4's uXRCE-DDS time sync ") + figure +
           " off this host's clock, being confirmed: poses stamped at their arrival until it has "
           "held for 5 s";
  }
  return std::string("PX4's uXRCE-DDS time sync ") + figure +
         " off this host's clock (capture times would land that far in its " +
         (*error_ms_ > 0 ? "past" : "future") +
         "): poses stamped at their arrival (timestamp_sample 0)";
}

}  // namespace mocaplink::core
