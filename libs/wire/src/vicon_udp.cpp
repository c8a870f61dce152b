#include "mocaplink/wire/vicon_udp.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace mocaplink::wire::vicon_udp {

namespace {

using vicon::parse_error;

// |sin b| above this is gimbal lock for to_euler (cos b below ~1e-6).
constexpr double kLockSine = 1.0 - 1e-12;

void put_le(std::vector<std::byte>& out, std::uint64_t bits, std::size_t bytes) {
  for (std::size_t i = 0; i < bytes; ++i) {
    out.push_back(static_cast<std::byte>((bits >> (8 * i)) & 0xFFu));
  }
}

Result<Object> parse_object(ByteReader& r, double max_abs_mm) {
  const std::size_t start = r.offset();
  const auto raw = r.bytes(kNameBytes);
  if (!raw) return parse_error(start, "object item shorter than 72 bytes");
  const auto* chars = reinterpret_cast<const char*>(raw->data());
  const auto length = static_cast<std::size_t>(std::find(chars, chars + kNameBytes, '\0') - chars);
  Object o;
  o.name.assign(chars, length);
  if (o.name.empty()) return parse_error(start, "object without a name");
  if (std::any_of(o.name.begin(), o.name.end(),
                  [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; })) {
    return parse_error(start, "control character in an object name");
  }
  std::array<double, 6> v{};
  for (double& x : v) {
    const std::size_t at = r.offset();
    x = *r.read<double>(Endian::little);  // the caller checked the 72 bytes
    if (!std::isfinite(x)) return parse_error(at, "non-finite number in object " + o.name);
  }
  o.t_mm = Eigen::Vector3d(v[0], v[1], v[2]);
  o.rot_rad = Eigen::Vector3d(v[3], v[4], v[5]);
  if (o.t_mm.cwiseAbs().maxCoeff() > max_abs_mm) {
    return parse_error(start + kNameBytes, "object " + o.name + " outside the arena bound");
  }
  return o;
}

}  // namespace

bool Object::all_zero() const {
  return t_mm.isZero(0.0) && rot_rad.isZero(0.0);
}

Result<Datagram> parse_datagram(std::span<const std::byte> bytes, double max_abs_mm) {
  ByteReader r(bytes);
  const auto frame = r.read<std::uint32_t>(Endian::little);
  const auto count = r.read<std::uint8_t>(Endian::little);
  if (!count) return parse_error(bytes.size(), "datagram shorter than 5 bytes");
  Datagram out;
  out.frame = *frame;
  for (unsigned i = 0; i < *count; ++i) {
    const std::size_t item_at = r.offset();
    const auto id = r.read<std::uint8_t>(Endian::little);
    const auto size = r.read<std::uint16_t>(Endian::little);
    if (!size) return parse_error(item_at, "item " + std::to_string(i) + " header truncated");
    const auto data = r.bytes(*size);
    if (!data) {
      return parse_error(item_at, "item " + std::to_string(i) + " of " + std::to_string(*size) +
                                      " bytes exceeds the datagram");
    }
    if (*id != kObjectItem) {
      ++out.unknown_items;
      continue;
    }
    if (*size < kObjectBytes) {
      return parse_error(item_at,
                         "object item of " + std::to_string(*size) + " bytes, expected 72");
    }
    ByteReader item(*data);
    auto object = parse_object(item, max_abs_mm);
    if (!object) {
      return parse_error(item_at + kItemHeaderBytes + object.error().offset, object.error().reason);
    }
    out.objects.push_back(std::move(object).value());
  }
  // The block's padding: zero bytes only. Anything else is an item the count left out, or bytes
  // that are not this stream; neither may become a pose.
  const std::size_t tail = r.offset();
  const auto rest = bytes.subspan(tail);
  const auto nonzero =
      std::find_if(rest.begin(), rest.end(), [](std::byte b) { return b != std::byte{0}; });
  if (nonzero != rest.end()) {
    const auto at = tail + static_cast<std::size_t>(nonzero - rest.begin());
    char value[8];
    std::snprintf(value, sizeof value, "0x%02x", static_cast<unsigned>(*nonzero));
    return parse_error(at, "trailing non-zero bytes after " + std::to_string(*count) +
                               (*count == 1 ? " item (" : " items (") + value + " in a " +
                               std::to_string(bytes.size()) + "-byte datagram)");
  }
  out.padding_bytes = rest.size();
  return out;
}

std::vector<std::byte> encode_datagram(std::uint32_t frame, std::span<const Object> objects,
                                       std::size_t block_bytes) {
  if (objects.size() > objects_per_block(block_bytes)) {
    std::fprintf(stderr, "vicon_udp::encode_datagram: %zu objects do not fit in %zu bytes\n",
                 objects.size(), block_bytes);
    std::abort();
  }
  std::vector<std::byte> out;
  out.reserve(std::max(block_bytes, kHeaderBytes + objects.size() * kObjectItemBytes));
  put_le(out, frame, 4);
  put_le(out, objects.size(), 1);
  for (const Object& o : objects) {
    put_le(out, kObjectItem, 1);
    put_le(out, kObjectBytes, 2);
    for (std::size_t i = 0; i < kNameBytes; ++i) {
      out.push_back(i < o.name.size() ? static_cast<std::byte>(o.name[i]) : std::byte{0});
    }
    for (const double x :
         {o.t_mm.x(), o.t_mm.y(), o.t_mm.z(), o.rot_rad.x(), o.rot_rad.y(), o.rot_rad.z()}) {
      put_le(out, std::bit_cast<std::uint64_t>(x), 8);
    }
  }
  if (out.size() < block_bytes) out.resize(block_bytes, std::byte{0});  // Tracker's padding
  return out;
}

std::string_view to_string(EulerOrder order) {
  return order == EulerOrder::xyz ? "xyz" : "zyx";
}

Eigen::Quaterniond to_quaternion(const Eigen::Vector3d& rot_rad, EulerOrder order) {
  const Eigen::Quaterniond qx(Eigen::AngleAxisd(rot_rad.x(), Eigen::Vector3d::UnitX()));
  const Eigen::Quaterniond qy(Eigen::AngleAxisd(rot_rad.y(), Eigen::Vector3d::UnitY()));
  const Eigen::Quaterniond qz(Eigen::AngleAxisd(rot_rad.z(), Eigen::Vector3d::UnitZ()));
  return (order == EulerOrder::xyz ? qx * qy * qz : qz * qy * qx).normalized();
}

Eigen::Vector3d to_euler(const Eigen::Quaterniond& q, EulerOrder order) {
  const Eigen::Matrix3d m = q.normalized().toRotationMatrix();
  if (order == EulerOrder::xyz) {
    // R = Rx(a)·Ry(b)·Rz(c): R02 = sin b, R12 = −sin a cos b, R22 = cos a cos b,
    // R01 = −cos b sin c, R00 = cos b cos c.
    const double b = std::asin(std::clamp(m(0, 2), -1.0, 1.0));
    // Gimbal lock (cos b = 0): only a ± c is defined; take c = 0, so R·e_y = (0, cos a, sin a).
    if (std::abs(m(0, 2)) > kLockSine) return {std::atan2(m(2, 1), m(1, 1)), b, 0.0};
    return {std::atan2(-m(1, 2), m(2, 2)), b, std::atan2(-m(0, 1), m(0, 0))};
  }
  // R = Rz(c)·Ry(b)·Rx(a): R20 = −sin b, R21 = cos b sin a, R22 = cos b cos a,
  // R10 = cos b sin c, R00 = cos b cos c.
  const double b = std::asin(std::clamp(-m(2, 0), -1.0, 1.0));
  // Gimbal lock: take a = 0, so R·e_y = (−sin c, cos c, 0).
  if (std::abs(m(2, 0)) > kLockSine) return {0.0, b, std::atan2(-m(0, 1), m(1, 1))};
  return {std::atan2(m(2, 1), m(2, 2)), b, std::atan2(m(1, 0), m(0, 0))};
}

}  // namespace mocaplink::wire::vicon_udp
