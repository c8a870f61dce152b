// A DashboardServer on 127.0.0.1:<free port> over a FakeBackend, and helpers to talk JSON to it.
#pragma once

#include <memory>
#include <string>

// Eigen (via the core headers) before httplib.h: httplib pulls in <resolv.h>, whose `_res` macro
// breaks Eigen's headers when they come after it.
#include "fake_backend.hpp"
#include "mocaplink/web/dashboard_server.hpp"

#include <gtest/gtest.h>
#include <httplib.h>
#include <nlohmann/json.hpp>

namespace mocaplink::web::testing {

class ApiTest : public ::testing::Test {
 protected:
  /// Starts the server; tests that need other settings call it again after stop().
  void start(DashboardServerConfig config = {}) {
    config.port = 0;
    server_ = std::make_unique<DashboardServer>(backend_, config);
    const auto error = server_->start();
    ASSERT_FALSE(error.has_value()) << *error;
    client_ = std::make_unique<httplib::Client>("127.0.0.1", server_->port());
    client_->set_read_timeout(10, 0);
  }
  void SetUp() override { start(); }
  void TearDown() override {
    client_.reset();
    if (server_) server_->stop();
  }

  httplib::Result get(const std::string& path, const httplib::Headers& headers = {}) {
    return client_->Get(path.c_str(), headers);
  }
  httplib::Result post(const std::string& path, const std::string& body,
                       const httplib::Headers& headers = {}) {
    return client_->Post(path.c_str(), headers, body, "application/json");
  }
  httplib::Result patch(const std::string& path, const std::string& body,
                        const httplib::Headers& headers = {}) {
    return client_->Patch(path.c_str(), headers, body, "application/json");
  }
  httplib::Result del(const std::string& path, const httplib::Headers& headers = {}) {
    return client_->Delete(path.c_str(), headers);
  }
  static nlohmann::json body_json(const httplib::Result& result) {
    return nlohmann::json::parse(result->body);
  }

  FakeBackend backend_;
  std::unique_ptr<DashboardServer> server_;
  std::unique_ptr<httplib::Client> client_;
};

}  // namespace mocaplink::web::testing
