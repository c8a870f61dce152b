#include "mocaplink/wire/ros2_messages.hpp"

#include <bit>
#include <cassert>
#include <cstring>

namespace mocaplink::wire {
namespace {

constexpr std::size_t kEncapsulationSize = 4;

void header(CdrWriter& w, const RosStamp& stamp, std::string_view frame_id) {
  w.i32(stamp.sec);
  w.u32(stamp.nanosec);
  w.string(frame_id);
}

void vector3(CdrWriter& w, const Eigen::Vector3d& v) {
  w.f64(v.x());
  w.f64(v.y());
  w.f64(v.z());
}

void quaternion(CdrWriter& w, const Eigen::Quaterniond& q) {
  w.f64(q.x());  // geometry_msgs/Quaternion is x, y, z, w
  w.f64(q.y());
  w.f64(q.z());
  w.f64(q.w());
}

void covariance(CdrWriter& w, const core::Matrix6d& m) {
  for (int row = 0; row < 6; ++row) {
    for (int col = 0; col < 6; ++col) w.f64(m(row, col));
  }
}

}  // namespace

RosStamp ros_stamp_from_unix_ns(std::int64_t unix_ns) {
  std::int64_t sec = unix_ns / 1'000'000'000;
  std::int64_t ns = unix_ns % 1'000'000'000;
  if (ns < 0) {
    ns += 1'000'000'000;
    --sec;
  }
  return RosStamp{static_cast<std::int32_t>(sec), static_cast<std::uint32_t>(ns)};
}

CdrWriter::CdrWriter(std::vector<std::uint8_t>& out) : out_(out) {
  static_assert(std::endian::native == std::endian::little,
                "CdrWriter writes host-order bytes: little-endian hosts only");
  // CDR_LE, no options: 00 01 00 00. Assigned, not inserted from a list: GCC 12's -O3
  // array-bounds check misreads an initializer-list insert into an empty vector.
  out_.assign(kEncapsulationSize, 0x00);
  out_[1] = 0x01;
}

void CdrWriter::put(const void* bytes, std::size_t size) {
  const auto* p = static_cast<const std::uint8_t*>(bytes);
  out_.insert(out_.end(), p, p + size);
}

void CdrWriter::align(std::size_t n) {
  const std::size_t offset = out_.size() - kEncapsulationSize;
  out_.resize(out_.size() + (n - offset % n) % n, 0);
}

void CdrWriter::u8(std::uint8_t v) {
  put(&v, 1);
}

void CdrWriter::i8(std::int8_t v) {
  put(&v, 1);
}

void CdrWriter::u64(std::uint64_t v) {
  align(8);
  put(&v, 8);
}

void CdrWriter::u32(std::uint32_t v) {
  align(4);
  put(&v, 4);
}

void CdrWriter::i32(std::int32_t v) {
  align(4);
  put(&v, 4);
}

void CdrWriter::f32(float v) {
  align(4);
  put(&v, 4);
}

void CdrWriter::f64(double v) {
  align(8);
  put(&v, 8);
}

void CdrWriter::string(std::string_view s) {
  assert(s.find('\0') == std::string_view::npos && "a CDR string holds no NUL");
  u32(static_cast<std::uint32_t>(s.size() + 1));
  put(s.data(), s.size());
  u8(0);
}

void encode_pose_stamped(const RosStamp& stamp, std::string_view frame_id,
                         const core::RosBodyState& state, std::vector<std::uint8_t>& out) {
  CdrWriter w(out);
  header(w, stamp, frame_id);
  vector3(w, state.position_m);  // geometry_msgs/Point
  quaternion(w, state.orientation);
}

void encode_odometry(const RosStamp& stamp, std::string_view frame_id,
                     std::string_view child_frame_id, const core::RosBodyState& state,
                     std::vector<std::uint8_t>& out) {
  CdrWriter w(out);
  header(w, stamp, frame_id);
  w.string(child_frame_id);
  vector3(w, state.position_m);
  quaternion(w, state.orientation);
  covariance(w, state.pose_covariance);
  vector3(w, state.linear_velocity_mps);
  vector3(w, state.angular_velocity_radps);
  covariance(w, state.twist_covariance);
}

void encode_tf_message(std::span<const RosTransform> transforms, std::vector<std::uint8_t>& out) {
  CdrWriter w(out);
  w.u32(static_cast<std::uint32_t>(transforms.size()));
  for (const RosTransform& t : transforms) {
    header(w, t.stamp, t.frame_id);
    w.string(t.child_frame_id);
    vector3(w, t.translation_m);  // geometry_msgs/Vector3
    quaternion(w, t.rotation);
  }
}

}  // namespace mocaplink::wire
