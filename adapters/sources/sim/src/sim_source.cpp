#include "mocaplink/sources/sim_source.hpp"

#include <array>
#include <chrono>
#include <cstdio>
#include <utility>

#include "mocaplink/io/clock.hpp"

namespace mocaplink::sources {
SimSource::SimSource(SimOptions config, std::string url)
    : world_(std::move(config)), url_(std::move(url)) {}

SimSource::~SimSource() {
  stop();
}

void SimSource::start(FrameSink on_frame, StateSink on_state) {
  thread_.start(
      [this, frame_sink = std::move(on_frame), state_sink = std::move(on_state)]() mutable {
        run(std::move(frame_sink), std::move(state_sink));
      });
}

void SimSource::stop() {
  thread_.stop();
}

void SimSource::run(FrameSink on_frame, StateSink on_state) {
  const SimOptions& config = world_.config();
  if (on_state) {
    std::array<char, 96> detail{};
    std::snprintf(detail.data(), detail.size(), "simulated, %u bodies at %g Hz", config.bodies,
                  config.rate_hz);
    on_state(SourceState::connected, detail.data());
  }
  const auto start = std::chrono::steady_clock::now();
  const std::chrono::duration<double> period(1.0 / config.rate_hz);
  for (std::uint64_t n = 1; config.frames == 0 || n <= config.frames; ++n) {
    const auto due = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                 period * static_cast<double>(n - 1));
    if (thread_.wait_until(due)) return;
    if (world_.dropped(n)) continue;
    core::MocapFrame frame = world_.frame(n);
    counters_.frames.fetch_add(1, std::memory_order_relaxed);
    if (on_frame) on_frame(std::move(frame), io::host_now());
  }
  if (on_state)
    on_state(SourceState::finished, "simulation reached frames=" + std::to_string(config.frames));
}

}  // namespace mocaplink::sources
