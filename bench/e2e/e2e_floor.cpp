// bench/e2e floor: the least any bridge can do with the same input, to measure mocaplink against
// (issue 15). It has the daemon's structure and nothing else: it opens the same source as
// `mocaplink run` (the [mocap] source of the e2e receivers' configuration, through the same source
// registry and source thread), hands each frame to a loop thread the same way (the same bounded
// queue, 256 frames, oldest dropped and counted, and one asio::post per batch), and there sends
// one datagram per vehicle on its own connected UDP socket, in the daemon's chunks of 4 vehicles
// and from as many threads as the daemon would use for that many vehicles (io::send_threads_for,
// io::ForkJoin; MOCAPLINK_SEND_THREADS applies alike): a copy of one ODOMETRY frame encoded once at
// start (the same size as mocaplink's), with only time_usec changed to the frame's host capture
// time (core::CaptureTimeMapper, as the bridge stamps it) and the header's system id set to each
// vehicle's (as mocaplink sends it; e2e_receivers --sockets shared tells vehicles apart by it; the
// checksum is left as it is). No tracking, no decimation, no encoding, no logic. A frame that
// waited too long for the loop is skipped, and once the loop is behind a frame with a newer one
// already waiting is superseded, as the daemon does both (core::LateFrames; every frame of the
// e2e source has every body, so a newer frame always has this one's bodies): a loop that cannot
// keep up loses frames the same way in both, and "lost" compares like with like.
// With --listen, each socket also waits for datagrams from its vehicle on the loop, as the daemon's
// UDP links do (an asio async_receive; what arrives is counted and dropped): the floor of a bridge
// that hears its vehicles. The kernel then checks the socket's waiters (the loop's epoll) for every
// datagram sent, which a socket nobody listens on skips (docs/performance.md, issue 15). asio also
// makes the sockets non-blocking, as the daemon's are: a send into a full buffer fails instead of
// waiting (counted, as every failed send is).
// With --shared-socket, the vehicles share one unconnected socket per send thread, and each thread
// sends its vehicles' datagrams with one sendmmsg (each to its vehicle's address): batched sends
// across vehicles, the other way a bridge could use sendmmsg (docs/performance.md).
// Usage: e2e_floor [--listen] [--shared-socket] --config C.toml   (written by e2e_receivers;
// stops on SIGTERM/SIGINT and prints "floor: N frames, M queue overflows, K late frames skipped,
// S frames superseded, F sends failed, ..." on stderr)
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <memory>
#include <regex>
#include <string>
#include <vector>

#include <asio/buffer.hpp>
#include <asio/io_context.hpp>
#include <asio/ip/udp.hpp>
#include <asio/post.hpp>
#include <asio/signal_set.hpp>

#include "mocaplink/core/late_frames.hpp"
#include "mocaplink/core/sender_clock.hpp"
#include "mocaplink/io/bounded_queue.hpp"
#include "mocaplink/io/clock.hpp"
#include "mocaplink/io/fork_join.hpp"
#include "mocaplink/io/send_threads.hpp"
#include "mocaplink/mavlink/frame.hpp"
#include "mocaplink/mavlink/messages.hpp"
#include "mocaplink/sources/registry.hpp"

namespace {

struct Vehicle {
  std::uint16_t port = 0;
  std::uint8_t system_id = 1;
};

struct Config {
  std::string source;
  std::vector<Vehicle> vehicles;  // in the file's order: one per udp://127.0.0.1 link
};

Config read_config(const std::string& path) {
  Config c;
  std::ifstream in(path);
  const std::regex source(R"re(^source = "(.*)"$)re");
  const std::regex link(R"re(^link = "udp://127\.0\.0\.1:(\d+)"$)re");
  const std::regex system_id(R"re(^system_id = (\d+)$)re");
  std::smatch m;
  for (std::string line; std::getline(in, line);) {
    if (std::regex_match(line, m, source)) c.source = m[1];
    if (std::regex_match(line, m, link)) {
      c.vehicles.push_back(Vehicle{static_cast<std::uint16_t>(std::stoi(m[1]))});
    }
    if (std::regex_match(line, m, system_id) && !c.vehicles.empty()) {  // after its link line
      c.vehicles.back().system_id = static_cast<std::uint8_t>(std::stoi(m[1]));
    }
  }
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  bool listen = false;
  bool shared = false;
  for (int i = 1; i + 2 < argc; ++i) {
    listen = listen || std::string(argv[i]) == "--listen";
    shared = shared || std::string(argv[i]) == "--shared-socket";
  }
  if (argc != 3 + (listen ? 1 : 0) + (shared ? 1 : 0) ||
      std::string(argv[argc - 2]) != "--config") {
    std::fprintf(stderr, "usage: e2e_floor [--listen] [--shared-socket] --config C.toml\n");
    return 1;
  }
  const Config config = read_config(argv[argc - 1]);
  if (config.source.empty() || config.vehicles.empty()) {
    std::fprintf(stderr, "e2e_floor: no source or no udp://127.0.0.1 links in %s\n",
                 argv[argc - 1]);
    return 1;
  }
  std::vector<int> sockets;
  std::vector<sockaddr_in> addresses;
  for (const Vehicle& vehicle : config.vehicles) {
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(vehicle.port);
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    addresses.push_back(addr);
    if (shared) continue;
    const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
    if (fd < 0 || ::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
      std::perror("e2e_floor: socket");
      return 1;
    }
    sockets.push_back(fd);
  }
  const std::size_t vehicle_count = config.vehicles.size();
  asio::io_context loop;
  // --listen: the sockets in the loop's reactor, each with a receive pending (sends stay ::send,
  // now non-blocking).
  struct Listener {
    explicit Listener(asio::io_context& loop) : socket(loop) {}
    asio::ip::udp::socket socket;
    std::array<std::uint8_t, 512> buffer{};
  };
  std::vector<std::unique_ptr<Listener>> listeners;
  std::uint64_t heard = 0;
  std::function<void(Listener&)> receive = [&](Listener& l) {
    l.socket.async_receive(asio::buffer(l.buffer), [&](const std::error_code& error, std::size_t) {
      if (error == asio::error::operation_aborted) return;
      if (!error) ++heard;
      receive(l);
    });
  };
  if (listen) {
    for (const int fd : sockets) {
      listeners.push_back(std::make_unique<Listener>(loop));
      listeners.back()->socket.assign(asio::ip::udp::v4(), fd);  // it owns (closes) fd now
      receive(*listeners.back());
    }
  }
  // One ODOMETRY as mocaplink's px4 profile fills it (quality and estimator type set, so the
  // payload is not truncated more than the bridge's), encoded once.
  mocaplink::mavlink::Odometry odometry{};
  odometry.quality = 100;
  odometry.estimator_type = 3;
  const mocaplink::mavlink::Frame frame =
      mocaplink::mavlink::encode(odometry, mocaplink::mavlink::FrameHeader{0, 1, 197});
  std::array<std::uint8_t, mocaplink::mavlink::kMaxFrameSize> datagram{};
  std::memcpy(datagram.data(), frame.bytes().data(), frame.size());
  const std::size_t size = frame.size();

  auto opened = mocaplink::sources::builtin_sources().open(config.source);
  if (auto* error = std::get_if<std::string>(&opened)) {
    std::fprintf(stderr, "e2e_floor: %s\n", error->c_str());
    return 1;
  }
  auto source = std::move(std::get<0>(opened));
  auto guard = asio::make_work_guard(loop);
  asio::signal_set signals(loop, SIGINT, SIGTERM);
  signals.async_wait([&](const std::error_code&, int) {
    source->stop();
    guard.reset();
    loop.stop();
  });
  mocaplink::core::CaptureTimeMapper mapper;
  struct Queued {
    mocaplink::core::SourceTime capture;
    std::optional<mocaplink::core::Duration> latency;
    mocaplink::core::HostTime received;
    mocaplink::core::HostTime queued;  // handed to the loop (how late the loop is)
  };
  mocaplink::io::BoundedQueue<Queued> queue(256);  // run_daemon.cpp's kQueueCapacity
  std::vector<Queued> batch;
  std::string warning;
  mocaplink::io::ForkJoin pool(mocaplink::io::max_send_threads(&warning));
  if (!warning.empty()) std::fprintf(stderr, "e2e_floor: %s\n", warning.c_str());
  const std::size_t threads = mocaplink::io::send_threads_for(vehicle_count, pool.max_parts());
  std::vector<std::array<std::uint8_t, mocaplink::mavlink::kMaxFrameSize>> datagrams(threads,
                                                                                     datagram);
  // --shared-socket: one unconnected socket per send thread, each thread's vehicles in one
  // sendmmsg (a datagram per vehicle, its own copy for its system id, sent to its address).
  std::vector<int> part_sockets;
  std::vector<std::array<std::uint8_t, mocaplink::mavlink::kMaxFrameSize>> per_vehicle;
  std::vector<std::vector<mmsghdr>> part_messages(threads);
  std::vector<iovec> iovecs(vehicle_count);
  if (shared) {
    per_vehicle.assign(vehicle_count, datagram);
    for (std::size_t part = 0; part < threads; ++part) {
      const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
      if (fd < 0) {
        std::perror("e2e_floor: socket");
        return 1;
      }
      part_sockets.push_back(fd);
    }
    for (std::size_t v = 0; v < vehicle_count; ++v) {
      per_vehicle[v][5] = config.vehicles[v].system_id;
      iovecs[v] = iovec{per_vehicle[v].data(), size};
    }
  }
  if (listen && shared) {
    for (const int fd : part_sockets) {
      listeners.push_back(std::make_unique<Listener>(loop));
      listeners.back()->socket.assign(asio::ip::udp::v4(), fd);
      receive(*listeners.back());
    }
  }
  std::uint64_t frames = 0;
  std::atomic<std::uint64_t> failed_sends{0};  // refused by the OS (a full buffer, an ICMP error)
  mocaplink::core::LateFrames late;   // late and superseded frames are skipped, as in the daemon
  mocaplink::core::MocapFrame stamp;  // what LateFrames reads of a frame: its capture time
  const mocaplink::core::MocapFrame no_bodies;  // supersedes any of the source's frames
  const auto drain = [&] {
    batch.clear();
    queue.drain(batch);
    if (batch.empty()) return;
    for (const Queued& f : batch) {
      stamp.capture_time = f.capture;
      late.observe(stamp);
    }
    late.begin_batch(batch.front().queued, mocaplink::io::host_now());  // as run_daemon.cpp does
    for (std::size_t i = 0; i < batch.size(); ++i) {
      const Queued& f = batch[i];
      if (i + 1 < batch.size() &&
          late.skip_if_superseded(no_bodies, f.received, no_bodies, batch[i + 1].received)) {
        continue;
      }
      if (late.skip_if_late(f.received, mocaplink::io::host_now())) continue;  // as the daemon does
      ++frames;
      const std::uint64_t time_usec =
          mocaplink::core::host_time_usec(mapper.on_frame(f.capture, f.received, f.latency));
      pool.run(threads, [&](std::size_t part) {
        constexpr std::size_t kChunk = 4;
        if (shared) {
          auto& messages = part_messages[part];
          messages.clear();
          for (std::size_t first = part * kChunk; first < vehicle_count;
               first += threads * kChunk) {
            for (std::size_t v = first; v < std::min(first + kChunk, vehicle_count); ++v) {
              for (std::size_t b = 0; b < 8; ++b) {
                per_vehicle[v][10 + b] = static_cast<std::uint8_t>(time_usec >> (8 * b));
              }
              mmsghdr m{};
              m.msg_hdr.msg_name = &addresses[v];
              m.msg_hdr.msg_namelen = sizeof(sockaddr_in);
              m.msg_hdr.msg_iov = &iovecs[v];
              m.msg_hdr.msg_iovlen = 1;
              messages.push_back(m);
            }
          }
          for (std::size_t k = 0; k < messages.size();) {
            const auto n = std::min<std::size_t>(messages.size() - k, 1024);
            const int done =
                ::sendmmsg(part_sockets[part], messages.data() + k, static_cast<unsigned>(n), 0);
            if (done <= 0) {
              failed_sends.fetch_add(1, std::memory_order_relaxed);
              ++k;
            } else {
              k += static_cast<std::size_t>(done);
            }
          }
          return;
        }
        auto& bytes = datagrams[part];
        for (std::size_t b = 0; b < 8; ++b) {
          bytes[10 + b] = static_cast<std::uint8_t>(time_usec >> (8 * b));
        }
        // The daemon's chunks: 4 vehicles, chunk i on thread i mod threads.
        for (std::size_t first = part * kChunk; first < sockets.size(); first += threads * kChunk) {
          for (std::size_t v = first; v < std::min(first + kChunk, sockets.size()); ++v) {
            bytes[5] = config.vehicles[v].system_id;
            if (::send(sockets[v], bytes.data(), size, 0) < 0) {
              failed_sends.fetch_add(1, std::memory_order_relaxed);
            }
          }
        }
      });
    }
    late.end_batch(mocaplink::io::host_now());
  };
  source->start(
      [&](mocaplink::core::MocapFrame f, mocaplink::core::HostTime received) {
        if (queue.push(
                Queued{f.capture_time, f.source_latency, received, mocaplink::io::host_now()})) {
          asio::post(loop, drain);
        }
      },
      [](mocaplink::sources::SourceState, const std::string&) {});
  loop.run();
  std::fprintf(
      stderr,
      "floor: %llu frames, %llu queue overflows, %llu late frames skipped, %llu frames "
      "superseded, %llu sends failed, %zu-byte datagrams, %zu threads%s\n",
      static_cast<unsigned long long>(frames), static_cast<unsigned long long>(queue.overflows()),
      static_cast<unsigned long long>(late.skipped()),
      static_cast<unsigned long long>(late.superseded()),
      static_cast<unsigned long long>(failed_sends.load()), size, threads,
      listen ? (", listening (" + std::to_string(heard) + " datagrams heard)").c_str() : "");
  return 0;
}
