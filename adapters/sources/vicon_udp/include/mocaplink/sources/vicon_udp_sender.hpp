// The Vicon Tracker UDP object stream emulator behind `mocaplink serve --protocol vicon-udp --to
// HOST:PORT`: one datagram per frame (vicon-tracker-udp.md §2) sent to HOST:PORT, unasked, as a
// Tracker does: the items, then zero bytes up to the block size. Settings (`serve --set
// KEY=VALUE`):
//   block_size=N          bytes of every datagram, as Tracker's "Data Block Size" (default 1024,
//                         the most common; 256 and 512 are Tracker's others; 80..65507, or 0 for
//                         no padding: exactly 5 + 75 bytes per object, which no Tracker sends).
//                         Objects that do not fit in one block (13 in 1024, 6 in 512, 3 in 256)
//                         go on in further blocks with the same frame number (unverified what
//                         Tracker does then; mocaplink's client merges them)
//   rotation=xyz|zyx      the Euler convention it encodes (default xyz, as the source's default)
//   frame_step=N          Vicon frame numbers per datagram (1..100, default 1; 2 = half the
//                         camera rate, as a Tracker streaming below its camera rate)
//   first_frame=N         the first frame number (0..4294967295, default 1; near 2^32 to wrap)
//   occluded=omit|zeros   an untracked body is left out (default) or sent with six zeros
//   per_datagram=N        at most N objects per datagram (1..255, default 255, and at most what
//                         fits in the block): more are split over several datagrams with the
//                         same frame number
// Bodies whose names exceed 24 bytes are cut to 24, as the item has no room for more.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <thread>

#include "mocaplink/core/mocap_frame.hpp"
#include "mocaplink/sources/descriptor.hpp"
#include "mocaplink/sources/loop_thread.hpp"
#include "mocaplink/wire/vicon_udp.hpp"

namespace mocaplink::sources {

struct ViconUdpSenderOptions {
  std::string to_host = "127.0.0.1";
  std::uint16_t to_port = wire::vicon_udp::kDefaultPort;
  double rate_hz = 100.0;
  wire::vicon_udp::EulerOrder rotation = wire::vicon_udp::EulerOrder::xyz;
  std::uint32_t frame_step = 1;
  std::uint32_t first_frame = 1;
  bool occluded_as_zeros = false;
  std::size_t per_datagram = 255;
  /// Bytes per datagram, zero-padded (0: unpadded, 5 + 75·n).
  std::size_t block_bytes = wire::vicon_udp::kDefaultBlockBytes;
};

/// The `serve --set` keys of the vicon-udp emulator.
inline constexpr std::array<std::string_view, 6> kViconUdpEmulatorKeys = {
    "block_size", "first_frame", "frame_step", "occluded", "per_datagram", "rotation"};

/// ViconUdpSenderOptions from serve's options, or why a setting is wrong (one line).
[[nodiscard]] config::ValueOrError<ViconUdpSenderOptions> vicon_udp_sender_options(
    const EmulatorOptions& options);

struct ViconUdpSenderCounters {
  std::atomic<std::uint64_t> frames{0};
  std::atomic<std::uint64_t> datagrams{0};
  std::atomic<std::uint64_t> send_errors{0};
};

class ViconUdpSender final : public Emulator {
 public:
  explicit ViconUdpSender(ViconUdpSenderOptions options);
  ~ViconUdpSender() override;

  [[nodiscard]] std::optional<std::string> start(FrameProvider provider) override;
  /// The local port datagrams leave from.
  [[nodiscard]] std::uint16_t port() const override { return port_; }
  void publish(core::MocapFrame frame) override;
  void stop() override;
  /// "N frames, N datagrams, N send errors".
  [[nodiscard]] std::string summary() const override;
  [[nodiscard]] const ViconUdpSenderCounters& counters() const { return counters_; }

 private:
  class Impl;
  ViconUdpSenderOptions options_;
  ViconUdpSenderCounters counters_;
  std::uint16_t port_ = 0;
  LoopThread<Impl> worker_;  // last: stopped first
};

}  // namespace mocaplink::sources
