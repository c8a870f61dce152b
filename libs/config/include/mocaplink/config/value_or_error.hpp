// A value or a human-readable reason why there is none: the result type of the small parsers in
// this library (axes, URLs, addresses). Expected failures are returned, never thrown.
#pragma once

#include <cassert>
#include <optional>
#include <string>
#include <utility>

namespace mocaplink::config {

/// Either a parsed value or an error message (one sentence, no trailing period, suitable for
/// "FILE:LINE:COL: key: <message>"). Thread-safety: a plain value type.
template <typename T>
class [[nodiscard]] ValueOrError {
 public:
  ValueOrError(T value) : value_(std::move(value)) {}  // NOLINT(google-explicit-constructor)
  static ValueOrError failure(std::string error) { return ValueOrError(std::move(error), 0); }

  [[nodiscard]] bool ok() const { return value_.has_value(); }
  explicit operator bool() const { return ok(); }
  /// The value; calling this on a failure is a programming error (asserts).
  [[nodiscard]] const T& value() const& {
    assert(value_.has_value());
    return *value_;
  }
  [[nodiscard]] T&& value() && {
    assert(value_.has_value());
    return std::move(*value_);
  }
  /// The reason; empty when ok().
  [[nodiscard]] const std::string& error() const { return error_; }

 private:
  ValueOrError(std::string error, int /*tag*/) : error_(std::move(error)) {}
  std::optional<T> value_;
  std::string error_;
};

}  // namespace mocaplink::config
