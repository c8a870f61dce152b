// A vehicle link: the one endpoint through which a vehicle gets its own poses and talks back
// (DESIGN.md "Data flow"; protocols/autopilots.md §10: one unicast endpoint per vehicle, never a
// broadcast). Implementations: UdpLink (link_udp.hpp), UdpInLink (link_udp_in.hpp), TcpLink
// (link_tcp.hpp), TcpInLink (link_tcp_in.hpp), SerialLink (link_serial.hpp).
//
// Sending takes one complete MAVLink frame per call (already encoded and, if configured, signed).
// Receiving runs every incoming byte through a mavlink::StreamParser — datagram mode for UDP,
// stream mode for serial and TCP — with the link's signing policy, and hands each accepted frame
// to the FrameHandler. Nothing a vehicle or the network does stops a link: errors are counted
// (LinkCounters) and the link keeps sending, reconnects or reopens as its kind allows.
//
// Threading: a link lives on one asio::io_context; every member function and every callback runs
// on that context's thread — with one exception: a link whose sends_in_place() is true may have
// send()/send_batch() called on another thread while the context's thread waits for that call to
// return (io::ForkJoin), one thread per link at a time. The io_context must not run handlers
// after the link is destroyed (destroy links after the loop has stopped).
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "mocaplink/core/dds_time_sync.hpp"
#include "mocaplink/core/retry_schedule.hpp"
#include "mocaplink/core/time.hpp"
#include "mocaplink/mavlink/frame.hpp"
#include "mocaplink/mavlink/signing.hpp"
#include "mocaplink/mavlink/stream_parser.hpp"

namespace mocaplink::io {

/// What a link can currently do.
///   connecting  opening, resolving or connecting (TCP: first attempt, or waiting to reconnect;
///               udpin/tcpin: listening, the vehicle has not spoken or connected yet)
///   up          frames are sent (UDP: the socket is open; whether anyone listens is not known)
///   down        cannot send now (TCP disconnected, serial device gone); frames are dropped and
///               counted while a retry is scheduled
///   closed      close() was called; final
/// The socket / device state. A different idea from core::HeartbeatState (whether the *vehicle* is
/// heard: a UDP socket is up while nobody answers) and from web::LinkHealth (the dashboard's
/// combination of both), so it stays its own type.
enum class TransportState { connecting, up, down, closed };

[[nodiscard]] constexpr const char* to_string(TransportState state) noexcept {
  switch (state) {
    case TransportState::connecting:
      return "connecting";
    case TransportState::up:
      return "up";
    case TransportState::down:
      return "down";
    case TransportState::closed:
      return "closed";
  }
  return "unknown";
}

/// Where a link itself decides the stamps of the poses it carries (ros2://: PX4's own time sync
/// converts them, core/dds_time_sync.hpp): which, and the sentence that says why.
struct LinkClock {
  core::DdsPoseStamps pose_stamps = core::DdsPoseStamps::arrival;
  std::string text;
};

/// Cumulative counts since the link was created. Drops of incoming bytes by reason are in
/// `parser` (bad CRC, bad signature, replay, unsigned rejected, ...).
struct LinkCounters {
  std::uint64_t frames_sent = 0;  ///< frames handed to the OS (UDP) or fully written
  std::uint64_t bytes_sent = 0;
  std::uint64_t send_errors = 0;      ///< OS errors on send/write other than those below
  std::uint64_t refused = 0;          ///< ECONNREFUSED: ICMP port unreachable (UDP), refused
                                      ///< connection attempts (TCP)
  std::uint64_t dropped_down = 0;     ///< frames dropped because the link was not up
  std::uint64_t dropped_backlog = 0;  ///< frames dropped because the OS or write backlog was full
  std::uint64_t bytes_received = 0;
  std::uint64_t receive_errors = 0;  ///< OS errors on receive other than ECONNREFUSED
  std::uint64_t connects = 0;        ///< successful opens/connections (reconnects = this − 1)
  /// Frames forwarded from ground stations (send_forwarded; issue 38): handed to the OS or
  /// written, and dropped — the link could not carry them beside its own frames (the forwarded
  /// queue was full) or was not up. frames_sent and bytes_sent include the forwarded ones.
  std::uint64_t forwarded_sent = 0;
  std::uint64_t forwarded_bytes = 0;
  std::uint64_t forwarded_dropped = 0;
  mavlink::ParserCounters parser;  ///< incoming frames accepted and dropped, by reason
};

/// Options common to every link kind.
struct LinkOptions {
  std::string name;  ///< for logs and state details (the vehicle name)
  /// With a key: incoming frames are verified against it and unsigned frames rejected (except
  /// RADIO_STATUS, mavlink-wire.md §7.5). Without: every CRC-valid frame is accepted.
  std::optional<mavlink::SigningKey> verify_key;
  /// Stream links (TCP, serial) queue at most this many bytes not yet written; frames beyond are
  /// dropped (dropped_backlog) so a slow link sheds load instead of adding latency. ≥ 280.
  std::size_t max_backlog_bytes = 16 * 1024;
  /// When to reconnect/reopen after a loss: at once (50 ms), then every 200 ms for 5 s, then
  /// doubling up to 4 s (core/retry_schedule.hpp, the schedule the mocap sources use).
  core::RetryPolicy retry{.max = std::chrono::milliseconds{4000}};
  /// The vehicle's MAVLink system id, when known. A listening link (udpin://) follows only the
  /// address that frames of this system come from, so that another program on its port (a ground
  /// station's heartbeat) cannot take the vehicle's poses. Unset: any accepted frame counts.
  std::optional<std::uint8_t> vehicle_system_id;
  /// Who is at the other end, for the listening links' state messages ("the vehicle spoke from
  /// ..."): "the vehicle", or "a ground station" for a `gcs` endpoint.
  std::string peer = "the vehicle";
};

class Link {
 public:
  /// One accepted incoming frame (valid only during the call) and the host time it arrived.
  using FrameHandler = std::function<void(const mavlink::FrameView& frame, core::HostTime t)>;
  /// The link's state changed; `detail` says why (e.g. the OS error text).
  using StateHandler = std::function<void(TransportState state, const std::string& detail)>;

  virtual ~Link() = default;
  Link(const Link&) = delete;
  Link& operator=(const Link&) = delete;

  /// Opens the link and starts receiving. Call once. Handlers may be empty.
  virtual void start(FrameHandler on_frame, StateHandler on_state) = 0;
  /// Sends one complete frame (≤ mavlink::kMaxFrameSize bytes). Returns false when the frame was
  /// dropped (counted): link not up, backlog full, or an OS error.
  virtual bool send(std::span<const std::uint8_t> frame) = 0;
  /// Sends several frames in order, each as send() would (counted alike); returns how many were
  /// sent. UDP hands them to the OS in one system call (sendmmsg) where it can; the default
  /// calls send() for each.
  virtual std::size_t send_batch(std::span<const std::span<const std::uint8_t>> frames);
  /// Sends one frame forwarded from a ground station (issue 38), never ahead of the link's own
  /// frames and never delaying them: a datagram link sends it at once (a datagram waits behind no
  /// other); a stream link queues it and writes it only where it cannot delay a pose
  /// (poses_first.hpp). Returns false when it was dropped (counted in forwarded_dropped).
  virtual bool send_forwarded(std::span<const std::uint8_t> frame);
  /// The period of the poses this link carries (1 / rate_hz; zero: unknown), for the poses-first
  /// rule of the links that have one.
  virtual void set_pose_period(std::chrono::nanoseconds /*period*/) {}
  /// Bytes of forwarded frames waiting for their turn (stream links).
  [[nodiscard]] virtual std::size_t forwarded_queued_bytes() const noexcept { return 0; }
  /// The link's capacity in bytes per second when it is known (a serial port's baud / 10).
  [[nodiscard]] virtual std::optional<double> capacity_bytes_per_second() const noexcept {
    return std::nullopt;
  }
  /// Stops receiving and reconnecting. Stream links try to write what is queued for at most
  /// `linger` before the socket closes; UDP sends synchronously, so nothing is pending.
  virtual void close(std::chrono::milliseconds linger = std::chrono::milliseconds{0}) = 0;
  /// True when send() and send_batch() finish their work inside the call, without the event loop
  /// (UDP: one synchronous non-blocking system call), so they may run on another thread while the
  /// loop's thread waits (see "Threading" above). Stream links queue and write from the loop.
  [[nodiscard]] virtual bool sends_in_place() const noexcept { return false; }
  /// Bytes accepted by send() but not yet written (0 for UDP).
  [[nodiscard]] virtual std::size_t backlog_bytes() const noexcept = 0;
  /// The URL the link was made from ("udp://127.0.0.1:14550").
  [[nodiscard]] virtual std::string url() const = 0;
  /// The link's own choice of pose stamps (nullopt: the MAVLink messages' own, the core's).
  [[nodiscard]] virtual std::optional<LinkClock> clock() const { return std::nullopt; }

  [[nodiscard]] TransportState state() const noexcept { return state_; }
  /// Counters, including a copy of the parser's.
  [[nodiscard]] LinkCounters counters() const noexcept;
  /// The link's signing clock as raised by correctly signed incoming frames (0 without a key):
  /// feed it to the outgoing signer (mavlink-wire.md §7.3).
  [[nodiscard]] std::uint64_t verified_timestamp_10us() const noexcept;
  [[nodiscard]] const std::string& name() const noexcept { return options_.name; }

 protected:
  explicit Link(LinkOptions options);

  /// One UDP datagram in: parsed in datagram mode, accepted frames delivered. Returns how many of
  /// them came from the vehicle (LinkOptions::vehicle_system_id; every frame when unset).
  std::size_t receive_datagram(std::span<const std::uint8_t> bytes);
  /// Stream bytes in (any chunking).
  void receive_stream(std::span<const std::uint8_t> bytes);
  /// The stream ended (connection closed): a partial frame is counted and discarded.
  void end_stream();
  /// Expires when the link is destroyed: handlers that may outlive it (name resolution) hold it.
  [[nodiscard]] std::weak_ptr<void> liveness() const { return alive_; }
  /// Changes the state and tells the StateHandler (only when it changes).
  void set_state(TransportState state, const std::string& detail);
  /// Tells the StateHandler something new about the current state (a listening link's vehicle
  /// now speaks from another address), without changing it.
  void report_state(const std::string& detail);
  void set_handlers(FrameHandler on_frame, StateHandler on_state);
  /// Next delay of options().retry's schedule; reset_backoff() after a success.
  [[nodiscard]] std::chrono::milliseconds next_backoff() noexcept { return backoff_.next(); }
  void reset_backoff() noexcept { backoff_.reset(); }

  LinkOptions options_;
  LinkCounters counters_;  // parser field unused here: counters() fills it from parser_

 private:
  std::shared_ptr<char> alive_ = std::make_shared<char>('\0');
  std::optional<mavlink::SignatureVerifier> verifier_;
  mavlink::StreamParser parser_;  // after verifier_: holds a pointer to it
  FrameHandler on_frame_;
  StateHandler on_state_;
  TransportState state_ = TransportState::connecting;
  core::RetrySchedule backoff_;
};

}  // namespace mocaplink::io
