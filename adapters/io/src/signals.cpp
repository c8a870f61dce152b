#include "mocaplink/io/signals.hpp"

#include <csignal>
#include <system_error>
#include <utility>

namespace mocaplink::io {

StopSignals::StopSignals(asio::io_context& loop, Handler on_signal)
    : signals_(loop, SIGINT, SIGTERM), on_signal_(std::move(on_signal)) {
  arm();
}

StopSignals::~StopSignals() {
  std::error_code ignored;
  signals_.cancel(ignored);
  signals_.clear(ignored);
}

void StopSignals::arm() {
  signals_.async_wait([this](const std::error_code& error, int signal_number) {
    if (error) return;  // cancelled: the set is being destroyed
    ++count_;
    on_signal_(signal_number, count_);
    arm();
  });
}

}  // namespace mocaplink::io
