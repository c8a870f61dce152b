#include "mocaplink/wire/qtm_protocol.hpp"

#include <algorithm>
#include <cctype>
#include <limits>

#include "mocaplink/wire/byte_reader.hpp"
#include "mocaplink/wire/vicon_codec.hpp"

namespace mocaplink::wire::qtm {

namespace {

using vicon::codec::Writer;

constexpr std::size_t kComponentHeaderBytes = 8;
constexpr std::size_t kSixDofHeaderBytes = 16;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

bool iequals(std::string_view a, std::string_view b) {
  return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](char x, char y) {
    return std::tolower(static_cast<unsigned char>(x)) ==
           std::tolower(static_cast<unsigned char>(y));
  });
}

bool is_six_dof(std::uint32_t type) {
  return type == 5 || type == 6 || type == 11 || type == 12;
}

template <std::size_t N>
bool read_floats(ByteReader& r, std::array<float, N>& out) {
  for (float& f : out) {
    const auto v = r.read<float>();
    if (!v) return false;
    f = *v;
  }
  return true;
}

Result<SixDof> parse_six_dof(std::span<const std::byte> component, std::size_t base) {
  ByteReader r(component);
  (void)r.skip(4);  // size: the caller cut the span to it
  SixDof out;
  out.type = static_cast<Component>(*r.read<std::uint32_t>());
  const auto count = r.read<std::uint32_t>();
  const auto drop = r.read<std::uint16_t>();
  const auto sync = r.read<std::uint16_t>();
  if (!count || !drop || !sync) {
    return parse_error(base + r.offset(), "6DOF component shorter than its 16-byte header");
  }
  out.drop_rate_permille = *drop;
  out.out_of_sync_permille = *sync;
  const std::size_t per_body = body_bytes(out.type);
  // Checked against the bytes present before anything is allocated for the bodies.
  if ((component.size() - kSixDofHeaderBytes) / per_body < *count ||
      kSixDofHeaderBytes + *count * per_body != component.size()) {
    return parse_error(base, "6DOF component of " + std::to_string(component.size()) +
                                 " bytes cannot hold " + std::to_string(*count) + " bodies of " +
                                 std::to_string(per_body) + " bytes");
  }
  out.bodies.resize(*count);
  for (Body6d& b : out.bodies) {
    b.rotation.fill(kNaN);
    b.euler_deg.fill(kNaN);
    b.residual = kNaN;
    bool ok = read_floats(r, b.position_mm);
    ok = ok && (has_matrix(out.type) ? read_floats(r, b.rotation) : read_floats(r, b.euler_deg));
    if (ok && has_residual(out.type)) {
      const auto res = r.read<float>();
      ok = res.has_value();
      if (res) b.residual = *res;
    }
    if (!ok) return parse_error(base + r.offset(), "6DOF body truncated");
  }
  return out;
}

}  // namespace

bool invalidates_parameters(std::uint8_t event) {
  switch (static_cast<Event>(event)) {
    case Event::connection_closed:
    case Event::capture_stopped:
    case Event::calibration_stopped:
    case Event::rt_from_file_stopped:
    case Event::camera_settings_changed:
    case Event::qtm_shutting_down:
      return true;
    default:
      return false;
  }
}

std::string_view to_string(Component c) {
  switch (c) {
    case Component::six_d:
      return "6D";
    case Component::six_d_euler:
      return "6DEuler";
    case Component::six_d_residual:
      return "6DRes";
    case Component::six_d_euler_residual:
      return "6DEulerRes";
  }
  return "?";
}

std::optional<Component> component_from_string(std::string_view name) {
  for (const auto c : {Component::six_d, Component::six_d_euler, Component::six_d_residual,
                       Component::six_d_euler_residual}) {
    if (iequals(name, to_string(c))) return c;
  }
  return std::nullopt;
}

std::size_t body_bytes(Component c) {
  const std::size_t floats = 3 + (has_matrix(c) ? 9u : 3u) + (has_residual(c) ? 1u : 0u);
  return 4 * floats;
}

bool has_matrix(Component c) {
  return c == Component::six_d || c == Component::six_d_residual;
}

bool has_residual(Component c) {
  return c == Component::six_d_residual || c == Component::six_d_euler_residual;
}

Result<PacketHeader> parse_header(std::span<const std::byte> bytes,
                                  std::uint32_t max_packet_bytes) {
  ByteReader r(bytes);
  const auto size = r.read<std::int32_t>();
  const auto type = r.read<std::int32_t>();
  if (!size || !type) return parse_error(r.offset(), "packet header shorter than 8 bytes");
  if (*size < static_cast<std::int32_t>(kHeaderBytes)) {
    return parse_error(0, "packet size " + std::to_string(*size) + " is below the 8 header bytes");
  }
  if (static_cast<std::uint32_t>(*size) > max_packet_bytes) {
    return parse_error(0, "packet size " + std::to_string(*size) + " exceeds the limit of " +
                              std::to_string(max_packet_bytes) + " bytes");
  }
  return PacketHeader{static_cast<std::uint32_t>(*size), static_cast<std::uint32_t>(*type)};
}

Result<PacketView> parse_packet(std::span<const std::byte> bytes, std::uint32_t max_packet_bytes) {
  auto header = parse_header(bytes, max_packet_bytes);
  if (!header) return header.error();
  if (header.value().size != bytes.size()) {
    return parse_error(0, "packet size field " + std::to_string(header.value().size) +
                              " but the datagram holds " + std::to_string(bytes.size()) + " bytes");
  }
  return PacketView{header.value().type, bytes.subspan(kHeaderBytes)};
}

std::vector<std::byte> encode_packet(PacketType type, std::span<const std::byte> payload) {
  std::vector<std::byte> out;
  out.reserve(kHeaderBytes + payload.size());
  Writer w(out);
  w.put(static_cast<std::int32_t>(kHeaderBytes + payload.size()));
  w.put(static_cast<std::int32_t>(type));
  w.put_bytes(payload);
  return out;
}

std::vector<std::byte> encode_text(PacketType type, std::string_view text, bool nul) {
  std::vector<std::byte> payload(text.size() + (nul ? 1 : 0));
  std::transform(text.begin(), text.end(), payload.begin(),
                 [](char c) { return static_cast<std::byte>(c); });
  return encode_packet(type, payload);
}

std::vector<std::byte> encode_event(std::uint8_t event) {
  const std::array<std::byte, 1> payload{static_cast<std::byte>(event)};
  return encode_packet(PacketType::event, payload);
}

std::string text_of(std::span<const std::byte> payload) {
  const auto nul = std::find(payload.begin(), payload.end(), std::byte{0});
  std::string out(static_cast<std::size_t>(nul - payload.begin()), '\0');
  std::transform(payload.begin(), nul, out.begin(),
                 [](std::byte b) { return static_cast<char>(b); });
  return out;
}

Result<DataPacket> parse_data(std::span<const std::byte> payload) {
  ByteReader r(payload);
  DataPacket out;
  const auto timestamp = r.read<std::int64_t>();
  const auto frame = r.read<std::uint32_t>();
  const auto count = r.read<std::uint32_t>();
  if (!timestamp || !frame || !count) {
    return parse_error(r.offset(), "data packet shorter than its 16-byte header");
  }
  out.timestamp_us = *timestamp;
  out.frame_number = *frame;
  for (std::uint32_t i = 0; i < *count; ++i) {
    const std::size_t start = r.offset();
    ByteReader peek(payload.subspan(start));
    const auto size = peek.read<std::uint32_t>();
    const auto type = peek.read<std::uint32_t>();
    if (!size || !type) return parse_error(start, "component header truncated");
    if (*size < kComponentHeaderBytes || *size > r.remaining()) {
      return parse_error(start, "component size " + std::to_string(*size) + " with " +
                                    std::to_string(r.remaining()) + " bytes left");
    }
    const auto component = *r.bytes(*size);
    if (!is_six_dof(*type)) {
      ++out.other_components;
      continue;
    }
    if (out.six_dof.size() >= 4) return parse_error(start, "more than four 6DOF components");
    auto six = parse_six_dof(component, kHeaderBytes + start);
    if (!six) return six.error();
    out.six_dof.push_back(std::move(six).value());
  }
  if (!r.empty()) {
    return parse_error(r.offset(),
                       std::to_string(r.remaining()) + " bytes after the last component");
  }
  return out;
}

std::vector<std::byte> encode_data(const DataPacket& packet) {
  std::vector<std::byte> out;
  Writer w(out);
  w.put(std::int32_t{0});  // size, patched below
  w.put(static_cast<std::int32_t>(PacketType::data));
  w.put(packet.timestamp_us);
  w.put(packet.frame_number);
  w.put(static_cast<std::uint32_t>(packet.six_dof.size()));
  for (const SixDof& c : packet.six_dof) {
    const std::size_t at = w.size();
    w.put(std::uint32_t{0});
    w.put(static_cast<std::uint32_t>(c.type));
    w.put(static_cast<std::uint32_t>(c.bodies.size()));
    w.put(c.drop_rate_permille);
    w.put(c.out_of_sync_permille);
    for (const Body6d& b : c.bodies) {
      for (const float f : b.position_mm) w.put(f);
      if (has_matrix(c.type)) {
        for (const float f : b.rotation) w.put(f);
      } else {
        for (const float f : b.euler_deg) w.put(f);
      }
      if (has_residual(c.type)) w.put(b.residual);
    }
    w.patch_u32(at, static_cast<std::uint32_t>(w.size() - at));
  }
  w.patch_u32(0, static_cast<std::uint32_t>(out.size()));
  return out;
}

}  // namespace mocaplink::wire::qtm
