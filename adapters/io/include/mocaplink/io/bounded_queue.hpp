// A bounded multi-producer, single-consumer hand-over queue: mocap sources run on their own
// threads and give frames to the event loop through it (DESIGN.md "Data flow", issue 5).
//
//   producer thread:  if (queue.push(std::move(frame))) post_wakeup_to_loop();
//   event loop:       queue.drain(batch); for (auto& f : batch) bridge.on_frame(f, ...);
//
// When full, push() discards the OLDEST item and counts one overflow: for a pose stream the
// freshest sample is worth most, and a stalled consumer must not grow memory without bound.
// push() returns true only on the empty → non-empty transition, so the producer posts at most
// one wake-up per batch instead of one per item.
// Memory: a ring that grows to `capacity` items and then allocates no more (core::Ring).
// Thread-safety: push/drain/size/overflows may be called from any thread.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <vector>

#include "mocaplink/core/ring.hpp"

namespace mocaplink::io {

template <typename T>
class BoundedQueue {
 public:
  /// `capacity` ≥ 1 items (0 is treated as 1).
  explicit BoundedQueue(std::size_t capacity) : capacity_(capacity == 0 ? 1 : capacity) {}

  /// Appends `item`; if the queue is full the oldest item is discarded and counted as an
  /// overflow. Returns true when the queue was empty before (the consumer needs waking).
  bool push(T item) {
    const std::lock_guard lock(mutex_);
    const bool was_empty = items_.empty();
    if (items_.size() >= capacity_) {
      items_.pop_front();
      overflows_.fetch_add(1, std::memory_order_relaxed);
    }
    items_.push_back(std::move(item));
    return was_empty;
  }

  /// Moves every queued item, oldest first, to the end of `out`. Returns how many were moved.
  std::size_t drain(std::vector<T>& out) {
    const std::lock_guard lock(mutex_);
    const std::size_t n = items_.size();
    for (std::size_t i = 0; i < n; ++i) out.push_back(std::move(items_[i]));
    items_.clear();
    return n;
  }

  [[nodiscard]] std::size_t size() const {
    const std::lock_guard lock(mutex_);
    return items_.size();
  }
  [[nodiscard]] std::size_t capacity() const noexcept { return capacity_; }
  /// Items discarded because the queue was full, since construction.
  [[nodiscard]] std::uint64_t overflows() const noexcept {
    return overflows_.load(std::memory_order_relaxed);
  }

 private:
  const std::size_t capacity_;
  mutable std::mutex mutex_;
  core::Ring<T> items_;  // guarded by mutex_; no allocation once it has held capacity_ items
  std::atomic<std::uint64_t> overflows_{0};
};

}  // namespace mocaplink::io
