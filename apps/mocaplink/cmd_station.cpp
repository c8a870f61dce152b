// `mocaplink bodies` and `mocaplink record` (DESIGN.md "Command line"): a Source feeding the
// Station, shown live, summarised once (text or JSON), or written to a recording.
//
// Exit codes (commands.hpp): 0 at least one frame arrived; 1 bad command line or source URL
// (nothing started); 2 no frame ever arrived (source unreachable, silent or empty) or the
// recording could not be written.
//
// Packets the source dropped unread (SourceCounters::rejected(): malformed or from a stranger)
// are shown with the latest reason in both commands, so a stream the source cannot read is never
// just "no frame arrived".
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <asio/io_context.hpp>
#include <asio/post.hpp>
#include <asio/steady_timer.hpp>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "mocaplink/core/station.hpp"
#include "mocaplink/io/clock.hpp"
#include "mocaplink/io/signals.hpp"
#include "mocaplink/io/terminal.hpp"
#include "mocaplink/sources/registry.hpp"
#include "mocaplink/wire/recording_csv.hpp"

namespace mocaplink::app {
namespace {

using Clock = std::chrono::steady_clock;
using sources::SourceState;

/// Packets a source dropped unread (malformed or refused) and the latest reason.
struct Rejections {
  std::uint64_t count = 0;
  std::string reason;
  /// "; 12 packets rejected: REASON" or "" when none (the no-frame and record lines).
  [[nodiscard]] std::string suffix() const {
    if (count == 0) return {};
    return fmt::format("; {} {} rejected{}", count, count == 1 ? "packet" : "packets",
                       reason.empty() ? std::string() : ": " + reason);
  }
};

/// A started Source feeding a Station, thread-safe: the source's thread calls in, the main thread
/// waits (on its own event loop, which also takes SIGINT/SIGTERM) and takes snapshots. `also` sees
/// every frame after the Station (record writes them).
class StationSession {
 public:
  using FrameHook = std::function<void(const core::MocapFrame&)>;

  StationSession(std::unique_ptr<sources::Source> source, FrameHook also)
      : source_(std::move(source)),
        also_(std::move(also)),
        signals_(loop_, [this](std::string_view, int) { loop_.stop(); }) {
    source_->start(
        [this](core::MocapFrame frame, core::HostTime received) {
          const std::lock_guard lock(mutex_);
          station_.on_frame(frame, received);
          if (also_) also_(frame);
        },
        [this](SourceState state, const std::string& detail) {
          {
            const std::lock_guard lock(mutex_);
            state_ = state;
            detail_ = detail;
            station_.on_connection(state == SourceState::connected);
          }
          if (state == SourceState::finished) asio::post(loop_, [this] { loop_.stop(); });
        });
  }
  ~StationSession() { source_->stop(); }
  StationSession(const StationSession&) = delete;
  StationSession& operator=(const StationSession&) = delete;

  /// Calls `tick` every `period` until `limit` (if any) has passed, the source finished or gave
  /// up (`finished`: nothing more will come), or SIGINT/SIGTERM.
  void run(std::optional<std::chrono::duration<double>> limit, std::chrono::milliseconds period,
           const std::function<void()>& tick) {
    const auto start = Clock::now();
    const auto end = limit ? start + std::chrono::duration_cast<Clock::duration>(*limit)
                           : Clock::time_point::max();
    {
      const std::lock_guard lock(mutex_);
      if (done_locked()) return;
    }
    asio::steady_timer timer(loop_);
    std::function<void()> wait = [&] {
      timer.expires_at(std::min(end, Clock::now() + period));
      timer.async_wait([&](const std::error_code& error) {
        if (error) return;
        if (Clock::now() >= end) {
          loop_.stop();
          return;
        }
        if (tick) tick();
        wait();
      });
    };
    wait();
    loop_.run();  // until the limit, `finished` (posted by the source's thread) or a signal
    timer.cancel();
  }

  [[nodiscard]] core::StationSnapshot snapshot() {
    const std::lock_guard lock(mutex_);
    return station_.snapshot(io::host_now());
  }
  [[nodiscard]] std::pair<SourceState, std::string> state() {
    const std::lock_guard lock(mutex_);
    return {state_, detail_};
  }
  /// Packets the source dropped unread, and why the latest was (any thread).
  [[nodiscard]] Rejections rejections() const {
    const auto& c = source_->counters();
    // The reason first: a source sets it before it counts.
    std::string reason = c.last_rejection.get();
    return {c.rejected(), std::move(reason)};
  }
  void stop() { source_->stop(); }

 private:
  // A network source that is disconnected keeps reconnecting, so only `finished` ends the wait.
  bool done_locked() const { return state_ == SourceState::finished; }

  std::unique_ptr<sources::Source> source_;
  FrameHook also_;
  asio::io_context loop_;
  io::StopSignals signals_;
  std::mutex mutex_;
  core::Station station_;
  SourceState state_ = SourceState::connecting;
  std::string detail_;
};

/// The source from the registry, or a message on stderr and exit code 1.
std::unique_ptr<sources::Source> open_source(const sources::SourceRegistry& sources,
                                             const std::string& command, const std::string& url,
                                             ExitCode& exit_code) {
  auto made = sources.open(url);
  if (auto* error = std::get_if<std::string>(&made)) {
    std::fprintf(stderr, "mocaplink %s: %s\n", command.c_str(), error->c_str());
    exit_code.value = 1;
    return nullptr;
  }
  return std::move(std::get<std::unique_ptr<sources::Source>>(made));
}

nlohmann::json to_json(const std::string& url, SourceState state, const core::StationSnapshot& s,
                       const Rejections& rejected) {
  const auto optional_number = [](const std::optional<double>& v) {
    return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
  };
  nlohmann::json bodies = nlohmann::json::array();
  for (const auto& b : s.bodies) {
    const auto& q = b.q_world_body;
    bodies.push_back({
        {"name", b.name},
        {"tracked", b.tracked},
        {"mirrored", b.mirrored},
        {"p_m", b.ever_tracked ? nlohmann::json{b.p_world_m.x(), b.p_world_m.y(), b.p_world_m.z()}
                               : nlohmann::json(nullptr)},
        {"q_wxyz",
         b.ever_tracked ? nlohmann::json{q.w(), q.x(), q.y(), q.z()} : nlohmann::json(nullptr)},
        {"frames_tracked", b.frames_tracked},
    });
  }
  return {{"source", url},
          {"connected", s.connected},
          {"state", sources::to_string(state)},
          {"frame_rate_hz", s.frame_rate_hz},
          {"latency_ms", optional_number(s.latency_ms)},
          {"jitter_ms", optional_number(s.jitter_ms)},
          {"frames", s.frames},
          {"dropped", s.drops_counted ? nlohmann::json(s.dropped) : nlohmann::json(nullptr)},
          {"rejected", rejected.count},
          {"rejected_reason",
           rejected.reason.empty() ? nlohmann::json(nullptr) : nlohmann::json(rejected.reason)},
          {"bodies", std::move(bodies)}};
}

std::string optional_ms(const std::optional<double>& v) {
  return v ? fmt::format("{:.2f} ms", *v) : std::string("n/a");
}

std::string to_text(const std::string& url, SourceState state, const std::string& detail,
                    const core::StationSnapshot& s, const Rejections& rejected) {
  std::string out = fmt::format("source    {}\nstate     {}{}\n", url, sources::to_string(state),
                                detail.empty() ? "" : " (" + detail + ")");
  out += fmt::format("rate      {:.1f} Hz{}\n", s.frame_rate_hz,
                     s.nominal_rate_hz ? fmt::format(" (source says {:g} Hz)", *s.nominal_rate_hz)
                                       : std::string());
  out += fmt::format("latency   {}   jitter {}\n", optional_ms(s.latency_ms),
                     optional_ms(s.jitter_ms));
  out += s.drops_counted
             ? fmt::format("frames    {}   dropped {}   restarts {}\n", s.frames, s.dropped,
                           s.restarts)
             : fmt::format("frames    {}   dropped n/a (no frame numbers from the source)\n",
                           s.frames);
  if (rejected.count > 0) {
    out += fmt::format("rejected  {}{}\n", rejected.count,
                       rejected.reason.empty() ? std::string() : "   last: " + rejected.reason);
  }
  out += fmt::format("{:<16} {:<7} {:>9} {:>9} {:>9} {:>9}  {:>7} {:>7} {:>7} {:>7}\n", "body",
                     "tracked", "frames", "x_m", "y_m", "z_m", "qw", "qx", "qy", "qz");
  for (const auto& b : s.bodies) {
    const auto& p = b.p_world_m;
    const auto& q = b.q_world_body;
    out += fmt::format("{:<16} {:<7} {:>9}", b.name, b.tracked ? "yes" : "no", b.frames_tracked);
    out += b.ever_tracked ? fmt::format(
                                " {:>9.4f} {:>9.4f} {:>9.4f}  {:>7.4f} {:>7.4f} {:>7.4f} "
                                "{:>7.4f}\n",
                                p.x(), p.y(), p.z(), q.w(), q.x(), q.y(), q.z())
                          : std::string("   (never tracked)\n");
  }
  for (const auto& b : s.bodies) {
    if (b.mirrored) {
      out += fmt::format(
          "{}: its rotation is mirrored (a left-handed matrix, determinant -1): not a pose; no "
          "axis setting can fix it: check the handedness of the mocap system's frame\n",
          b.name);
    }
  }
  return out;
}

void run_bodies(const sources::SourceRegistry& sources, const std::string& url,
                std::optional<double> seconds, bool json, ExitCode& exit_code) {
  auto source = open_source(sources, "bodies", url, exit_code);
  if (!source) return;
  StationSession session(std::move(source), nullptr);
  const bool live = !json && !seconds;
  const bool terminal = io::stdout_is_ansi_terminal();
  const auto show = [&] {
    const auto [state, detail] = session.state();
    const std::string text = to_text(url, state, detail, session.snapshot(), session.rejections());
    // On a terminal, redraw in place (home + clear); piped, print blocks one after another.
    std::fputs(terminal ? ("\x1b[H\x1b[2J" + text).c_str() : (text + "\n").c_str(), stdout);
    std::fflush(stdout);
  };
  std::optional<std::chrono::duration<double>> limit;
  if (seconds) limit = std::chrono::duration<double>(*seconds);
  session.run(limit, std::chrono::milliseconds(500), live ? std::function<void()>(show) : nullptr);
  const auto snapshot = session.snapshot();
  const auto [state, detail] = session.state();
  session.stop();
  const auto rejected = session.rejections();
  if (json) {
    std::puts(to_json(url, state, snapshot, rejected).dump().c_str());
  } else {
    std::fputs(to_text(url, state, detail, snapshot, rejected).c_str(), stdout);
  }
  if (snapshot.frames == 0) {
    std::fprintf(stderr, "mocaplink bodies: no frame arrived from %s%s%s\n", url.c_str(),
                 detail.empty() ? "" : (" (" + detail + ")").c_str(), rejected.suffix().c_str());
    exit_code.value = 2;
  }
}

void run_record(const sources::SourceRegistry& sources, const std::string& url,
                const std::string& out_path, std::optional<double> seconds, ExitCode& exit_code) {
  auto source = open_source(sources, "record", url, exit_code);
  if (!source) return;
  std::ofstream out(out_path, std::ios::binary | std::ios::trunc);
  if (!out) {
    std::fprintf(stderr, "mocaplink record: cannot create '%s'\n", out_path.c_str());
    exit_code.value = 2;
    return;
  }
  // The header waits for the first frame, which tells the source's rate; runs on the source's
  // thread under the session's lock.
  std::optional<core::SourceTime> first_capture;
  auto write = [&](const core::MocapFrame& frame) {
    if (!first_capture) {
      first_capture = frame.capture_time;
      out << wire::format_recording_header(url, frame.frame_rate_hz);
    }
    out << wire::format_recording_frame(frame, *first_capture);
  };
  StationSession session(std::move(source), write);
  std::optional<std::chrono::duration<double>> limit;
  if (seconds) limit = std::chrono::duration<double>(*seconds);
  session.run(limit, std::chrono::milliseconds(500), nullptr);
  session.stop();  // no callback after this: `out` and `first_capture` are ours again
  const auto snapshot = session.snapshot();
  const auto [state, detail] = session.state();
  if (!first_capture) out << wire::format_recording_header(url, std::nullopt);
  out.close();
  if (!out) {
    std::fprintf(stderr, "mocaplink record: error writing '%s'\n", out_path.c_str());
    exit_code.value = 2;
    return;
  }
  const std::string dropped =
      snapshot.drops_counted ? std::to_string(snapshot.dropped) : std::string("n/a");
  const auto rejected = session.rejections();
  std::fprintf(stderr, "mocaplink record: %llu frames (%s dropped, %zu bodies) to %s%s\n",
               static_cast<unsigned long long>(snapshot.frames), dropped.c_str(),
               snapshot.bodies.size(), out_path.c_str(), rejected.suffix().c_str());
  if (snapshot.frames == 0) {
    std::fprintf(stderr, "mocaplink record: no frame arrived from %s%s%s\n", url.c_str(),
                 detail.empty() ? "" : (" (" + detail + ")").c_str(), rejected.suffix().c_str());
    exit_code.value = 2;
  }
}

}  // namespace

void add_station_commands(CLI::App& app, ExitCode& exit_code,
                          const sources::SourceRegistry& sources) {
  struct Options {
    std::string source;
    std::string out;
    std::optional<double> seconds;
    bool json = false;
  };
  auto options = std::make_shared<Options>();

  auto* bodies = app.add_subcommand(
      "bodies",
      "What the Station sees: rate, latency, drops, bodies, tracking (live view, or one "
      "summary after --seconds)");
  bodies->add_option("--source", options->source, "Source URL, e.g. sim:// or vicon://HOST")
      ->required();
  bodies->add_option("--seconds", options->seconds, "Print one summary after N s and exit")
      ->check(CLI::PositiveNumber);
  bodies->add_flag("--json", options->json,
                   "Print one JSON object at the end (after --seconds, end of a replay, Ctrl-C)");
  bodies->callback([options, &exit_code, &sources] {
    run_bodies(sources, options->source, options->seconds, options->json, exit_code);
  });

  auto* record = app.add_subcommand("record", "Write mocap frames to a CSV recording");
  record->add_option("--source", options->source, "Source URL")->required();
  record->add_option("--out", options->out, "Recording file to write (replaced)")->required();
  record->add_option("--seconds", options->seconds, "Stop after N s (default: Ctrl-C or end)")
      ->check(CLI::PositiveNumber);
  record->callback([options, &exit_code, &sources] {
    run_record(sources, options->source, options->out, options->seconds, exit_code);
  });
}

}  // namespace mocaplink::app
