// PX4's uXRCE-DDS messages (px4_messages.hpp).
#include "mocaplink/wire/px4_messages.hpp"

#include <cmath>
#include <limits>

#include "mocaplink/wire/byte_reader.hpp"
#include "mocaplink/wire/ros2_messages.hpp"

namespace mocaplink::wire {
namespace {

constexpr std::size_t kHeader = 4;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
// MAV_FRAME values ODOMETRY uses (common.xml).
constexpr std::uint8_t kMavFrameLocalNed = 1;
constexpr std::uint8_t kMavFrameBodyFrd = 12;
constexpr std::uint8_t kMavFrameLocalFrd = 20;

void floats(CdrWriter& w, std::span<const float> v) {
  for (const float f : v) w.f32(f);
}

/// The payload after a CDR header (00 00 big endian, 00 01 little endian; options ignored).
struct Cdr {
  std::span<const std::uint8_t> payload;
  Endian order = Endian::little;
};
std::optional<Cdr> cdr(std::span<const std::uint8_t> sample, std::size_t payload_bytes) {
  if (sample.size() < kHeader + payload_bytes || sample[0] != 0x00 || sample[1] > 0x01) {
    return std::nullopt;
  }
  return Cdr{sample.subspan(kHeader), sample[1] == 0x01 ? Endian::little : Endian::big};
}

/// Fixed-offset reads of a CDR payload whose length was checked.
class Fields {
 public:
  explicit Fields(const Cdr& c) : reader_(std::as_bytes(c.payload)), order_(c.order) {}
  template <typename T>
  T at(std::size_t offset) {
    ByteReader r = reader_;
    (void)r.skip(offset);
    return r.read<T>(order_).value_or(T{});
  }
  template <std::size_t N>
  std::array<float, N> floats_at(std::size_t offset) {
    std::array<float, N> out{};
    for (std::size_t i = 0; i < N; ++i) out[i] = at<float>(offset + 4 * i);
    return out;
  }

 private:
  ByteReader reader_;
  Endian order_;
};

}  // namespace

void encode_px4_vehicle_odometry(const Px4VehicleOdometry& m, std::vector<std::uint8_t>& out) {
  CdrWriter w(out);
  w.u64(m.timestamp);
  w.u64(m.timestamp_sample);
  w.u8(m.pose_frame);
  floats(w, m.position);
  floats(w, m.q);
  w.u8(m.velocity_frame);
  floats(w, m.velocity);
  floats(w, m.angular_velocity);
  floats(w, m.position_variance);
  floats(w, m.orientation_variance);
  floats(w, m.velocity_variance);
  w.u8(m.reset_counter);
  w.i8(m.quality);
}

std::optional<Px4VehicleOdometry> decode_px4_vehicle_odometry(
    std::span<const std::uint8_t> sample) {
  const auto c = cdr(sample, kPx4VehicleOdometryPayload);
  if (!c) return std::nullopt;
  Fields f(*c);
  Px4VehicleOdometry m;
  m.timestamp = f.at<std::uint64_t>(0);
  m.timestamp_sample = f.at<std::uint64_t>(8);
  m.pose_frame = f.at<std::uint8_t>(16);
  m.position = f.floats_at<3>(20);
  m.q = f.floats_at<4>(32);
  m.velocity_frame = f.at<std::uint8_t>(48);
  m.velocity = f.floats_at<3>(52);
  m.angular_velocity = f.floats_at<3>(64);
  m.position_variance = f.floats_at<3>(76);
  m.orientation_variance = f.floats_at<3>(88);
  m.velocity_variance = f.floats_at<3>(100);
  m.reset_counter = f.at<std::uint8_t>(112);
  m.quality = f.at<std::int8_t>(113);
  return m;
}

std::optional<Px4VehicleStatus> decode_px4_vehicle_status(std::span<const std::uint8_t> sample) {
  // timestamp 0, armed_time 8, takeoff_time 16, arming_state 24, latest_arming_reason 25,
  // latest_disarming_reason 26, nav_state_timestamp 32, nav_state_user_intention 40, nav_state 41.
  constexpr std::size_t kRead = 42;
  const auto c = cdr(sample, kRead);
  if (!c) return std::nullopt;
  Fields f(*c);
  Px4VehicleStatus s;
  s.timestamp = f.at<std::uint64_t>(0);
  s.armed_time = f.at<std::uint64_t>(8);
  s.takeoff_time = f.at<std::uint64_t>(16);
  s.arming_state = f.at<std::uint8_t>(24);
  s.nav_state = f.at<std::uint8_t>(41);
  return s;
}

Px4VehicleOdometry px4_vehicle_odometry_of(const mavlink::Odometry& m, std::uint64_t timestamp_us,
                                           std::uint64_t timestamp_sample_us) {
  Px4VehicleOdometry o;
  o.timestamp = timestamp_us;
  o.timestamp_sample = timestamp_sample_us;
  if (m.frame_id == kMavFrameLocalNed || m.frame_id == kMavFrameLocalFrd) {
    o.pose_frame = m.frame_id == kMavFrameLocalNed ? Px4VehicleOdometry::kFrameNed
                                                   : Px4VehicleOdometry::kFrameFrd;
    o.position = {m.x, m.y, m.z};
    o.q = {m.q[0], m.q[1], m.q[2], m.q[3]};
  } else {
    o.position = {kNaN, kNaN, kNaN};
    o.q = {kNaN, kNaN, kNaN, kNaN};
  }
  switch (m.child_frame_id) {
    case kMavFrameBodyFrd:
      o.velocity_frame = Px4VehicleOdometry::kVelocityFrameBodyFrd;
      break;
    case kMavFrameLocalNed:
      o.velocity_frame = Px4VehicleOdometry::kFrameNed;
      break;
    case kMavFrameLocalFrd:
      o.velocity_frame = Px4VehicleOdometry::kFrameFrd;
      break;
    default:
      o.velocity_frame = Px4VehicleOdometry::kFrameUnknown;
      break;
  }
  if (o.velocity_frame != Px4VehicleOdometry::kFrameUnknown) {
    o.velocity = {m.vx, m.vy, m.vz};
  } else {
    o.velocity = {kNaN, kNaN, kNaN};
  }
  o.angular_velocity = {m.rollspeed, m.pitchspeed, m.yawspeed};
  // Upper-right triangles, row-major, of 6×6 matrices: the diagonal is at 0, 6, 11, 15, 18, 20.
  const auto& pc = m.pose_covariance;
  const auto& vc = m.velocity_covariance;
  if (std::isnan(pc[0])) {
    o.position_variance = {kNaN, kNaN, kNaN};
    o.orientation_variance = {kNaN, kNaN, kNaN};
  } else {
    o.position_variance = {pc[0], pc[6], pc[11]};
    o.orientation_variance = {pc[15], pc[18], pc[20]};
  }
  if (std::isnan(vc[0])) {
    o.velocity_variance = {kNaN, kNaN, kNaN};
  } else {
    o.velocity_variance = {vc[0], vc[6], vc[11]};
  }
  o.reset_counter = m.reset_counter;
  o.quality = m.quality;
  return o;
}

}  // namespace mocaplink::wire
