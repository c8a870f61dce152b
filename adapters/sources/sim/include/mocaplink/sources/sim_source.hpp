// `sim://` as a Source: a thread that emits SimWorld frames in real time at rate_hz.
#pragma once

#include <string>

#include "mocaplink/sources/descriptor.hpp"
#include "mocaplink/sources/sim_world.hpp"
#include "mocaplink/sources/source.hpp"
#include "mocaplink/sources/source_thread.hpp"

namespace mocaplink::sources {

/// Emits frame n at host time start + (n − 1)/rate_hz (sleep_until, so no drift accumulates; a
/// late thread catches up without skipping numbers). Dropped frames (config.drop) are skipped, so
/// the consumer sees gaps in frame numbers exactly as with a real system. State: `connected` on
/// start, `finished` after config.frames frame numbers (when non-zero).
/// Thread-safety: start/stop from one controlling thread; callbacks run on the source's thread.
class SimSource final : public Source {
 public:
  /// `config` must pass validate_sim_options. `url` is shown by url().
  SimSource(SimOptions config, std::string url);
  ~SimSource() override;

  void start(FrameSink on_frame, StateSink on_state) override;
  void stop() override;
  [[nodiscard]] std::string url() const override { return url_; }
  [[nodiscard]] const SourceCounters& counters() const override { return counters_; }
  [[nodiscard]] const SimWorld& world() const { return world_; }

 private:
  void run(FrameSink on_frame, StateSink on_state);

  SimWorld world_;
  std::string url_;
  SourceCounters counters_;
  SourceThread thread_;  // last: joined before the members its body uses are destroyed
};

/// sim:// for the source registry: parse_sim_options, then a SimSource.
[[nodiscard]] SourceDescriptor sim_source_descriptor();

}  // namespace mocaplink::sources
