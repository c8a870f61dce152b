#include "mocaplink/web/dashboard_client.hpp"

#include <httplib.h>

namespace mocaplink::web {
namespace {

/// Where a client reaches a server listening on `host`: the loopback address of its family when
/// it listens on every interface.
std::string reachable_host(const std::string& host) {
  if (host.empty() || host == "0.0.0.0") return "127.0.0.1";
  if (host == "::") return "::1";
  return host;
}

std::optional<HttpAnswer> answer_of(const httplib::Result& result, std::string& error) {
  if (!result) {
    error = httplib::to_string(result.error());
    return std::nullopt;
  }
  return HttpAnswer{result->status, result->body};
}

}  // namespace

struct DashboardClient::Impl {
  Impl(const std::string& host, int port) : client(host, port) {}
  httplib::Client client;
};

DashboardClient::DashboardClient(const config::HttpSettings& http,
                                 std::chrono::milliseconds timeout) {
  const std::string host = reachable_host(http.listen.host);
  const bool v6 = host.find(':') != std::string::npos;
  address_ = "http://" + (v6 ? "[" + host + "]" : host) + ":" + std::to_string(http.listen.port);
  impl_ = std::make_unique<Impl>(host, http.listen.port);
  impl_->client.set_connection_timeout(timeout);
  impl_->client.set_read_timeout(timeout);
  impl_->client.set_write_timeout(timeout);
  if (!http.token.empty()) impl_->client.set_bearer_token_auth(http.token);
}

DashboardClient::~DashboardClient() = default;

std::optional<HttpAnswer> DashboardClient::get(const std::string& path, std::string& error) {
  return answer_of(impl_->client.Get(path), error);
}

std::optional<HttpAnswer> DashboardClient::post_json(const std::string& path,
                                                     const std::string& body, std::string& error) {
  return answer_of(impl_->client.Post(path, body, "application/json"), error);
}

}  // namespace mocaplink::web
