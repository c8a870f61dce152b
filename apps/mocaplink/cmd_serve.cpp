// `mocaplink serve --protocol P --from sim|replay:FILE [--listen ADDR] [--rate HZ]` (DESIGN.md
// "Command line"): emulate a mocap server. Only the Vicon DataStream protocol exists so far
// (adapters/sources/vicon, ViconServer); other protocols exit 1 with "not supported yet".
//
// --from sim            the built-in simulator (Body1, Body2, Body3; sim:// defaults) at --rate
// --from sim://?KEYS    the same with sim:// keys (bodies, noise_mm, seed, occlude, …); rate_hz
//                       is always --rate
// --from replay:FILE    a mocaplink recording, with its recorded timing (replay://FILE?KEYS too)
// --listen ADDR         HOST:PORT, :PORT or HOST (IPv6 as [ADDR]:PORT); default 0.0.0.0:801
// --rate HZ             frame rate of the sim and of StreamInfo (replay: used when a frame does
//                       not say); default 100
// On start one line goes to stdout: "serving vicon on HOST:PORT from SOURCE at RATE Hz" (PORT is
// the bound one, so --listen 127.0.0.1:0 works for scripts). Runs until SIGINT/SIGTERM (exit 0).
// Exit 1: bad arguments; exit 2: cannot listen or cannot read the recording.
#include <charconv>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <variant>

#include <asio/io_context.hpp>

#include "commands.hpp"
#include "mocaplink/io/signals.hpp"
#include "mocaplink/sources/sim_world.hpp"
#include "mocaplink/sources/source_factory.hpp"
#include "mocaplink/sources/vicon_server.hpp"
#if __has_include("mocaplink/sources/replay_source.hpp")
#include "mocaplink/sources/replay_source.hpp"
#define MOCAPLINK_SERVE_HAS_REPLAY 1
#endif

namespace mocaplink::app {
namespace {

struct ServeArgs {
  std::string protocol;
  std::string from;
  std::string listen = "0.0.0.0:801";
  double rate_hz = 100.0;
};

// `--from sim`, `sim://?…`, `replay:FILE` or `replay://FILE` → the source URL parser every other
// command uses (config::parse_source_url), so the options and ranges are the same everywhere.
config::ValueOrError<config::SourceUrl> parse_from(const std::string& from) {
  if (from == "sim") return config::parse_source_url("sim://");
  if (from.starts_with("replay:") && !from.starts_with("replay://")) {
    return config::parse_source_url("replay://" + from.substr(7));
  }
  return config::parse_source_url(from);
}

// "HOST:PORT", ":PORT", "HOST", "[V6]:PORT" → host, port. nullopt on a bad port.
std::optional<std::pair<std::string, std::uint16_t>> parse_listen(const std::string& text) {
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
  unsigned port = 801;
  if (!port_text.empty()) {
    const auto [end, ec] =
        std::from_chars(port_text.data(), port_text.data() + port_text.size(), port);
    if (ec != std::errc{} || end != port_text.data() + port_text.size() || port > 65535) {
      return std::nullopt;
    }
  }
  return std::make_pair(host, static_cast<std::uint16_t>(port));
}

int run_serve(const ServeArgs& args) {
  if (args.protocol != "vicon") {
    std::fprintf(stderr, "mocaplink serve: protocol '%s' is not supported yet (supported: vicon)\n",
                 args.protocol.c_str());
    return 1;
  }
  if (!(args.rate_hz > 0.0 && args.rate_hz <= 2000.0)) {
    std::fprintf(stderr, "mocaplink serve: --rate must be in (0, 2000] Hz\n");
    return 1;
  }
  const auto listen = parse_listen(args.listen);
  if (!listen) {
    std::fprintf(stderr, "mocaplink serve: bad --listen '%s' (expected HOST:PORT, :PORT or HOST)\n",
                 args.listen.c_str());
    return 1;
  }

  std::unique_ptr<sources::SimWorld> world;
#ifdef MOCAPLINK_SERVE_HAS_REPLAY
  std::unique_ptr<sources::ReplaySource> replay;
#endif
  const auto from_url = parse_from(args.from);
  if (!from_url) {
    std::fprintf(
        stderr, "mocaplink serve: bad --from '%s' (expected sim, sim://?KEYS or replay:FILE): %s\n",
        args.from.c_str(), from_url.error().c_str());
    return 1;
  }
  const config::SourceUrl& source = from_url.value();
  if (source.kind == config::SourceKind::sim) {
    sources::SimConfig sim = source.sim;
    sim.rate_hz = args.rate_hz;
    if (const auto err = sources::validate_sim_config(sim); !err.empty()) {
      std::fprintf(stderr, "mocaplink serve: --from %s: %s\n", args.from.c_str(), err.c_str());
      return 1;
    }
    world = std::make_unique<sources::SimWorld>(sim);
  } else if (source.kind == config::SourceKind::replay) {
#ifdef MOCAPLINK_SERVE_HAS_REPLAY
    const sources::ReplayConfig config{source.replay_path, source.replay_speed, source.replay_loop};
    auto opened = sources::ReplaySource::open(config, args.from);
    if (const auto* err = std::get_if<std::string>(&opened)) {
      std::fprintf(stderr, "mocaplink serve: %s\n", err->c_str());
      return 2;
    }
    replay = std::move(std::get<std::unique_ptr<sources::ReplaySource>>(opened));
#else
    std::fprintf(stderr, "mocaplink serve: --from replay: is not available in this build\n");
    return 1;
#endif
  } else {
    std::fprintf(stderr, "mocaplink serve: bad --from '%s' (expected sim or replay:FILE)\n",
                 args.from.c_str());
    return 1;
  }

  // SIGINT/SIGTERM from here on stop the server cleanly (a signal during start-up waits for run).
  asio::io_context loop;
  io::StopSignals stop_signals(loop, [&loop](int, int) { loop.stop(); });
  sources::ViconServerOptions options;
  options.listen_host = listen->first;
  options.port = listen->second;
  options.rate_hz = args.rate_hz;
  sources::ViconServer server(options);
  sources::ViconServer::FrameProvider provider;
  if (world) {
    provider = [w = world.get()](std::uint64_t tick) -> std::optional<core::MocapFrame> {
      const std::uint64_t n = tick + 1;  // SimWorld numbers frames from 1
      if (w->dropped(n) || (w->config().frames != 0 && n > w->config().frames)) {
        return std::nullopt;
      }
      return w->frame(n);
    };
  }
  if (const auto err = server.start(std::move(provider))) {
    std::fprintf(stderr, "mocaplink serve: %s%s\n", err->c_str(),
                 listen->second < 1024 ? " (ports below 1024 need root; try --listen :8801)" : "");
    return 2;
  }
#ifdef MOCAPLINK_SERVE_HAS_REPLAY
  if (replay) {
    replay->start([&server](core::MocapFrame f, core::HostTime) { server.publish(std::move(f)); },
                  [](sources::SourceState s, const std::string& detail) {
                    std::fprintf(stderr, "mocaplink serve: replay %s%s%s\n", to_string(s),
                                 detail.empty() ? "" : ": ", detail.c_str());
                  });
  }
#endif
  std::printf("serving vicon on %s:%u from %s at %g Hz\n", listen->first.c_str(),
              static_cast<unsigned>(server.port()), args.from.c_str(), args.rate_hz);
  std::fflush(stdout);

  loop.run();  // until SIGINT/SIGTERM
#ifdef MOCAPLINK_SERVE_HAS_REPLAY
  if (replay) replay->stop();
#endif
  server.stop();
  const auto& c = server.counters();
  std::fprintf(stderr,
               "mocaplink serve: stopped; %llu frames, %llu clients, %llu frames dropped for slow "
               "clients, %llu malformed requests\n",
               static_cast<unsigned long long>(c.frames.load()),
               static_cast<unsigned long long>(c.clients_accepted.load()),
               static_cast<unsigned long long>(c.frames_dropped.load()),
               static_cast<unsigned long long>(c.malformed_requests.load()));
  return 0;
}

}  // namespace

void add_serve_commands(CLI::App& app, ExitCode& exit_code) {
  auto args = std::make_shared<ServeArgs>();
  CLI::App* serve =
      app.add_subcommand("serve", "Emulate a mocap server (vicon) from sim or a replay");
  serve->add_option("--protocol", args->protocol, "Protocol to serve: vicon")->required();
  serve->add_option("--from", args->from, "sim, sim://?KEYS, or replay:FILE")->required();
  serve->add_option("--listen", args->listen, "HOST:PORT, :PORT or HOST (default 0.0.0.0:801)");
  serve->add_option("--rate", args->rate_hz, "Frame rate in Hz (default 100)");
  serve->callback([args, &exit_code] { exit_code.value = run_serve(*args); });
}

}  // namespace mocaplink::app
