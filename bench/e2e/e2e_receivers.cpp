// bench/e2e receivers: N UDP "vehicles" on loopback for `mocaplink run`. Binds N sockets, writes a
// run configuration (sim:// source at --mocap-hz, one px4 vehicle per socket at --rate-hz, bodies
// shared round-robin), then counts every ODOMETRY per socket and its latency: the kernel's receive
// time of the datagram (SO_TIMESTAMPNS: when it reached the socket, as a vehicle's network stack
// would have it) − the frame's time_usec (the pose's capture time on the bridge's steady clock,
// CLOCK_MONOTONIC: docs/performance.md "End to end"; the kernel stamps CLOCK_REALTIME, turned
// into CLOCK_MONOTONIC with the two clocks' offset read at each poll).
// The receivers stand in for vehicles, which are other machines: to cost the machine under test as
// little as they can, they never sleep on the sockets (a sender waking a receiver per datagram
// would pay the wake-up inside its send) but poll every --poll-ms and read whatever arrived with
// recvmmsg. The kernel's timestamps make the latency independent of the polling.
// With --sockets shared, 250 vehicles share a socket (a large receive buffer, read in batches of
// 64; the configuration refuses one system id twice on a link), and a datagram's vehicle is told
// by its socket and the system id in its MAVLink header: vehicle i (from 0) sends to socket
// i div 250 with system_id i mod 250 + 1 (the floor stamps the ids too). For hundreds of vehicles
// this costs the machine a fraction of N sockets' polling (one recvmmsg per 64 datagrams, not one
// per socket that has anything), so what is measured is the bridge. mocaplink warns at start that
// the vehicles share links.
// Stops when nothing has arrived for --idle-s after the first datagram (the bridge was stopped),
// and prints one JSON line.
// Usage: e2e_receivers --vehicles N --config OUT.toml [--seconds 30] [--rate-hz 240]
//                      [--mocap-hz 240] [--bodies 64] [--source URL] [--http ADDR]
//                      [--first-address 127.0.0.2] [--report-s S] [--idle-s 1.5] [--poll-ms 2]
//                      [--sockets each|shared]
// --source replaces the sim:// source, --http adds a dashboard, --first-address binds vehicle 1 to
// another loopback address (bench/soak black-holes it), --report-s also prints one JSON line every
// S seconds with what arrived in that interval (bench/soak), --idle-s is the silence that ends it
// (--first-address needs --sockets each).
#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <sys/epoll.h>
#include <sys/socket.h>
#include <sys/uio.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

std::int64_t clock_ns(clockid_t clock) {
  timespec ts{};
  ::clock_gettime(clock, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

std::int64_t monotonic_us() {
  return clock_ns(CLOCK_MONOTONIC) / 1000;
}

/// CLOCK_REALTIME − CLOCK_MONOTONIC now (ns): the kernel stamps datagrams on the first.
std::int64_t realtime_minus_monotonic_ns() {
  const std::int64_t before = clock_ns(CLOCK_MONOTONIC);
  const std::int64_t real = clock_ns(CLOCK_REALTIME);
  const std::int64_t after = clock_ns(CLOCK_MONOTONIC);
  return real - (before + (after - before) / 2);
}

double percentile(std::vector<std::int64_t>& v, double p) {
  if (v.empty()) return 0.0;
  const auto k = static_cast<std::size_t>(p * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return static_cast<double>(v[k]);
}

}  // namespace

int main(int argc, char** argv) {
  int vehicles = 1;
  double seconds = 30.0;
  double rate_hz = 240.0;
  double mocap_hz = 240.0;
  int bodies = 64;
  std::string config_path;
  std::string source;
  std::string http;
  std::string first_address = "127.0.0.1";
  double report_s = 0.0;
  double idle_s = 1.5;
  double poll_ms = 2.0;
  std::string sockets_mode = "each";
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    const char* value = argv[i + 1];
    if (key == "--vehicles") vehicles = std::atoi(value);
    if (key == "--seconds") seconds = std::atof(value);
    if (key == "--rate-hz") rate_hz = std::atof(value);
    if (key == "--mocap-hz") mocap_hz = std::atof(value);
    if (key == "--bodies") bodies = std::atoi(value);
    if (key == "--config") config_path = value;
    if (key == "--source") source = value;
    if (key == "--http") http = value;
    if (key == "--first-address") first_address = value;
    if (key == "--report-s") report_s = std::atof(value);
    if (key == "--idle-s") idle_s = std::atof(value);
    if (key == "--poll-ms") poll_ms = std::atof(value);
    if (key == "--sockets") sockets_mode = value;
  }
  const bool shared = sockets_mode == "shared";
  constexpr int kPerSocket = 250;  // system ids 1..250 on one socket
  if (!shared && sockets_mode != "each") {
    std::fprintf(stderr, "--sockets is each or shared, not %s\n", sockets_mode.c_str());
    return 1;
  }
  if (shared && first_address != "127.0.0.1") {
    std::fprintf(stderr, "--first-address needs --sockets each\n");
    return 1;
  }
  if (vehicles < 1 || config_path.empty()) {
    std::fprintf(stderr, "usage: e2e_receivers --vehicles N --config OUT.toml [...]\n");
    return 1;
  }
  bodies = std::min(bodies, vehicles);
  const int epoll = ::epoll_create1(0);
  std::vector<int> sockets;
  std::FILE* config = std::fopen(config_path.c_str(), "w");
  if (config == nullptr) return 1;
  if (source.empty()) {
    std::fprintf(config, "[mocap]\nsource = \"sim://?bodies=%d&rate_hz=%g\"\n", bodies, mocap_hz);
  } else {
    std::fprintf(config, "[mocap]\nsource = \"%s\"\n", source.c_str());
  }
  if (!http.empty()) std::fprintf(config, "[http]\nlisten = \"%s\"\n", http.c_str());
  std::uint16_t port = 0;  // the port of vehicle i's socket
  for (int i = 0; i < vehicles; ++i) {
    if (!shared || i % kPerSocket == 0) {
      const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK, 0);
      const int buffer = shared ? 64 << 20 : 1 << 20;
      // Beyond net.core.rmem_max only with CAP_NET_ADMIN (root); else what the system allows.
      if (!shared || ::setsockopt(fd, SOL_SOCKET, SO_RCVBUFFORCE, &buffer, sizeof buffer) != 0) {
        ::setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &buffer, sizeof buffer);
      }
      const int on = 1;
      if (::setsockopt(fd, SOL_SOCKET, SO_TIMESTAMPNS, &on, sizeof on) != 0) {
        std::perror("SO_TIMESTAMPNS");
        return 1;
      }
      sockaddr_in addr{};
      addr.sin_family = AF_INET;
      addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
      if (i == 0 && ::inet_pton(AF_INET, first_address.c_str(), &addr.sin_addr) != 1) {
        std::fprintf(stderr, "bad --first-address %s\n", first_address.c_str());
        return 1;
      }
      socklen_t len = sizeof addr;
      if (::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 ||
          ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) != 0) {
        std::perror("bind");
        return 1;
      }
      epoll_event ev{};
      ev.events = EPOLLIN;
      ev.data.u32 = static_cast<std::uint32_t>(sockets.size());
      ::epoll_ctl(epoll, EPOLL_CTL_ADD, fd, &ev);
      sockets.push_back(fd);
      port = ntohs(addr.sin_port);
    }
    std::fprintf(config,
                 "[[vehicle]]\nname = \"v%d\"\nbody = \"Body%d\"\nlink = \"udp://%s:%d\"\n"
                 "system_id = %d\nprofile = \"px4\"\nrate_hz = %g\n",
                 i + 1, i % bodies + 1, i == 0 ? first_address.c_str() : "127.0.0.1", port,
                 i % kPerSocket + 1, rate_hz);
  }
  std::fclose(config);
  std::printf("ready\n");
  std::fflush(stdout);

  std::vector<std::uint64_t> odometry(static_cast<std::size_t>(vehicles), 0);
  std::vector<std::int64_t> latencies_us;
  // The first and the last vehicle's own latencies: the first shows what comes before any
  // vehicle's send, the difference what each vehicle before the last adds (docs/performance.md).
  std::vector<std::int64_t> first_vehicle_us;
  std::vector<std::int64_t> last_vehicle_us;
  if (report_s <= 0.0) {
    latencies_us.reserve(static_cast<std::size_t>(vehicles * rate_hz * seconds * 1.1));
  }
  std::array<epoll_event, 1024> events{};
  constexpr std::size_t kBatch = 64;
  std::array<std::array<std::uint8_t, 2048>, kBatch> buffers{};
  std::array<std::array<char, CMSG_SPACE(sizeof(timespec))>, kBatch> controls{};
  std::array<iovec, kBatch> iov{};
  std::array<mmsghdr, kBatch> msgs{};
  std::int64_t first_us = 0;
  std::int64_t last_us = 0;
  const auto idle_us = static_cast<std::int64_t>(idle_s * 1e6);
  const auto report_us = static_cast<std::int64_t>(report_s * 1e6);
  std::int64_t next_report_us = monotonic_us() + report_us;
  std::vector<std::uint64_t> interval_odometry(static_cast<std::size_t>(vehicles), 0);
  std::vector<std::int64_t> interval_latencies_us;
  while (first_us == 0 || monotonic_us() - last_us < idle_us) {
    if (report_us > 0 && monotonic_us() >= next_report_us) {
      next_report_us += report_us;
      std::uint64_t sum = 0;
      for (const auto c : interval_odometry) sum += c;
      const double v1 = static_cast<double>(interval_odometry[0]);
      const double q50 = percentile(interval_latencies_us, 0.50);
      const double q99 = percentile(interval_latencies_us, 0.99);
      const double qmax = interval_latencies_us.empty()
                              ? 0.0
                              : static_cast<double>(*std::max_element(interval_latencies_us.begin(),
                                                                      interval_latencies_us.end()));
      std::printf(
          "{\"interval\":true,\"odometry\":%llu,\"vehicle1\":%.0f,"
          "\"latency_us\":{\"p50\":%.0f,\"p99\":%.0f,\"max\":%.0f}}\n",
          static_cast<unsigned long long>(sum), v1, q50, q99, qmax);
      std::fflush(stdout);
      std::fill(interval_odometry.begin(), interval_odometry.end(), 0);
      interval_latencies_us.clear();
    }
    // Sleep, then read whatever arrived (no wake-up per datagram: see the header).
    const timespec pause{0, static_cast<long>(poll_ms * 1e6)};
    ::nanosleep(&pause, nullptr);
    const std::int64_t offset_ns = realtime_minus_monotonic_ns();
    while (true) {
      const int n = ::epoll_wait(epoll, events.data(), static_cast<int>(events.size()), 0);
      if (n <= 0) break;
      for (int e = 0; e < n; ++e) {
        const std::uint32_t socket = events[static_cast<std::size_t>(e)].data.u32;
        while (true) {
          for (std::size_t m = 0; m < kBatch; ++m) {
            iov[m] = iovec{buffers[m].data(), buffers[m].size()};
            msgs[m].msg_hdr = msghdr{};
            msgs[m].msg_hdr.msg_iov = &iov[m];
            msgs[m].msg_hdr.msg_iovlen = 1;
            msgs[m].msg_hdr.msg_control = controls[m].data();
            msgs[m].msg_hdr.msg_controllen = controls[m].size();
          }
          const int got = ::recvmmsg(sockets[socket], msgs.data(), kBatch, MSG_DONTWAIT, nullptr);
          if (got <= 0) break;
          const std::int64_t now_us = monotonic_us();
          if (first_us == 0) first_us = now_us;
          last_us = now_us;
          for (int m = 0; m < got; ++m) {
            const auto& buffer = buffers[static_cast<std::size_t>(m)];
            const std::size_t size = msgs[static_cast<std::size_t>(m)].msg_len;
            // MAVLink 2 ODOMETRY (id 331): time_usec is the first payload field (uint64 LE, at 10).
            if (size < 18 || buffer[0] != 0xFD) continue;
            const std::uint32_t msgid = std::uint32_t{buffer[7]} | (std::uint32_t{buffer[8]} << 8) |
                                        (std::uint32_t{buffer[9]} << 16);
            if (msgid != 331) continue;
            // The vehicle: its socket, or a shared socket's and its system id.
            std::size_t v = socket;
            if (shared) {
              if (buffer[5] < 1) continue;
              v = std::size_t{socket} * std::size_t{kPerSocket} + std::size_t{buffer[5]} - 1;
              if (v >= odometry.size()) continue;
            }
            std::uint64_t time_usec = 0;
            for (std::size_t b = 0; b < 8; ++b) {
              time_usec |= std::uint64_t{buffer[10 + b]} << (8 * b);
            }
            // The kernel's receive time; without one (never expected) the read time.
            std::int64_t received_us = now_us;
            msghdr& header = msgs[static_cast<std::size_t>(m)].msg_hdr;
            for (cmsghdr* c = CMSG_FIRSTHDR(&header); c != nullptr; c = CMSG_NXTHDR(&header, c)) {
              if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SCM_TIMESTAMPNS) {
                timespec ts{};
                std::memcpy(&ts, CMSG_DATA(c), sizeof ts);
                const std::int64_t real_ns =
                    static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
                received_us = (real_ns - offset_ns) / 1000;
              }
            }
            ++odometry[v];
            const std::int64_t latency_us = received_us - static_cast<std::int64_t>(time_usec);
            if (report_us > 0) {  // an hour of samples would not fit: per interval only
              ++interval_odometry[v];
              interval_latencies_us.push_back(latency_us);
            } else {
              latencies_us.push_back(latency_us);
              if (v == 0) first_vehicle_us.push_back(latency_us);
              if (v + 1 == odometry.size()) last_vehicle_us.push_back(latency_us);
            }
          }
          if (static_cast<std::size_t>(got) < kBatch) break;
        }
      }
      if (n < static_cast<int>(events.size())) break;
    }
  }
  std::uint64_t total = 0;
  std::uint64_t min_v = odometry[0];
  for (const auto c : odometry) {
    total += c;
    min_v = std::min(min_v, c);
  }
  const double max_latency =
      latencies_us.empty()
          ? 0.0
          : static_cast<double>(*std::max_element(latencies_us.begin(), latencies_us.end()));
  const double p50 = percentile(latencies_us, 0.50);
  const double p99 = percentile(latencies_us, 0.99);
  seconds = static_cast<double>(last_us - first_us) / 1e6;
  std::printf(
      "{\"vehicles\":%d,\"seconds\":%.1f,\"odometry\":%llu,\"min_per_vehicle\":%llu,"
      "\"latency_us\":{\"p50\":%.0f,\"p99\":%.0f,\"max\":%.0f},"
      "\"first_vehicle_p50_us\":%.0f,\"last_vehicle_p50_us\":%.0f}\n",
      vehicles, seconds, static_cast<unsigned long long>(total),
      static_cast<unsigned long long>(min_v), p50, p99, max_latency,
      percentile(first_vehicle_us, 0.50), percentile(last_vehicle_us, 0.50));
  return 0;
}
