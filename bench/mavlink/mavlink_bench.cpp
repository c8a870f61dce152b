// MAVLink codec throughput, one core (issue 2 targets: 2× the official C library).
//   encode HIL_GPS, encode ODOMETRY        encode_into a reused buffer (header, fields, truncation,
//                                          CRC), seq advancing per frame
//   parse mixed stream                     StreamParser.feed over a stream of 8 message types
//                                          (framing + CRC + typed decode of every frame)
//   parse + verify signed stream           the same with every frame signed and checked by a
//                                          SignatureVerifier (SHA-256, replay state)
// items_per_second = messages/s.
#include <benchmark/benchmark.h>

#include <vector>

#include "mocaplink/mavlink/frame.hpp"
#include "mocaplink/mavlink/sequence.hpp"
#include "mocaplink/mavlink/stream_parser.hpp"

namespace {

namespace mav = mocaplink::mavlink;

mav::HilGps sample_hil_gps() {
  mav::HilGps m;
  m.time_usec = 1'700'000'000'123'456;
  m.lat = 473'977'418;
  m.lon = 85'455'938;
  m.alt = 488'000;
  m.eph = 100;
  m.epv = 150;
  m.vel = 123;
  m.vn = 100;
  m.ve = -50;
  m.vd = -5;
  m.cog = 27'000;
  m.fix_type = 3;
  m.satellites_visible = 12;
  m.id = 1;
  m.yaw = 9'000;
  return m;
}

mav::Odometry sample_odometry() {
  mav::Odometry m;
  m.time_usec = 1'700'000'000'523'456;
  m.x = 0.5F;
  m.y = -1.25F;
  m.z = -0.8F;
  m.q = {0.9238795F, 0.0F, 0.0F, 0.3826834F};
  m.vx = 0.1F;
  m.vy = -0.05F;
  m.vz = 0.02F;
  m.rollspeed = 0.001F;
  m.pitchspeed = -0.002F;
  m.yawspeed = 0.05F;
  for (std::size_t i = 0; i < 21; ++i) {
    m.pose_covariance[i] = 1e-4F * static_cast<float>(i + 1);
    m.velocity_covariance[i] = 1e-3F * static_cast<float>(i + 1);
  }
  m.frame_id = 20;
  m.child_frame_id = 12;
  m.reset_counter = 1;
  m.estimator_type = 3;
  m.quality = 100;
  return m;
}

template <typename M>
void encode_loop(benchmark::State& state, const M& msg) {
  std::array<std::uint8_t, mav::kMaxFrameSize> buffer{};
  mav::SequenceCounter seq(1, 197);
  for (auto _ : state) {
    benchmark::DoNotOptimize(msg);
    const std::size_t n = mav::encode_into(msg, seq.next(), buffer);
    benchmark::DoNotOptimize(n);
    benchmark::DoNotOptimize(buffer.data());
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_EncodeHilGps(benchmark::State& state) {
  encode_loop(state, sample_hil_gps());
}
void BM_EncodeOdometry(benchmark::State& state) {
  encode_loop(state, sample_odometry());
}

constexpr std::size_t kStreamFrames = 1000;

// A vehicle-like mix: telemetry from the autopilot plus what a bridge sends.
std::vector<std::uint8_t> mixed_stream(const mav::SigningKey* key) {
  std::vector<std::uint8_t> out;
  mav::SequenceCounter seq(1, 1);
  std::uint64_t ts = 1'000'000;
  for (std::size_t i = 0; i < kStreamFrames; ++i) {
    mav::Frame f;
    const mav::SignParams sign{key, 0, ts++};
    const mav::SignParams* s = key != nullptr ? &sign : nullptr;
    const auto h = seq.next();
    switch (i % 8) {
      case 0:
        f = mav::encode(mav::Heartbeat{.custom_mode = 65536, .type = 2, .autopilot = 12}, h, s);
        break;
      case 1:
        f = mav::encode(sample_odometry(), h, s);
        break;
      case 2:
        f = mav::encode(sample_hil_gps(), h, s);
        break;
      case 3:
        f = mav::encode(
            mav::Attitude{.time_boot_ms = 1234, .roll = 0.1F, .pitch = 0.2F, .yaw = 0.3F}, h, s);
        break;
      case 4:
        f = mav::encode(mav::Timesync{.tc1 = 0, .ts1 = 123456789, .target_system = 1}, h, s);
        break;
      case 5:
        f = mav::encode(
            mav::GlobalPositionInt{
                .time_boot_ms = 5, .lat = 473977418, .lon = 85455938, .alt = 488000},
            h, s);
        break;
      case 6:
        f = mav::encode(
            mav::LocalPositionNed{.time_boot_ms = 9, .x = 1.5F, .y = -2.25F, .z = -0.1F}, h, s);
        break;
      default:
        f = mav::encode(
            mav::SysStatus{.load = 500, .voltage_battery = 12000, .battery_remaining = 80}, h, s);
        break;
    }
    out.insert(out.end(), f.bytes().begin(), f.bytes().end());
  }
  return out;
}

void parse_loop(benchmark::State& state, const std::vector<std::uint8_t>& stream,
                const mav::SigningKey* key) {
  std::size_t frames = 0;
  for (auto _ : state) {
    // A fresh verifier per pass: the same stream again would be a replay.
    std::optional<mav::SignatureVerifier> verifier;
    if (key != nullptr) verifier.emplace(*key, mav::SignatureVerifier::Options{});
    mav::StreamParser parser(verifier ? &*verifier : nullptr);
    parser.feed(stream, 0, [&](const mav::FrameView& f) {
      auto msg = mav::decode_message(f);
      benchmark::DoNotOptimize(msg);
      ++frames;
    });
  }
  const auto passes = static_cast<std::size_t>(state.iterations());
  if (frames != passes * kStreamFrames) state.SkipWithError("frames were dropped");
  state.SetItemsProcessed(static_cast<std::int64_t>(frames));
  state.SetBytesProcessed(static_cast<std::int64_t>(passes * stream.size()));
}

void BM_ParseMixedStream(benchmark::State& state) {
  static const auto stream = mixed_stream(nullptr);
  parse_loop(state, stream, nullptr);
}

void BM_ParseVerifySignedStream(benchmark::State& state) {
  static const mav::SigningKey key(std::array<std::uint8_t, 32>{1, 2, 3, 4, 5, 6, 7, 8});
  static const auto stream = mixed_stream(&key);
  parse_loop(state, stream, &key);
}

BENCHMARK(BM_EncodeHilGps);
BENCHMARK(BM_EncodeOdometry);
BENCHMARK(BM_ParseMixedStream);
BENCHMARK(BM_ParseVerifySignedStream);

}  // namespace

BENCHMARK_MAIN();
