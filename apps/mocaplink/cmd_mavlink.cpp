// `mocaplink mavlink encode|decode|listen` (DESIGN.md "Command line"; docs/mavlink.md).
//
//   encode [FILE|-]              golden-vector JSON (one object or {"vectors":[...]}) → "<id>
//   <hex>" decode [--key HEX] [FILE|-]  hex frames (one or several per line) → one JSON object per
//   frame listen URL                   bind udp://host:port, print each received frame as decode
//   does,
//                                counters on stderr every few seconds; Ctrl-C exits 0
// Bad input: one message per problem on stderr, exit 1.
#include <array>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <iterator>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include <fmt/format.h>
#include <asio/steady_timer.hpp>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "mocaplink/io/signals.hpp"
#include "mocaplink/io/udp_bind.hpp"
#include "mocaplink/mavlink/frame.hpp"
#include "mocaplink/mavlink/stream_parser.hpp"

namespace mocaplink::app {
namespace {

namespace mav = mocaplink::mavlink;
using nlohmann::json;

// Char arrays are strings on the JSON side (XML char[N], NUL-padded).
template <typename T>
constexpr bool kIsCharArray = false;
template <std::size_t N>
constexpr bool kIsCharArray<std::array<char, N>> = true;

struct InputError {
  std::string message;
};

std::string read_input(const std::string& path) {
  if (path == "-") {
    return {std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>()};
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError{"cannot open '" + path + "'"};
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// ---- JSON → fields ---------------------------------------------------------------------------

template <typename T>
T integer_from(const json& j, const std::string& where) {
  // 64-bit values arrive as decimal strings (JSON numbers lose precision beyond 2^53).
  if (j.is_string()) {
    const auto& s = j.get_ref<const std::string&>();
    T v{};
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc{} || end != s.data() + s.size()) {
      throw InputError{where + ": '" + s + "' is not an integer in range"};
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
    throw InputError{where + ": expected an integer, got " + j.dump()};
  }
  throw InputError{where + ": " + j.dump() + " out of range"};
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
  throw InputError{where +
                   ": expected a number, \"NaN\", \"Infinity\", \"-Infinity\" or \"-0\", got " +
                   j.dump()};
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
      throw InputError{where + ": expected a string of at most " + std::to_string(field.size()) +
                       " characters"};
    }
    field.fill('\0');
    const auto& s = j.get_ref<const std::string&>();
    std::copy(s.begin(), s.end(), field.begin());
  } else if constexpr (requires { std::tuple_size<T>::value; }) {
    if (!j.is_array() || j.size() != field.size()) {
      throw InputError{where + ": expected an array of " + std::to_string(field.size())};
    }
    for (std::size_t i = 0; i < field.size(); ++i) {
      scalar_from(j[i], field[i], where + "[" + std::to_string(i) + "]");
    }
  } else {
    scalar_from(j, field, where);
  }
}

mav::Message message_from(const json& v, const std::string& where) {
  if (!v.is_object() || !v.contains("msg") || !v["msg"].is_string()) {
    throw InputError{where + ": expected an object with \"msg\" (message name)"};
  }
  const auto name = v["msg"].get<std::string>();
  auto msg = mav::make_message(name);
  if (!msg) throw InputError{where + ": unknown message '" + name + "'"};
  const json fields = v.value("fields", json::object());
  if (!fields.is_object()) throw InputError{where + ": \"fields\" must be an object"};
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
        throw InputError{where + ": " + name + " has no field '" + key + "'"};
      }
    }
  }
  return *msg;
}

std::string to_hex(std::span<const std::uint8_t> bytes) {
  std::string out;
  out.reserve(bytes.size() * 2);
  for (const auto b : bytes) out += fmt::format("{:02x}", b);
  return out;
}

int run_encode(const std::string& path) {
  const std::string text = read_input(path);
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    throw InputError{"invalid JSON: " + std::string(e.what())};
  }
  const bool many = doc.is_object() && doc.contains("vectors");
  const json vectors = many ? doc["vectors"] : json::array({doc});
  if (!vectors.is_array()) throw InputError{"\"vectors\" must be an array"};
  std::optional<mav::SigningKey> doc_key;
  if (doc.is_object() && doc.contains("key_hex")) {
    doc_key = mav::SigningKey::from_hex(doc.value("key_hex", ""));
    if (!doc_key) throw InputError{"key_hex: expected 64 hex digits"};
  }
  std::string out;
  for (std::size_t i = 0; i < vectors.size(); ++i) {
    const json& v = vectors[i];
    const std::string where = many ? "vectors[" + std::to_string(i) + "]" : "input";
    const mav::Message msg = message_from(v, where);
    mav::FrameHeader header;
    header.seq = integer_from<std::uint8_t>(v.value("seq", json(0)), where + ".seq");
    header.sysid = integer_from<std::uint8_t>(v.value("sysid", json(1)), where + ".sysid");
    header.compid = integer_from<std::uint8_t>(v.value("compid", json(1)), where + ".compid");
    std::optional<mav::SignParams> sign;
    if (v.contains("sign")) {
      const json& s = v["sign"];
      if (!doc_key) throw InputError{where + ".sign: no key_hex in the input"};
      sign = mav::SignParams{
          &*doc_key,
          integer_from<std::uint8_t>(s.value("link_id", json(0)), where + ".sign.link_id"),
          integer_from<std::uint64_t>(s.value("timestamp", json(0)), where + ".sign.timestamp")};
      if (sign->timestamp_10us > mav::kMaxSigningTimestamp) {
        throw InputError{where + ".sign.timestamp: exceeds 48 bits"};
      }
    }
    const mav::Frame frame = mav::encode(msg, header, sign ? &*sign : nullptr);
    std::string id = v.value("id", "");
    if (id.empty()) {
      id = std::string(mav::message_info(msg).name);
      for (auto& c : id) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
    out += id + " " + to_hex(frame.bytes()) + "\n";
  }
  std::fwrite(out.data(), 1, out.size(), stdout);
  return 0;
}

// ---- frame → JSON ----------------------------------------------------------------------------

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

std::string frame_json(const mav::FrameView& f, const mav::SigningKey* key) {
  std::string out = fmt::format(
      "{{\"msgid\":{},\"name\":{},\"version\":{},\"seq\":{},\"sysid\":{},\"compid\":{},\"len\":{},"
      "\"incompat_flags\":{},\"compat_flags\":{},\"crc\":{},\"fields\":",
      f.msgid, f.info ? "\"" + std::string(f.info->name) + "\"" : std::string("null"), f.version,
      f.seq, f.sysid, f.compid, f.len, f.incompat_flags, f.compat_flags, f.crc);
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

// ---- decode ----------------------------------------------------------------------------------

bool is_hex(std::string_view s) {
  return std::all_of(s.begin(), s.end(),
                     [](char c) { return std::isxdigit(static_cast<unsigned char>(c)); });
}

int run_decode(const std::string& path, const std::string& key_hex) {
  std::optional<mav::SigningKey> key;
  if (!key_hex.empty()) {
    key = mav::SigningKey::from_hex(key_hex);
    if (!key) throw InputError{"--key: expected 64 hex digits"};
  }
  std::istringstream in(read_input(path));
  std::string line;
  std::size_t line_no = 0;
  int errors = 0;
  std::string out;
  while (std::getline(in, line)) {
    ++line_no;
    std::istringstream tokens(line);
    std::vector<std::string> words{std::istream_iterator<std::string>(tokens), {}};
    if (words.empty() || words[0].starts_with('#')) continue;
    // "<id> <hex>" lines (encode's output) are accepted: a first word that is not hex is a label.
    if (words.size() > 1 && !is_hex(words[0])) words.erase(words.begin());
    std::string hex;
    for (const auto& w : words) hex += w;
    const auto report = [&](const std::string& what) {
      std::fprintf(stderr, "mocaplink: line %zu: %s\n", line_no, what.c_str());
      ++errors;
    };
    if (!is_hex(hex) || hex.size() % 2 != 0) {
      report("not an even number of hex digits");
      continue;
    }
    std::vector<std::uint8_t> bytes(hex.size() / 2);
    for (std::size_t i = 0; i < bytes.size(); ++i) {
      bytes[i] = static_cast<std::uint8_t>(std::stoul(hex.substr(2 * i, 2), nullptr, 16));
    }
    for (std::size_t pos = 0; pos < bytes.size();) {
      const auto rest = std::span<const std::uint8_t>(bytes).subspan(pos);
      const auto size = mav::frame_size(rest);
      if (!size || *size > rest.size()) {
        report(fmt::format("byte {}: truncated frame", pos));
        break;
      }
      if (*size == 0) {
        report(fmt::format("byte {}: 0x{:02x} is not a MAVLink start byte (fd/fe)", pos, rest[0]));
        break;
      }
      const auto frame = mav::parse_frame(rest.first(*size));
      if (!frame) {
        report(fmt::format("byte {}: {}", pos + frame.error_offset(), to_string(frame.error())));
      } else {
        out += frame_json(*frame, key ? &*key : nullptr);
      }
      pos += *size;
    }
  }
  std::fwrite(out.data(), 1, out.size(), stdout);
  return errors == 0 ? 0 : 1;
}

// ---- listen ----------------------------------------------------------------------------------

int run_listen(const std::string& url_text) {
  std::string error;
  const auto url = io::parse_udp_url(url_text, error);
  if (!url) throw InputError{error};
  asio::io_context loop;
  auto socket = io::bind_udp(loop, *url, error);
  if (!socket) {
    std::fprintf(stderr, "mocaplink: %s\n", error.c_str());
    return 2;
  }
  const auto local = socket->local_endpoint();
  std::fprintf(stderr, "mocaplink: listening on udp://%s:%u\n", local.address().to_string().c_str(),
               static_cast<unsigned>(local.port()));
  std::fflush(stderr);
  mav::StreamParser parser;  // no signing policy: an inspector shows everything
  std::array<std::uint8_t, 65536> datagram{};
  asio::ip::udp::endpoint sender;
  std::function<void()> receive = [&] {
    socket->async_receive_from(
        asio::buffer(datagram), sender, [&](std::error_code ec, std::size_t n) {
          if (ec == asio::error::operation_aborted) return;
          if (!ec) {
            std::string out;
            parser.feed_datagram(std::span<const std::uint8_t>(datagram.data(), n), 0,
                                 [&](const mav::FrameView& f) { out += frame_json(f, nullptr); });
            std::fwrite(out.data(), 1, out.size(), stdout);
            std::fflush(stdout);
          }
          receive();  // ICMP errors (ec set) never stop the listener
        });
  };
  receive();
  asio::steady_timer timer(loop);
  std::function<void()> tick = [&] {
    timer.expires_after(std::chrono::seconds(5));
    timer.async_wait([&](std::error_code ec) {
      if (ec) return;
      std::string line = "mocaplink: counters";
      parser.counters().for_each([&](std::string_view name, std::uint64_t value) {
        line += fmt::format(" {}={}", name, value);
      });
      std::fprintf(stderr, "%s\n", line.c_str());
      tick();
    });
  };
  tick();
  io::StopSignals stop(loop, [&](int, int) { loop.stop(); });
  loop.run();
  return 0;
}

template <typename F>
void run_guarded(ExitCode& exit_code, F&& body) {
  try {
    exit_code.value = body();
  } catch (const InputError& e) {
    std::fprintf(stderr, "mocaplink: %s\n", e.message.c_str());
    exit_code.value = 1;
  }
}

}  // namespace

void add_mavlink_commands(CLI::App& app, ExitCode& exit_code) {
  auto* mavlink = app.add_subcommand("mavlink", "MAVLink tools: encode, decode, listen");
  mavlink->require_subcommand(1);
  // Option storage must outlive parsing; the callbacks own it.
  struct Options {
    std::string encode_path = "-";
    std::string decode_path = "-";
    std::string decode_key;
    std::string listen_url;
  };
  const auto opts = std::make_shared<Options>();

  auto* encode = mavlink->add_subcommand(
      "encode", "Golden-vector JSON (one object or {\"vectors\":[...]}) to '<id> <hex>' lines");
  encode->add_option("FILE", opts->encode_path, "input file, or - for stdin")
      ->capture_default_str();
  encode->callback([&exit_code, opts] {
    run_guarded(exit_code, [&] { return run_encode(opts->encode_path); });
  });

  auto* decode = mavlink->add_subcommand("decode", "Hex frames to one JSON object per frame");
  decode->add_option("--key", opts->decode_key, "signing key (64 hex digits) to check signatures");
  decode->add_option("FILE", opts->decode_path, "input file, or - for stdin")
      ->capture_default_str();
  decode->callback([&exit_code, opts] {
    run_guarded(exit_code, [&] { return run_decode(opts->decode_path, opts->decode_key); });
  });

  auto* listen =
      mavlink->add_subcommand("listen", "Print decoded MAVLink traffic received on a UDP port");
  listen->add_option("URL", opts->listen_url, "udp://host:port to bind (port 0: any free port)")
      ->required();
  listen->callback(
      [&exit_code, opts] { run_guarded(exit_code, [&] { return run_listen(opts->listen_url); }); });
}

}  // namespace mocaplink::app
