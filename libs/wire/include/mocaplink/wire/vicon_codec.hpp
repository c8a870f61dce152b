// Field-level encoding of the DataStream primitive types (spec §2): little-endian scalars, bool as
// one byte, string = u32 length + bytes (no terminator), vector/set = u32 count + elements, map =
// u32 count + key,value pairs, fixed arrays without count; structures are their fields in order
// with no padding. One description per structure (a `fields()` tuple of references) drives both
// directions, so encoder and decoder cannot disagree about the order.
//
// Decoding reads through ByteReader and is bounds-checked: every count and length is checked
// against the bytes that remain before anything is allocated, so memory stays proportional to the
// input (each element needs at least one wire byte). Pure; not thread-safe per object.
#pragma once

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <span>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "mocaplink/wire/byte_reader.hpp"

namespace mocaplink::wire::vicon::codec {

/// Appends little-endian values to a byte vector.
class Writer {
 public:
  explicit Writer(std::vector<std::byte>& out) : out_(out) {}

  template <typename T>
  requires std::is_arithmetic_v<T>
  void put(T value) {
    std::array<std::byte, sizeof(T)> raw{};
    std::memcpy(raw.data(), &value, sizeof(T));
    if constexpr (std::endian::native == std::endian::big) {
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(raw[i], raw[sizeof(T) - 1 - i]);
    }
    // resize + memcpy, not insert(end, raw.begin(), raw.end()): on a vector reserved to the
    // exact size, GCC 12 at -O2 and above inlines insert's reallocation path and reports a false
    // -Wstringop-overflow (a file-by-file build of qtm_protocol.cpp showed it).
    const std::size_t at = out_.size();
    out_.resize(at + sizeof(T));
    std::memcpy(out_.data() + at, raw.data(), sizeof(T));
  }

  void put_bytes(std::span<const std::byte> bytes) {
    out_.insert(out_.end(), bytes.begin(), bytes.end());
  }

  /// Overwrites a u32 written earlier at byte `at` (length fields filled in afterwards).
  void patch_u32(std::size_t at, std::uint32_t value) {
    for (std::size_t i = 0; i < 4; ++i) {
      out_[at + i] = static_cast<std::byte>((value >> (8 * i)) & 0xFFu);
    }
  }

  [[nodiscard]] std::size_t size() const { return out_.size(); }

 private:
  std::vector<std::byte>& out_;
};

/// Bounds-checked reader that remembers the first failure (offset + reason).
class Reader {
 public:
  explicit Reader(std::span<const std::byte> bytes, std::size_t base_offset = 0)
      : in_(bytes), base_(base_offset) {}

  template <typename T>
  requires std::is_arithmetic_v<T>
  [[nodiscard]] bool get(T& out, const char* what) {
    auto v = in_.read<T>(Endian::little);
    if (!v) return fail(std::string("truncated ") + what);
    out = *v;
    return true;
  }

  /// A u32 element count that must fit in the remaining bytes (every element is >= 1 byte).
  [[nodiscard]] bool get_count(std::uint32_t& out, const char* what) {
    if (!get(out, what)) return false;
    if (out > in_.remaining()) {
      return fail(std::string(what) + " " + std::to_string(out) + " exceeds the " +
                  std::to_string(in_.remaining()) + " bytes left");
    }
    return true;
  }

  [[nodiscard]] bool get_string(std::string& out, std::uint32_t length) {
    auto s = in_.string(length);
    if (!s) return fail("truncated string");
    out = std::move(*s);
    return true;
  }

  /// Records the first failure; always returns false.
  bool fail(std::string reason) {
    if (!failed_) {
      failed_ = true;
      error_ = ParseError{base_ + in_.offset(), std::move(reason)};
    }
    return false;
  }

  [[nodiscard]] bool failed() const { return failed_; }
  [[nodiscard]] const ParseError& error() const { return error_; }
  [[nodiscard]] std::size_t offset() const { return base_ + in_.offset(); }
  [[nodiscard]] std::size_t remaining() const { return in_.remaining(); }

 private:
  ByteReader in_;
  std::size_t base_;
  bool failed_ = false;
  ParseError error_{};
};

template <typename T>
concept HasFields = requires(T& t) {
  fields(t);
};

// --- encoding -------------------------------------------------------------------------------

inline void write(Writer& w, bool v) {
  w.put<std::uint8_t>(v ? 1 : 0);
}

template <typename T>
requires(std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) void write(Writer& w, T v) {
  w.put(v);
}

inline void write(Writer& w, const std::string& s) {
  w.put(static_cast<std::uint32_t>(s.size()));
  w.put_bytes(std::as_bytes(std::span(s.data(), s.size())));
}

template <typename T, std::size_t N>
void write(Writer& w, const std::array<T, N>& a) {
  for (const auto& e : a) write(w, e);
}

template <typename A, typename B>
void write(Writer& w, const std::pair<A, B>& p) {
  write(w, p.first);
  write(w, p.second);
}

template <typename T>
void write(Writer& w, const std::vector<T>& v) {
  w.put(static_cast<std::uint32_t>(v.size()));
  for (const auto& e : v) write(w, e);
}

template <HasFields T>
void write(Writer& w, const T& s) {
  std::apply([&w](const auto&... f) { (write(w, f), ...); }, fields(s));
}

// --- decoding -------------------------------------------------------------------------------

/// bool: 0 = false, anything else true (the SDK copies the byte into a C++ bool, §2).
inline bool read(Reader& r, bool& out) {
  std::uint8_t b = 0;
  if (!r.get(b, "bool")) return false;
  out = b != 0;
  return true;
}

template <typename T>
requires(std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) bool read(Reader& r, T& out) {
  return r.get(out, "number");
}

inline bool read(Reader& r, std::string& out) {
  std::uint32_t length = 0;
  if (!r.get_count(length, "string length")) return false;
  return r.get_string(out, length);
}

template <typename T, std::size_t N>
bool read(Reader& r, std::array<T, N>& a) {
  for (auto& e : a) {
    if (!read(r, e)) return false;
  }
  return true;
}

template <typename A, typename B>
bool read(Reader& r, std::pair<A, B>& p) {
  return read(r, p.first) && read(r, p.second);
}

template <typename T>
bool read(Reader& r, std::vector<T>& v) {
  std::uint32_t count = 0;
  if (!r.get_count(count, "element count")) return false;
  v.clear();
  // No reserve(count): elements are appended as they parse, so a lying count fails at the first
  // missing element and memory stays proportional to the bytes actually present.
  for (std::uint32_t i = 0; i < count; ++i) {
    T e{};
    if (!read(r, e)) return false;
    v.push_back(std::move(e));
  }
  return true;
}

template <HasFields T>
bool read(Reader& r, T& s) {
  return std::apply([&r](auto&... f) { return (read(r, f) && ...); }, fields(s));
}

}  // namespace mocaplink::wire::vicon::codec

/// Declares the wire field order of a structure (both directions): fields(s) → tuple of refs.
#define MOCAPLINK_VICON_FIELDS(Type, ...)              \
  [[maybe_unused]] inline auto fields(Type& s) {       \
    return std::tie(__VA_ARGS__);                      \
  }                                                    \
  [[maybe_unused]] inline auto fields(const Type& s) { \
    return std::tie(__VA_ARGS__);                      \
  }
