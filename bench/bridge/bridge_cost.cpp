// Per-frame CPU cost of the bridge's core (issue 14: sizing a Raspberry Pi for N vehicles).
//
//   bridge_cost [--frames N] [--repetitions R] [--only-vehicles N --only-sending 0|1 [--signing 0]]
//   bridge_cost --tick N
//
// --tick N: the clock-driven side instead (issue 50): N vehicles sending, none of them heard, 300
// calls of Bridge::on_tick 100 ms apart (the daemon's cadence) and a BridgeSnapshot every tenth:
// the thread CPU time of each, median and largest, and the messages a tick returns to be sent
// (their sends are not in the figure).
//
// --only-*: one run of one case and no table, for an instruction count of Bridge::on_frame with
// valgrind --tool=callgrind --toggle-collect='mocaplink::core::Bridge::on_frame*'; --signing 0
// leaves the vehicles unsigned, as bench/e2e's are.
//
// For N = 1, 4, 16 and 64 vehicles, each following its own rigid body in 240 Hz frames (every body
// in every frame, slow circles): the thread CPU time of Bridge::on_frame per frame,
//   * "tracking": vehicles disabled (every body filtered, nothing built or sent), and
//   * "sending": vehicles sending ODOMETRY (profile px4) at 240 Hz, i.e. one message per vehicle
//     per frame, signed with a key;
// the difference divided by the messages is the cost of one vehicle message (build, encode, sign).
// Medians of R repetitions. Prints a Markdown table (docs/performance.md).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "mocaplink/core/bridge.hpp"

namespace mc = mocaplink::core;

namespace {

constexpr double kFrameRateHz = 240.0;

double thread_cpu_ns() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e9 + static_cast<double>(ts.tv_nsec);
}

mc::BridgeConfig make_config(std::size_t vehicles, bool sending, bool signing = true) {
  mc::BridgeConfig config;
  config.origin = mc::GeodeticPosition{47.3977, 8.5456, 488.0};
  for (std::size_t i = 0; i < vehicles; ++i) {
    mc::VehicleSpec v;
    v.name = "v" + std::to_string(i);
    v.body = "Body" + std::to_string(i);
    v.system_id = static_cast<std::uint8_t>(i % 250 + 1);  // ids repeat beyond 250 vehicles
    v.rate_hz = kFrameRateHz;
    v.enabled = sending;
    if (signing) v.signing_key = std::array<std::uint8_t, 32>{};
    config.vehicles.push_back(v);
  }
  return config;
}

mc::MocapFrame make_frame(std::size_t vehicles, std::uint64_t n) {
  mc::MocapFrame frame;
  frame.frame_number = n;
  const double t = static_cast<double>(n) / kFrameRateHz;
  frame.capture_time = mc::source_time_from_ns(static_cast<std::int64_t>(t * 1e9));
  frame.frame_rate_hz = kFrameRateHz;
  for (std::size_t i = 0; i < vehicles; ++i) {
    mc::BodySample b;
    b.name = "Body" + std::to_string(i);
    b.tracked = true;
    const double phase = t * 0.5 + static_cast<double>(i);
    b.p_world_m = {std::cos(phase), std::sin(phase), 1.0 + 0.1 * static_cast<double>(i % 4)};
    b.q_world_body = Eigen::Quaterniond(Eigen::AngleAxisd(phase, Eigen::Vector3d::UnitZ()));
    frame.bodies.push_back(b);
  }
  return frame;
}

struct Result {
  double ns_per_frame = 0;
  double messages_per_frame = 0;
};

Result run(std::size_t vehicles, bool sending, std::uint64_t frames, bool signing = true) {
  // Frames are built before timing: the adapter's parsing is not part of this figure.
  std::vector<mc::MocapFrame> input;
  input.reserve(frames);
  for (std::uint64_t n = 0; n < frames; ++n) input.push_back(make_frame(vehicles, n));
  auto made = mc::Bridge::make(make_config(vehicles, sending, signing), mc::host_time_from_ns(0));
  auto& bridge = std::get<mc::Bridge>(made);
  // Host receive time = capture time + 2 ms; a warm-up second is not timed.
  const auto received = [](std::uint64_t n) {
    return mc::host_time_from_ns(
        static_cast<std::int64_t>(static_cast<double>(n) / kFrameRateHz * 1e9) + 2'000'000);
  };
  const std::uint64_t warmup = std::min<std::uint64_t>(frames / 4, 240);
  for (std::uint64_t n = 0; n < warmup; ++n) (void)bridge.on_frame(input[n], received(n));
  std::size_t messages = 0;
  const double start = thread_cpu_ns();
  for (std::uint64_t n = warmup; n < frames; ++n) {
    messages += bridge.on_frame(input[n], received(n)).messages.size();
  }
  const double elapsed = thread_cpu_ns() - start;
  const auto timed = static_cast<double>(frames - warmup);
  return {elapsed / timed, static_cast<double>(messages) / timed};
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

void run_ticks(std::size_t vehicles) {
  auto made = mc::Bridge::make(make_config(vehicles, true), mc::host_time_from_ns(0));
  auto& bridge = std::get<mc::Bridge>(made);
  constexpr int kTicks = 300;
  std::vector<double> ticks;
  std::vector<double> snapshots;
  std::size_t messages = 0;
  for (int k = 1; k <= kTicks; ++k) {
    const auto now = mc::host_time_from_ns(std::int64_t{k} * 100'000'000);
    const double start = thread_cpu_ns();
    messages += bridge.on_tick(now).messages.size();
    ticks.push_back(thread_cpu_ns() - start);
    if (k % 10 == 0) {
      const double before = thread_cpu_ns();
      (void)bridge.snapshot(now);
      snapshots.push_back(thread_cpu_ns() - before);
    }
  }
  std::printf(
      "%zu vehicles: on_tick median %.0f us, at most %.0f us, %.1f messages a tick; snapshot "
      "median %.0f us, at most %.0f us\n",
      vehicles, median(ticks) / 1e3, *std::max_element(ticks.begin(), ticks.end()) / 1e3,
      static_cast<double>(messages) / kTicks, median(snapshots) / 1e3,
      *std::max_element(snapshots.begin(), snapshots.end()) / 1e3);
}

}  // namespace

int main(int argc, char** argv) {
  std::uint64_t frames = 4800;  // 20 s at 240 Hz
  int repetitions = 7;
  long only_vehicles = 0;
  int only_sending = 1;
  int signing = 1;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string_view arg = argv[i];
    if (arg == "--frames") frames = std::strtoull(argv[i + 1], nullptr, 10);
    if (arg == "--repetitions") repetitions = std::atoi(argv[i + 1]);
    if (arg == "--only-vehicles") only_vehicles = std::atol(argv[i + 1]);
    if (arg == "--only-sending") only_sending = std::atoi(argv[i + 1]);
    if (arg == "--signing") signing = std::atoi(argv[i + 1]);
    if (arg == "--tick") {
      run_ticks(static_cast<std::size_t>(std::strtoul(argv[i + 1], nullptr, 10)));
      return 0;
    }
  }
  if (only_vehicles > 0) {
    const Result r =
        run(static_cast<std::size_t>(only_vehicles), only_sending != 0, frames, signing != 0);
    std::printf("%ld vehicles, %s%s: %.0f ns/frame, %.2f messages/frame\n", only_vehicles,
                only_sending != 0 ? "sending" : "tracking", signing != 0 ? "" : ", unsigned",
                r.ns_per_frame, r.messages_per_frame);
    return 0;
  }
  std::printf(
      "| vehicles | tracking ns/frame | sending ns/frame | messages/frame | ns/message |"
      " CPU at 240 Hz |\n|---|---|---|---|---|---|\n");
  for (const std::size_t vehicles : {1u, 4u, 16u, 64u}) {
    std::vector<double> tracking, sending, per_message;
    double messages = 0;
    for (int r = 0; r < repetitions; ++r) {
      const Result t = run(vehicles, false, frames);
      const Result s = run(vehicles, true, frames);
      tracking.push_back(t.ns_per_frame);
      sending.push_back(s.ns_per_frame);
      messages = s.messages_per_frame;
      per_message.push_back(s.messages_per_frame > 0
                                ? (s.ns_per_frame - t.ns_per_frame) / s.messages_per_frame
                                : 0.0);
    }
    const double send_ns = median(sending);
    std::printf("| %zu | %.0f | %.0f | %.2f | %.0f | %.2f %% |\n", vehicles, median(tracking),
                send_ns, messages, median(per_message), send_ns * kFrameRateHz / 1e7);
  }
  return 0;
}
