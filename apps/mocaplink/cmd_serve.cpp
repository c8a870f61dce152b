// `mocaplink serve --protocol P --from sim|replay:FILE [--listen ADDR] [--rate HZ] [--to HOST:PORT]
// [--set KEY=VALUE]...` (DESIGN.md "Command line"): emulate a mocap server. P is any registered
// source with an emulator (SourceDescriptor::make_emulator); others exit 1 with "not supported
// yet".
//
// --from sim            the built-in simulator (Body1, Body2, Body3; sim:// defaults) at --rate
// --from sim://?KEYS    the same with sim:// keys (bodies, noise_mm, seed, occlude, …); rate_hz
//                       is always --rate
// --from replay:FILE    a mocaplink recording, with its recorded timing (replay://FILE?KEYS too)
// --from URL            any other source URL (the source registry opens it), relayed as it comes
// --listen ADDR         HOST:PORT, :PORT or HOST (IPv6 as [ADDR]:PORT); default 0.0.0.0 and the
//                       protocol's port (vicon: 801)
// --rate HZ             frame rate of the sim and of StreamInfo (replay: used when a frame does
//                       not say); default 100
// --to HOST:PORT        where a protocol that sends datagrams unasked sends them (required for
//                       those, refused by the others: nothing is sent that was not asked for)
// --set KEY=VALUE       a setting of the protocol's emulator (docs/sources.md lists them per
//                       protocol); repeatable, each key once
// --stall AT_S:FOR_MS   a network stall, for tests of what a client does with late frames: the
//                       frames of FOR_MS from AT_S seconds after start are held back, then
//                       published at once with the first frame after it (a burst, as a TCP
//                       connection delivers its backlog); every protocol
// On start one line goes to stdout: "serving P on HOST:PORT from SOURCE at RATE Hz" (PORT is
// the bound one, so --listen 127.0.0.1:0 works for scripts; "to HOST:PORT" for a protocol that
// sends to --to). Runs until SIGINT/SIGTERM (exit 0).
// Exit 1: bad arguments; exit 2: cannot listen or cannot read the recording.
#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include <asio/io_context.hpp>

#include "commands.hpp"
#include "mocaplink/config/url.hpp"
#include "mocaplink/io/signals.hpp"
#include "mocaplink/sources/registry.hpp"
#include "mocaplink/text/did_you_mean.hpp"

namespace mocaplink::app {
namespace {

struct ServeArgs {
  std::string protocol;
  std::string from;
  std::optional<std::string> listen;
  double rate_hz = 100.0;
  std::optional<std::string> to;
  std::vector<std::string> settings;
  std::optional<std::string> stall;
};

/// --stall AT_S:FOR_MS (see the file comment).
struct Stall {
  std::chrono::nanoseconds at{};
  std::chrono::nanoseconds length{};
};

/// "AT_S:FOR_MS" with 0 ≤ AT_S ≤ 3600 and 0 < FOR_MS ≤ 60000; nullopt otherwise.
std::optional<Stall> parse_stall(const std::string& text) {
  const auto colon = text.find(':');
  if (colon == std::string::npos) return std::nullopt;
  const auto number = [](std::string_view part) -> std::optional<double> {
    double value = 0.0;
    const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), value);
    if (part.empty() || ec != std::errc{} || end != part.data() + part.size()) return std::nullopt;
    return value;
  };
  const auto at = number(std::string_view(text).substr(0, colon));
  const auto length = number(std::string_view(text).substr(colon + 1));
  if (!at || !length || !(*at >= 0.0 && *at <= 3600.0) || !(*length > 0.0 && *length <= 60000.0)) {
    return std::nullopt;
  }
  return Stall{
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::duration<double>(*at)),
      std::chrono::duration_cast<std::chrono::nanoseconds>(
          std::chrono::duration<double, std::milli>(*length))};
}

/// Holds the frames published during a Stall and lets them out in one burst after it. Called on
/// the source's thread only.
class StallingPublisher {
 public:
  StallingPublisher(sources::Emulator& server, std::optional<Stall> stall)
      : server_(server), stall_(stall) {}

  void publish(core::MocapFrame frame) {
    if (stall_) {
      const auto elapsed = std::chrono::steady_clock::now() - start_;
      if (elapsed >= stall_->at && elapsed < stall_->at + stall_->length) {
        held_.push_back(std::move(frame));
        return;
      }
      for (auto& held : held_) server_.publish(std::move(held));
      held_.clear();
    }
    server_.publish(std::move(frame));
  }

 private:
  sources::Emulator& server_;
  std::optional<Stall> stall_;
  std::vector<core::MocapFrame> held_;
  const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// `--from sim` and `replay:FILE` are shorthands for sim:// and replay://FILE.
std::string from_url(const std::string& from) {
  if (from == "sim") return "sim://";
  if (from.starts_with("replay:") && !from.starts_with("replay://")) {
    return "replay://" + from.substr(7);
  }
  return from;
}

// `url` with its rate_hz option set to `rate_hz` (when its source has one: the simulator), so the
// frames come at --rate. Other query items keep their order.
std::string with_rate(const sources::SourceRegistry& sources, const std::string& url,
                      double rate_hz) {
  const auto parts = config::split_url(url);
  if (!parts) return url;
  const auto* source = sources.find(parts.value().scheme);
  if (source == nullptr || std::find(source->option_keys.begin(), source->option_keys.end(),
                                     "rate_hz") == source->option_keys.end()) {
    return url;
  }
  std::string out = std::string(url.substr(0, url.find('?'))) + "?";
  for (const auto& [key, value] : parts.value().query) {
    if (key != "rate_hz") out += std::string(key) + "=" + std::string(value) + "&";
  }
  return out + "rate_hz=" + config::format_number(rate_hz);
}

// "HOST:PORT", ":PORT", "HOST", "[V6]:PORT" → host, port (`default_port` when not given).
// nullopt on a bad port.
std::optional<std::pair<std::string, std::uint16_t>> parse_listen(const std::string& text,
                                                                  std::uint16_t default_port) {
  std::string host = text;
  std::string port_text;
  if (text.starts_with('[')) {
    const auto close = text.find(']');
    if (close == std::string::npos) return std::nullopt;
    host = text.substr(1, close - 1);
    if (close + 1 < text.size()) {
      if (text[close + 1] != ':') return std::nullopt;
      port_text = text.substr(close + 2);
    }
  } else if (const auto colon = text.rfind(':'); colon != std::string::npos) {
    host = text.substr(0, colon);
    port_text = text.substr(colon + 1);
  }
  if (host.empty()) host = "0.0.0.0";
  unsigned port = default_port;
  if (!port_text.empty()) {
    const auto [end, ec] =
        std::from_chars(port_text.data(), port_text.data() + port_text.size(), port);
    if (ec != std::errc{} || end != port_text.data() + port_text.size() || port > 65535) {
      return std::nullopt;
    }
  }
  return std::make_pair(host, static_cast<std::uint16_t>(port));
}

std::string join(const std::vector<std::string_view>& names) {
  std::string out;
  for (const auto name : names) out += (out.empty() ? "" : ", ") + std::string(name);
  return out;
}

// The protocols whose emulators send unasked (they take --to), for messages.
std::string senders(const sources::SourceRegistry& sources) {
  std::vector<std::string_view> out;
  for (const auto scheme : sources.servable()) {
    if (sources.find(scheme)->emulator_sends) out.push_back(scheme);
  }
  return out.empty() ? "none" : join(out);
}

// --to and --set into `options`; "" or the first problem, for stderr (exit 1).
std::string read_emulator_args(const ServeArgs& args, const sources::SourceDescriptor& protocol,
                               const sources::SourceRegistry& sources,
                               sources::EmulatorOptions& options) {
  const std::string name(protocol.scheme);
  if (protocol.emulator_sends && !args.to) {
    return "--to HOST:PORT is required: " + name + " sends its datagrams there";
  }
  if (!protocol.emulator_sends && args.to) {
    return "--to is only for protocols that send unasked (" + senders(sources) + "); " + name +
           " clients connect to --listen";
  }
  if (args.to) {
    const auto to = parse_listen(*args.to, 0);
    if (!to || to->second == 0 || args.to->find(':') == std::string::npos) {
      return "bad --to '" + *args.to + "' (expected HOST:PORT)";
    }
    options.to_host = to->first;
    options.to_port = to->second;
  }
  for (const auto& item : args.settings) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0) {
      return "bad --set '" + item + "' (expected KEY=VALUE)";
    }
    std::string key = item.substr(0, eq);
    const auto& keys = protocol.emulator_option_keys;
    if (std::find(keys.begin(), keys.end(), key) == keys.end()) {
      std::vector<std::string_view> names(keys.begin(), keys.end());
      return "unknown --set key '" + key + "' for " + name + " (" +
             (names.empty() ? std::string("it takes none") : "known: " + join(names)) + ")" +
             text::did_you_mean(key, keys);
    }
    for (const auto& [seen, value] : options.settings) {
      if (seen == key) return "--set " + key + " given twice";
    }
    options.settings.emplace_back(std::move(key), item.substr(eq + 1));
  }
  return {};
}

int run_serve(const ServeArgs& args, const sources::SourceRegistry& sources) {
  const sources::SourceDescriptor* protocol = sources.find(args.protocol);
  if (protocol == nullptr || !protocol->make_emulator) {
    std::fprintf(stderr, "mocaplink serve: protocol '%s' is not supported yet (supported: %s)\n",
                 args.protocol.c_str(), join(sources.servable()).c_str());
    return 1;
  }
  if (!(args.rate_hz > 0.0 && args.rate_hz <= 2000.0)) {
    std::fprintf(stderr, "mocaplink serve: --rate must be in (0, 2000] Hz\n");
    return 1;
  }
  const auto listen = parse_listen(args.listen.value_or(":" + std::to_string(protocol->serve_port)),
                                   protocol->serve_port);
  if (!listen) {
    std::fprintf(stderr, "mocaplink serve: bad --listen '%s' (expected HOST:PORT, :PORT or HOST)\n",
                 args.listen.value_or("").c_str());
    return 1;
  }
  const std::optional<Stall> stall = args.stall ? parse_stall(*args.stall) : std::nullopt;
  if (args.stall && !stall) {
    std::fprintf(stderr,
                 "mocaplink serve: bad --stall '%s' (expected AT_S:FOR_MS, 0 <= AT_S <= 3600, "
                 "0 < FOR_MS <= 60000)\n",
                 args.stall->c_str());
    return 1;
  }

  sources::EmulatorOptions emulator_options;
  emulator_options.listen_host = listen->first;
  emulator_options.port = listen->second;
  emulator_options.rate_hz = args.rate_hz;
  if (const auto err = read_emulator_args(args, *protocol, sources, emulator_options);
      !err.empty()) {
    std::fprintf(stderr, "mocaplink serve: %s\n", err.c_str());
    return 1;
  }
  auto made = protocol->make_emulator(emulator_options);
  if (const auto* err = std::get_if<std::string>(&made)) {
    std::fprintf(stderr, "mocaplink serve: %s: %s\n", args.protocol.c_str(), err->c_str());
    return 1;
  }
  const auto server = std::move(std::get<std::unique_ptr<sources::Emulator>>(made));

  const std::string url = with_rate(sources, from_url(args.from), args.rate_hz);
  if (const auto check = sources.check(url); !check.error.empty()) {
    std::fprintf(
        stderr, "mocaplink serve: bad --from '%s' (expected sim, sim://?KEYS or replay:FILE): %s\n",
        args.from.c_str(), check.error.c_str());
    return 1;
  }
  auto opened = sources.open(url);
  if (const auto* err = std::get_if<std::string>(&opened)) {
    std::fprintf(stderr, "mocaplink serve: %s\n", err->c_str());
    return 2;
  }
  const auto source = std::move(std::get<std::unique_ptr<sources::Source>>(opened));

  // SIGINT/SIGTERM from here on stop the server cleanly (a signal during start-up waits for run).
  asio::io_context loop;
  io::StopSignals stop_signals(loop, [&loop](std::string_view, int) { loop.stop(); });
  if (const auto err = server->start({})) {
    std::fprintf(stderr, "mocaplink serve: %s%s\n", err->c_str(),
                 listen->second < 1024 ? " (ports below 1024 need root; try --listen :8801)" : "");
    return 2;
  }
  const std::string scheme = url.substr(0, url.find(':'));
  StallingPublisher publisher(*server, stall);
  source->start(
      [&publisher](core::MocapFrame f, core::HostTime) { publisher.publish(std::move(f)); },
      [&scheme](sources::SourceState s, const std::string& detail) {
        std::fprintf(stderr, "mocaplink serve: %s %s%s%s\n", scheme.c_str(), to_string(s),
                     detail.empty() ? "" : ": ", detail.c_str());
      });
  if (protocol->emulator_sends) {
    std::printf("serving %s to %s:%u from %s at %g Hz\n", args.protocol.c_str(),
                emulator_options.to_host.c_str(), static_cast<unsigned>(emulator_options.to_port),
                args.from.c_str(), args.rate_hz);
  } else {
    std::printf("serving %s on %s:%u from %s at %g Hz\n", args.protocol.c_str(),
                listen->first.c_str(), static_cast<unsigned>(server->port()), args.from.c_str(),
                args.rate_hz);
  }
  std::fflush(stdout);

  loop.run();  // until SIGINT/SIGTERM
  source->stop();
  server->stop();
  std::fprintf(stderr, "mocaplink serve: stopped; %s\n", server->summary().c_str());
  return 0;
}

}  // namespace

void add_serve_commands(CLI::App& app, ExitCode& exit_code,
                        const sources::SourceRegistry& sources) {
  auto args = std::make_shared<ServeArgs>();
  CLI::App* serve = app.add_subcommand(
      "serve", "Emulate a mocap server (" + join(sources.servable()) + ") from sim or a replay");
  serve->add_option("--protocol", args->protocol, "Protocol to serve: " + join(sources.servable()))
      ->required();
  serve->add_option("--from", args->from, "sim, sim://?KEYS, or replay:FILE")->required();
  serve->add_option(
      "--listen", args->listen,
      "HOST:PORT, :PORT or HOST (default 0.0.0.0 and the protocol's port; vicon: 801)");
  serve->add_option("--rate", args->rate_hz, "Frame rate in Hz (default 100)");
  serve->add_option(
      "--to", args->to,
      "HOST:PORT to send to, for protocols that send unasked (" + senders(sources) + ")");
  serve->add_option("--set", args->settings,
                    "KEY=VALUE setting of the protocol's emulator (repeatable; docs/sources.md)");
  serve->add_option("--stall", args->stall,
                    "AT_S:FOR_MS: hold the frames of FOR_MS from AT_S s after start back, then "
                    "send them at once (a network stall and its backlog, for tests)");
  serve->callback([args, &exit_code, &sources] { exit_code.value = run_serve(*args, sources); });
}

}  // namespace mocaplink::app
