// How many threads send one frame's datagrams (issue 15; docs/daemon.md "Threads"). The daemon and
// the benchmark's floor (bench/e2e) both ask here, so they are measured on the same structure.
//
// Sending is most of what the bridge does per frame: on loopback, each UDP send also delivers the
// datagram, about 2–6 µs on the team machine (docs/performance.md), so 1000 vehicles at 240 Hz
// need more than one core. Waking a worker costs tens of µs, more than a few sends, so a frame is
// sent by one more thread per kVehiclesPerSendThread vehicles, up to the cores the process may
// run on (at most kMaxSendThreads), and small fleets stay on the loop's thread alone.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

namespace mocaplink::io {

inline constexpr std::size_t kVehiclesPerSendThread = 100;
inline constexpr std::size_t kMaxSendThreads = 4;

/// Threads to send to `vehicles` vehicles: ceil(vehicles / kVehiclesPerSendThread) clamped to
/// [1, max_threads] (max_threads 0 counts as 1).
[[nodiscard]] constexpr std::size_t send_threads_for(std::size_t vehicles,
                                                     std::size_t max_threads) noexcept {
  const std::size_t wanted = (vehicles + kVehiclesPerSendThread - 1) / kVehiclesPerSendThread;
  const std::size_t cap = max_threads == 0 ? 1 : max_threads;
  return wanted < 1 ? 1 : (wanted > cap ? cap : wanted);
}

/// The most threads that may send: MOCAPLINK_SEND_THREADS when set (1–64; 1 keeps every send on
/// the loop's thread), else the cores the process may run on (on Linux its CPU affinity: taskset,
/// systemd's CPUAffinity=, a cpuset; elsewhere the machine's cores), at most kMaxSendThreads. A
/// malformed value is ignored with `warning` set to say so.
[[nodiscard]] std::size_t max_send_threads(std::string* warning);

}  // namespace mocaplink::io
