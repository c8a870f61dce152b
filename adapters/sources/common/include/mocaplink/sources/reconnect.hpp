// What every reconnecting network source shares (DESIGN.md "Fault behaviour": reconnect with
// back-off): its connection state reported once per change — every `disconnected` is reported,
// each with its own reason. The delay before the next attempt is core::RetrySchedule (the same
// for the vehicle links). Used on the source's own thread.
#pragma once

#include <string>
#include <utility>

#include "mocaplink/sources/source.hpp"

namespace mocaplink::sources {

class StateReporter {
 public:
  explicit StateReporter(StateSink sink) : sink_(std::move(sink)) {}
  void operator()(SourceState state, const std::string& detail) {
    if (state == state_ && state != SourceState::disconnected) return;
    state_ = state;
    if (sink_) sink_(state, detail);
  }

 private:
  StateSink sink_;
  SourceState state_ = SourceState::disconnected;
};

}  // namespace mocaplink::sources
