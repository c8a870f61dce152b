// Ring: a FIFO of T in one growable array — std::deque's push_back / pop_front / front / index
// without its allocation every few pushes (a deque allocates a new block every 512 bytes pushed,
// for ever). The array doubles when full, so a ring that holds at most N items stops allocating
// once it has held N: the per-frame path then never touches the heap (issue 15).
// Items are kept in insertion order: (*this)[0] is the oldest. A popped item stays in its slot
// until a push overwrites it (move-assigned), so T must be default-constructible and
// move-assignable. Pure; not thread-safe.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

namespace mocaplink::core {

template <typename T>
class Ring {
 public:
  [[nodiscard]] std::size_t size() const noexcept { return size_; }
  [[nodiscard]] bool empty() const noexcept { return size_ == 0; }
  /// Storage allocated (items that fit before the next growth).
  [[nodiscard]] std::size_t capacity() const noexcept { return items_.size(); }

  void push_back(T item) {
    if (size_ == items_.size()) grow();
    items_[(head_ + size_) % items_.size()] = std::move(item);
    ++size_;
  }
  /// Precondition: !empty().
  void pop_front() {
    head_ = (head_ + 1) % items_.size();
    --size_;
  }
  void clear() noexcept {
    head_ = 0;
    size_ = 0;
  }
  /// i-th oldest; precondition: i < size().
  [[nodiscard]] T& operator[](std::size_t i) { return items_[(head_ + i) % items_.size()]; }
  [[nodiscard]] const T& operator[](std::size_t i) const {
    return items_[(head_ + i) % items_.size()];
  }
  [[nodiscard]] const T& front() const { return (*this)[0]; }
  [[nodiscard]] const T& back() const { return (*this)[size_ - 1]; }

 private:
  void grow() {
    std::vector<T> bigger(items_.empty() ? 16 : 2 * items_.size());
    for (std::size_t i = 0; i < size_; ++i) {
      bigger[i] = std::move(items_[(head_ + i) % items_.size()]);
    }
    items_ = std::move(bigger);
    head_ = 0;
  }

  std::vector<T> items_;  // items_.size() is the capacity
  std::size_t head_ = 0;  // index of the oldest item
  std::size_t size_ = 0;
};

}  // namespace mocaplink::core
