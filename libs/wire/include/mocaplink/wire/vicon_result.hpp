// Expected-like result of the Vicon DataStream parsers: a value or a ParseError (byte offset +
// reason). Never throws; reading value() of an error (or error() of a value) is a programming
// error and aborts via the variant's checked access being avoided by the callers' ok() test.
#pragma once

#include <cstdlib>
#include <string>
#include <utility>
#include <variant>

#include "mocaplink/wire/byte_reader.hpp"

namespace mocaplink::wire::vicon {

template <typename T>
class [[nodiscard]] Result {
 public:
  Result(T value) : v_(std::move(value)) {}           // NOLINT(google-explicit-constructor)
  Result(ParseError error) : v_(std::move(error)) {}  // NOLINT(google-explicit-constructor)

  [[nodiscard]] bool ok() const { return v_.index() == 0; }
  explicit operator bool() const { return ok(); }

  /// The value; aborts when !ok() (programming error).
  [[nodiscard]] T& value() & { return checked<T>(); }
  [[nodiscard]] const T& value() const& { return checked<T>(); }
  [[nodiscard]] T&& value() && { return std::move(checked<T>()); }
  /// The error; aborts when ok() (programming error).
  [[nodiscard]] const ParseError& error() const { return checked<ParseError>(); }

 private:
  template <typename U>
  U& checked() {
    U* p = std::get_if<U>(&v_);
    if (p == nullptr) std::abort();
    return *p;
  }
  template <typename U>
  const U& checked() const {
    const U* p = std::get_if<U>(&v_);
    if (p == nullptr) std::abort();
    return *p;
  }

  std::variant<T, ParseError> v_;
};

/// A ParseError at `offset` with `reason`.
[[nodiscard]] inline ParseError parse_error(std::size_t offset, std::string reason) {
  return ParseError{offset, std::move(reason)};
}

}  // namespace mocaplink::wire::vicon
