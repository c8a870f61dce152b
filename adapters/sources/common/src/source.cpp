#include "mocaplink/sources/source.hpp"

#include "mocaplink/sources/source_thread.hpp"

namespace mocaplink::sources {

void SourceThread::start(std::function<void()> body) {
  thread_ = std::thread(std::move(body));
}

void SourceThread::stop() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

}  // namespace mocaplink::sources
