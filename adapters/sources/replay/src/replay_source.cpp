#include "mocaplink/sources/replay_source.hpp"

#include <array>
#include <chrono>
#include <fstream>
#include <optional>
#include <utility>

#include "mocaplink/io/clock.hpp"
#include "mocaplink/wire/recording_csv.hpp"

namespace mocaplink::sources {
namespace {

/// Reads lines of at most kMaxRecordingLineBytes (+ '\r') bytes: a longer line is reported, not
/// buffered, so a hostile file cannot make us allocate without bound.
class LineReader {
 public:
  enum class Status { line, end, too_long, io_error };

  explicit LineReader(const std::string& path) : in_(path, std::ios::binary) {}
  [[nodiscard]] bool is_open() const { return in_.is_open(); }

  Status next(std::string_view& line) {
    in_.getline(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    const auto count = static_cast<std::size_t>(in_.gcount());
    if (in_.bad()) return Status::io_error;
    if (in_.eof()) {
      if (count == 0) return Status::end;
      line = std::string_view(buffer_.data(), count);  // last line without '\n'
      return Status::line;
    }
    if (in_.fail()) return Status::too_long;             // buffer filled before a '\n'
    line = std::string_view(buffer_.data(), count - 1);  // gcount includes the '\n'
    return Status::line;
  }

 private:
  std::ifstream in_;
  std::array<char, wire::kMaxRecordingLineBytes + 2> buffer_{};  // + '\r' + NUL
};

/// Feeds one more line (or the end) to `reader`; nullopt at a clean end of pass.
std::optional<wire::RecordingStep> read_step(LineReader& lines, wire::RecordingReader& reader,
                                             bool& at_end) {
  if (at_end) return std::nullopt;
  std::string_view line;
  switch (lines.next(line)) {
    case LineReader::Status::line:
      return reader.feed_line(line);
    case LineReader::Status::end:
      at_end = true;
      return reader.finish();
    case LineReader::Status::too_long:
      return wire::RecordingError{
          reader.line_number() + 1,
          "line longer than " + std::to_string(wire::kMaxRecordingLineBytes) + " bytes"};
    case LineReader::Status::io_error:
      break;
  }
  return wire::RecordingError{reader.line_number() + 1, "read error"};
}

std::string describe(const std::string& path, const wire::RecordingError& error) {
  return path + ":" + std::to_string(error.line) + ": " + error.message;
}

}  // namespace

std::variant<std::unique_ptr<ReplaySource>, std::string> ReplaySource::open(ReplayOptions config,
                                                                            std::string url) {
  LineReader lines(config.path);
  if (!lines.is_open()) return "replay://: cannot open '" + config.path + "'";
  // Read up to the first row: the header comment and column line are checked here.
  wire::RecordingReader reader;
  bool at_end = false;
  while (auto step = read_step(lines, reader, at_end)) {
    if (const auto* error = std::get_if<wire::RecordingError>(&*step)) {
      return "replay://: " + describe(config.path, *error);
    }
    if (reader.header_complete()) break;
  }
  return std::unique_ptr<ReplaySource>(new ReplaySource(std::move(config), std::move(url)));
}

ReplaySource::ReplaySource(ReplayOptions config, std::string url)
    : config_(std::move(config)), url_(std::move(url)) {}

ReplaySource::~ReplaySource() {
  stop();
}

void ReplaySource::start(FrameSink on_frame, StateSink on_state) {
  thread_.start([this, frame_sink = std::move(on_frame), state_sink = std::move(on_state)] {
    run(frame_sink, state_sink);
  });
}

void ReplaySource::stop() {
  thread_.stop();
}

void ReplaySource::run(const FrameSink& on_frame, const StateSink& on_state) {
  const auto state = [&](SourceState s, const std::string& detail) {
    if (on_state) on_state(s, detail);
  };
  state(SourceState::connected, "replaying " + config_.path);
  const auto start = std::chrono::steady_clock::now();
  ReplaySchedule schedule(config_.speed);
  std::uint64_t delivered = 0;
  std::uint64_t delivered_this_pass = 0;
  do {
    LineReader lines(config_.path);
    if (!lines.is_open()) {
      state(SourceState::finished, "cannot open '" + config_.path + "'");
      return;
    }
    wire::RecordingReader reader;
    bool at_end = false;
    delivered_this_pass = 0;
    while (auto step = read_step(lines, reader, at_end)) {
      if (const auto* error = std::get_if<wire::RecordingError>(&*step)) {
        counters_.malformed.fetch_add(1, std::memory_order_relaxed);
        state(SourceState::finished, describe(config_.path, *error));
        return;
      }
      auto& frame = std::get<std::optional<core::MocapFrame>>(*step);
      if (!frame) continue;
      const core::Duration due = schedule.due(frame->capture_time);
      if (thread_.wait_until(config_.speed > 0.0 ? start + due : start)) return;
      ++delivered;
      ++delivered_this_pass;
      counters_.frames.fetch_add(1, std::memory_order_relaxed);
      if (on_frame) on_frame(std::move(*frame), io::host_now());
    }
    schedule.next_pass();
  } while (config_.loop && delivered_this_pass > 0);
  state(SourceState::finished, std::to_string(delivered) + " frames replayed");
}

}  // namespace mocaplink::sources
