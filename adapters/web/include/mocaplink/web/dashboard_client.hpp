// A client of a running daemon's dashboard API (docs/api.md), for the CLI: `mocaplink vehicle
// setup` reads and applies through `mocaplink run` when it owns the vehicle's link, instead of
// opening that link a second time (a udpin:// port or a bound udp:// port can have one owner, and
// a PX4 answers one address).
//
// Blocking, one request at a time; not thread-safe. Talks plain HTTP to the address the config's
// [http] listen names (an unspecified address, 0.0.0.0 or ::, is reached on loopback), with the
// config's token when it has one.
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <string>

#include "mocaplink/config/config.hpp"

namespace mocaplink::web {

struct HttpAnswer {
  int status = 0;
  std::string body;
};

class DashboardClient {
 public:
  DashboardClient(const config::HttpSettings& http, std::chrono::milliseconds timeout);
  ~DashboardClient();
  DashboardClient(const DashboardClient&) = delete;
  DashboardClient& operator=(const DashboardClient&) = delete;

  /// "http://127.0.0.1:8080", as messages name it.
  [[nodiscard]] const std::string& address() const noexcept { return address_; }

  /// GET `path`. nullopt, with `error` saying why, when nothing answered (refused, timed out).
  [[nodiscard]] std::optional<HttpAnswer> get(const std::string& path, std::string& error);
  /// POST `path` with a JSON body (Content-Type: application/json).
  [[nodiscard]] std::optional<HttpAnswer> post_json(const std::string& path,
                                                    const std::string& body, std::string& error);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string address_;
};

}  // namespace mocaplink::web
