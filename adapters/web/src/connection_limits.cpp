#include "mocaplink/web/connection_limits.hpp"

#include <algorithm>
#include <cassert>

namespace mocaplink::web {

ClientSlots::ClientSlots(std::size_t per_client) : per_client_(per_client) {
  assert(per_client >= 1);
}

bool ClientSlots::try_acquire(const std::string& address) {
  std::lock_guard lock(mutex_);
  std::size_t& held = open_by_address_[address];
  if (held >= per_client_) {
    ++refused_;
    return false;
  }
  ++held;
  ++open_;
  return true;
}

void ClientSlots::release(const std::string& address) {
  std::lock_guard lock(mutex_);
  const auto it = open_by_address_.find(address);
  assert(it != open_by_address_.end() && it->second > 0);
  if (it == open_by_address_.end()) return;
  --open_;
  // Forget addresses without connections: a scanner walking many addresses leaves nothing behind.
  if (--it->second == 0) open_by_address_.erase(it);
}

std::size_t ClientSlots::open() const {
  std::lock_guard lock(mutex_);
  return open_;
}

std::uint64_t ClientSlots::refused() const {
  std::lock_guard lock(mutex_);
  return refused_;
}

RequestDeadline::RequestDeadline(std::chrono::milliseconds total, std::chrono::milliseconds silence)
    : total_(total), silence_(silence) {
  assert(total > std::chrono::milliseconds::zero() && silence > std::chrono::milliseconds::zero());
}

std::optional<std::chrono::milliseconds> RequestDeadline::next_wait(Clock::time_point now) const {
  if (now >= deadline_) return std::nullopt;
  // Round up: a wait of 0 ms while time is left would spin.
  const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline_ - now);
  return std::min(silence_, left);
}

}  // namespace mocaplink::web
