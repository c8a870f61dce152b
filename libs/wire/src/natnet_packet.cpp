#include "mocaplink/wire/natnet_packet.hpp"

#include <algorithm>
#include <utility>

#include "mocaplink/wire/vicon_codec.hpp"

namespace mocaplink::wire::natnet {

namespace {

// Little-endian appender shared with the Vicon codecs.
using Writer = vicon::codec::Writer;

constexpr std::size_t kSenderBytes = 264;
constexpr std::size_t kServerInfo3Bytes = 279;
constexpr std::size_t kRigidBodyItemBytes = 38;  // §4.2, 3.0+
constexpr std::size_t kLabeledMarkerBytes = 26;  // §4.1, 3.0+

// A bounds-checked cursor over one payload that keeps the first error (offset + reason).
class Cursor {
 public:
  explicit Cursor(std::span<const std::byte> bytes) : in_(bytes) {}

  template <typename T>
  bool get(T& out, const char* what) {
    if (failed_) return false;
    auto v = in_.read<T>(Endian::little);
    if (!v) return fail(std::string("truncated ") + what);
    out = *v;
    return true;
  }

  bool get_floats(std::span<float> out, const char* what) {
    for (float& f : out) {
      if (!get(f, what)) return false;
    }
    return true;
  }

  // A count that must be >= 0, <= limit and fit `min_item_bytes` per item in what remains.
  bool get_count(std::size_t& out, const char* what, std::size_t limit,
                 std::size_t min_item_bytes) {
    std::int32_t n = 0;
    if (!get(n, what)) return false;
    if (n < 0) return fail(std::string("negative ") + what);
    const auto count = static_cast<std::size_t>(n);
    if (count > limit) return fail(std::string(what) + " " + std::to_string(n) + " over the limit");
    if (min_item_bytes > 0 && count > in_.remaining() / min_item_bytes) {
      return fail(std::string(what) + " " + std::to_string(n) + " exceeds the " +
                  std::to_string(in_.remaining()) + " bytes left");
    }
    out = count;
    return true;
  }

  bool get_string(std::string& out, const char* what) {
    if (failed_) return false;
    auto s = in_.cstring(kMaxNameBytes);
    if (!s) return fail(std::string(what) + " not NUL-terminated within 256 bytes");
    out = std::move(*s);
    return true;
  }

  bool skip(std::size_t n, const char* what) {
    if (failed_) return false;
    if (!in_.skip(n)) return fail(std::string("truncated ") + what);
    return true;
  }

  bool fail(std::string reason) {
    if (!failed_) {
      failed_ = true;
      error_ = ParseError{in_.offset(), std::move(reason)};
    }
    return false;
  }

  bool at_end(const char* what) {
    if (failed_) return false;
    if (!in_.empty()) {
      return fail(std::to_string(in_.remaining()) + " bytes left after the " + what +
                  " (version or layout mismatch)");
    }
    return true;
  }

  [[nodiscard]] std::size_t offset() const { return in_.offset(); }
  [[nodiscard]] std::size_t remaining() const { return in_.remaining(); }
  [[nodiscard]] bool failed() const { return failed_; }
  [[nodiscard]] const ParseError& error() const { return error_; }

 private:
  ByteReader in_;
  bool failed_ = false;
  ParseError error_{};
};

void put_floats(Writer& w, std::span<const float> values) {
  for (const float f : values) w.put(f);
}

void put_string(Writer& w, const std::string& s) {
  const std::size_t n = std::min(s.size(), kMaxNameBytes - 1);
  w.put_bytes(std::as_bytes(std::span(s.data(), n)));
  w.put<std::uint8_t>(0);
}

void put_count(Writer& w, std::size_t n) {
  w.put(static_cast<std::int32_t>(n));
}

// A section's byte-size field (4.1+), patched once the section is written.
std::size_t begin_size(Writer& w, Version v) {
  if (!v.at_least(4, 1)) return 0;
  const std::size_t at = w.size();
  w.put<std::int32_t>(0);
  return at;
}

void end_size(Writer& w, Version v, std::size_t at) {
  if (!v.at_least(4, 1)) return;
  w.patch_u32(at, static_cast<std::uint32_t>(w.size() - at - 4));
}

void put_sender(Writer& w, const SenderInfo& s) {
  std::array<std::byte, kMaxNameBytes> name{};
  const std::size_t n = std::min(s.name.size(), kMaxNameBytes - 1);
  for (std::size_t i = 0; i < n; ++i) name[i] = static_cast<std::byte>(s.name[i]);
  w.put_bytes(name);
  for (const auto b : s.app_version) w.put(b);
  for (const auto b : s.natnet_version) w.put(b);
}

bool get_sender(Cursor& c, SenderInfo& s, std::span<const std::byte> payload) {
  if (payload.size() < kSenderBytes) return c.fail("sender block shorter than 264 bytes");
  const auto name = payload.first(kMaxNameBytes);
  const auto nul = std::find(name.begin(), name.end(), std::byte{0});
  s.name.assign(reinterpret_cast<const char*>(name.data()),
                static_cast<std::size_t>(nul - name.begin()));
  if (!c.skip(kMaxNameBytes, "name")) return false;
  for (auto& b : s.app_version) c.get(b, "app version");
  for (auto& b : s.natnet_version) c.get(b, "natnet version");
  return !c.failed();
}

template <typename T>
Result<T> finish(Cursor& c, T value) {
  if (c.failed()) return c.error();
  return value;
}

// §3.2 rigid-body description (also skeleton bones and asset bodies).
bool get_rigid_body_description(Cursor& c, RigidBodyDescription& rb, Version v) {
  if (v.at_least(2, 0) && !c.get_string(rb.name, "rigid-body name")) return false;
  c.get(rb.id, "rigid-body id");
  c.get(rb.parent_id, "parent id");
  c.get_floats(rb.offset, "offset");
  if (v.at_least(4, 2)) c.get_floats(rb.quat_offset, "quaternion offset");
  if (c.failed() || !v.at_least(3, 0)) return !c.failed();
  std::size_t n = 0;
  if (!c.get_count(n, "marker count", kMaxMarkers, 16)) return false;
  for (std::size_t i = 0; i < n && !c.failed(); ++i) {
    std::array<float, 3> p{};
    if (c.get_floats(p, "marker position")) rb.marker_positions.push_back(p);
  }
  for (std::size_t i = 0; i < n && !c.failed(); ++i) {
    std::int32_t label = 0;
    if (c.get(label, "marker label")) rb.marker_labels.push_back(label);
  }
  if (v.at_least(4, 0)) {
    for (std::size_t i = 0; i < n && !c.failed(); ++i) {
      std::string name;
      if (c.get_string(name, "marker name")) rb.marker_names.push_back(std::move(name));
    }
  }
  return !c.failed();
}

void put_rigid_body_description(Writer& w, const RigidBodyDescription& rb, Version v) {
  put_string(w, rb.name);
  w.put(rb.id);
  w.put(rb.parent_id);
  put_floats(w, rb.offset);
  if (v.at_least(4, 2)) put_floats(w, rb.quat_offset);
  if (!v.at_least(3, 0)) return;
  const std::size_t n = rb.marker_positions.size();
  put_count(w, n);
  for (const auto& p : rb.marker_positions) put_floats(w, p);
  for (std::size_t i = 0; i < n; ++i) {
    w.put(i < rb.marker_labels.size() ? rb.marker_labels[i] : std::int32_t{0});
  }
  if (v.at_least(4, 0)) {
    for (std::size_t i = 0; i < n; ++i) {
      put_string(w, i < rb.marker_names.size() ? rb.marker_names[i] : std::string());
    }
  }
}

bool skip_strings(Cursor& c, std::size_t n) {
  std::string ignored;
  for (std::size_t i = 0; i < n && !c.failed(); ++i) c.get_string(ignored, "name");
  return !c.failed();
}

bool skip_string_list(Cursor& c) {
  std::size_t n = 0;
  return c.get_count(n, "name count", kMaxMarkers, 1) && skip_strings(c, n);
}

// Parses one dataset of a known type; false on error, `known` false for an unknown type.
bool get_dataset(Cursor& c, std::int32_t type, Version v, ModelDefinitions& out, bool& known) {
  known = true;
  std::string name;
  switch (type) {
    case 0: {  // marker set
      MarkerSetDescription set;
      std::size_t n = 0;
      if (!c.get_string(set.name, "marker-set name") ||
          !c.get_count(n, "marker count", kMaxMarkers, 1)) {
        return false;
      }
      for (std::size_t i = 0; i < n && !c.failed(); ++i) {
        std::string marker;
        if (c.get_string(marker, "marker name")) set.marker_names.push_back(std::move(marker));
      }
      if (!c.failed()) out.marker_sets.push_back(std::move(set));
      return !c.failed();
    }
    case 1: {
      RigidBodyDescription rb;
      if (!get_rigid_body_description(c, rb, v)) return false;
      out.rigid_bodies.push_back(std::move(rb));
      return true;
    }
    case 2: {  // skeleton: bones are rigid-body descriptions in another id space
      std::int32_t id = 0;
      std::size_t bones = 0;
      if (!c.get_string(name, "skeleton name") || !c.get(id, "skeleton id") ||
          !c.get_count(bones, "bone count", kMaxRigidBodies, 16)) {
        return false;
      }
      for (std::size_t i = 0; i < bones; ++i) {
        RigidBodyDescription bone;
        if (!get_rigid_body_description(c, bone, v)) return false;
      }
      ++out.other_datasets;
      return true;
    }
    case 3: {  // force plate (3.0+ layout)
      if (!v.at_least(3, 0)) break;
      std::int32_t id = 0;
      if (!c.get(id, "force-plate id") || !c.get_string(name, "serial")) return false;
      // width, length, 3 offset, 12×12 calibration, 4×3 corners, plate type, channel data type
      if (!c.skip(4 * (2 + 3 + 144 + 12) + 4 + 4, "force plate")) return false;
      ++out.other_datasets;
      return skip_string_list(c);
    }
    case 4: {  // device (3.0+ layout)
      if (!v.at_least(3, 0)) break;
      std::int32_t id = 0;
      if (!c.get(id, "device id") || !c.get_string(name, "device name") ||
          !c.get_string(name, "serial") || !c.skip(8, "device types")) {
        return false;
      }
      ++out.other_datasets;
      return skip_string_list(c);
    }
    case 5:  // camera (4.0+)
      if (!v.at_least(4, 0)) break;
      ++out.other_datasets;
      return c.get_string(name, "camera name") && c.skip(7 * 4, "camera pose");
    case 6: {  // asset (4.1+)
      if (!v.at_least(4, 1)) break;
      std::int32_t ints[2] = {};
      std::size_t n = 0;
      if (!c.get_string(name, "asset name") || !c.get(ints[0], "asset type") ||
          !c.get(ints[1], "asset id") || !c.get_count(n, "asset bodies", kMaxRigidBodies, 16)) {
        return false;
      }
      for (std::size_t i = 0; i < n; ++i) {
        RigidBodyDescription rb;
        if (!get_rigid_body_description(c, rb, v)) return false;
      }
      if (!c.get_count(n, "asset markers", kMaxMarkers, 23)) return false;
      for (std::size_t i = 0; i < n; ++i) {
        if (!c.get_string(name, "asset marker name") || !c.skip(4 + 12 + 4 + 2, "asset marker")) {
          return false;
        }
      }
      ++out.other_datasets;
      return true;
    }
    default:
      break;
  }
  known = false;
  return true;
}

}  // namespace

bool supported(Version v) {
  return v >= Version{2, 5} && v < Version{5, 0};
}

Result<Packet> split_packet(std::span<const std::byte> datagram) {
  ByteReader r(datagram);
  const auto id = r.read<std::uint16_t>();
  const auto length = r.read<std::uint16_t>();
  if (!id || !length) return vicon::parse_error(0, "datagram shorter than the 4-byte header");
  if (r.remaining() < *length) {
    return vicon::parse_error(kHeaderBytes, "payload of " + std::to_string(*length) +
                                                " bytes announced, " +
                                                std::to_string(r.remaining()) + " received");
  }
  return Packet{*id, datagram.subspan(kHeaderBytes, *length), r.remaining() - *length};
}

std::vector<std::byte> encode_packet(MessageId id, std::span<const std::byte> payload) {
  std::vector<std::byte> out;
  out.reserve(kHeaderBytes + payload.size());
  Writer w(out);
  w.put(static_cast<std::uint16_t>(id));
  w.put(static_cast<std::uint16_t>(payload.size()));
  w.put_bytes(payload);
  return out;
}

std::vector<std::byte> encode_empty(MessageId id) {
  return encode_packet(id, {});
}

Result<ConnectRequest> parse_connect(std::span<const std::byte> payload) {
  Cursor c(payload);
  ConnectRequest req;
  if (!get_sender(c, req.sender, payload)) return c.error();
  if (c.remaining() >= 5) {
    std::uint8_t subscribed = 0;
    c.get(subscribed, "options");
    for (auto& b : req.requested_bitstream) c.get(b, "requested bitstream");
  }
  return finish(c, std::move(req));  // further bytes (samples pad with zeros) are ignored
}

std::vector<std::byte> encode_connect(const ConnectRequest& request) {
  std::vector<std::byte> payload;
  Writer w(payload);
  put_sender(w, request.sender);
  w.put<std::uint8_t>(0);  // subscribed data only: no
  for (const auto b : request.requested_bitstream) w.put(b);
  return encode_packet(MessageId::connect, payload);
}

Result<ServerInfo> parse_server_info(std::span<const std::byte> payload) {
  Cursor c(payload);
  ServerInfo info;
  if (!get_sender(c, info.sender, payload)) return c.error();
  if (info.version().at_least(3, 0) || payload.size() >= kServerInfo3Bytes) {
    info.has_connection_info = true;
    std::uint8_t multicast = 0;
    c.get(info.clock_hz, "clock frequency");
    c.get(info.data_port, "data port");
    c.get(multicast, "multicast flag");
    for (auto& b : info.multicast_group) c.get(b, "multicast group");
    info.multicast = multicast != 0;
  }
  c.at_end("server info");
  return finish(c, std::move(info));
}

std::vector<std::byte> encode_server_info(const ServerInfo& info) {
  std::vector<std::byte> payload;
  Writer w(payload);
  put_sender(w, info.sender);
  if (info.has_connection_info) {
    w.put(info.clock_hz);
    w.put(info.data_port);
    w.put<std::uint8_t>(info.multicast ? 1 : 0);
    for (const auto b : info.multicast_group) w.put(b);
  }
  return encode_packet(MessageId::server_info, payload);
}

Result<std::string> parse_string_payload(std::span<const std::byte> payload) {
  Cursor c(payload);
  std::string text;
  ByteReader r(payload);
  auto s = r.cstring(payload.size());
  if (!s) return vicon::parse_error(0, "string not NUL-terminated");
  text = std::move(*s);
  return text;  // bytes after the NUL (padding) are ignored
}

std::vector<std::byte> encode_string_packet(MessageId id, const std::string& text) {
  std::vector<std::byte> payload;
  Writer w(payload);
  w.put_bytes(std::as_bytes(std::span(text.data(), text.size())));
  w.put<std::uint8_t>(0);
  return encode_packet(id, payload);
}

std::string parse_response_text(std::span<const std::byte> payload) {
  std::string text;
  for (const std::byte b : payload) {
    if (b == std::byte{0}) break;
    text.push_back(static_cast<char>(b));
  }
  return text;
}

std::vector<std::byte> encode_response_text(const std::string& text) {
  return encode_packet(MessageId::response, std::as_bytes(std::span(text.data(), text.size())));
}

Result<std::uint64_t> parse_echo_request(std::span<const std::byte> payload) {
  Cursor c(payload);
  std::uint64_t value = 0;
  c.get(value, "echo value");
  c.at_end("echo request");
  return finish(c, value);
}

std::vector<std::byte> encode_echo_response(const EchoResponse& echo) {
  std::vector<std::byte> payload;
  Writer w(payload);
  w.put(echo.client_value);
  w.put(echo.server_rx_ticks);
  return encode_packet(MessageId::echo_response, payload);
}

Result<ModelDefinitions> parse_model_definitions(std::span<const std::byte> payload, Version v) {
  Cursor c(payload);
  ModelDefinitions out;
  std::size_t count = 0;
  if (!c.get_count(count, "dataset count", kMaxRigidBodies * 4, 4)) return c.error();
  const bool sized = v.at_least(4, 1);
  for (std::size_t i = 0; i < count; ++i) {
    std::int32_t type = 0;
    if (!c.get(type, "dataset type")) break;
    std::int32_t size_bytes = -1;
    if (sized) {
      if (!c.get(size_bytes, "dataset size")) break;
      if (size_bytes < 0 || static_cast<std::size_t>(size_bytes) > c.remaining()) {
        c.fail("dataset size " + std::to_string(size_bytes) + " exceeds the payload");
        break;
      }
    }
    const std::size_t start = c.offset();
    if (sized) {
      // Parse the dataset on its own bytes, then move on by its declared size.
      ModelDefinitions one;
      Cursor inner(payload.subspan(start, static_cast<std::size_t>(size_bytes)));
      bool known = true;
      const bool ok = get_dataset(inner, type, v, one, known);
      if (!known) {
        ++out.unknown_datasets;
      } else if (!ok || inner.remaining() != 0) {
        ++out.size_mismatches;
      }
      if (known && ok) {
        for (auto& rb : one.rigid_bodies) out.rigid_bodies.push_back(std::move(rb));
        for (auto& ms : one.marker_sets) out.marker_sets.push_back(std::move(ms));
        out.other_datasets += one.other_datasets;
      }
      if (!c.skip(static_cast<std::size_t>(size_bytes), "dataset")) break;
      continue;
    }
    bool known = true;
    if (!get_dataset(c, type, v, out, known)) break;
    if (!known) {
      c.fail("unknown dataset type " + std::to_string(type) + " before 4.1 (cannot be skipped)");
      break;
    }
  }
  c.at_end("model definitions");
  return finish(c, std::move(out));
}

std::vector<std::byte> encode_model_definitions(const ModelDefinitions& defs, Version v) {
  std::vector<std::byte> payload;
  Writer w(payload);
  put_count(w, defs.marker_sets.size() + defs.rigid_bodies.size());
  for (const auto& set : defs.marker_sets) {
    w.put<std::int32_t>(0);
    const std::size_t at = begin_size(w, v);
    put_string(w, set.name);
    put_count(w, set.marker_names.size());
    for (const auto& n : set.marker_names) put_string(w, n);
    end_size(w, v, at);
  }
  for (const auto& rb : defs.rigid_bodies) {
    w.put<std::int32_t>(1);
    const std::size_t at = begin_size(w, v);
    put_rigid_body_description(w, rb, v);
    end_size(w, v, at);
  }
  return encode_packet(MessageId::model_def, payload);
}

namespace {

bool get_rigid_body(Cursor& c, RigidBodySample& rb, Version v) {
  c.get(rb.id, "rigid-body id");
  c.get_floats(rb.position, "position");
  c.get_floats(rb.orientation, "orientation");
  if (!v.at_least(3, 0)) {  // §6: per-body marker data before 3.0
    std::size_t n = 0;
    if (!c.get_count(n, "rigid-body marker count", kMaxMarkers, 12)) return false;
    c.skip(n * 12, "rigid-body markers");
    if (v.at_least(2, 0)) c.skip(n * 8, "rigid-body marker ids and sizes");
    if (v.at_least(2, 0)) c.get(rb.mean_error, "mean error");
    if (v.at_least(2, 6)) {
      c.get(rb.params, "rigid-body params");
    } else {
      rb.params = 0x01;  // no tracking-valid bit before 2.6: every body counts as tracked
    }
    return !c.failed();
  }
  c.get(rb.mean_error, "mean error");
  c.get(rb.params, "rigid-body params");
  return !c.failed();
}

void put_rigid_body(Writer& w, const RigidBodySample& rb) {
  w.put(rb.id);
  put_floats(w, rb.position);
  put_floats(w, rb.orientation);
  w.put(rb.mean_error);
  w.put(rb.params);
}

// Reads a 4.1+ section header (count, size) and returns the section's bytes as a sub-cursor span.
bool get_sized_section(Cursor& c, std::span<const std::byte> payload, std::size_t& count,
                       std::span<const std::byte>& bytes, const char* what) {
  std::int32_t size = 0;
  if (!c.get_count(count, what, kMaxMarkers * 4, 0) || !c.get(size, "section size")) return false;
  if (size < 0 || static_cast<std::size_t>(size) > c.remaining()) {
    return c.fail(std::string(what) + " section size " + std::to_string(size) +
                  " exceeds the payload");
  }
  bytes = payload.subspan(c.offset(), static_cast<std::size_t>(size));
  return c.skip(static_cast<std::size_t>(size), what);
}

bool get_marker_sets(Cursor& c, FrameOfData& f) {
  std::size_t n = 0;
  if (!c.get_count(n, "marker-set count", kMaxMarkers, 5)) return false;
  for (std::size_t i = 0; i < n; ++i) {
    MarkerSetSample set;
    std::size_t m = 0;
    if (!c.get_string(set.name, "marker-set name") ||
        !c.get_count(m, "marker count", kMaxMarkers, 12)) {
      return false;
    }
    for (std::size_t k = 0; k < m; ++k) {
      std::array<float, 3> p{};
      if (!c.get_floats(p, "marker")) return false;
      set.markers.push_back(p);
    }
    f.marker_sets.push_back(std::move(set));
  }
  return true;
}

bool get_other_markers(Cursor& c, FrameOfData& f) {
  std::size_t n = 0;
  if (!c.get_count(n, "marker count", kMaxMarkers, 12)) return false;
  for (std::size_t i = 0; i < n; ++i) {
    std::array<float, 3> p{};
    if (!c.get_floats(p, "marker")) return false;
    f.other_markers.push_back(p);
  }
  return true;
}

bool get_rigid_bodies(Cursor& c, FrameOfData& f, Version v) {
  std::size_t n = 0;
  if (!c.get_count(n, "rigid-body count", kMaxRigidBodies, v.at_least(3, 0) ? 38 : 32)) {
    return false;
  }
  for (std::size_t i = 0; i < n; ++i) {
    RigidBodySample rb;
    if (!get_rigid_body(c, rb, v)) return false;
    f.rigid_bodies.push_back(rb);
  }
  return true;
}

bool get_skeletons(Cursor& c, FrameOfData& f, Version v) {
  std::size_t n = 0;
  if (!c.get_count(n, "skeleton count", kMaxRigidBodies, 8)) return false;
  for (std::size_t i = 0; i < n; ++i) {
    std::int32_t id = 0;
    std::size_t bones = 0;
    if (!c.get(id, "skeleton id") || !c.get_count(bones, "bone count", kMaxRigidBodies, 32)) {
      return false;
    }
    for (std::size_t k = 0; k < bones; ++k) {
      RigidBodySample bone;
      if (!get_rigid_body(c, bone, v)) return false;
    }
  }
  f.skeletons = n;
  return true;
}

bool get_assets(Cursor& c, FrameOfData& f, Version v) {
  std::size_t n = 0;
  if (!c.get_count(n, "asset count", kMaxRigidBodies, 12)) return false;
  for (std::size_t i = 0; i < n; ++i) {
    std::int32_t id = 0;
    std::size_t bodies = 0;
    std::size_t markers = 0;
    if (!c.get(id, "asset id") || !c.get_count(bodies, "asset bodies", kMaxRigidBodies, 38)) {
      return false;
    }
    for (std::size_t k = 0; k < bodies; ++k) {
      RigidBodySample rb;
      if (!get_rigid_body(c, rb, v)) return false;
    }
    if (!c.get_count(markers, "asset markers", kMaxMarkers, 26) ||
        !c.skip(markers * 26, "asset markers")) {
      return false;
    }
  }
  f.assets = n;
  return true;
}

bool get_labeled_markers(Cursor& c, FrameOfData& f, Version v) {
  std::size_t n = 0;
  if (!c.get_count(n, "labelled-marker count", kMaxMarkers, 20)) return false;
  for (std::size_t i = 0; i < n; ++i) {
    LabeledMarker m;
    c.get(m.id, "marker id");
    c.get_floats(m.position, "marker position");
    c.get(m.size, "marker size");
    if (v.at_least(2, 6)) c.get(m.params, "marker params");
    if (v.at_least(3, 0)) c.get(m.residual, "marker residual");
    if (c.failed()) return false;
    f.labeled_markers.push_back(m);
  }
  return true;
}

// Force plates and devices: id, channels, each with frames of f32.
bool get_analog(Cursor& c, std::size_t& out, const char* what) {
  std::size_t n = 0;
  if (!c.get_count(n, what, kMaxMarkers, 8)) return false;
  for (std::size_t i = 0; i < n; ++i) {
    std::int32_t id = 0;
    std::size_t channels = 0;
    if (!c.get(id, "analog id") || !c.get_count(channels, "channel count", kMaxMarkers, 4)) {
      return false;
    }
    for (std::size_t k = 0; k < channels; ++k) {
      std::size_t frames = 0;
      if (!c.get_count(frames, "analog frame count", kMaxMarkers, 4) ||
          !c.skip(frames * 4, "analog samples")) {
        return false;
      }
    }
  }
  out = n;
  return true;
}

// One section of a 4.1+ frame: parsed on its own bytes (which it must fill exactly).
template <typename Parse>
bool sized_section(Cursor& c, std::span<const std::byte> payload, const char* what, Parse parse) {
  std::size_t count = 0;
  std::span<const std::byte> bytes;
  const std::size_t at = c.offset();
  if (!get_sized_section(c, payload, count, bytes, what)) return false;
  // The section's parser expects the count first: hand it a view that starts with the count.
  std::vector<std::byte> with_count(payload.begin() + static_cast<std::ptrdiff_t>(at),
                                    payload.begin() + static_cast<std::ptrdiff_t>(at) + 4);
  with_count.insert(with_count.end(), bytes.begin(), bytes.end());
  Cursor inner(with_count);
  if (!parse(inner) || !inner.at_end(what)) {
    return c.fail(std::string(what) + " section: " + inner.error().reason);
  }
  return true;
}

}  // namespace

Result<FrameOfData> parse_frame(std::span<const std::byte> payload, Version v) {
  Cursor c(payload);
  FrameOfData f;
  if (!supported(v)) {
    return vicon::parse_error(0, "unsupported bitstream version " + v.to_string());
  }
  c.get(f.frame_number, "frame number");
  if (v.at_least(4, 1)) {
    sized_section(c, payload, "marker sets", [&](Cursor& in) { return get_marker_sets(in, f); }) &&
        sized_section(c, payload, "other markers",
                      [&](Cursor& in) { return get_other_markers(in, f); }) &&
        sized_section(c, payload, "rigid bodies",
                      [&](Cursor& in) { return get_rigid_bodies(in, f, v); }) &&
        sized_section(c, payload, "skeletons",
                      [&](Cursor& in) { return get_skeletons(in, f, v); }) &&
        sized_section(c, payload, "assets", [&](Cursor& in) { return get_assets(in, f, v); }) &&
        sized_section(c, payload, "labelled markers",
                      [&](Cursor& in) { return get_labeled_markers(in, f, v); }) &&
        sized_section(c, payload, "force plates",
                      [&](Cursor& in) { return get_analog(in, f.force_plates, "force plates"); }) &&
        sized_section(c, payload, "devices",
                      [&](Cursor& in) { return get_analog(in, f.devices, "devices"); });
  } else {
    get_marker_sets(c, f) && get_other_markers(c, f) && get_rigid_bodies(c, f, v) &&
        (!v.at_least(2, 1) || get_skeletons(c, f, v)) &&
        (!v.at_least(2, 3) || get_labeled_markers(c, f, v)) &&
        (!v.at_least(2, 9) || get_analog(c, f.force_plates, "force plates")) &&
        (!v.at_least(2, 11) || get_analog(c, f.devices, "devices"));
  }
  if (!v.at_least(3, 0)) c.get(f.software_latency_s, "software latency");
  c.get(f.timecode, "timecode");
  c.get(f.timecode_subframe, "timecode subframe");
  // natnet.md §4.3 lists the timestamp and the params for every version; the NatNet 2.5 frames of
  // Motive 1.5 (tests/data/natnet/natnet_decode) have neither: both from 2.6 (f32 timestamp in
  // 2.6, f64 from 2.7), as natnet-decode reads them.
  if (v.at_least(2, 7)) {
    c.get(f.timestamp_s, "timestamp");
  } else if (v.at_least(2, 6)) {
    float ts = 0.0f;
    if (c.get(ts, "timestamp")) f.timestamp_s = ts;
  }
  if (v.at_least(3, 0)) {
    c.get(f.mid_exposure_ticks, "mid-exposure timestamp");
    c.get(f.data_received_ticks, "data-received timestamp");
    c.get(f.transmit_ticks, "transmit timestamp");
  }
  if (v.at_least(4, 1)) {
    c.get(f.precision_s, "precision timestamp");
    c.get(f.precision_fraction, "precision fraction");
  }
  std::int16_t params = 0;
  if (v.at_least(2, 6)) c.get(params, "frame params");
  f.params = static_cast<std::uint16_t>(params);
  std::int32_t end_tag = 0;
  c.get(end_tag, "end-of-data tag");
  c.at_end("frame");
  return finish(c, std::move(f));
}

std::vector<std::byte> encode_frame(const FrameOfData& f, Version v) {
  std::vector<std::byte> payload;
  payload.reserve(128 + f.rigid_bodies.size() * kRigidBodyItemBytes +
                  f.labeled_markers.size() * kLabeledMarkerBytes);
  Writer w(payload);
  w.put(f.frame_number);
  put_count(w, f.marker_sets.size());
  std::size_t at = begin_size(w, v);
  for (const auto& set : f.marker_sets) {
    put_string(w, set.name);
    put_count(w, set.markers.size());
    for (const auto& p : set.markers) put_floats(w, p);
  }
  end_size(w, v, at);
  put_count(w, f.other_markers.size());
  at = begin_size(w, v);
  for (const auto& p : f.other_markers) put_floats(w, p);
  end_size(w, v, at);
  put_count(w, f.rigid_bodies.size());
  at = begin_size(w, v);
  for (const auto& rb : f.rigid_bodies) put_rigid_body(w, rb);
  end_size(w, v, at);
  const int empty_sections = v.at_least(4, 1) ? 2 : 1;  // skeletons (+ assets)
  for (int i = 0; i < empty_sections; ++i) {
    put_count(w, 0);
    end_size(w, v, begin_size(w, v));
  }
  put_count(w, f.labeled_markers.size());
  at = begin_size(w, v);
  for (const auto& m : f.labeled_markers) {
    w.put(m.id);
    put_floats(w, m.position);
    w.put(m.size);
    w.put(m.params);
    w.put(m.residual);
  }
  end_size(w, v, at);
  for (int i = 0; i < 2; ++i) {  // force plates, devices
    put_count(w, 0);
    end_size(w, v, begin_size(w, v));
  }
  w.put(f.timecode);
  w.put(f.timecode_subframe);
  w.put(f.timestamp_s);
  w.put(f.mid_exposure_ticks);
  w.put(f.data_received_ticks);
  w.put(f.transmit_ticks);
  if (v.at_least(4, 1)) {
    w.put(f.precision_s);
    w.put(f.precision_fraction);
  }
  w.put(static_cast<std::int16_t>(f.params));
  w.put<std::int32_t>(0);
  return encode_packet(MessageId::frame_of_data, payload);
}

}  // namespace mocaplink::wire::natnet
