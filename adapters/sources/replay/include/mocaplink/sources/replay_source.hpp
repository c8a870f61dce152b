// `replay://` as a Source: a thread that reads a recording line by line (memory bounded by one
// frame) and delivers its frames with the recorded timing scaled by speed.
#pragma once

#include <memory>
#include <string>
#include <variant>

#include "mocaplink/sources/descriptor.hpp"
#include "mocaplink/sources/replay_options.hpp"
#include "mocaplink/sources/source.hpp"
#include "mocaplink/sources/source_thread.hpp"

namespace mocaplink::sources {

/// States: `connected` when playback starts, then `finished` once nothing more will come: at the
/// end of the file (detail: "N frames replayed"), or with detail "FILE:LINE: reason" when the file
/// turns out malformed mid-way or unreadable (malformed is incremented; the frames completed
/// before the bad line have been delivered, not the one still open when it came).
/// Frames keep the recorded frame numbers and capture times (the source clock is the
/// recording's); `received` is the host time of delivery.
/// Thread-safety: start/stop from one controlling thread; callbacks run on the source's thread.
class ReplaySource final : public Source {
 public:
  /// Opens the file and checks that it starts like a recording (header comment and column line),
  /// so that a wrong path or a wrong file is reported before anything starts.
  [[nodiscard]] static std::variant<std::unique_ptr<ReplaySource>, std::string> open(
      ReplayOptions config, std::string url);
  ~ReplaySource() override;

  void start(FrameSink on_frame, StateSink on_state) override;
  void stop() override;
  [[nodiscard]] std::string url() const override { return url_; }
  [[nodiscard]] const SourceCounters& counters() const override { return counters_; }

 private:
  ReplaySource(ReplayOptions config, std::string url);
  void run(const FrameSink& on_frame, const StateSink& on_state);

  ReplayOptions config_;
  std::string url_;
  SourceCounters counters_;
  SourceThread thread_;  // last: joined before the members its body uses are destroyed
};

/// replay:// for the source registry: parse_replay_options, then ReplaySource::open.
[[nodiscard]] SourceDescriptor replay_source_descriptor();

}  // namespace mocaplink::sources
