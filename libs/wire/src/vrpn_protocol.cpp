#include "mocaplink/wire/vrpn_protocol.hpp"

#include <bit>
#include <cmath>

#include "mocaplink/core/quaternion.hpp"

namespace mocaplink::wire::vrpn {

namespace {

using vicon::parse_error;

/// Appends `value` big-endian (network order, §1).
template <typename T>
void put_be(std::vector<std::byte>& out, T value) {
  using U = std::conditional_t<sizeof(T) == 8, std::uint64_t, std::uint32_t>;
  static_assert(sizeof(T) == sizeof(U));
  const U bits = std::bit_cast<U>(value);
  for (int shift = static_cast<int>(sizeof(U) * 8) - 8; shift >= 0; shift -= 8) {
    out.push_back(static_cast<std::byte>((bits >> shift) & 0xFFu));
  }
}

bool has_control_character(std::string_view s) {
  for (const char c : s) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return true;
  }
  return false;
}

}  // namespace

std::array<std::byte, kCookieBytes> make_cookie(char log_mode) {
  std::array<std::byte, kCookieBytes> out{};
  std::size_t i = 0;
  for (const char c : kMagic) out[i++] = static_cast<std::byte>(c);
  out[16] = std::byte{' '};
  out[17] = std::byte{' '};
  out[18] = static_cast<std::byte>(log_mode);
  return out;
}

Result<Cookie> parse_cookie(std::span<const std::byte> bytes) {
  if (bytes.size() < kCookieBytes) {
    return parse_error(bytes.size(), "cookie shorter than 24 bytes");
  }
  std::string magic(reinterpret_cast<const char*>(bytes.data()), kMagic.size());
  if (!magic.starts_with(kMagicMajor)) {
    for (char& c : magic) {
      if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) > 0x7e) c = '?';
    }
    return parse_error(0, "not a VRPN 07.xx cookie: \"" + magic + "\"");
  }
  const char mode = static_cast<char>(bytes[18]);
  if (mode < '0' || mode > '3') return parse_error(18, "cookie log mode is not '0'..'3'");
  return Cookie{std::move(magic), mode};
}

Result<Header> parse_header(std::span<const std::byte> bytes, std::uint32_t max_payload) {
  ByteReader r(bytes);
  const auto length = r.read<std::uint32_t>(Endian::big);
  const auto sec = r.read<std::uint32_t>(Endian::big);
  const auto usec = r.read<std::uint32_t>(Endian::big);
  const auto sender = r.read<std::int32_t>(Endian::big);
  const auto type = r.read<std::int32_t>(Endian::big);
  if (!type || !r.skip(4)) return parse_error(r.offset(), "header shorter than 24 bytes");
  if (*length < kHeaderBytes) {
    return parse_error(0, "message length " + std::to_string(*length) + " < 24");
  }
  if (*length - kHeaderBytes > max_payload) {
    return parse_error(0, "message payload of " + std::to_string(*length - kHeaderBytes) +
                              " bytes exceeds " + std::to_string(max_payload));
  }
  if (*usec >= 1'000'000u) return parse_error(8, "time microseconds ≥ 1000000");
  return Header{*length, Timeval{*sec, *usec}, *sender, *type};
}

Result<std::string> parse_description(std::span<const std::byte> payload) {
  ByteReader r(payload);
  const auto length = r.read<std::uint32_t>(Endian::big);
  if (!length) return parse_error(0, "description shorter than 4 bytes");
  if (*length < 2 || *length > kMaxNameBytes) {
    return parse_error(0, "description name length " + std::to_string(*length) + " outside 2.." +
                              std::to_string(kMaxNameBytes));
  }
  if (r.remaining() != *length) {
    return parse_error(4, "description name length " + std::to_string(*length) + " but " +
                              std::to_string(r.remaining()) + " bytes follow");
  }
  auto name = r.cstring(*length);
  if (!name || name->size() + 1 != *length) {
    return parse_error(4, "description name is not one NUL-terminated string");
  }
  if (has_control_character(*name)) return parse_error(4, "control character in a name");
  return std::move(*name);
}

Result<PosQuat> parse_pos_quat(std::span<const std::byte> payload) {
  if (payload.size() < kPosQuatBytes) {
    return parse_error(payload.size(), "Pos_Quat payload of " + std::to_string(payload.size()) +
                                           " bytes, expected 64");
  }
  ByteReader r(payload);
  PosQuat out;
  out.sensor = *r.read<std::int32_t>(Endian::big);
  (void)r.skip(4);
  std::array<double, 7> v{};
  for (double& x : v) {
    x = *r.read<double>(Endian::big);
    if (!std::isfinite(x)) return parse_error(r.offset() - 8, "non-finite number in Pos_Quat");
  }
  if (out.sensor < 0) return parse_error(0, "negative sensor number");
  out.p_m = Eigen::Vector3d(v[0], v[1], v[2]);
  const Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);  // the wire is x, y, z, w
  if (core::check_quaternion(q) != core::QuaternionFault::none) {
    return parse_error(32, "Pos_Quat quaternion is not a unit quaternion");
  }
  out.q_world_sensor = q.normalized();
  return out;
}

std::vector<std::byte> encode_message(Timeval time, std::int32_t sender, std::int32_t type,
                                      std::span<const std::byte> payload, std::uint32_t sequence) {
  std::vector<std::byte> out;
  out.reserve(kHeaderBytes + payload.size() + 7);
  put_be(out, static_cast<std::uint32_t>(kHeaderBytes + payload.size()));
  put_be(out, time.sec);
  put_be(out, time.usec);
  put_be(out, sender);
  put_be(out, type);
  put_be(out, sequence);
  out.insert(out.end(), payload.begin(), payload.end());
  while (out.size() % 8 != 0) out.push_back(std::byte{0});
  return out;
}

std::vector<std::byte> encode_description(Timeval time, std::int32_t kind, std::int32_t id,
                                          std::string_view name, std::uint32_t sequence) {
  std::vector<std::byte> payload;
  put_be(payload, static_cast<std::uint32_t>(name.size() + 1));
  for (const char c : name) payload.push_back(static_cast<std::byte>(c));
  payload.push_back(std::byte{0});
  return encode_message(time, id, kind, payload, sequence);
}

std::vector<std::byte> encode_pos_quat(const PosQuat& report) {
  std::vector<std::byte> out;
  put_be(out, report.sensor);
  put_be(out, report.sensor);
  for (const double x :
       {report.p_m.x(), report.p_m.y(), report.p_m.z(), report.q_world_sensor.x(),
        report.q_world_sensor.y(), report.q_world_sensor.z(), report.q_world_sensor.w()}) {
    put_be(out, x);
  }
  return out;
}

std::vector<std::byte> encode_velocity(std::int32_t sensor, const Eigen::Vector3d& v_m_s,
                                       const Eigen::Quaterniond& vel_quat, double vel_quat_dt_s) {
  std::vector<std::byte> out;
  put_be(out, sensor);
  put_be(out, sensor);
  for (const double x : {v_m_s.x(), v_m_s.y(), v_m_s.z(), vel_quat.x(), vel_quat.y(), vel_quat.z(),
                         vel_quat.w(), vel_quat_dt_s}) {
    put_be(out, x);
  }
  return out;
}

}  // namespace mocaplink::wire::vrpn
