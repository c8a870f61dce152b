// Bounds-checked little/big-endian reader over untrusted bytes. Every parser of outside bytes reads
// through this (STYLE.md "Errors"): no pointer walks, no reads past the end. A failed read leaves
// the reader unchanged and returns std::nullopt; callers turn that into a ParseError with offset().
#pragma once

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <span>
#include <string>
#include <type_traits>

namespace mocaplink::wire {

enum class Endian { little, big };

/// Why a parser rejected its input, and where (byte offset from the start of the buffer).
struct ParseError {
  std::size_t offset = 0;
  std::string reason;
};

class ByteReader {
 public:
  explicit ByteReader(std::span<const std::byte> bytes) : bytes_(bytes) {}

  [[nodiscard]] std::size_t offset() const { return offset_; }
  [[nodiscard]] std::size_t remaining() const { return bytes_.size() - offset_; }
  [[nodiscard]] bool empty() const { return remaining() == 0; }

  /// Reads an arithmetic value (integer, float or double) in the given byte order.
  template <typename T>
  [[nodiscard]] std::optional<T> read(Endian order = Endian::little) {
    static_assert(std::is_arithmetic_v<T>);
    if (remaining() < sizeof(T)) return std::nullopt;
    std::array<std::byte, sizeof(T)> raw{};
    std::memcpy(raw.data(), bytes_.data() + offset_, sizeof(T));
    const bool native_little = std::endian::native == std::endian::little;
    if ((order == Endian::little) != native_little) {
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
    }
    T value{};
    std::memcpy(&value, raw.data(), sizeof(T));
    offset_ += sizeof(T);
    return value;
  }

  /// The next `n` bytes as a sub-span, or nullopt if fewer remain.
  [[nodiscard]] std::optional<std::span<const std::byte>> bytes(std::size_t n) {
    if (remaining() < n) return std::nullopt;
    auto out = bytes_.subspan(offset_, n);
    offset_ += n;
    return out;
  }

  /// Skips `n` bytes; false (and no movement) if fewer remain.
  [[nodiscard]] bool skip(std::size_t n) {
    if (remaining() < n) return false;
    offset_ += n;
    return true;
  }

  /// A string of exactly `n` bytes (not NUL-terminated on the wire).
  [[nodiscard]] std::optional<std::string> string(std::size_t n) {
    auto raw = bytes(n);
    if (!raw) return std::nullopt;
    return std::string(reinterpret_cast<const char*>(raw->data()), raw->size());
  }

  /// A NUL-terminated string; nullopt if no NUL occurs before the end or within `max_len` bytes.
  [[nodiscard]] std::optional<std::string> cstring(std::size_t max_len);

 private:
  std::span<const std::byte> bytes_;
  std::size_t offset_ = 0;
};

/// View any contiguous byte-like buffer as std::byte.
inline std::span<const std::byte> as_bytes(const void* data, std::size_t size) {
  return {static_cast<const std::byte*>(data), size};
}

}  // namespace mocaplink::wire
