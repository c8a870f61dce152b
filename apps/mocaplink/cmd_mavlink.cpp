// `mocaplink mavlink encode|decode|listen` (DESIGN.md "Command line"; docs/mavlink.md).
//
// clang-format off
//   encode [FILE|-]              golden-vector JSON (one object or {"vectors":[...]}) → "<id> <hex>"
//   decode [--key HEX] [FILE|-]  hex frames (one or several per line) → one JSON object per frame
//   listen URL                   bind udp://host:port, print each received frame as decode does,
//                                counters on stderr every few seconds; Ctrl-C exits 0
// clang-format on
// Bad input: one message per problem on stderr, exit 1. The JSON codec is mocaplink::mavlink_json.
#include <array>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <iterator>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <asio/steady_timer.hpp>

#include "commands.hpp"
#include "mocaplink/io/signals.hpp"
#include "mocaplink/io/udp_bind.hpp"
#include "mocaplink/mavlink/frame.hpp"
#include "mocaplink/mavlink/stream_parser.hpp"
#include "mocaplink/mavlink_json/mavlink_json.hpp"
#include "mocaplink/text/hex.hpp"

namespace mocaplink::app {
namespace {

namespace mav = mocaplink::mavlink;

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

int run_encode(const std::string& path) {
  std::string out;
  for (const auto& v : mavlink_json::encode_vectors_text(read_input(path))) {
    out += v.id + " " + text::to_hex(v.frame.bytes()) + "\n";
  }
  std::fwrite(out.data(), 1, out.size(), stdout);
  return 0;
}

// ---- decode ----------------------------------------------------------------------------------

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
    if (words.size() > 1 && !text::is_hex(words[0])) words.erase(words.begin());
    std::string hex;
    for (const auto& w : words) hex += w;
    const auto report = [&](const std::string& what) {
      std::fprintf(stderr, "mocaplink: line %zu: %s\n", line_no, what.c_str());
      ++errors;
    };
    const auto decoded = text::from_hex(hex);
    if (!decoded) {
      report("not an even number of hex digits");
      continue;
    }
    const std::vector<std::uint8_t>& bytes = *decoded;
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
        out += mavlink_json::frame_to_json(*frame, key ? &*key : nullptr);
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
            parser.feed_datagram(
                std::span<const std::uint8_t>(datagram.data(), n), 0,
                [&](const mav::FrameView& f) { out += mavlink_json::frame_to_json(f, nullptr); });
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
  io::StopSignals stop(loop, [&](std::string_view, int) { loop.stop(); });
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
  } catch (const mavlink_json::InputError& e) {
    std::fprintf(stderr, "mocaplink: %s\n", e.what());
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
