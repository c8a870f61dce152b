// Bridge: the whole core as one step function of timestamped inputs (DESIGN.md "Data flow").
//
//   Bridge bridge = *Bridge::make(config, start_time);
//   out = bridge.on_frame(frame, received);                  // mocap frame → poses to send
//   out = bridge.on_vehicle_message(i, message, received);   // vehicle i said something
//   out = bridge.on_tick(now);                  // heartbeats, origin, silence, stream requests
//   for (auto& m : out.messages) link[m.vehicle].send(m.frame.bytes());
//   for (auto& e : out.events) log(e);                       // rate-limit in the adapter
//   snapshot = bridge.snapshot(now);                         // for the dashboard
//
// It owns the Station (source figures), one Tracker per distinct (body, body axes), one Sender and
// one VehicleState per vehicle, and the CaptureTimeMapper (sender_clock.hpp). No sockets, threads,
// clocks, files or logs: the adapter calls it from one thread (or under one mutex), passing host
// times from one steady clock that never goes backwards, and sends what it returns. Call on_tick
// about every 100 ms (heartbeat and origin cadence is exact to the tick period).
//
// A frame whose capture time is more than loss_timeout_ms earlier than the latest one means the
// source restarted (its clock started again; reordered datagrams are only a few frames late, and
// the Trackers refuse those): every Tracker moves its time line onto the new clock with the
// outage's length in host time (Tracker::on_clock_restart) and judges the body's next pose as a
// return after that gap — reset_counter advances only for a body that is not where it could have
// got to (docs/frames.md "Gaps and jumps"); a restart alone is no jump.
//
// Per frame: every tracker gets its body's sample (on_sample), or on_missing when the body is not
// in the frame, once; each enabled vehicle's Sender sees its body's estimate after that body's
// tracker has run (on_frame runs a body's tracker when its first vehicle needs it, see
// begin_frame). Vehicles whose body
// is never seen send nothing but heartbeats (and GPS fix 0 only once the body was seen).
// Vehicles can be added and removed while the bridge runs (the dashboard). A vehicle is named by
// its slot index: the index it had in config.vehicles, or the one add_vehicle() returned. Slots
// never move; remove_vehicle() empties one and the next add_vehicle() reuses the lowest empty
// slot, so an adapter can keep per-vehicle state (links, files) in a vector indexed the same way.
// A body's Tracker lives while some vehicle follows it; removing the last such vehicle drops it.
// Thread-safety: not thread-safe (except emit_frame after track_bodies, below); snapshot()
// returns an independent copy.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <unordered_set>
#include <variant>
#include <vector>

#include "mocaplink/core/axis_mapping.hpp"
#include "mocaplink/core/body_estimate.hpp"
#include "mocaplink/core/geodesy.hpp"
#include "mocaplink/core/latency_window.hpp"
#include "mocaplink/core/message_builders.hpp"
#include "mocaplink/core/mocap_frame.hpp"
#include "mocaplink/core/profile.hpp"
#include "mocaplink/core/sender.hpp"
#include "mocaplink/core/sender_clock.hpp"
#include "mocaplink/core/station.hpp"
#include "mocaplink/core/time.hpp"
#include "mocaplink/core/tracker.hpp"
#include "mocaplink/core/vehicle_setup.hpp"
#include "mocaplink/core/vehicle_state.hpp"
#include "mocaplink/core/vehicle_streams.hpp"

namespace mocaplink::core {

/// The configuration's defaults (DESIGN.md "Configuration"): mocap world +z up, +x north
/// (Vicon/QTM); rigid body +x forward, +z up (FLU), mapped to FRD.
[[nodiscard]] WorldAxisMapping default_world_axes();
[[nodiscard]] BodyAxisMapping default_body_axes();

/// Whether the source's clock started again between a frame (`last_capture`, handed over at
/// `last_received`) and the next: its capture time went back by more than `step_back`
/// (loss_timeout_ms: a reordered datagram is a few frame periods late), or ran ahead of the host's
/// clock by more than kSourceClockLeap — a server restarted on a clock ahead of its old one (frame
/// numbers from a new base), a time stamp taken from a wall clock that NTP stepped. A clock that
/// kept running through an outage advances with the host's: that gap is real, no restart. The
/// Bridge and the recorder (--record) apply the same rule.
[[nodiscard]] bool source_clock_restarted(SourceTime last_capture, HostTime last_received,
                                          SourceTime capture, HostTime received,
                                          Duration step_back);

/// Longest vehicle name (1..64 of [A-Za-z0-9_.-]) and rigid-body name (1..256 bytes), in bytes:
/// the config file and the dashboard API check these.
inline constexpr std::size_t kMaxVehicleNameLength = 64;
inline constexpr std::size_t kMaxBodyNameLength = 256;
/// 1..kMaxVehicleNameLength of [A-Za-z0-9_.-] (vehicle names appear in file names and URLs).
[[nodiscard]] bool is_valid_vehicle_name(std::string_view name);
/// 1..kMaxBodyNameLength bytes without control characters (U+0000..U+001F, U+007F).
[[nodiscard]] bool is_valid_body_name(std::string_view body);

/// One vehicle: the one description of a vehicle. config::Vehicle holds it (with the vehicle's
/// link) once the config rules passed (docs/architecture.md, "A vehicle's description"). Its
/// frames are signed as link id slot + 1, one channel per vehicle.
struct VehicleSpec {
  std::string name;  ///< unique, for events and the dashboard
  std::string body;  ///< rigid-body name in the mocap frames
  std::uint8_t system_id = 1;
  std::uint8_t component_id = kVisionComponentId;
  Profile profile = Profile::px4;
  std::vector<MessageKind> messages;  ///< profile custom only
  double rate_hz = 50.0;              ///< (0, kMaxSenderRateHz]
  std::optional<std::array<std::uint8_t, 32>> signing_key;
  BodyAxisMapping body_axes = default_body_axes();  ///< rigid-body axes → FRD
  bool enabled = true;                              ///< false: tracked and shown, nothing sent
  /// What the link carries. px4_dds: the poses only, and nothing else is sent (no HEARTBEAT,
  /// TIMESYNC, origin, stream or parameter requests); the set-up list is unavailable.
  VehicleLink link = VehicleLink::mavlink;
};

/// Bodies tracked for publication beside the vehicles' bodies (the [ros2] topics, docs/ros2.md).
/// A body a vehicle follows is published with that vehicle's body axes; any other with `axes`.
struct PublishedBodies {
  bool enabled = false;
  /// Every body the frames name (each from the first frame that names it), or only `names`.
  bool all = true;
  std::vector<std::string> names;
  BodyAxisMapping axes = default_body_axes();  ///< [mocap] body_forward / body_up
};

/// A published body after end_frame (Bridge::published_bodies): valid until the next begin_frame,
/// add_vehicle or remove_vehicle.
struct PublishedBody {
  std::string_view name;
  const BodyEstimate* estimate = nullptr;
  const BodyAxisMapping* axes = nullptr;
};

struct BridgeConfig {
  WorldAxisMapping world = default_world_axes();  ///< mocap world → NED
  /// The source's customary up axis (Vicon, QTM, Tracker UDP +z; Motive +y; nullopt when it has
  /// none, VRPN, sim, replay): breaks ties when the agreement names an axis fix (axis_fix.hpp).
  std::optional<SignedAxis> source_up;
  /// Geodetic origin of the mocap frame (altitude AMSL, used as is: docs/messages.md "Altitude").
  /// Required when a vehicle's messages need it (HIL_GPS, GPS_INPUT).
  std::optional<GeodeticPosition> origin;
  std::vector<VehicleSpec> vehicles;
  TrackerConfig tracking;
  StationConfig station;
  GpsOptions gps;
  AgreementThresholds agreement;
  CaptureTimeMapper::Config capture_time;
  /// Send our own TIMESYNC requests (1 Hz) to measure RTT and offset (diagnostics only).
  bool timesync_requests = true;
  PublishedBodies published;
};

/// Why make() refused a config (the config library normally catches these first).
struct BridgeConfigError {
  /// "vehicle[2].rate_hz" (vehicles numbered from 1 by slot, as the configuration numbers its
  /// [[vehicle]] tables), "origin", ...
  std::string field;
  std::string message;
};

enum class BridgeEventKind : std::uint8_t {
  body_tracking,  ///< a body (re)gained tracking (text: after how long / reset)
  body_lost,      ///< a body went LOST
  body_reset,     ///< a body's pose jumped (reset_counter incremented)
  /// a body's rotation from the source is a reflection (BodySample::mirrored): named once when
  /// it starts, as a mistake no axis setting can fix (issue 48)
  body_mirrored,
  vehicle_link,  ///< a vehicle's heartbeat state changed (alive / silent)
  origin_state,  ///< a vehicle's origin state changed (confirmed / conflict / sending)
  agreement,     ///< a vehicle's agreement verdict changed
  /// what was asked of a vehicle for the agreement check and the outcome (vehicle_streams.hpp):
  /// a few per vehicle boot, never one per retransmission, so the log keeps every one
  vehicle_streams,
  /// the vehicle's set-up (vehicle_setup.hpp): its autopilot, the check list's verdict, writes
  /// and their confirmation, its STATUSTEXT warnings
  vehicle_setup,
  /// the vehicle's clock against the host's (vehicle_clock.hpp): steady, or unsteady and what
  /// mocaplink does about it; a few per vehicle boot
  vehicle_clock,
};
[[nodiscard]] std::string_view to_string(BridgeEventKind kind);

/// Something the operator should know; the adapter logs it (rate-limited) and shows it.
struct BridgeEvent {
  BridgeEventKind kind = BridgeEventKind::body_tracking;
  HostTime time{};
  std::optional<std::size_t> vehicle;  ///< vehicle index, when about a vehicle
  std::string subject;                 ///< body or vehicle name
  std::string text;                    ///< one line, human-readable
};

/// What one step produced.
struct BridgeOutput {
  std::vector<OutgoingMessage> messages;  ///< in send order; per vehicle, seq is consecutive
  std::vector<BridgeEvent> events;
};

/// One tracked body on the dashboard.
struct BodySnapshot {
  std::string name;
  BodyEstimate estimate;
};

/// One vehicle on the dashboard.
struct VehicleStatus {
  std::size_t index = 0;  ///< the vehicle's slot (Bridge, "Vehicles can be added")
  std::string name;
  std::string body;
  Profile profile = Profile::px4;
  bool enabled = true;
  VehicleLink link = VehicleLink::mavlink;
  SenderSnapshot sender;
  VehicleSnapshot vehicle;
  VehicleStreamsSnapshot streams;  ///< ATTITUDE / LOCAL_POSITION_NED requests (agreement check)
  VehicleSetupSnapshot setup;      ///< autopilot, parameters, STATUSTEXT, estimator, delay
};

/// Immutable copy of everything the dashboard shows.
struct BridgeSnapshot {
  HostTime time{};
  StationSnapshot station;
  std::vector<BodySnapshot> bodies;
  std::vector<VehicleStatus> vehicles;  ///< the live vehicles, by slot
  std::optional<GeodeticPosition> origin;
  std::optional<Duration> capture_offset;  ///< host − source clock offset (CaptureTimeMapper)
  std::uint64_t source_restarts = 0;       ///< frames whose capture time went backwards
};

class Bridge {
 public:
  /// Validates `config` (rates, ids, custom lists, origin present when needed, unique vehicle
  /// names) and builds the object graph. `start` is the host time the bridge starts
  /// (LOCAL_POSITION_NED time_boot_ms counts from it).
  [[nodiscard]] static std::variant<Bridge, BridgeConfigError> make(const BridgeConfig& config,
                                                                    HostTime start);

  /// How old `frame`'s data is at `now` (it was received at `received`; nothing changes): the
  /// time since its capture, placed on the host clock by the capture times of the frames before
  /// it (CaptureTimeMapper, the offset of the least-delayed frames), and never less than the time
  /// since it was received. A frame whose capture continues the stream but arrives late — a TCP
  /// backlog after a network stall, a VRPN round held back, a replay behind its schedule — is as
  /// old as its capture, however recently it arrived. Only the time since `received` counts for
  /// the first frame, and for a frame whose capture time jumped back by more than
  /// loss_timeout_ms (the source's clock started again: on_frame re-seeds from it) or lies ahead
  /// of the clock (a source clock that jumped forward).
  [[nodiscard]] Duration frame_age(const MocapFrame& frame, HostTime received, HostTime now) const;

  /// A mocap frame received at `received`.
  BridgeOutput on_frame(const MocapFrame& frame, HostTime received);
  /// The same into `out` (cleared first): a caller that keeps `out` from frame to frame reuses
  /// its capacity, so the per-frame path does not allocate once it has grown.
  void on_frame(const MocapFrame& frame, HostTime received, BridgeOutput& out);
  /// on_frame in steps, for a caller that sends each vehicle's poses as soon as they are built
  /// (docs/daemon.md "Vehicles in chunks"): begin_frame does what the vehicles need before any
  /// body (capture time, source restarts; `out` cleared). emit_frame lets the vehicles in
  /// slots [first, end) (empty slots skipped, `end` clamped to slot_count()) react to the frame,
  /// appending their messages to `messages` in slot order, and tracks each one's body first if
  /// no earlier emit_frame of this frame did: the first vehicles' poses do not wait for every
  /// body's filter. end_frame tracks the bodies no vehicle needed (disabled vehicles'), appends
  /// the frame's body events to `out`, in body order, and gives the frame to the Station.
  /// begin_frame, emit_frame(0, slot_count()), end_frame is exactly on_frame, and so is any order
  /// of emit_frame calls over disjoint ranges that cover the slots: the same messages per vehicle,
  /// the same events. `frame` must stay alive until end_frame. emit_frame for a slot twice in one
  /// frame, or outside begin_frame … end_frame, is a programming error. Threads: emit_frame may
  /// track, so it runs on one thread at a time; after track_bodies() (every body tracked) calls of
  /// emit_frame for disjoint slot ranges touch disjoint state (each vehicle's Sender; the rest is
  /// only read) and may run on different threads at once, provided nothing else of the Bridge runs
  /// meanwhile.
  void begin_frame(const MocapFrame& frame, HostTime received, BridgeOutput& out);
  void track_bodies();
  void emit_frame(std::size_t first, std::size_t end, std::vector<OutgoingMessage>& messages);
  void end_frame(BridgeOutput& out);
  /// After end_frame: the published bodies (BridgeConfig::published) with a fresh pose in that
  /// frame (BodyEstimate::pose_valid: a body not tracked in a frame is not published in it), in
  /// body order, appended to `out`; and the frame's capture time on the host clock.
  void published_bodies(std::vector<PublishedBody>& out) const;
  [[nodiscard]] HostTime frame_capture() const { return frame_context_.capture; }
  /// A decoded message from vehicle `vehicle`'s link (its slot; an empty or out-of-range slot is
  /// ignored).
  BridgeOutput on_vehicle_message(std::size_t vehicle, const ReceivedMessage& message,
                                  HostTime received);
  /// Time passes: heartbeats, origin messages, TIMESYNC requests, link timeouts, and the requests
  /// for ATTITUDE / LOCAL_POSITION_NED (vehicle_streams.hpp) of enabled vehicles.
  BridgeOutput on_tick(HostTime now);
  /// on_tick in parts, for a caller that lets frames through between them (docs/daemon.md "The
  /// tick in parts"): begin_tick takes what is the same for every vehicle in a tick (the frames'
  /// median capture age); tick_vehicles then ticks the vehicles in slots [first, end) (empty slots
  /// skipped, `end` clamped to slot_count()) at `now`, into `out` (cleared first). begin_tick and
  /// tick_vehicles(now, 0, slot_count(), out) are exactly on_tick(now), and so are calls over
  /// disjoint ranges that cover the slots, in any order: the same messages per vehicle, the same
  /// events. Each part takes its own `now`, the time it runs (a TIMESYNC request carries it).
  void begin_tick();
  void tick_vehicles(HostTime now, std::size_t first, std::size_t end, BridgeOutput& out);
  /// The mocap source connected or went away (Station figures).
  void on_source_connection(bool connected);
  /// Wall clock: `unix_us` is the Unix time (µs) at host time `host`. Enables GPS_INPUT
  /// time_week/time_week_ms and signing timestamps; call at start and whenever convenient (the
  /// last call wins; GPS time then follows the steady clock, so it never jumps with NTP).
  void set_wall_clock(HostTime host, std::int64_t unix_us);

  // Runtime control (dashboard). Empty or out-of-range slot, or a bad value → false, nothing
  // changes.
  bool set_rate_hz(std::size_t vehicle, double rate_hz);
  bool set_messages(std::size_t vehicle, const MessageSet& messages);
  bool set_paused(std::size_t vehicle, bool paused);
  /// A px4_dds vehicle's link sends capture stamps (true: PX4's own time sync converts them, so
  /// EKF2_EV_DELAY is 0) or stamps of 0 that PX4 takes at arrival (false, the default: the delay
  /// recommendation is then the whole measured delay). Ignored for a MAVLink link.
  bool set_capture_stamps(std::size_t vehicle, bool capture);

  /// Writes the fixes of the named parameters to the vehicle in `slot` (VehicleSetup::apply: only
  /// wrong items of its list as it stands, never while armed). The writes go out from the next
  /// on_tick. An empty slot is refused.
  SetupRequestResult apply_setup(std::size_t slot, std::span<const std::string> parameters,
                                 HostTime now);
  /// Asks the vehicle in `slot` to reboot (refused while armed); the command is in `out`.
  SetupRequestResult reboot_vehicle(std::size_t slot, HostTime now, BridgeOutput& out);

  /// The vehicle's next signed frame uses a timestamp above `timestamp_10us`: its persisted value
  /// at start, or that of a correctly signed frame it sent us (mavlink-wire.md §7.3). False for
  /// an empty slot; no effect on a vehicle without a signing key.
  bool raise_signing_timestamp(std::size_t vehicle, std::uint64_t timestamp_10us);

  /// Adds a vehicle, checked as make() checks config.vehicles (the error's field reads
  /// "vehicle[SLOT + 1]..."; a name in use is refused with field "vehicle[SLOT + 1].name"). Returns
  /// its slot. It starts like a configured one: heartbeats from the next on_tick, poses from the
  /// next frame in which its body has an estimate (a body no other vehicle follows is tracked from
  /// then on).
  [[nodiscard]] std::variant<std::size_t, BridgeConfigError> add_vehicle(const VehicleSpec& spec);
  /// Removes the vehicle in `slot`: nothing more is sent to it or accepted from it. False when the
  /// slot is empty or out of range.
  bool remove_vehicle(std::size_t slot);
  /// The slot the next add_vehicle() will use (the lowest empty one, or slot_count()).
  [[nodiscard]] std::size_t next_slot() const;
  /// The slot of the live vehicle named `name`.
  [[nodiscard]] std::optional<std::size_t> find_vehicle(std::string_view name) const;
  /// The live vehicle in `slot` as it was added (nullptr for an empty or out-of-range slot). Its
  /// rate and messages are the ones it started with; the Sender's, in snapshot(), are live.
  [[nodiscard]] const VehicleSpec* vehicle(std::size_t slot) const;

  [[nodiscard]] BridgeSnapshot snapshot(HostTime now) const;
  /// Live vehicles.
  [[nodiscard]] std::size_t vehicle_count() const;
  /// One past the highest slot ever used (live or empty).
  [[nodiscard]] std::size_t slot_count() const { return vehicles_.size(); }
  /// The configuration make() was given (its vehicles are the ones at start).
  [[nodiscard]] const BridgeConfig& config() const { return config_; }

 private:
  struct Body {
    std::string name;
    BodyAxisMapping axes;
    Tracker tracker;
    TrackingState last_state = TrackingState::unseen;
    std::uint8_t last_reset_counter = 0;
    BodyEstimate published;  ///< tracker.estimate() after this frame: what is sent
    /// Where this body was in the last frame's body list: sources list bodies in a stable order,
    /// so looking there first finds it without comparing every name (track_body()).
    std::size_t frame_index_hint = 0;
    std::uint64_t tracked_frame = 0;  ///< the last frame_number_ its tracker saw
    bool exported = false;            ///< in published_bodies() (BridgeConfig::published)
    bool mirrored = false;            ///< its sample in the latest frame was mirrored
    bool named_mirrored = false;      ///< body_mirrored given for the current stretch
  };
  struct Vehicle {
    VehicleSpec spec;
    std::size_t body = 0;  ///< index into bodies_
    Sender sender;
    VehicleState state;
    bool sends_origin = false;
    VehicleStreams streams;
    VehicleSetup setup;
    std::uint64_t reboots_seen = 0;  ///< streams' reboot count the setup last followed
    bool capture_stamps = false;     ///< px4_dds only: set_capture_stamps
  };
  Bridge(const BridgeConfig& config, HostTime start);

  [[nodiscard]] std::optional<BridgeConfigError> validate_vehicle(const VehicleSpec& spec,
                                                                  std::size_t slot) const;
  /// Builds the vehicle in `slot` (== vehicles_.size() appends), sharing or creating its Body.
  void place_vehicle(const VehicleSpec& spec, std::size_t slot);
  /// Marks the body named `name` published, adding it (with the published axes) if no vehicle
  /// follows it. A name already published is left as it is.
  void publish_body(std::string_view name);
  [[nodiscard]] Vehicle* live(std::size_t slot);

  /// Gives the body the current frame's sample (or its absence), once per frame.
  void track_body(Body& body);
  /// Body events (reset, lost, tracking) of the current frame, from each body's published state.
  void body_events(BridgeOutput& out);
  [[nodiscard]] std::optional<GpsTime> gps_time(HostTime t) const;
  /// A capture-time step back larger than this is a restart of the source's clock, not a
  /// reordered datagram (loss_timeout_ms; source_clock_restarted).
  [[nodiscard]] Duration max_capture_step_back() const;
  [[nodiscard]] std::uint64_t signing_now_10us(HostTime t) const;
  void vehicle_events(std::size_t index, const VehicleReaction& reaction, HostTime now,
                      BridgeOutput& out) const;
  void stream_events(std::size_t index, std::vector<std::string>& notes, HostTime now,
                     BridgeOutput& out,
                     BridgeEventKind kind = BridgeEventKind::vehicle_streams) const;
  /// What the set-up's delay recommendation measures for a vehicle now: the frames' median
  /// capture age (capture_age_, computed once per tick) and what the vehicle's TIMESYNC says.
  [[nodiscard]] DelayInputs delay_inputs(std::optional<double> capture_age_ms,
                                         const VehicleSnapshot& heard) const;

  BridgeConfig config_;
  HostTime start_{};
  Station station_;
  CaptureTimeMapper capture_mapper_;
  std::optional<LocalGeodeticFrame> geodetic_;
  std::vector<Body> bodies_;
  std::vector<std::optional<Vehicle>> vehicles_;  // by slot; std::nullopt: removed
  std::optional<Duration> unix_minus_host_;
  std::optional<SourceTime> last_capture_;
  SendContext frame_context_;          // of the frame begin_frame() saw last (emit_frame reads it)
  const MocapFrame* frame_ = nullptr;  // begin_frame … end_frame: the frame being tracked
  std::uint64_t frame_number_ = 0;     // frames begun (Body::tracked_frame compares with it)
  bool frame_restarted_ = false;       // the current frame is the first after a source restart
  std::optional<HostTime> last_received_;  // when the previous frame was handed over
  Duration restart_gap_{};    // host time from the old clock's last frame to the restart frame
  bool all_tracked_ = false;  // track_bodies() ran in this frame (asserted by track_body)
  std::uint64_t source_restarts_ = 0;
  /// With PublishedBodies::all: the names already published (end_frame adds each new one once).
  std::unordered_set<std::string> published_names_;
  /// Capture → received of recent frames (received − the capture time placed on the host clock,
  /// which includes the latency the source reports): the set-up's delay recommendation.
  LatencyWindow capture_age_;
  std::optional<double> tick_capture_age_ms_;  // capture_age_'s median at begin_tick
};

}  // namespace mocaplink::core
