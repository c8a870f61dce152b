#include "mocaplink/io/fork_join.hpp"

#include <algorithm>

namespace mocaplink::io {

ForkJoin::ForkJoin(std::size_t max_parts) : max_parts_(std::max<std::size_t>(max_parts, 1)) {}

ForkJoin::~ForkJoin() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  start_.notify_all();
  for (auto& worker : workers_) worker.join();
}

void ForkJoin::run_parts(std::size_t parts, void* task, Trampoline call) {
  parts = std::clamp<std::size_t>(parts, 1, max_parts_);
  if (parts == 1) {
    call(task, 0);
    return;
  }
  // Workers for parts 1 .. parts − 1, started once and kept. A new worker has seen every run
  // before this one (only this thread changes generation_).
  while (workers_.size() + 1 < parts) {
    const std::size_t part = workers_.size() + 1;
    const std::uint64_t seen = generation_;
    workers_.emplace_back([this, part, seen] { work(part, seen); });
  }
  {
    const std::lock_guard lock(mutex_);
    ++generation_;
    parts_ = parts;
    remaining_ = parts - 1;
    task_ = task;
    call_ = call;
  }
  start_.notify_all();
  call(task, 0);
  std::unique_lock lock(mutex_);
  done_.wait(lock, [this] { return remaining_ == 0; });
}

void ForkJoin::work(std::size_t part, std::uint64_t seen) {
  std::unique_lock lock(mutex_);
  while (true) {
    start_.wait(lock, [&] { return stopping_ || generation_ != seen; });
    if (stopping_) return;
    seen = generation_;
    if (part >= parts_) continue;  // this run has fewer parts
    void* task = task_;
    const Trampoline call = call_;
    lock.unlock();
    call(task, part);
    lock.lock();
    if (--remaining_ == 0) done_.notify_one();
  }
}

}  // namespace mocaplink::io
