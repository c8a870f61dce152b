// A frame as the DataStream emulator serves it, in wire units (mm, row-major rotation matrices,
// 135 MHz ticks), and the builder that turns core::MocapFrames into it with subject ids that stay
// stable for the server's lifetime (§8.11: ids are the server's choice, stable for the session).
// Pure. ServedFrameBuilder is not thread-safe.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "mocaplink/core/mocap_frame.hpp"
#include "mocaplink/wire/vicon_items.hpp"

namespace mocaplink::wire::vicon {

/// One subject with one root segment of the same name (segment id 1), as Vicon Tracker objects
/// are understood to be (§8.11, inferred).
struct ServedSubject {
  std::uint32_t subject_id = 0;  ///< >= 1, stable
  std::string name;
  bool tracked = false;                    ///< false: the segment is left out (occluded, §9.3)
  std::array<double, 3> translation_mm{};  ///< world, mm
  std::array<double, 9> rotation{};        ///< row-major, segment → world
};

struct ServedFrame {
  /// Monotonic production counter of the server (1, 2, …); decides "newer" in pre-fetch mode,
  /// independent of the frame ids the provider chose.
  std::uint64_t sequence = 0;
  std::uint32_t frame_id = 0;           ///< FrameInfo; never kInvalidFrameId
  std::int64_t frame_period_ticks = 0;  ///< StreamInfo; 135 MHz ticks per frame
  std::vector<ServedSubject> subjects;  ///< every subject seen so far, in id order
  std::vector<LatencySample> latency;   ///< empty: no LatencyInfo item in the frame
  std::optional<Timecode> timecode;     ///< absent: no Timecode item
};

/// 135 MHz ticks per frame for a rate in Hz, rounded (100 → 1 350 000). rate_hz must be > 0.
[[nodiscard]] std::int64_t frame_period_ticks(double rate_hz);

class ServedFrameBuilder {
 public:
  /// Builds the next ServedFrame: positions m → mm, quaternion → matrix; frame_id = the frame's
  /// number truncated to u32 (0xFFFFFFFF becomes 0); bodies not in this frame but seen before
  /// are served as occluded; source_latency becomes one sample "Emulator Acquisition".
  [[nodiscard]] ServedFrame build(const core::MocapFrame& frame, std::int64_t period_ticks);

 private:
  std::map<std::string, std::size_t> index_by_name_;
  std::vector<ServedSubject> subjects_;
  std::uint64_t sequence_ = 0;
};

}  // namespace mocaplink::wire::vicon
