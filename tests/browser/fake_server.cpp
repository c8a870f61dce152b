// web_fake_server [--token TOKEN]: the dashboard server on 127.0.0.1:<free port> over the tests'
// FakeBackend, its lab moving in real time. Prints "listening on PORT" once it accepts
// connections, and exits when its standard input closes (the test that started it went away).
#include <chrono>
#include <cstdio>
#include <iostream>
#include <string>

#include "fake_backend.hpp"
#include "mocaplink/web/dashboard_server.hpp"

namespace {

using mocaplink::web::testing::FakeBackend;

// The fake's time follows the steady clock, so bodies move and counters grow live.
class LiveBackend final : public mocaplink::web::DashboardBackend {
 public:
  mocaplink::web::StatusView status() override {
    fake_.set_time(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count());
    return fake_.status();
  }
  std::optional<mocaplink::web::ApiError> apply(
      const mocaplink::web::VehicleChange& change) override {
    fake_.set_time(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count());
    return fake_.apply(change);
  }

 private:
  FakeBackend fake_;
  const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace

int main(int argc, char** argv) {
  mocaplink::web::DashboardServerConfig config;
  config.port = 0;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::string(argv[i]) == "--token") config.token = argv[i + 1];
  }
  LiveBackend backend;
  mocaplink::web::DashboardServer server(backend, config);
  if (auto error = server.start()) {
    std::fprintf(stderr, "web_fake_server: %s\n", error->c_str());
    return 2;
  }
  std::printf("listening on %u\n", static_cast<unsigned>(server.port()));
  std::fflush(stdout);
  while (std::cin.get() != EOF) {
  }
  server.stop();
  return 0;
}
