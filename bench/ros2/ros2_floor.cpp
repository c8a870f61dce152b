// bench/ros2 floor: the least any ROS 2 publisher can do with mocaplink's input, to measure
// `mocaplink run`'s [ros2] topics against (issue 46). It opens the same source (through the same
// source registry and source thread), hands each frame to one publishing thread through the same
// kind of bounded queue, and there writes, per tracked body, a PoseStamped and an Odometry sample
// and one TFMessage of every body per frame, on the same topics, type names and QoS through the
// same DDS writer as adapters/ros2 (its internal dds.hpp seam). The samples are encoded once, when
// a body is first seen, with a sentinel stamp; per frame only the stamp fields are overwritten
// with the frame's capture time on the wall clock (CaptureTimeMapper, as the bridge maps it). No
// tracking, no frames, no conversion, no encoding.
//
//   ros2_floor --source URL --domain D [--namespace mocap] [--frame-id world]
//
// Loopback only (interface "loopback", as bench/ros2/run_ros2.sh runs mocaplink). Stops on
// SIGTERM/SIGINT and prints "ros2_floor: N frames, M samples written, E write errors, O queue
// overflows" on stderr.
#include <algorithm>
#include <array>
#include <atomic>
#include <condition_variable>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "../../adapters/ros2/src/dds.hpp"
#include "mocaplink/core/ros.hpp"
#include "mocaplink/core/sender_clock.hpp"
#include "mocaplink/io/clock.hpp"
#include "mocaplink/sources/registry.hpp"
#include "mocaplink/wire/ros2_messages.hpp"

namespace {

namespace core = mocaplink::core;
namespace wire = mocaplink::wire;
namespace dds = mocaplink::ros2::detail;

std::atomic<bool> g_stop{false};
void on_signal(int /*sig*/) {
  g_stop = true;
}

// A stamp no real one equals (1985-02-10): its seconds' four bytes mark every stamp field.
constexpr wire::RosStamp kSentinel{0x1D1D1D1D, 0};

/// The offsets of every stamp in `sample` (the sentinel's seconds, then its nanoseconds).
std::vector<std::size_t> stamp_offsets(const std::vector<std::uint8_t>& sample) {
  std::array<std::uint8_t, 4> mark{};
  std::memcpy(mark.data(), &kSentinel.sec, 4);
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i + 8 <= sample.size(); ++i) {
    if (std::equal(mark.begin(), mark.end(), sample.begin() + static_cast<std::ptrdiff_t>(i))) {
      out.push_back(i);
      i += 7;
    }
  }
  return out;
}

struct Sample {
  std::unique_ptr<dds::Writer> writer;
  std::vector<std::uint8_t> bytes;
  std::vector<std::size_t> stamps;
  void stamp(const wire::RosStamp& s) {
    for (const std::size_t at : stamps) {
      std::memcpy(bytes.data() + at, &s.sec, 4);
      std::memcpy(bytes.data() + at + 4, &s.nanosec, 4);
    }
  }
};

struct Queued {
  core::SourceTime capture;
  std::optional<core::Duration> latency;
  core::HostTime received;
  std::vector<std::string> tracked;  // the names of the bodies tracked in the frame
};

}  // namespace

int main(int argc, char** argv) {
  std::string source_url;
  std::uint32_t domain = 0;
  std::string ns = "mocap";
  std::string frame_id = "world";
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--source") source_url = argv[i + 1];
    if (flag == "--domain") domain = static_cast<std::uint32_t>(std::stoul(argv[i + 1]));
    if (flag == "--namespace") ns = argv[i + 1];
    if (flag == "--frame-id") frame_id = argv[i + 1];
  }
  if (source_url.empty()) {
    std::fprintf(stderr,
                 "usage: ros2_floor --source URL --domain D [--namespace mocap] "
                 "[--frame-id world]\n");
    return 1;
  }
  std::string error;
  auto participant = dds::make_participant({domain, "loopback", "mocaplink_ros2_floor"}, error);
  if (!participant) {
    std::fprintf(stderr, "ros2_floor: %s\n", error.c_str());
    return 1;
  }
  auto writer = [&](const std::string& topic, std::string_view type, std::uint32_t depth) {
    auto w = participant->make_writer({"rt" + topic, std::string(type), depth, 2048, {}}, error);
    if (!w) {
      std::fprintf(stderr, "ros2_floor: %s\n", error.c_str());
      std::exit(1);
    }
    return w;
  };

  std::mutex mutex;
  std::condition_variable wake;
  std::deque<Queued> queue;
  std::uint64_t overflows = 0;
  auto opened = mocaplink::sources::builtin_sources().open(source_url);
  if (auto* e = std::get_if<std::string>(&opened)) {
    std::fprintf(stderr, "ros2_floor: %s\n", e->c_str());
    return 1;
  }
  auto source = std::move(std::get<0>(opened));
  source->start(
      [&](core::MocapFrame f, core::HostTime received) {
        Queued q{f.capture_time, f.source_latency, received, {}};
        for (const core::BodySample& b : f.bodies) {
          if (b.tracked) q.tracked.push_back(b.name);
        }
        const std::lock_guard lock(mutex);
        if (queue.size() >= 64) {  // publisher.cpp's queue: the oldest frame goes
          queue.pop_front();
          ++overflows;
        }
        queue.push_back(std::move(q));
        wake.notify_one();
      },
      [](mocaplink::sources::SourceState, const std::string&) {});
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);

  // The publishing thread (here: main): one writer per topic, the samples pre-encoded per body.
  std::map<std::string, std::pair<Sample, Sample>> bodies;  // pose, odom
  Sample tf;
  tf.writer = writer("/tf", wire::kRosTfMessageType, 100);
  std::vector<std::string> tf_bodies;  // the bodies tf.bytes was encoded for
  core::CaptureTimeMapper mapper;
  std::uint64_t frames = 0;
  std::uint64_t written = 0;
  std::uint64_t errors = 0;
  const core::RosBodyState rest;  // any pose: the floor converts nothing
  std::vector<Queued> batch;
  while (!g_stop) {
    {
      std::unique_lock lock(mutex);
      wake.wait_for(lock, std::chrono::milliseconds(100), [&] { return !queue.empty(); });
      batch.assign(std::make_move_iterator(queue.begin()), std::make_move_iterator(queue.end()));
      queue.clear();
    }
    for (const Queued& f : batch) {
      ++frames;
      const wire::RosStamp stamp = wire::ros_stamp_from_unix_ns(
          mocaplink::io::unix_ns_of(mapper.on_frame(f.capture, f.received, f.latency)));
      for (const std::string& name : f.tracked) {
        auto [it, added] = bodies.try_emplace(name);
        auto& [pose, odom] = it->second;
        if (added) {
          const std::string token = core::ros_name_token(name);
          const std::string base = "/" + ns + "/" + token;
          pose.writer = writer(base + "/pose", wire::kRosPoseStampedType, 10);
          wire::encode_pose_stamped(kSentinel, frame_id, rest, pose.bytes);
          pose.stamps = stamp_offsets(pose.bytes);
          odom.writer = writer(base + "/odom", wire::kRosOdometryType, 10);
          wire::encode_odometry(kSentinel, frame_id, token, rest, odom.bytes);
          odom.stamps = stamp_offsets(odom.bytes);
        }
        for (Sample* s : {&pose, &odom}) {
          s->stamp(stamp);
          s->writer->write(s->bytes) ? ++written : ++errors;
        }
      }
      if (f.tracked != tf_bodies) {  // a new set of bodies: encoded once more
        tf_bodies = f.tracked;
        std::vector<std::string> tokens;
        for (const std::string& name : tf_bodies) tokens.push_back(core::ros_name_token(name));
        std::vector<wire::RosTransform> transforms;
        for (const std::string& token : tokens) transforms.push_back({kSentinel, frame_id, token});
        wire::encode_tf_message(transforms, tf.bytes);
        tf.stamps = stamp_offsets(tf.bytes);
      }
      if (!tf_bodies.empty()) {
        tf.stamp(stamp);
        tf.writer->write(tf.bytes) ? ++written : ++errors;
      }
    }
  }
  source->stop();
  std::fprintf(stderr,
               "ros2_floor: %llu frames, %llu samples written, %llu write errors, %llu queue "
               "overflows\n",
               static_cast<unsigned long long>(frames), static_cast<unsigned long long>(written),
               static_cast<unsigned long long>(errors), static_cast<unsigned long long>(overflows));
  return 0;
}
