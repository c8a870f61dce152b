// Issue 15: no allocation on the per-frame path. Once warmed up, Bridge::on_frame into a kept
// BridgeOutput must not touch the heap, for every profile (every message kind), signed or not,
// decimated or not, with a body going in and out of tracking — except for the text of an event
// (a state change) in the frame that reports it. This executable replaces the global operator new
// to count allocations (its own binary: the replacement is process-wide).
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <new>
#include <string>
#include <variant>
#include <vector>

#include <gtest/gtest.h>

#include "mocaplink/core/bridge.hpp"

namespace {
std::atomic<std::size_t> g_allocations{0};
}  // namespace

// GCC sees the standard allocator's inlined delete call free() a pointer from operator new and
// warns; here both are ours and pair malloc with free.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif

void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}

namespace mocaplink::core {
namespace {

constexpr double kRateHz = 240.0;
constexpr std::size_t kBodies = 6;

MocapFrame make_frame(std::uint64_t n) {
  MocapFrame frame;
  frame.frame_number = n;
  const double t = static_cast<double>(n) / kRateHz;
  frame.capture_time = source_time_from_ns(static_cast<std::int64_t>(t * 1e9));
  frame.frame_rate_hz = kRateHz;
  for (std::size_t i = 0; i < kBodies; ++i) {
    BodySample b;
    b.name = "Body" + std::to_string(i + 1);
    // Body 1 is occluded for 0.5 s of every 2 s (lost, then back: tracking events and resets).
    b.tracked = !(i == 0 && std::fmod(t, 2.0) > 1.5);
    const double phase = t * 0.5 + static_cast<double>(i);
    b.p_world_m = {std::cos(phase), std::sin(phase), 1.0 + 0.1 * static_cast<double>(i)};
    b.q_world_body = Eigen::Quaterniond(Eigen::AngleAxisd(phase, Eigen::Vector3d::UnitZ()));
    frame.bodies.push_back(b);
  }
  return frame;
}

TEST(BridgeAllocation, OnFrameAllocatesNothingOnceWarm) {
  BridgeConfig config;
  config.origin = GeodeticPosition{47.3977, 8.5456, 488.0};
  // One vehicle per profile (custom: every message kind), half of them signed.
  const std::vector<Profile> profiles = {Profile::px4,     Profile::ardupilot,
                                         Profile::px4_gps, Profile::ardupilot_gps,
                                         Profile::classic, Profile::custom};
  for (std::size_t i = 0; i < profiles.size(); ++i) {
    VehicleSpec v;
    v.name = "v" + std::to_string(i + 1);
    v.body = "Body" + std::to_string(i % kBodies + 1);
    v.system_id = static_cast<std::uint8_t>(i + 1);
    v.profile = profiles[i];
    if (profiles[i] == Profile::custom) {
      for (const auto& row : kMessages) v.messages.push_back(row.kind);
    }
    v.rate_hz = i % 2 == 0 ? kRateHz : 50.0;  // every frame, and decimated
    if (i % 2 == 1) v.signing_key = std::array<std::uint8_t, 32>{};
    config.vehicles.push_back(v);
  }
  auto made = Bridge::make(config, host_time_from_ns(0));
  ASSERT_TRUE(std::holds_alternative<Bridge>(made)) << std::get<BridgeConfigError>(made).message;
  auto& bridge = std::get<Bridge>(made);
  bridge.set_wall_clock(host_time_from_ns(0), 1'790'000'000'000'000);

  // 30 s of frames, built before counting (a source's frame is its own allocation).
  std::vector<MocapFrame> frames;
  for (std::uint64_t n = 0; n < 30 * 240; ++n) frames.push_back(make_frame(n));
  const auto received = [](std::size_t n) {
    return host_time_from_ns(static_cast<std::int64_t>(static_cast<double>(n) / kRateHz * 1e9) +
                             2'000'000);
  };
  BridgeOutput out;
  // Warm-up: 4 s, two occlusion cycles (every body seen, lost and back at least once).
  const std::size_t warm = 4 * 240;
  for (std::size_t n = 0; n < warm; ++n) bridge.on_frame(frames[n], received(n), out);

  std::size_t messages = 0;
  std::size_t events = 0;
  std::size_t quiet_frame_allocations = 0;  // in frames that reported no event
  std::size_t event_allocations = 0;        // in frames that did
  for (std::size_t n = warm; n < frames.size(); ++n) {
    const std::size_t before = g_allocations.load();
    bridge.on_frame(frames[n], received(n), out);
    const std::size_t allocations = g_allocations.load() - before;
    messages += out.messages.size();
    events += out.events.size();
    (out.events.empty() ? quiet_frame_allocations : event_allocations) += allocations;
  }
  EXPECT_GT(messages, 6u * 20 * 50);  // every vehicle sent throughout
  EXPECT_GE(events, 10u);             // body 1's losses and returns were reported
  EXPECT_EQ(quiet_frame_allocations, 0u) << "over " << frames.size() - warm << " frames";
  // An event is a state change (a body lost, a vehicle heard), a few per minute: its text may
  // allocate, nothing else.
  EXPECT_LE(event_allocations, 2 * events);
}

}  // namespace
}  // namespace mocaplink::core
