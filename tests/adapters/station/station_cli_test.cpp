// `mocaplink bodies` and `mocaplink record` through the real binary: JSON summary of a simulated
// source, bad URLs, and record sim → CSV → replay → CSV giving the same frames.
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <variant>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_test_support.hpp"
#include "mocaplink/sources/sim_world.hpp"
#include "mocaplink/wire/recording_csv.hpp"

namespace {

using mocaplink::test::ProcessResult;
using mocaplink::test::read_file;
using mocaplink::test::run_mocaplink;

TEST(BodiesCommand, JsonSummaryOfASimulatedSource) {
  const ProcessResult run =
      run_mocaplink("bodies --source 'sim://?bodies=4&rate_hz=100' --seconds 1 --json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto j =
      nlohmann::json::parse(run.out);  // exactly one object: parse() rejects trailing text
  EXPECT_EQ(j.at("source"), "sim://?bodies=4&rate_hz=100");
  EXPECT_EQ(j.at("connected"), true);
  // Plausibility only (the machine may be loaded): about 100 frames in 1 s at 100 Hz.
  EXPECT_GT(j.at("frame_rate_hz").get<double>(), 50.0);
  EXPECT_LT(j.at("frame_rate_hz").get<double>(), 150.0);
  EXPECT_GT(j.at("frames").get<int>(), 50);
  EXPECT_EQ(j.at("dropped"), 0);
  EXPECT_TRUE(j.at("latency_ms").is_null());  // the simulator reports none
  const auto& bodies = j.at("bodies");
  ASSERT_EQ(bodies.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    const auto& b = bodies[i];
    EXPECT_EQ(b.at("name"), "Body" + std::to_string(i + 1));
    EXPECT_EQ(b.at("tracked"), true);
    ASSERT_EQ(b.at("p_m").size(), 3u);
    EXPECT_GT(b.at("p_m")[2].get<double>(), 0.8);  // flying, z up
    ASSERT_EQ(b.at("q_wxyz").size(), 4u);
    EXPECT_EQ(b.at("frames_tracked"), j.at("frames"));
  }
}

TEST(BodiesCommand, BadUrlIsAClearErrorAndExitOne) {
  const ProcessResult unknown_key =
      run_mocaplink("bodies --source 'sim://?bodys=3' --seconds 1 --json");
  EXPECT_EQ(unknown_key.exit_code, 1);
  EXPECT_NE(unknown_key.err.find("unknown option \"bodys\" for sim://; did you mean \"bodies\"?"),
            std::string::npos)
      << unknown_key.err;
  EXPECT_TRUE(unknown_key.out.empty());
  const ProcessResult scheme = run_mocaplink("bodies --source 'nope://x' --seconds 1");
  EXPECT_EQ(scheme.exit_code, 1);
  EXPECT_NE(scheme.err.find("unknown source scheme \"nope\""), std::string::npos) << scheme.err;
  const ProcessResult missing =
      run_mocaplink("bodies --source replay:///nonexistent/run.csv --seconds 1");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.err.find("cannot open"), std::string::npos) << missing.err;
}

TEST(RecordCommand, SimToCsvToReplayGivesTheSameFrames) {
  // A finite simulation (frames=120) with drops and occlusions, recorded as fast as it runs.
  const std::string sim_url =
      "sim://?bodies=3&rate_hz=1000&frames=120&drop=0.1&occlude=0.3&occlude_s=0.02&seed=5";
  const std::string first = testing::TempDir() + "/station_cli_first.csv";
  const std::string second = testing::TempDir() + "/station_cli_second.csv";
  const ProcessResult record = run_mocaplink("record --source '" + sim_url + "' --out " + first);
  ASSERT_EQ(record.exit_code, 0) << record.err;

  // 1. The file holds exactly the simulator's frames (independent of the reader's writer: the
  //    expected values come from SimWorld, compared at the written precision).
  const std::string text = read_file(first);
  auto parsed = mocaplink::wire::parse_recording(text);
  ASSERT_TRUE(std::holds_alternative<mocaplink::wire::Recording>(parsed))
      << mocaplink::wire::to_string(std::get<mocaplink::wire::RecordingError>(parsed));
  const auto& recording = std::get<mocaplink::wire::Recording>(parsed);
  EXPECT_EQ(recording.header.source, sim_url);
  EXPECT_EQ(recording.header.rate_hz, 1000.0);
  mocaplink::sources::SimOptions config;
  config.bodies = 3;
  config.rate_hz = 1000;
  config.drop = 0.1;
  config.occlude = 0.3;
  config.occlude_s = 0.02;
  config.seed = 5;
  const mocaplink::sources::SimWorld world(config);
  std::size_t k = 0;
  for (std::uint64_t n = 1; n <= 120; ++n) {
    if (world.dropped(n)) continue;
    ASSERT_LT(k, recording.frames.size());
    const auto& got = recording.frames[k++];
    const auto want = world.frame(n);
    ASSERT_EQ(got.frame_number, n);
    EXPECT_NEAR(mocaplink::core::to_seconds(got.capture_time.time_since_epoch()), world.time_s(n),
                1e-9);
    ASSERT_EQ(got.bodies.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i) {
      EXPECT_EQ(got.bodies[i].name, want.bodies[i].name);
      ASSERT_EQ(got.bodies[i].tracked, want.bodies[i].tracked) << "frame " << n << " body " << i;
      if (!want.bodies[i].tracked) continue;
      EXPECT_LT((got.bodies[i].p_world_m - want.bodies[i].p_world_m).cwiseAbs().maxCoeff(), 5.1e-7);
      EXPECT_LT((got.bodies[i].q_world_body.coeffs() - want.bodies[i].q_world_body.coeffs())
                    .cwiseAbs()
                    .maxCoeff(),
                2e-6);
    }
  }
  EXPECT_EQ(k, recording.frames.size());
  EXPECT_LT(k, 120u);                                      // some frames dropped
  EXPECT_NE(text.find(",0,,,,,,,\n"), std::string::npos);  // some occluded rows

  // 2. Replaying it and recording again reproduces every frame: numbers, times, names, tracking
  //    and positions exactly (same text), quaternions to the written precision (the reader
  //    normalises them, which can move the 6th decimal).
  const ProcessResult again =
      run_mocaplink("record --source 'replay://" + first + "?speed=0' --out " + second);
  ASSERT_EQ(again.exit_code, 0) << again.err;
  const std::string replayed = read_file(second);
  EXPECT_EQ(replayed.rfind("# mocaplink recording 1; source=replay://", 0), 0u);
  auto reparsed = mocaplink::wire::parse_recording(replayed);
  ASSERT_TRUE(std::holds_alternative<mocaplink::wire::Recording>(reparsed));
  const auto& copy = std::get<mocaplink::wire::Recording>(reparsed);
  EXPECT_EQ(copy.header.rate_hz, 1000.0);
  ASSERT_EQ(copy.frames.size(), recording.frames.size());
  for (std::size_t f = 0; f < copy.frames.size(); ++f) {
    const auto& a = recording.frames[f];
    const auto& b = copy.frames[f];
    ASSERT_EQ(a.frame_number, b.frame_number);
    ASSERT_EQ(a.capture_time, b.capture_time);
    ASSERT_EQ(a.bodies.size(), b.bodies.size());
    for (std::size_t i = 0; i < a.bodies.size(); ++i) {
      EXPECT_EQ(a.bodies[i].name, b.bodies[i].name);
      ASSERT_EQ(a.bodies[i].tracked, b.bodies[i].tracked);
      if (!a.bodies[i].tracked) continue;
      EXPECT_EQ(a.bodies[i].p_world_m, b.bodies[i].p_world_m) << "frame " << a.frame_number;
      EXPECT_LT((a.bodies[i].q_world_body.coeffs() - b.bodies[i].q_world_body.coeffs())
                    .cwiseAbs()
                    .maxCoeff(),
                2e-6);
    }
  }

  // 3. bodies on the replay sees the same frames and drops.
  const ProcessResult bodies =
      run_mocaplink("bodies --source 'replay://" + first + "?speed=0' --json");
  ASSERT_EQ(bodies.exit_code, 0) << bodies.err;
  const auto j = nlohmann::json::parse(bodies.out);
  EXPECT_EQ(j.at("frames").get<std::size_t>(), k);
  // Drops are the gaps between the first and last delivered frame numbers.
  const std::uint64_t span =
      recording.frames.back().frame_number - recording.frames.front().frame_number + 1;
  EXPECT_EQ(j.at("dropped").get<std::uint64_t>(), span - k);
  EXPECT_EQ(j.at("bodies").size(), 3u);
}

TEST(RecordCommand, SourceThatNeverDeliversExitsTwo) {
  // A recording with a header but no rows: the source finishes without a frame.
  const std::string empty = testing::TempDir() + "/station_cli_empty.csv";
  std::ofstream(empty) << mocaplink::wire::format_recording_header("test", 100.0);
  const std::string out = testing::TempDir() + "/station_cli_empty_out.csv";
  const ProcessResult run = run_mocaplink("record --source 'replay://" + empty + "' --out " + out);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("no frame arrived"), std::string::npos) << run.err;
  const ProcessResult bodies =
      run_mocaplink("bodies --source 'replay://" + empty + "' --seconds 5 --json");
  EXPECT_EQ(bodies.exit_code, 2);
  EXPECT_EQ(nlohmann::json::parse(bodies.out).at("frames"), 0);
}

}  // namespace

namespace {

TEST(RecordCommand, SecondsEndsAnEndlessSource) {
  const std::string out = testing::TempDir() + "/station_cli_seconds.csv";
  const ProcessResult run =
      run_mocaplink("record --source 'sim://?bodies=2&rate_hz=100' --seconds 0.5 --out " + out);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  auto parsed = mocaplink::wire::parse_recording(read_file(out));
  ASSERT_TRUE(std::holds_alternative<mocaplink::wire::Recording>(parsed));
  const auto& recording = std::get<mocaplink::wire::Recording>(parsed);
  EXPECT_EQ(recording.header.source, "sim://?bodies=2&rate_hz=100");
  EXPECT_EQ(recording.header.rate_hz, 100.0);
  EXPECT_GT(recording.frames.size(), 5u);  // ~50; only "it stopped and wrote frames" matters
  EXPECT_EQ(recording.frames.front().frame_number, 1u);
  EXPECT_EQ(recording.frames.front().capture_time.time_since_epoch().count(), 0);  // from frame 1
  EXPECT_NE(run.err.find("frames (0 dropped, 2 bodies)"), std::string::npos) << run.err;
}

}  // namespace
