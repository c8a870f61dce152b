// vrpn_rounds: the emulator on 127.0.0.1 publishes Body1 at 100 Hz and Body2 at 50 Hz (every
// other update), the vrpn:// client reads them; for each delivered frame, how long after the
// update was published it reached the sink, and how old its `received` time says it is. Rounds
// holding both bodies and rounds holding Body1 alone are counted apart.
//
//   vrpn_rounds [SECONDS]      (default 10)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "mocaplink/io/clock.hpp"
#include "mocaplink/sources/vrpn_server.hpp"
#include "mocaplink/sources/vrpn_source.hpp"

using namespace mocaplink;
using Ms = std::chrono::duration<double, std::milli>;

namespace {

core::MocapFrame update(std::uint64_t n, bool with_body2) {
  core::MocapFrame f;
  f.frame_number = n;
  f.capture_time = core::source_time_from_ns(static_cast<std::int64_t>(n) * 10'000'000);
  core::BodySample b1;
  b1.name = "Body1";
  b1.tracked = true;
  b1.p_world_m = Eigen::Vector3d(0.001 * static_cast<double>(n), 0, 1);
  f.bodies.push_back(b1);
  if (with_body2) {
    core::BodySample b2 = b1;
    b2.name = "Body2";
    f.bodies.push_back(b2);
  }
  return f;
}

void print(const char* what, std::vector<double> ms) {
  if (ms.empty()) {
    std::printf("%-34s none\n", what);
    return;
  }
  std::sort(ms.begin(), ms.end());
  const auto at = [&](double q) {
    return ms[static_cast<std::size_t>(q * static_cast<double>(ms.size() - 1))];
  };
  std::printf("%-34s n=%5zu  median %6.3f  p95 %6.3f  p99 %6.3f  max %6.3f ms\n", what, ms.size(),
              at(0.5), at(0.95), at(0.99), ms.back());
}

}  // namespace

int main(int argc, char** argv) {
  const int seconds = argc > 1 ? std::atoi(argv[1]) : 10;
  sources::VrpnServerOptions so;
  so.listen_host = "127.0.0.1";
  so.port = 0;
  sources::VrpnServer server(so);
  if (auto err = server.start({})) {
    std::fprintf(stderr, "serve: %s\n", err->c_str());
    return 1;
  }
  sources::VrpnSourceOptions co;
  co.target.host = "127.0.0.1";
  co.target.port = server.port();
  sources::VrpnSource client(co, "vrpn://127.0.0.1");

  std::mutex mutex;
  std::map<std::uint64_t, core::HostTime> published;  // update number → publish time
  std::vector<double> full_late, full_age, single_late, single_age;
  bool connected = false;
  client.start(
      [&](core::MocapFrame frame, core::HostTime received) {
        const auto now = io::host_now();
        const std::lock_guard lock(mutex);
        for (const auto& b : frame.bodies) {
          if (b.name != "Body1") continue;
          const auto n = static_cast<std::uint64_t>(std::llround(b.p_world_m.x() / 0.001));
          const auto it = published.find(n);
          if (it == published.end()) return;
          const bool full = frame.bodies.size() == 2;
          (full ? full_late : single_late).push_back(Ms(now - it->second).count());
          (full ? full_age : single_age).push_back(Ms(now - received).count());
        }
      },
      [&](sources::SourceState s, const std::string&) {
        const std::lock_guard lock(mutex);
        if (s == sources::SourceState::connected) connected = true;
      });
  for (int i = 0; i < 500; ++i) {  // until the client's cookie is in
    {
      const std::lock_guard lock(mutex);
      if (connected) break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  auto next = std::chrono::steady_clock::now();
  for (std::uint64_t n = 1; n <= static_cast<std::uint64_t>(seconds) * 100; ++n) {
    std::this_thread::sleep_until(next);
    next += std::chrono::milliseconds(10);
    {
      const std::lock_guard lock(mutex);
      published[n] = io::host_now();
    }
    server.publish(update(n, n % 2 == 0));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  client.stop();
  server.stop();
  const std::lock_guard lock(mutex);
  std::printf("Body1 at 100 Hz, Body2 at 50 Hz, %d s over 127.0.0.1\n", seconds);
  std::printf("publish -> sink (how late the round is delivered):\n");
  print("  rounds with Body1 and Body2", full_late);
  print("  rounds with Body1 alone", single_late);
  std::printf("received -> sink (the age the frame reports when delivered):\n");
  print("  rounds with Body1 and Body2", full_age);
  print("  rounds with Body1 alone", single_age);
  return 0;
}
