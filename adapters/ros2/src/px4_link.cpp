// The ros2:// link to a PX4 over uXRCE-DDS (px4_link.hpp).
#include "mocaplink/ros2/px4_link.hpp"

#include <array>
#include <cmath>
#include <mutex>
#include <optional>
#include <vector>

#include <spdlog/spdlog.h>
#include <asio/post.hpp>

#include "dds.hpp"
#include "mocaplink/core/dds_time_sync.hpp"
#include "mocaplink/core/quaternion.hpp"
#include "mocaplink/core/vehicle_state.hpp"
#include "mocaplink/io/clock.hpp"
#include "mocaplink/mavlink/frame.hpp"
#include "mocaplink/wire/px4_messages.hpp"

namespace mocaplink::ros2 {
namespace {

constexpr std::uint32_t kOdometrySampleBytes = 4 + wire::kPx4VehicleOdometryPayload;
constexpr std::uint32_t kStatusSampleBytes = 1024;  // v1.14's is 88 bytes, later ones a little more
/// Heard again after this long without a sample: the vehicle restarted or reconnected.
constexpr auto kSilence = std::chrono::seconds(3);
constexpr std::uint8_t kComponentAutopilot = 1;
constexpr std::uint8_t kMavModeFlagCustomModeEnabled = 1;
constexpr std::uint8_t kMavStateStandby = 3;
constexpr std::uint8_t kMavStateActive = 4;

/// PX4's custom_mode of a nav_state (main mode in byte 2, AUTO and POSCTL sub-mode in byte 3),
/// as PX4's own MAVLink heartbeat reports it; 0 for a state it has no mode for.
std::uint32_t px4_custom_mode(std::uint8_t nav_state) {
  struct Mode {
    std::uint8_t nav_state, main, sub;
  };
  static constexpr std::array<Mode, 17> kModes{{{0, 1, 0},      // MANUAL
                                                {1, 2, 0},      // ALTCTL
                                                {2, 3, 0},      // POSCTL
                                                {3, 4, 4},      // AUTO_MISSION
                                                {4, 4, 3},      // AUTO_LOITER
                                                {5, 4, 5},      // AUTO_RTL
                                                {10, 5, 0},     // ACRO
                                                {12, 4, 6},     // DESCEND (as LAND)
                                                {13, 1, 0},     // TERMINATION (as MANUAL)
                                                {14, 6, 0},     // OFFBOARD
                                                {15, 7, 0},     // STAB
                                                {17, 4, 2},     // AUTO_TAKEOFF
                                                {18, 4, 6},     // AUTO_LAND
                                                {19, 4, 8},     // AUTO_FOLLOW_TARGET
                                                {20, 4, 9},     // AUTO_PRECLAND
                                                {21, 3, 1},     // ORBIT
                                                {22, 4, 10}}};  // AUTO_VTOL_TAKEOFF
  for (const Mode& m : kModes) {
    if (m.nav_state == nav_state) {
      return (static_cast<std::uint32_t>(m.main) << 16) | (static_cast<std::uint32_t>(m.sub) << 24);
    }
  }
  return 0;
}

class Px4DdsLink final : public io::Link {
 public:
  Px4DdsLink(asio::io_context& loop, Px4LinkSettings settings, io::LinkOptions options)
      : io::Link(std::move(options)), loop_(loop), settings_(std::move(settings)) {}

  ~Px4DdsLink() override { close(); }

  void start(FrameHandler on_frame, StateHandler on_state) override {
    set_handlers(std::move(on_frame), std::move(on_state));
    std::string error;
    participant_ = detail::shared_participant(
        detail::ParticipantSettings{settings_.domain_id, settings_.network_interface, "mocaplink"},
        error);
    if (!participant_) {
      set_state(io::TransportState::down, "no DDS participant: " + error);
      return;
    }
    detail::WriterSettings ws;
    ws.topic = px4_topic(settings_.ns, "in", "vehicle_visual_odometry");
    ws.type = std::string(wire::kPx4VehicleOdometryType);
    ws.depth = 1;  // the newest pose only: an older one is of no use to EKF2
    ws.max_sample_bytes = kOdometrySampleBytes;
    ws.on_matched = [this, alive = liveness()](std::uint32_t count) {
      asio::post(loop_, [this, alive, count] {
        if (alive.expired()) return;
        report_state(count > 0 ? "PX4's Agent reads the poses (" + std::to_string(count) +
                                     " reader" + (count == 1 ? ")" : "s)")
                               : "no Agent reads the poses");
      });
    };
    writer_ = participant_->make_writer(ws, error);
    if (!writer_) {
      set_state(io::TransportState::down, error);
      return;
    }
    for (const char* name : {"vehicle_status", "vehicle_status_v1"}) {
      read(name, wire::kPx4VehicleStatusType, kStatusSampleBytes,
           [this](std::span<const std::uint8_t> s, std::int64_t at) { on_status(s, at); });
    }
    read("vehicle_odometry", wire::kPx4VehicleOdometryType, kOdometrySampleBytes,
         [this](std::span<const std::uint8_t> s, std::int64_t at) { on_odometry(s, at); });
    set_state(io::TransportState::up,
              "DDS topics of " + (settings_.ns.empty() ? std::string("no namespace")
                                                       : "namespace " + settings_.ns));
  }

  bool send(std::span<const std::uint8_t> frame) override {
    if (state() != io::TransportState::up || !writer_) {
      ++counters_.dropped_down;
      return false;
    }
    const auto parsed = mavlink::parse_frame(frame);
    if (!parsed || parsed->msgid != mavlink::Odometry::kId) {
      return true;  // nothing to carry over DDS: not a loss
    }
    const auto message = mavlink::decode_message(*parsed);
    const auto* odometry = message ? std::get_if<mavlink::Odometry>(&*message) : nullptr;
    if (odometry == nullptr) return true;
    // time_usec is the capture time on the host's steady clock (core/sender_clock.hpp). It goes
    // only while PX4's own time sync converts it right; else 0, which PX4 stamps on arrival
    // (core/dds_time_sync.hpp).
    std::uint64_t sample_us = 0;
    std::uint64_t now_us = 0;
    if (sync_.stamps() == core::DdsPoseStamps::capture) {
      const core::HostTime capture{std::chrono::microseconds(odometry->time_usec)};
      sample_us = static_cast<std::uint64_t>(io::unix_ns_of(capture) / 1000);
      now_us = static_cast<std::uint64_t>(io::unix_now_us());
    }
    encoded_.clear();
    wire::encode_px4_vehicle_odometry(wire::px4_vehicle_odometry_of(*odometry, now_us, sample_us),
                                      encoded_);
    if (!writer_->write(encoded_)) {
      ++counters_.send_errors;
      return false;
    }
    ++counters_.frames_sent;
    counters_.bytes_sent += encoded_.size();
    return true;
  }

  bool send_forwarded(std::span<const std::uint8_t> /*frame*/) override {
    ++counters_.forwarded_dropped;  // a ground station's MAVLink has no DDS counterpart
    return false;
  }

  void close(std::chrono::milliseconds /*linger*/ = std::chrono::milliseconds{0}) override {
    readers_.clear();  // no callback runs after this
    writer_.reset();
    participant_.reset();
    if (state() != io::TransportState::closed) set_state(io::TransportState::closed, "closed");
  }

  [[nodiscard]] std::size_t backlog_bytes() const noexcept override { return 0; }
  [[nodiscard]] std::string url() const override { return "ros2://" + settings_.ns; }
  [[nodiscard]] std::optional<io::LinkClock> clock() const override {
    return io::LinkClock{sync_.stamps(), sync_.text()};
  }

 private:
  /// A sample of PX4's and when it arrived here (µs since 1970, taken on DDS's thread).
  using OnSample = std::function<void(std::span<const std::uint8_t>, std::int64_t arrival_us)>;

  void read(const char* topic_name, std::string_view type, std::uint32_t max_bytes,
            OnSample on_loop) {
    detail::ReaderSettings rs;
    rs.topic = px4_topic(settings_.ns, "out", topic_name);
    rs.type = std::string(type);
    rs.depth = 1;
    rs.max_sample_bytes = max_bytes;
    rs.on_sample = [this, alive = liveness(), on_loop](std::span<const std::uint8_t> sample) {
      asio::post(loop_, [this, alive, on_loop, arrival_us = io::unix_now_us(),
                         bytes = std::vector<std::uint8_t>(sample.begin(), sample.end())] {
        if (alive.expired() || state() == io::TransportState::closed) return;
        counters_.bytes_received += bytes.size();
        on_loop(bytes, arrival_us);
      });
    };
    std::string error;
    auto reader = participant_->make_reader(rs, error);
    if (!reader) {
      spdlog::warn("{}: cannot read {}: {}", name(), rs.topic, error);
      return;
    }
    readers_.push_back(std::move(reader));
  }

  /// The time_boot_ms of a sample stamped `timestamp_us` that arrived at `arrival_us` (see the file
  /// comment); the stamp also judges PX4's time sync (sync_).
  std::uint32_t boot_ms(std::uint64_t timestamp_us, std::int64_t arrival_us) {
    const core::HostTime now = io::host_now();
    if (sync_.on_sample(timestamp_us, arrival_us, now))
      spdlog::info("{}: {}", name(), sync_.text());
    if (!last_heard_ || now - *last_heard_ > kSilence) heard_since_ = now;
    last_heard_ = now;
    if (timestamp_us > 0 && timestamp_us < core::kWallClockStampUs) {
      return static_cast<std::uint32_t>(timestamp_us / 1000);
    }
    return static_cast<std::uint32_t>(
        std::chrono::duration_cast<std::chrono::milliseconds>(now - heard_since_).count());
  }

  void deliver(const mavlink::Message& message) {
    const mavlink::FrameHeader header{seq_++, settings_.system_id, kComponentAutopilot};
    const mavlink::Frame frame =
        std::visit([&](const auto& m) { return mavlink::encode(m, header); }, message);
    (void)receive_datagram(frame.bytes());
  }

  void on_status(std::span<const std::uint8_t> sample, std::int64_t arrival_us) {
    const auto status = wire::decode_px4_vehicle_status(sample);
    if (!status) {
      ++counters_.receive_errors;
      return;
    }
    (void)boot_ms(status->timestamp, arrival_us);
    mavlink::Heartbeat hb;
    hb.type = 0;  // MAV_TYPE_GENERIC: the type's field moves between PX4 versions
    hb.autopilot = core::kMavAutopilotPx4;
    hb.base_mode = kMavModeFlagCustomModeEnabled |
                   (status->armed() ? core::kMavModeFlagSafetyArmed : std::uint8_t{0});
    hb.custom_mode = px4_custom_mode(status->nav_state);
    hb.system_status = status->armed() ? kMavStateActive : kMavStateStandby;
    deliver(hb);
  }

  void on_odometry(std::span<const std::uint8_t> sample, std::int64_t arrival_us) {
    const auto odometry = wire::decode_px4_vehicle_odometry(sample);
    if (!odometry) {
      ++counters_.receive_errors;
      return;
    }
    const std::uint32_t t_ms = boot_ms(odometry->timestamp, arrival_us);
    if (odometry->pose_frame != wire::Px4VehicleOdometry::kFrameNed) return;
    const auto& q = odometry->q;
    if (std::isfinite(q[0])) {
      const Eigen::Quaterniond q_ned_frd(q[0], q[1], q[2], q[3]);
      const core::Euler321 e = core::euler_321_from_quaternion(q_ned_frd.normalized());
      mavlink::Attitude att;
      att.time_boot_ms = t_ms;
      att.roll = static_cast<float>(e.roll_rad);
      att.pitch = static_cast<float>(e.pitch_rad);
      att.yaw = static_cast<float>(e.yaw_rad);
      att.rollspeed = odometry->angular_velocity[0];
      att.pitchspeed = odometry->angular_velocity[1];
      att.yawspeed = odometry->angular_velocity[2];
      deliver(att);
    }
    if (std::isfinite(odometry->position[0])) {
      mavlink::LocalPositionNed pos;
      pos.time_boot_ms = t_ms;
      pos.x = odometry->position[0];
      pos.y = odometry->position[1];
      pos.z = odometry->position[2];
      if (odometry->velocity_frame == wire::Px4VehicleOdometry::kFrameNed) {
        pos.vx = odometry->velocity[0];
        pos.vy = odometry->velocity[1];
        pos.vz = odometry->velocity[2];
      }
      deliver(pos);
    }
  }

  asio::io_context& loop_;
  const Px4LinkSettings settings_;
  std::shared_ptr<detail::Participant> participant_;
  std::unique_ptr<detail::Writer> writer_;
  std::vector<std::unique_ptr<detail::Reader>> readers_;
  std::vector<std::uint8_t> encoded_;
  std::uint8_t seq_ = 0;
  core::DdsTimeSyncCheck sync_;  ///< PX4's time sync, from its stamps: which stamps to send
  std::optional<core::HostTime> last_heard_;
  core::HostTime heard_since_{};
};

}  // namespace

std::string px4_topic(const std::string& ns, const std::string& direction,
                      const std::string& name) {
  return "rt/" + (ns.empty() ? std::string() : ns + "/") + "fmu/" + direction + "/" + name;
}

std::unique_ptr<io::Link> make_px4_link(asio::io_context& loop, const Px4LinkSettings& settings,
                                        io::LinkOptions options) {
  return std::make_unique<Px4DdsLink>(loop, settings, std::move(options));
}

}  // namespace mocaplink::ros2
