// The ros2:// link against a scripted PX4 on real DDS over loopback: a second participant plays
// PX4's uXRCE-DDS side (its Agent's writers of vehicle_status and vehicle_odometry, its reader of
// vehicle_visual_odometry). The payload offsets checked here are PX4's (ros2-dds.md §4), the
// VehicleStatus bytes are written by hand in v1.14's layout; a Cyclone DDS reader of the same
// topic is tests/apps/run's job.
#include "mocaplink/ros2/px4_link.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <mutex>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "dds.hpp"
#include "mocaplink/io/clock.hpp"
#include "mocaplink/mavlink/frame.hpp"
#include "mocaplink/wire/px4_messages.hpp"

namespace mocaplink::ros2 {
namespace {

using namespace std::chrono_literals;

/// v1.14's VehicleStatus (88-byte payload): timestamp, armed_time, takeoff_time, arming_state
/// at 24, nav_state at 41; the rest zero.
std::vector<std::uint8_t> vehicle_status_v114(std::uint64_t boot_us, bool armed,
                                              std::uint8_t nav_state) {
  std::vector<std::uint8_t> s(4 + 88, 0);
  s[1] = 0x01;  // CDR_LE
  std::memcpy(s.data() + 4, &boot_us, 8);
  s[4 + 24] = armed ? 2 : 1;
  s[4 + 41] = nav_state;
  return s;
}

template <typename T>
T payload_at(const std::vector<std::uint8_t>& sample, std::size_t offset) {
  T v{};
  std::memcpy(&v, sample.data() + 4 + offset, sizeof v);
  return v;
}

TEST(Px4Link, HeardArmedAndPosesAsVehicleOdometry) {
  const auto domain = static_cast<std::uint32_t>(60 + getpid() % 100);
  std::string error;
  auto px4 = detail::make_participant({domain, "loopback", "fake_px4"}, error);
  ASSERT_TRUE(px4) << error;
  std::mutex mutex;
  std::vector<std::vector<std::uint8_t>> poses;  // what "PX4" received
  detail::ReaderSettings in;
  in.topic = "rt/px4_1/fmu/in/vehicle_visual_odometry";
  in.type = std::string(wire::kPx4VehicleOdometryType);
  in.max_sample_bytes = 118;
  in.on_sample = [&](std::span<const std::uint8_t> s) {
    const std::lock_guard lock(mutex);
    poses.emplace_back(s.begin(), s.end());
  };
  auto pose_reader = px4->make_reader(in, error);
  ASSERT_TRUE(pose_reader) << error;
  detail::WriterSettings status_out;
  status_out.topic = "rt/px4_1/fmu/out/vehicle_status";
  status_out.type = std::string(wire::kPx4VehicleStatusType);
  status_out.max_sample_bytes = 1024;
  auto status_writer = px4->make_writer(status_out, error);
  ASSERT_TRUE(status_writer) << error;
  detail::WriterSettings odom_out;
  odom_out.topic = "rt/px4_1/fmu/out/vehicle_odometry";
  odom_out.type = std::string(wire::kPx4VehicleOdometryType);
  odom_out.max_sample_bytes = 118;
  auto odom_writer = px4->make_writer(odom_out, error);
  ASSERT_TRUE(odom_writer) << error;

  asio::io_context loop;
  io::LinkOptions options;
  options.name = "q1";
  auto link = make_px4_link(loop, {"px4_1", domain, "loopback", 2}, options);
  std::vector<mavlink::Message> heard;
  link->start(
      [&](const mavlink::FrameView& f, core::HostTime) {
        EXPECT_EQ(f.sysid, 2);
        if (auto m = mavlink::decode_message(f)) heard.push_back(*m);
      },
      {});
  EXPECT_EQ(link->state(), io::TransportState::up);
  EXPECT_EQ(link->url(), "ros2://px4_1");

  // PX4's estimate: at (1, 2, -3) NED, yawed 90° (nose east).
  wire::Px4VehicleOdometry estimate;
  estimate.timestamp = 61'000'000;
  estimate.pose_frame = wire::Px4VehicleOdometry::kFrameNed;
  estimate.position = {1, 2, -3};
  estimate.q = {0.70710678F, 0, 0, 0.70710678F};
  estimate.velocity_frame = wire::Px4VehicleOdometry::kFrameNed;
  std::vector<std::uint8_t> estimate_sample;
  wire::encode_px4_vehicle_odometry(estimate, estimate_sample);

  mavlink::Odometry pose;
  pose.frame_id = 20;        // MAV_FRAME_LOCAL_FRD, as the px4 profile sends
  pose.child_frame_id = 12;  // MAV_FRAME_BODY_FRD
  pose.x = 0.5F;
  pose.q = {1, 0, 0, 0};
  pose.reset_counter = 4;
  pose.quality = 90;
  const auto deadline = std::chrono::steady_clock::now() + 15s;
  auto has_all = [&] {
    bool hb = false, att = false, pos = false;
    for (const auto& m : heard) {
      hb = hb || std::holds_alternative<mavlink::Heartbeat>(m);
      att = att || std::holds_alternative<mavlink::Attitude>(m);
      pos = pos || std::holds_alternative<mavlink::LocalPositionNed>(m);
    }
    const std::lock_guard lock(mutex);
    return hb && att && pos && poses.size() >= 3;
  };
  while (!has_all() && std::chrono::steady_clock::now() < deadline) {
    ASSERT_TRUE(status_writer->write(vehicle_status_v114(61'000'000, true, 2)));
    ASSERT_TRUE(odom_writer->write(estimate_sample));
    const core::HostTime capture = io::host_now() - 7ms;
    pose.time_usec = static_cast<std::uint64_t>(
        std::chrono::duration_cast<std::chrono::microseconds>(capture.time_since_epoch()).count());
    const mavlink::Frame frame = mavlink::encode(pose, mavlink::FrameHeader{0, 1, 197});
    EXPECT_TRUE(link->send(frame.bytes()));
    // A heartbeat has no DDS counterpart: taken, not sent.
    EXPECT_TRUE(link->send(mavlink::encode(mavlink::Heartbeat{}, {0, 1, 197}).bytes()));
    std::this_thread::sleep_for(50ms);  // the DDS threads post what they received
    loop.restart();
    loop.poll();
  }
  ASSERT_TRUE(has_all()) << "heard " << heard.size() << " frames, PX4 got " << [&] {
    const std::lock_guard lock(mutex);
    return poses.size();
  }() << " poses";
  for (const auto& m : heard) {
    if (const auto* hb = std::get_if<mavlink::Heartbeat>(&m)) {
      EXPECT_EQ(hb->autopilot, 12);                        // MAV_AUTOPILOT_PX4
      EXPECT_NE(hb->base_mode & 128, 0);                   // MAV_MODE_FLAG_SAFETY_ARMED
      EXPECT_EQ(hb->custom_mode, std::uint32_t{3} << 16);  // POSCTL
    } else if (const auto* att = std::get_if<mavlink::Attitude>(&m)) {
      EXPECT_NEAR(att->yaw, 1.5707963, 1e-5);
      EXPECT_NEAR(att->roll, 0, 1e-6);
      EXPECT_EQ(att->time_boot_ms, 61'000U);  // PX4's boot time, so the agreement check settles
    } else if (const auto* p = std::get_if<mavlink::LocalPositionNed>(&m)) {
      EXPECT_EQ(p->x, 1);
      EXPECT_EQ(p->z, -3);
    }
  }
  const std::lock_guard lock(mutex);
  const std::vector<std::uint8_t> last = poses.back();
  ASSERT_EQ(last.size(), 118U);
  EXPECT_EQ(last[1], 0x01);
  // This PX4 stamps what it sends with its boot time (its uXRCE-DDS time sync not running), so
  // its sync cannot be judged: the poses go stamped 0, which PX4 stamps on their arrival
  // (core/dds_time_sync.hpp; capture stamps are run.px4_dds's, against wall-clock stamps).
  EXPECT_EQ(payload_at<std::uint64_t>(last, 0), 0U);
  EXPECT_EQ(payload_at<std::uint64_t>(last, 8), 0U);
  const auto clock = link->clock();
  ASSERT_TRUE(clock);
  EXPECT_EQ(clock->pose_stamps, core::DdsPoseStamps::arrival);
  EXPECT_NE(clock->text.find("not judged yet"), std::string::npos) << clock->text;
  EXPECT_EQ(payload_at<std::uint8_t>(last, 16), 2);  // POSE_FRAME_FRD
  EXPECT_EQ(payload_at<float>(last, 20), 0.5F);
  EXPECT_EQ(payload_at<float>(last, 32), 1.0F);      // q w
  EXPECT_EQ(payload_at<std::uint8_t>(last, 48), 3);  // VELOCITY_FRAME_BODY_FRD
  EXPECT_EQ(payload_at<std::uint8_t>(last, 112), 4);
  EXPECT_EQ(payload_at<std::int8_t>(last, 113), 90);
  EXPECT_GE(link->counters().frames_sent, 3U);
  link->close();
}

}  // namespace
}  // namespace mocaplink::ros2
