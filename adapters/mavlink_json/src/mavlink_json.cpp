#include "mocaplink/mavlink_json/mavlink_json.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <type_traits>

#include <fmt/format.h>

#include "mocaplink/text/hex.hpp"

namespace mocaplink::mavlink_json {
namespace {

namespace mav = mocaplink::mavlink;
using nlohmann::json;
using text::to_hex;

// Char arrays are strings on the JSON side (XML char[N], NUL-padded).
template <typename T>
constexpr bool kIsCharArray = false;
template <std::size_t N>
constexpr bool kIsCharArray<std::array<char, N>> = true;

// ---- JSON → fields ---------------------------------------------------------------------------

template <typename T>
T integer_from(const json& j, const std::string& where) {
  // 64-bit values arrive as decimal strings (JSON numbers lose precision beyond 2^53).
  if (j.is_string()) {
    const auto& s = j.get_ref<const std::string&>();
    T v{};
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc{} || end != s.data() + s.size()) {
      throw InputError(where + ": '" + s + "' is not an integer in range");
    }
    return v;
  }
  if (j.is_number_unsigned()) {
    const auto v = j.get<std::uint64_t>();
    if (v <= static_cast<std::uint64_t>(std::numeric_limits<T>::max())) return static_cast<T>(v);
  } else if (j.is_number_integer()) {
    const auto v = j.get<std::int64_t>();
    if (std::is_signed_v<T>
            ? v >= static_cast<std::int64_t>(std::numeric_limits<T>::min()) &&
                  v <= static_cast<std::int64_t>(std::numeric_limits<T>::max())
            : v >= 0 && static_cast<std::uint64_t>(v) <=
                            static_cast<std::uint64_t>(std::numeric_limits<T>::max())) {
      return static_cast<T>(v);
    }
  } else {
    throw InputError(where + ": expected an integer, got " + j.dump());
  }
  throw InputError(where + ": " + j.dump() + " out of range");
}

float float_from(const json& j, const std::string& where) {
  if (j.is_number()) return static_cast<float>(j.get<double>());
  if (j.is_string()) {
    const auto& s = j.get_ref<const std::string&>();
    if (s == "NaN") return std::numeric_limits<float>::quiet_NaN();
    if (s == "Infinity") return std::numeric_limits<float>::infinity();
    if (s == "-Infinity") return -std::numeric_limits<float>::infinity();
    if (s == "-0") return -0.0F;
  }
  throw InputError(where +
                   ": expected a number, \"NaN\", \"Infinity\", \"-Infinity\" or \"-0\", got " +
                   j.dump());
}

template <typename T>
void scalar_from(const json& j, T& out, const std::string& where) {
  if constexpr (std::is_same_v<T, float>) {
    out = float_from(j, where);
  } else if constexpr (std::is_same_v<T, double>) {
    out = static_cast<double>(float_from(j, where));
  } else {
    out = integer_from<T>(j, where);
  }
}

template <typename T>
void field_from(const json& j, T& field, const std::string& where) {
  if constexpr (kIsCharArray<T>) {
    if (!j.is_string() || j.get_ref<const std::string&>().size() > field.size()) {
      throw InputError(where + ": expected a string of at most " + std::to_string(field.size()) +
                       " characters");
    }
    field.fill('\0');
    const auto& s = j.get_ref<const std::string&>();
    std::copy(s.begin(), s.end(), field.begin());
  } else if constexpr (requires { std::tuple_size<T>::value; }) {
    if (!j.is_array() || j.size() != field.size()) {
      throw InputError(where + ": expected an array of " + std::to_string(field.size()));
    }
    for (std::size_t i = 0; i < field.size(); ++i) {
      scalar_from(j[i], field[i], where + "[" + std::to_string(i) + "]");
    }
  } else {
    scalar_from(j, field, where);
  }
}

}  // namespace

mavlink::Message message_from_json(const json& v, const std::string& where) {
  if (!v.is_object() || !v.contains("msg") || !v["msg"].is_string()) {
    throw InputError(where + ": expected an object with \"msg\" (message name)");
  }
  const auto name = v["msg"].get<std::string>();
  auto msg = mav::make_message(name);
  if (!msg) throw InputError(where + ": unknown message '" + name + "'");
  const json fields = v.value("fields", json::object());
  if (!fields.is_object()) throw InputError(where + ": \"fields\" must be an object");
  std::size_t used = 0;
  std::visit(
      [&](auto& m) {
        mav::for_each_field(m, [&](const mav::FieldInfo& info, auto& field) {
          const auto it = fields.find(std::string(info.name));
          if (it == fields.end()) return;  // absent fields are 0
          ++used;
          field_from(*it, field, where + "." + std::string(info.name));
        });
      },
      *msg);
  if (used != fields.size()) {
    for (const auto& [key, value] : fields.items()) {
      const auto& infos = mav::message_info(*msg).fields;
      if (std::none_of(infos.begin(), infos.end(), [&](const auto& f) { return f.name == key; })) {
        throw InputError(where + ": " + name + " has no field '" + key + "'");
      }
    }
  }
  return *msg;
}

std::vector<EncodedVector> encode_vectors(const json& document) {
  const bool many = document.is_object() && document.contains("vectors");
  const json vectors = many ? document["vectors"] : json::array({document});
  if (!vectors.is_array()) throw InputError("\"vectors\" must be an array");
  std::optional<mav::SigningKey> key;
  if (document.is_object() && document.contains("key_hex")) {
    key = mav::SigningKey::from_hex(document.value("key_hex", ""));
    if (!key) throw InputError("key_hex: expected 64 hex digits");
  }
  std::vector<EncodedVector> out;
  for (std::size_t i = 0; i < vectors.size(); ++i) {
    const json& v = vectors[i];
    const std::string where = many ? "vectors[" + std::to_string(i) + "]" : "input";
    const mav::Message msg = message_from_json(v, where);
    mav::FrameHeader header;
    header.seq = integer_from<std::uint8_t>(v.value("seq", json(0)), where + ".seq");
    header.sysid = integer_from<std::uint8_t>(v.value("sysid", json(1)), where + ".sysid");
    header.compid = integer_from<std::uint8_t>(v.value("compid", json(1)), where + ".compid");
    std::optional<mav::SignParams> sign;
    if (v.contains("sign")) {
      const json& s = v["sign"];
      if (!key) throw InputError(where + ".sign: no key_hex in the input");
      sign = mav::SignParams{
          &*key, integer_from<std::uint8_t>(s.value("link_id", json(0)), where + ".sign.link_id"),
          integer_from<std::uint64_t>(s.value("timestamp", json(0)), where + ".sign.timestamp")};
      if (sign->timestamp_10us > mav::kMaxSigningTimestamp) {
        throw InputError(where + ".sign.timestamp: exceeds 48 bits");
      }
    }
    std::string id = v.value("id", "");
    if (id.empty()) {
      id = std::string(mav::message_info(msg).name);
      for (auto& c : id) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
    out.push_back({std::move(id), mav::encode(msg, header, sign ? &*sign : nullptr)});
  }
  return out;
}

std::vector<EncodedVector> encode_vectors_text(std::string_view document_text) {
  json document;
  try {
    document = json::parse(document_text);
  } catch (const json::parse_error& e) {
    throw InputError("invalid JSON: " + std::string(e.what()));
  }
  return encode_vectors(document);
}

// ---- frame → JSON ----------------------------------------------------------------------------

namespace {

void append_float(std::string& out, double v, bool is_float) {
  if (std::isnan(v)) {
    out += "\"NaN\"";
  } else if (std::isinf(v)) {
    out += v > 0 ? "\"Infinity\"" : "\"-Infinity\"";
  } else if (v == 0 && std::signbit(v)) {
    out += "\"-0\"";
  } else {
    // Shortest text that reads back to the same float32 (or double).
    std::array<char, 64> buf{};
    const auto res = is_float
                         ? std::to_chars(buf.data(), buf.data() + buf.size(), static_cast<float>(v))
                         : std::to_chars(buf.data(), buf.data() + buf.size(), v);
    out.append(buf.data(), res.ptr);
  }
}

template <typename T>
void append_scalar(std::string& out, T v) {
  if constexpr (std::is_floating_point_v<T>) {
    append_float(out, static_cast<double>(v), std::is_same_v<T, float>);
  } else if constexpr (sizeof(T) == 8) {
    out += fmt::format("\"{}\"", v);  // 64-bit integers as decimal strings
  } else {
    out += fmt::format("{}", +v);
  }
}

template <typename T>
void append_field(std::string& out, const T& field) {
  if constexpr (kIsCharArray<T>) {
    std::string s(field.data(), field.size());
    s.resize(std::min(s.size(), s.find('\0')));
    out += json(s).dump(-1, ' ', false, json::error_handler_t::replace);
  } else if constexpr (requires { std::tuple_size<T>::value; }) {
    out += '[';
    for (std::size_t i = 0; i < field.size(); ++i) {
      if (i > 0) out += ',';
      append_scalar(out, field[i]);
    }
    out += ']';
  } else {
    append_scalar(out, field);
  }
}

}  // namespace

std::string frame_to_json(const mavlink::FrameView& f, const mavlink::SigningKey* key) {
  std::string out = fmt::format(
      "{{\"msgid\":{},\"name\":{},\"version\":{},\"seq\":{},\"sysid\":{},\"compid\":{},\"len\":{},"
      "\"incompat_flags\":{},\"compat_flags\":{},\"crc\":{},\"fields\":",
      f.msgid, f.info != nullptr ? fmt::format("\"{}\"", f.info->name) : std::string("null"),
      f.version, f.seq, f.sysid, f.compid, f.len, f.incompat_flags, f.compat_flags, f.crc);
  if (const auto msg = mav::decode_message(f)) {
    out += '{';
    bool first = true;
    std::visit(
        [&](const auto& m) {
          mav::for_each_field(m, [&](const mav::FieldInfo& info, const auto& field) {
            out += fmt::format("{}\"{}\":", first ? "" : ",", info.name);
            first = false;
            append_field(out, field);
          });
        },
        *msg);
    out += '}';
  } else {
    out += fmt::format("null,\"payload\":\"{}\"", to_hex(f.payload));
  }
  if (f.signature) {
    out += fmt::format(
        ",\"link_id\":{},\"sig_timestamp\":\"{}\",\"signature\":\"{}\",\"signature_valid\":{}",
        f.signature->link_id, f.signature->timestamp_10us, to_hex(f.signature->signature),
        key != nullptr && key->verify(f.bytes) ? "true" : "false");
  }
  out += "}\n";
  return out;
}

}  // namespace mocaplink::mavlink_json
