// `vicon-udp://` as a Source: a UDP socket bound to the configured address that reads Vicon
// Tracker's object stream (vicon-tracker-udp.md) on its own thread, through
// wire::vicon_udp::Stream (every datagram validated; late ones dropped; frame gaps, wraps and
// restarts counted; zero and frozen objects untracked).
//
// There is no connection: the state is `connected` while datagrams arrive and `disconnected`
// after `lost` without one (then one frame with every body untracked goes out, so no pose
// outlives the stream). Datagrams padded with zeros to Tracker's block size are read. A malformed
// datagram (SourceCounters::malformed) or one from another sender than `from` (::refused) is
// dropped and counted, its reason kept in SourceCounters::last_rejection; it never ends the
// source.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "mocaplink/sources/descriptor.hpp"
#include "mocaplink/sources/loop_thread.hpp"
#include "mocaplink/sources/source.hpp"
#include "mocaplink/sources/vicon_udp_options.hpp"
#include "mocaplink/wire/vicon_udp_stream.hpp"

namespace mocaplink::sources {

/// Counters beyond SourceCounters; read from any thread.
struct ViconUdpCounters {
  std::atomic<std::uint64_t> datagrams{0};
  std::atomic<std::uint64_t> foreign{0};  ///< datagrams from another address than `from`
  std::atomic<std::uint64_t> late{0};
  std::atomic<std::uint64_t> wraps{0};
  std::atomic<std::uint64_t> restarts{0};
  std::atomic<std::uint64_t> gaps{0};
  std::atomic<std::uint64_t> split_frames{0};
  std::atomic<std::uint64_t> unknown_items{0};
  std::atomic<std::uint64_t> untracked{0};
  std::atomic<std::uint64_t> padded{0};  ///< datagrams with zero padding after the items
};

class ViconUdpSource final : public Source {
 public:
  ViconUdpSource(ViconUdpOptions options, std::string url);
  ~ViconUdpSource() override;

  /// Binds and spawns the receive thread; a bind error is reported as state `disconnected` with
  /// the reason (and the source stays silent). Call once.
  void start(FrameSink on_frame, StateSink on_state) override;
  void stop() override;
  [[nodiscard]] std::string url() const override { return url_; }
  [[nodiscard]] const SourceCounters& counters() const override { return counters_; }
  [[nodiscard]] const ViconUdpCounters& udp_counters() const { return udp_counters_; }
  /// The port bound (after start; 0 before or when the bind failed).
  [[nodiscard]] std::uint16_t bound_port() const { return bound_port_; }
  /// The most recent reason a datagram was dropped ("" if none); any thread.
  [[nodiscard]] std::string last_error() const;

 private:
  class Receiver;  // Asio state (vicon_udp_source.cpp)
  friend class Receiver;

  ViconUdpOptions options_;
  std::string url_;
  SourceCounters counters_;
  ViconUdpCounters udp_counters_;
  std::atomic<std::uint16_t> bound_port_{0};
  mutable std::mutex mutex_;
  std::string last_error_;       // guarded by mutex_
  LoopThread<Receiver> worker_;  // last: stopped first
};

/// vicon-udp:// for the source registry: parse_vicon_udp_options, a ViconUdpSource, and the
/// ViconUdpSender emulator for `serve --protocol vicon-udp --to HOST:PORT`.
[[nodiscard]] SourceDescriptor vicon_udp_source_descriptor();

}  // namespace mocaplink::sources
